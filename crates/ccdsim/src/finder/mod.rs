//! Next-event finders (broad phases) and their contract.
//!
//! # Contract
//!
//! A finder serves one [`World`]. It is given the world once through [`Finder::init`], told
//! through [`Finder::update`] which bodies' stored states changed, and asked through
//! [`Finder::next_event`] for the next event. That event must be exactly — bit for bit — the
//! minimum under [`Event`]'s total order of
//! [`toi_circle_circle`](crate::contact::narrow::toi_circle_circle) over all body pairs and
//! [`toi_circle_wall`](crate::contact::narrow::toi_circle_wall) over all (body, wall) pairs, evaluated
//! on the world's stored states: what [`AllPairs`] computes. Any internal bookkeeping (cell
//! crossings, rebuilt trees) stays inside the finder. When that minimum lies at an infinite
//! time there is no next event ([`finite_event`]): a contact at an infinite time never
//! happens.
//!
//! In a periodic world ([`World::periodic`]) the pair function is
//! [`toi_circle_circle_periodic`](crate::contact::periodic::toi_circle_circle_periodic) and each body's
//! exit from the box ([`toi_box_exit`](crate::contact::periodic::toi_box_exit)) is an event too, a wall
//! event naming face `f` as wall `walls.len() + f`; the simulation applies exits silently. In a
//! sheared periodic world ([`World::shear`]) the pair function is
//! [`toi_bodies_sheared`](crate::contact::lees_edwards::toi_bodies_sheared). Every finder of
//! this crate serves periodic and sheared worlds; a finder that cannot would refuse them in
//! `init` with [`FinderError::Unsupported`].

mod all_pairs;
pub mod bvh;
mod cells;
mod options;
mod sedgewick;

pub use all_pairs::{all_pairs_next_event, AllPairs};
pub use options::{
    auto_cells_skin, auto_cells_skin_at, finder_options, FinderOption, FinderOptions, LIST_PACKING,
};

/// `e`, unless its time is infinite (or undefined): a contact at an infinite time never
/// happens. Times of impact overflow to infinity only in degenerate runs, when speeds have
/// decayed to near the smallest normal number (an inelastic collapse between two walls);
/// resolving such an event would put every later state at an infinite time, and the next
/// predictions at undefined ones. Every finder applies this to the minimum it finds, so
/// they still agree bit for bit.
#[must_use]
#[inline]
pub fn finite_event(e: Option<Event>) -> Option<Event> {
    e.filter(|e| e.time < f64::INFINITY)
}
pub use bvh::BvhFinder;
pub use cells::{check_options as check_cells_options, Cells, CellsStats};
pub use sedgewick::{Sedgewick, SedgewickStats};

use crate::event::Event;
use crate::geom::Aabb;
use crate::world::World;

/// A broad phase that finds the next event of a world. Object safe.
pub trait Finder<const D: usize>: Send {
    /// The finder's name as the CLI knows it, e.g. `all-pairs`.
    fn name(&self) -> &'static str;

    /// Prepares for `world`; called before any other method and again whenever bodies or walls
    /// are added or removed. Refuses worlds it cannot serve.
    fn init(&mut self, world: &World<D>) -> Result<(), FinderError>;

    /// Tells the finder that the stored states of `changed` were replaced (a collision or an
    /// edit); every other body is as it was.
    fn update(&mut self, world: &World<D>, changed: &[usize]);

    /// Tells the finder that every body's stored state was replaced at the current time
    /// (velocities rescaled, say), with radii, walls, filters and laws as they were. By
    /// default a fresh `init`; a finder that can take in every body's new state for less
    /// than a rebuild does that instead.
    fn all_changed(&mut self, world: &World<D>) -> Result<(), FinderError> {
        self.init(world)
    }

    /// The next event under the total order, or `None` when no event will ever happen.
    fn next_event(&mut self, world: &World<D>) -> Option<Event>;

    /// Boxes of the finder's spatial structure for the current state, for viewers; empty for
    /// finders without one.
    fn debug_boxes(&mut self, _world: &World<D>) -> Vec<DebugBox<D>> {
        Vec::new()
    }

    /// Memory held by the finder's own structures, for benchmarks; `None` for finders that do
    /// not track it.
    fn memory(&self) -> Option<FinderMemory> {
        None
    }

    /// Counters of the finder's internal work since its last `init` (name, count), for
    /// benchmarks and profiling; empty for finders that keep none.
    fn counters(&self) -> Vec<(&'static str, u64)> {
        Vec::new()
    }
}

/// Memory held by a finder's own structures, bytes (payload only: allocator overhead and
/// spare capacity are not counted).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct FinderMemory {
    /// Bytes held now.
    pub bytes: usize,
    /// Most bytes held at once since the last `init`.
    pub peak_bytes: usize,
}

/// One box of a finder's spatial structure, for drawing.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DebugBox<const D: usize> {
    /// The box, metres.
    pub aabb: Aabb<D>,
    /// Depth in the structure (0 = root); leaves are deepest.
    pub depth: u32,
    /// True for a box around a single body.
    pub leaf: bool,
}

/// Why a finder cannot be made or cannot serve a world.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum FinderError {
    /// No finder has this name.
    #[error("unknown finder `{name}` (known: {known})")]
    Unknown {
        /// The name asked for.
        name: String,
        /// The known names, comma-separated.
        known: String,
    },
    /// The finder cannot serve this world.
    #[error("finder `{finder}` cannot run this scene: {why}")]
    Unsupported {
        /// The finder's name.
        finder: &'static str,
        /// Why.
        why: String,
    },
    /// An option of the finder is out of range.
    #[error("finder option `{option}`: {why}")]
    Option {
        /// The option.
        option: &'static str,
        /// Why.
        why: String,
    },
}

/// Names of every finder [`make_finder`] knows.
pub const FINDER_NAMES: &[&str] = &["all-pairs", "bvh", "sedgewick", "cells"];

/// Makes the finder called `name`.
pub fn make_finder<const D: usize>(
    name: &str,
    options: &FinderOptions,
) -> Result<Box<dyn Finder<D>>, FinderError> {
    match name {
        "all-pairs" => Ok(Box::new(AllPairs::new())),
        "bvh" => Ok(Box::new(BvhFinder::new(options)?)),
        "sedgewick" => Ok(Box::new(Sedgewick::new())),
        "cells" => Ok(Box::new(Cells::<D>::with_options(options)?)),
        _ => Err(FinderError::Unknown {
            name: name.to_string(),
            known: FINDER_NAMES.join(", "),
        }),
    }
}
