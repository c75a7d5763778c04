//! Predictions of the `cells` finder: scanning a body's neighbour cells and walls for its
//! earliest event, checking that a cached event is still live, and scheduling the body's next
//! cell crossing.

use super::grid::Grid;
use super::key::{ordered, Key};
use super::{Cells, KEY_IS_CROSSING, NO_CROSSING, SECOND_KNOWN};
use crate::geom::Vector;
use crate::narrow::{toi_circle_circle, toi_circle_circle_shifted, toi_circle_wall, Motion};
use crate::periodic::toi_box_exit;
use crate::world::World;

/// The two earliest of one body's candidate events.
///
/// `second` is a lower bound of every candidate but `key`'s own, as long as `known`; when the
/// cached `key` goes stale, `second` can take its place without a rescan (see the module docs).
#[derive(Clone, Copy, Debug)]
pub(super) struct Best {
    /// The earliest candidate so far under the full event order.
    pub key: Key,
    /// For a body–body candidate: the image code of the partner (see `Grid::visit_product`).
    pub image: u8,
    /// The second earliest candidate (or a lower bound of all but `key`'s).
    pub second: Key,
    /// Image code of `second`'s partner.
    pub second_image: u8,
    /// `second` is valid; false after `second` was promoted, until the next full scan.
    pub known: bool,
}

impl Best {
    /// No candidate yet.
    pub const NONE: Best = Best {
        key: Key::NEVER,
        image: 0,
        second: Key::NEVER,
        second_image: 0,
        known: true,
    };

    /// Time word below which a candidate changes the records.
    #[inline(always)]
    pub fn threshold(&self) -> u64 {
        if self.known {
            self.second.time
        } else {
            self.key.time
        }
    }

    /// Takes a candidate into account.
    #[inline]
    pub fn offer(&mut self, key: Key, image: u8) {
        if key < self.key {
            // The old earliest bounds everything else from below, the new candidate excepted.
            self.second = self.key;
            self.second_image = self.image;
            self.known = true;
            self.key = key;
            self.image = image;
        } else if self.known && key < self.second {
            self.second = key;
            self.second_image = image;
        }
    }
}

/// A body whose events are being predicted: index, stored motion and radius.
#[derive(Clone, Copy, Debug)]
pub(super) struct Probe<const D: usize> {
    /// Body index.
    pub i: usize,
    /// Its stored motion.
    pub m: Motion<D>,
    /// Its radius.
    pub r: f64,
}

impl<const D: usize> Probe<D> {
    /// Body `i` of `world`.
    #[inline]
    pub fn of(world: &World<D>, i: usize) -> Self {
        Probe {
            i,
            m: world.motion(i),
            r: world.radii()[i],
        }
    }
}

impl<const D: usize> Cells<D> {
    /// Time of impact of body `p` with body `j` (motion `mj`, radius `rj`; image displaced by
    /// `shift`), computed exactly as the oracle does: by the same pure function, lower index
    /// first.
    #[inline(always)]
    fn pair_toi(
        &self,
        p: &Probe<D>,
        j: usize,
        mj: &Motion<D>,
        rj: f64,
        shift: &Vector<D>,
    ) -> Option<f64> {
        let (i, mi, ri) = (p.i, &p.m, p.r);
        if self.periodic {
            if i < j {
                toi_circle_circle_shifted(mi, ri, mj, rj, *shift)
            } else {
                toi_circle_circle_shifted(mj, rj, mi, ri, -*shift)
            }
        } else if i < j {
            toi_circle_circle(mi, ri, mj, rj)
        } else {
            toi_circle_circle(mj, rj, mi, ri)
        }
    }

