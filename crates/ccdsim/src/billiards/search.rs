//! How a shot finds its next event: the finders of ccdsim's scenes, for balls on the cloth.
//!
//! Every finder gives the oracle's event bit for bit: the earliest, under the shot's order,
//! of the pure contact functions ([`super::contact_time`]) over every pair of balls and every
//! ball and part of the table, and of every ball's state change. They differ in what they
//! compute and keep:
//!
//! - `all-pairs` computes every prediction afresh at each event (the oracle);
//! - `sedgewick` keeps every prediction in an event calendar (a priority queue) and renews a
//!   ball's when it has an event;
//! - `cells` lists each ball in the cells of a grid over the table its swept box
//!   ([`super::contact_time::Flight::swept_box`]: its whole flight, until its state
//!   changes) covers, and looks for contacts only with the balls and table parts sharing a
//!   cell with it;
//! - `bvh` does the same through bounding-volume hierarchies over the balls' swept boxes
//!   and the table's parts.
//!
//! A ball's flight always ends (a sliding ball rolls, a rolling ball stops) unless the
//! cloth has no rolling friction, so its swept box is finite and needs no time horizon; an
//! unbounded box meets every cell and node. Boxes that do not overlap hold no contact
//! ([`super::contact_time::Flight::swept_box`]), so leaving their pairs out changes no
//! prediction.

use std::fmt;
use std::str::FromStr;

use super::ball_grid::BallGrid;
use super::box_tree::BoxTree;
use super::table::Table;
use crate::geom::{Aabb, Vector};

/// How a shot finds its next event (the CLI's `--finder` on pool scenes). Each gives the
/// same events, bit for bit.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum PoolFinder {
    /// Every prediction computed afresh at each event: the oracle.
    AllPairs,
    /// Every prediction kept in an event calendar, a ball's renewed when it has an event.
    Sedgewick,
    /// A grid over the table; contacts looked for among the balls and table parts whose
    /// swept boxes share a cell.
    #[default]
    Cells,
    /// Bounding-volume hierarchies over the balls' swept boxes and the table's parts.
    Bvh,
}

impl PoolFinder {
    /// Every finder, the oracle first.
    pub const ALL: [PoolFinder; 4] = [
        PoolFinder::AllPairs,
        PoolFinder::Sedgewick,
        PoolFinder::Cells,
        PoolFinder::Bvh,
    ];

    /// The finder's name as the CLI knows it.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            PoolFinder::AllPairs => "all-pairs",
            PoolFinder::Sedgewick => "sedgewick",
            PoolFinder::Cells => "cells",
            PoolFinder::Bvh => "bvh",
        }
    }
}

impl fmt::Display for PoolFinder {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for PoolFinder {
    type Err = String;

    /// A finder by its name: `all-pairs`, `sedgewick`, `cells` or `bvh`.
    fn from_str(name: &str) -> Result<Self, String> {
        PoolFinder::ALL
            .into_iter()
            .find(|f| f.name() == name)
            .ok_or_else(|| {
                format!(
                    "unknown finder `{name}` for a pool scene (all-pairs, sedgewick, cells, bvh)"
                )
            })
    }
}

/// A part of the table a ball can meet, as the broad phases number them: the cushions, then
/// the jaws, then the pockets.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum TablePart {
    /// A straight cushion.
    Cushion(usize),
    /// A jaw.
    Jaw(usize),
    /// A pocket.
    Pocket(usize),
}

/// Every part of `table`, in the broad phases' numbering, and its box.
pub(crate) fn parts_of(table: &Table) -> (Vec<TablePart>, Vec<Aabb<2>>) {
    let mut parts = Vec::new();
    let mut boxes = Vec::new();
    for (k, c) in table.cushions.iter().enumerate() {
        parts.push(TablePart::Cushion(k));
        boxes.push(c.bounds());
    }
    for (k, j) in table.jaws.iter().enumerate() {
        parts.push(TablePart::Jaw(k));
        boxes.push(j.bounds());
    }
    for (k, p) in table.pockets.iter().enumerate() {
        parts.push(TablePart::Pocket(k));
        boxes.push(p.bounds());
    }
    (parts, boxes)
}

/// Which balls and table parts a ball's contacts are looked for among.
#[derive(Clone, Debug)]
pub(crate) enum BroadPhase {
    /// Every ball and every part (`all-pairs`, `sedgewick`).
    Everything,
    /// The `cells` grid.
    Grid(BallGrid),
    /// The `bvh` hierarchies.
    Trees {
        /// Over the balls' swept boxes, rebuilt when one changes.
        balls: BoxTree<2>,
        /// Whether a box changed since the last build.
        stale: bool,
        /// Over the table's parts.
        parts: BoxTree<2>,
    },
}

