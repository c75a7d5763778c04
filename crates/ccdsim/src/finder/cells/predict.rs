//! Predictions of the `cells` finder: scanning a body's neighbour cells and walls for its
//! earliest event, and scheduling its next cell crossing.

use super::grid::Neighbour;
use super::queue::{Key, NONE};
use super::Cells;
use crate::narrow::{toi_circle_circle, toi_circle_circle_shifted, toi_circle_wall, Motion};
use crate::world::World;

/// The running minimum of one body's candidate events.
#[derive(Clone, Copy, Debug)]
pub(super) struct Best {
    /// The earliest candidate so far under the full event order.
    pub key: Key,
    /// For a body–body candidate: the partner's change count it was computed with.
    pub stamp: u64,
}

impl Best {
    /// No candidate yet.
    pub const NONE: Best = Best {
        key: Key::NEVER,
        stamp: 0,
    };
}

impl<const D: usize> Cells<D> {
    /// Offers body `i` (motion `mi`) every pair with a body filed in `cells`, through the
    /// image shift of each cell. The time of a pair is computed exactly as the oracle does:
    /// by the same pure function, lower index first.
    #[inline]
    pub(super) fn scan_pairs(
        &self,
        world: &World<D>,
        i: usize,
        mi: &Motion<D>,
        cells: &[Neighbour<D>],
        best: &mut Best,
    ) {
        let radii = world.radii();
        let ri = radii[i];
        let positions = world.positions();
        let velocities = world.velocities();
        let times = world.times();
        for nb in cells {
            let mut j = self.grid.first(nb.cell);
            while j != NONE {
                let ju = j as usize;
                j = self.grid.after(j);
                if ju == i {
                    continue;
                }
                let mj = Motion {
                    pos: positions[ju],
                    vel: velocities[ju],
                    time: times[ju],
                };
                let rj = radii[ju];
                let t = if self.periodic {
                    if i < ju {
                        toi_circle_circle_shifted(mi, ri, &mj, rj, nb.shift)
                    } else {
                        toi_circle_circle_shifted(&mj, rj, mi, ri, -nb.shift)
                    }
                } else if i < ju {
                    toi_circle_circle(mi, ri, &mj, rj)
                } else {
                    toi_circle_circle(&mj, rj, mi, ri)
                };
                if let Some(t) = t {
                    let key = Key::body(t, i.min(ju), i.max(ju));
                    if key < best.key {
                        best.key = key;
                        best.stamp = world.change_count(ju);
                    }
                }
            }
        }
    }

    /// Offers body `i` every wall within reach of cell `cell`.
    #[inline]
    pub(super) fn scan_walls(
        &self,
        world: &World<D>,
        i: usize,
        mi: &Motion<D>,
        cell: u32,
        best: &mut Best,
    ) {
        let walls = world.walls();
        let ri = world.radii()[i];
        for &w in self.grid.walls_of(cell) {
            if let Some(t) = toi_circle_wall(mi, ri, &walls[w as usize]) {
                let key = Key::wall(t, i, w as usize);
                if key < best.key {
                    best.key = key;
                    best.stamp = 0;
                }
            }
        }
    }

    /// Recomputes body `i`'s earliest event from scratch (after its state changed, or when its
    /// cached event went stale) and reschedules it.
    pub(super) fn recompute(&mut self, world: &World<D>, i: usize) {
        self.stats.recomputes += 1;
        let mi = world.motion(i);
        let cell = self.grid.cell_of(i);
        let mut best = Best::NONE;
        let neighbours = self.grid.neighbours(cell);
        self.scan_pairs(world, i, &mi, neighbours.as_slice(), &mut best);
        self.scan_walls(world, i, &mi, cell, &mut best);
        self.best[i] = best.key;
        self.stamp[i] = best.stamp;
        self.schedule(i, &mi, cell);
    }

    /// Sets body `i`'s queue key: its next crossing or its cached event, whichever is first.
    pub(super) fn schedule(&mut self, i: usize, mi: &Motion<D>, cell: u32) {
        let crossing = match self.grid.next_crossing(cell, mi) {
            Some((t, code)) => {
                self.cross[i] = code;
                Key::crossing(t)
            }
            None => {
                self.cross[i] = super::NO_CROSSING;
                Key::NEVER
            }
        };
        self.queue.set(i, crossing.min(self.best[i]));
    }
}
