//! The options the `bvh` finder reads, declared for tools (see [`FinderOption`]).

use crate::finder::{FinderOption, FinderOptions};

/// The `bvh` finder's options: the growth and shrink factors of its time step Δ and the first
/// Δ (thesis §4.7).
pub const OPTIONS: &[FinderOption] = &[
    FinderOption {
        finder: "bvh",
        name: "bvh_grow",
        help: "factor by which the time step grows while no event is found (finite, > 1)",
        default: "2",
        set: |o: &mut FinderOptions, v| o.bvh_grow = v,
    },
    FinderOption {
        finder: "bvh",
        name: "bvh_shrink",
        help: "factor by which the time step shrinks after an event (in (0, 1])",
        default: "0.5",
        set: |o: &mut FinderOptions, v| o.bvh_shrink = v,
    },
    FinderOption {
        finder: "bvh",
        name: "bvh_initial_dt",
        help: "the first time step, seconds (finite, > 0)",
        default: "0.001",
        set: |o: &mut FinderOptions, v| o.bvh_initial_dt = v,
    },
];