impl BroadPhase {
    /// The broad phase of `finder` for `n` balls of radius `radius` (m) on `table`, no
    /// ball placed yet.
    pub fn new(finder: PoolFinder, table: &Table, n: usize, radius: f64) -> BroadPhase {
        match finder {
            PoolFinder::AllPairs | PoolFinder::Sedgewick => BroadPhase::Everything,
            PoolFinder::Cells => {
                let (_, boxes) = parts_of(table);
                let surface = Aabb {
                    min: Vector::ZERO,
                    max: Vector([table.width, table.length]),
                };
                let extent = boxes.iter().fold(surface, |e, b| e.union(*b));
                // About four diameters a cell, and no more than 32 cells along the table.
                let cell = (8.0 * radius).max(table.width.max(table.length) / 32.0);
                BroadPhase::Grid(BallGrid::new(extent, cell, n, &boxes))
            }
            PoolFinder::Bvh => {
                let (_, boxes) = parts_of(table);
                let mut parts = BoxTree::default();
                parts.build(&boxes);
                BroadPhase::Trees {
                    balls: BoxTree::default(),
                    stale: true,
                    parts,
                }
            }
        }
    }

    /// Ball `i`'s swept box is now `boxes[i]` ([`Aabb::EMPTY`] once it is pocketed).
    pub fn place(&mut self, i: usize, boxes: &[Aabb<2>]) {
        match self {
            BroadPhase::Everything => {}
            BroadPhase::Grid(grid) => grid.place(i, &boxes[i]),
            BroadPhase::Trees { stale, .. } => *stale = true,
        }
    }

    /// The other balls and the table parts (by [`parts_of`]'s numbering) ball `i`'s
    /// contacts are looked for among, a superset of those whose boxes overlap its box, into
    /// `balls` and `parts` (cleared first); `None` for every ball and part.
    pub fn near(
        &mut self,
        i: usize,
        boxes: &[Aabb<2>],
        balls: &mut Vec<usize>,
        parts: &mut Vec<usize>,
    ) -> Option<()> {
        balls.clear();
        parts.clear();
        match self {
            BroadPhase::Everything => return None,
            BroadPhase::Grid(grid) => grid.near(i, balls, parts),
            BroadPhase::Trees {
                balls: tree,
                stale,
                parts: part_tree,
            } => {
                if *stale {
                    tree.build(boxes);
                    *stale = false;
                }
                let b = &boxes[i];
                if b.min[0] <= b.max[0] {
                    tree.overlapping(b, balls);
                    balls.retain(|&j| j != i);
                    part_tree.overlapping(b, parts);
                }
            }
        }
        Some(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::billiards::PocketTableSpecs;

    #[test]
    fn finders_are_named_as_the_cli_names_them() {
        for f in PoolFinder::ALL {
            assert_eq!(f.name().parse::<PoolFinder>(), Ok(f));
        }
        assert_eq!(PoolFinder::default(), PoolFinder::Cells);
        assert!("grid".parse::<PoolFinder>().unwrap_err().contains("bvh"));
    }

    #[test]
    fn the_grid_and_the_trees_leave_out_what_no_box_reaches() {
        let table = Table::pool(&PocketTableSpecs::default());
        let r = 0.028575;
        let centre = Vector([table.width / 2.0, table.length / 2.0]);
        let boxes = [
            Aabb::of_ball(Vector([0.2, 0.2]), r),
            // Touching ball 0: their boxes share a face.
            Aabb::of_ball(Vector([0.2 + 2.0 * r, 0.2]), r),
            Aabb::of_ball(centre, r),
            Aabb::EMPTY,
        ];
        for finder in [PoolFinder::Cells, PoolFinder::Bvh] {
            let mut broad = BroadPhase::new(finder, &table, boxes.len(), r);
            for i in 0..boxes.len() {
                broad.place(i, &boxes);
            }
            let (mut balls, mut parts) = (Vec::new(), Vec::new());
            assert!(broad.near(0, &boxes, &mut balls, &mut parts).is_some());
            assert!(
                balls.contains(&1) && !balls.contains(&2),
                "{finder}: {balls:?}"
            );
            broad.near(2, &boxes, &mut balls, &mut parts);
            assert!(!balls.contains(&0) && parts.is_empty(), "{finder}");
            broad.near(3, &boxes, &mut balls, &mut parts);
            assert!(
                balls.is_empty() && parts.is_empty(),
                "{finder}: a pocketed ball"
            );
        }
        let mut everything = BroadPhase::new(PoolFinder::Sedgewick, &table, 4, r);
        let (mut balls, mut parts) = (Vec::new(), Vec::new());
        assert!(everything.near(0, &boxes, &mut balls, &mut parts).is_none());
    }
}
