//! The options the `cells` finder reads, declared for tools (see [`FinderOption`]).

use crate::finder::{FinderOption, FinderOptions};

/// The `cells` finder's options: the skin of its neighbour lists.
pub const OPTIONS: &[FinderOption] = &[FinderOption {
    finder: "cells",
    name: "cells_skin",
    help: "skin of the neighbour lists (periodic worlds), relative to the largest contact \
           distance; 0 turns the lists off (cell crossings), else in [0.001, 1]",
    default: "automatic (no lists in 2D, 0.4 in 3D)",
    set: |o: &mut FinderOptions, v| o.cells_skin = Some(v),
}];