    /// Offers body `p` every pair with the bodies `others` (image codes `images`, see
    /// `Grid::visit_neighbours`). Times come from the oracle's narrow phase, lower index first
    /// (see [`super::kernel`]).
    #[inline]
    fn scan_bodies(
        &self,
        world: &World<D>,
        p: &Probe<D>,
        others: &[u32],
        images: &[u8],
        best: &mut Best,
    ) {
        let i = p.i;
        let radii = world.radii();
        let (positions, velocities, times) = (world.positions(), world.velocities(), world.times());
        for (&j, &image) in others.iter().zip(images) {
            let ju = j as usize;
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
                let shift = self.shifts[image as usize];
                if i < ju {
                    toi_circle_circle_shifted(&p.m, p.r, &mj, rj, shift)
                } else {
                    toi_circle_circle_shifted(&mj, rj, &p.m, p.r, -shift)
                }
            } else if i < ju {
                toi_circle_circle(&p.m, p.r, &mj, rj)
            } else {
                toi_circle_circle(&mj, rj, &p.m, p.r)
            };
            if let Some(t) = t {
                let bits = ordered(t);
                if bits <= best.threshold() {
                    best.offer(Key::body_bits(bits, i.min(ju), i.max(ju)), image);
                }
            }
        }
    }

    /// Offers body `p` every pair with a body in its neighbour cells.
    pub(super) fn scan_neighbours(&mut self, world: &World<D>, p: &Probe<D>, best: &mut Best) {
        let (mut others, mut images) = (
            std::mem::take(&mut self.scratch_bodies),
            std::mem::take(&mut self.scratch_images),
        );
        others.clear();
        images.clear();
        let k = self.grid.coords_of(p.i);
        self.grid.gather_neighbours(&k, &mut others, &mut images);
        self.scan_bodies(world, p, &others, &images, best);
        self.scratch_bodies = others;
        self.scratch_images = images;
    }

    /// Offers body `p`, just moved into its cell along `axis` in direction `up`, every pair
    /// with a body in the layer of cells that became its neighbours.
    pub(super) fn scan_entered_layer(
        &mut self,
        world: &World<D>,
        p: &Probe<D>,
        axis: usize,
        up: bool,
        best: &mut Best,
    ) {
        let (mut others, mut images) = (
            std::mem::take(&mut self.scratch_bodies),
            std::mem::take(&mut self.scratch_images),
        );
        others.clear();
        images.clear();
        let k = self.grid.coords_of(p.i);
        self.grid
            .gather_entered_layer(&k, axis, up, &mut others, &mut images);
        self.scan_bodies(world, p, &others, &images, best);
        self.scratch_bodies = others;
        self.scratch_images = images;
    }

    /// Offers body `p` every wall within reach of its cell.
    #[inline]
    pub(super) fn scan_walls(&self, world: &World<D>, p: &Probe<D>, best: &mut Best) {
        let walls = self.grid.walls_of(self.grid.cell_of(p.i));
        for &w in walls {
            if let Some(t) = toi_circle_wall(&p.m, p.r, &world.walls()[w as usize]) {
                best.offer(Key::wall(t, p.i, w as usize), Grid::<D>::ZERO_IMAGE);
            }
        }
    }

    /// Offers body `p` its exit from the periodic box, if the world is periodic.
    #[inline]
    pub(super) fn scan_exit(&self, world: &World<D>, p: &Probe<D>, best: &mut Best) {
        let Some(size) = world.periodic() else {
            return;
        };
        if let Some((t, face)) = toi_box_exit(&p.m, &size) {
            best.offer(
                Key::wall(t, p.i, self.faces_from + face),
                Grid::<D>::ZERO_IMAGE,
            );
        }
    }

    /// True when body `i`'s cached event is still a live term: a wall event depends on `i`
    /// alone (recomputed whenever `i` changes); a body event is evaluated again, for the same
    /// image, on the current stored states and must come out bit for bit the same.
    pub(super) fn is_live(&self, world: &World<D>, i: usize) -> bool {
        let key = self.best[i];
        let Some(j) = key.partner(i) else {
            return true;
        };
        let shift = self.shifts[self.image[i] as usize];
        let t = self.pair_toi(
            &Probe::of(world, i),
            j,
            &world.motion(j),
            world.radii()[j],
            &shift,
        );
        t.is_some_and(|t| Key::body(t, i.min(j), i.max(j)) == key)
    }

    /// Recomputes body `i`'s earliest event from scratch (after its state changed, or when its
    /// cached event went stale) and reschedules it.
    pub(super) fn recompute(&mut self, world: &World<D>, i: usize) {
        self.stats.recomputes += 1;
        let p = Probe::of(world, i);
        let mut best = Best::NONE;
        self.scan_neighbours(world, &p, &mut best);
        self.scan_walls(world, &p, &mut best);
        self.scan_exit(world, &p, &mut best);
        self.store(i, &best);
        self.schedule(i, &p.m);
    }

    /// Body `i`'s records.
    #[inline]
    pub(super) fn records(&self, i: usize) -> Best {
        Best {
            key: self.best[i],
            image: self.image[i],
            second: self.second[i],
            second_image: self.second_image[i] & !SECOND_KNOWN,
            known: self.second_image[i] & SECOND_KNOWN != 0,
        }
    }

    /// Stores body `i`'s records.
    #[inline]
    pub(super) fn store(&mut self, i: usize, best: &Best) {
        self.best[i] = best.key;
        self.image[i] = best.image;
        self.second[i] = best.second;
        self.second_image[i] = best.second_image | if best.known { SECOND_KNOWN } else { 0 };
    }

    /// Replaces body `i`'s stale cached event by its second one, if that is known, and
    /// reschedules it; false when a full rescan is needed.
    pub(super) fn promote_second(&mut self, world: &World<D>, i: usize) -> bool {
        let mut best = self.records(i);
        if !best.known {
            return false;
        }
        best.key = best.second;
        best.image = best.second_image;
        best.known = false;
        self.store(i, &best);
        self.schedule(i, &world.motion(i));
        true
    }

    /// Sets body `i`'s queue key: its next crossing or its cached event, whichever is first.
    pub(super) fn schedule(&mut self, i: usize, mi: &Motion<D>) {
        let k = self.grid.coords_of(i);
        let key = match self.grid.next_crossing(&k, mi) {
            Some((t, code)) => {
                let crossing = Key::crossing(t, i);
                if crossing < self.best[i] {
                    self.cross[i] = code | KEY_IS_CROSSING;
                    crossing
                } else {
                    self.cross[i] = code;
                    self.best[i]
                }
            }
            None => {
                self.cross[i] = NO_CROSSING;
                self.best[i]
            }
        };
        self.queue.set(i, key);
    }
}
