//! Recomputing the two bodies of a collision in one pass over their neighbourhoods.
//!
//! After a collision of bodies `i` and `j` both are recomputed. They touch, so their cells are
//! the same or neighbours, and their 3^D blocks overlap: in 2D the union is 9 to 14 cells of
//! the 18 that two separate scans visit. [`Cells::recompute_pair`] gathers the union once (the
//! table `PairBlock` of the grid, see `gather`): the slots of the cells in both blocks, from
//! which `i` and `j` are then dropped, then those of `i`'s block only, then those of `j`'s
//! block only, without a branch per cell. A quad of the shared cells' bodies is loaded once
//! and evaluated against `i` and against `j` by the four-lane kernel, the quads of one block
//! only against that block's owner, and the pair `(i, j)` itself is evaluated once and
//! offered to both. A union with a cell that overflows its slots is left to two `recompute`s.
//!
//! Why one pass: the union is 9 to 14 cells where two scans visit 18, and gathering it without
//! a branch per cell removed most of the scans' mispredictions (figures and what was tried:
//! `bench/results/amd-epyc-2vcpu/cells-history.md`).
//!
//! # Why the records are those of two `recompute`s, bit for bit
//!
//! * *Same candidates.* `i`'s candidates are the bodies of the cells of both blocks and of
//!   `i`'s block only, that is of `i`'s block, `i` excepted; `j`, filed in a cell of both
//!   blocks, is dropped from the gathered bodies and offered up front. Likewise for `j`. (No
//!   cell overflows, so the slots hold every body of the union, each once; the drop removes
//!   exactly the entries equal to `i` or `j`.) Both cells are interior, so every cell of
//!   either block exists without wrapping and is seen through the zero image, as
//!   `scan_interior` sees it.
//! * *Same times.* Each candidate's time is the one the separate scan computes (see
//!   `gather`: the kernel's lane on the same records, lower index first, with the zero shift,
//!   `+0` either way round, or the scalar [`Cells::offer_body`] for a rare lane), offered
//!   with the same key, image and threshold test; the pair `(i, j)` from
//!   [`Cells::pair_toi`], the same function with the same arguments. Nothing is stored between the two scans that the second one reads:
//!   a scan reads the world (unchanged) and the grid (unchanged), and `store` writes only
//!   the records of the body it stores.
//! * *Order does not matter.* [`Best`] keeps the two smallest keys it is offered under the
//!   full key order (and `known` stays true in a full scan). The keys offered to one body are
//!   pairwise distinct: a body–body key names its pair, and in an interior block every body
//!   lies in exactly one cell, seen through one image, so each pair is offered once; wall
//!   keys name their wall, a box exit its face, and no class shares a tie word with another.
//!   The two smallest of a set of distinct keys, and the image that goes with each, do not
//!   depend on the order they come in; nor does `second_image` when fewer than two keys
//!   come (it is `Best::NONE`'s). The `tests` module checks this against two `recompute`s.
//! * Walls, box exit, `store` and `schedule` follow for `i`, then for `j`, exactly as the two
//!   `recompute`s do them, in that order, and `recomputes` counts two.

use super::candidate::{Best, Probe};
use super::gather::{Gathered, GATHER_2D, GATHER_3D};
use super::grid::Grid;
use super::key::Key;
use super::{Cells, Mode};
use crate::collision_filter::CollisionFilter;
use crate::contact::narrow_lanes::Side;
use crate::geom::Vector;
use crate::motion::Body;
use crate::motion::Laws;
use crate::prefetch::prefetch;
use crate::world::World;

impl<const D: usize> Cells<D> {
    /// Recomputes bodies `i` and `j` (both changed, at the same state of the world) as
    /// `recompute(i)` then `recompute(j)` would, in one scan of their neighbourhoods, when
    /// that applies: crossing mode, two distinct bodies filed in interior cells that are the
    /// same or neighbours. Returns false, having done nothing, otherwise.
    #[inline(always)]
    pub(super) fn recompute_pair(&mut self, world: &World<D>, i: usize, j: usize) -> bool {
        if matches!(self.mode, Mode::Lists(_)) || i == j || self.shear.is_some() {
            return false;
        }
        let (pi, pj) = (Probe::of(world, i), Probe::of(world, j));
        let (mut bi, mut bj) = (Best::NONE, Best::NONE);
        if !self.scan_pair(world, &pi, &pj, &mut bi, &mut bj) {
            return false;
        }
        self.stats.recomputes += 2;
        self.scan_walls(world, &pi, &mut bi);
        self.scan_exit(world, &pi, &mut bi);
        self.store(world, i, &bi, true);
        self.schedule(i, &pi.b.motion);
        self.scan_walls(world, &pj, &mut bj);
        self.scan_exit(world, &pj, &mut bj);
        self.store(world, j, &bj, true);
        self.schedule(j, &pj.b.motion);
        true
    }

    /// Offers `bi` and `bj` the body candidates of `pi` and of `pj` (see the module docs),
    /// and returns true, if their cells are interior and the same or neighbours and no cell
    /// of the union overflows its slots; else returns false, having offered nothing.
    #[inline(always)]
    fn scan_pair(
        &self,
        world: &World<D>,
        pi: &Probe<D>,
        pj: &Probe<D>,
        bi: &mut Best,
        bj: &mut Best,
    ) -> bool {
        if D == 2 {
            self.scan_pair_in::<GATHER_2D>(world, pi, pj, bi, bj)
        } else {
            self.scan_pair_in::<GATHER_3D>(world, pi, pj, bi, bj)
        }
    }

    /// [`Cells::scan_pair`] with a buffer of `CAP` candidates.
    #[inline(always)]
    fn scan_pair_in<const CAP: usize>(
        &self,
        world: &World<D>,
        pi: &Probe<D>,
        pj: &Probe<D>,
        bi: &mut Best,
        bj: &mut Best,
    ) -> bool {
        let (i, j) = (pi.i, pj.i);
        if self.resting() {
            return false;
        }
        let Some((base, block)) = self
            .grid
            .interior_pair(&self.cached[i].coords, &self.cached[j].coords)
        else {
            return false;
        };
        // Every cell's slots, without a branch per cell: the shared cells' (less `i` and `j`),
        // then those of `i`'s block only, then those of `j`'s block only.
        let mut g = Gathered::<CAP>::new();
        let cell = |off: isize| self.grid.cell((base as isize + off) as u32);
        let (shared, rest) = block.offsets.split_at(block.shared);
        let (only_i, only_j) = rest.split_at(block.only_first);
        for &off in shared {
            g.push(cell(off));
        }
        g.drop_probes(i as u32, j as u32);
        let e0 = g.n;
        for &off in only_i {
            g.push(cell(off));
        }
        let e1 = g.n;
        for &off in only_j {
            g.push(cell(off));
        }
        if g.overflow() {
            return false;
        }
        let bodies = world.bodies();
        if self.hints {
            for &k in &g.ids[..g.n] {
                prefetch(&bodies[k as usize]);
            }
        }
        // The pair itself, once, for both (the candidates are the others).
        let zero = Vector::ZERO;
        if let Some(t) = self.pair_toi(pi, j, &pj.b, &zero) {
            let key = Key::body(t, i.min(j), i.max(j));
            bi.offer(key, Grid::<D>::ZERO_IMAGE);
            bj.offer(key, Grid::<D>::ZERO_IMAGE);
        }
        let si = Side::splat(&pi.b.motion, pi.b.radius);
        let sj = Side::splat(&pj.b.motion, pj.b.radius);
        let ids = &g.ids[..];
        let parts = (e0, e1, g.n);
        let (i, j) = ((pi, &si, bi), (pj, &sj, bj));
        // The world's kind, once per scan: the loops are compiled for each.
        let law = self.laws.as_ref();
        let filters = &self.filters[..];
        match (self.periodic, law.is_some()) {
            (true, false) => {
                Self::scan_pair_parts::<true, false>(law, filters, bodies, i, j, ids, parts)
            }
            (false, false) => {
                Self::scan_pair_parts::<false, false>(law, filters, bodies, i, j, ids, parts)
            }
            (true, true) => {
                Self::scan_pair_parts::<true, true>(law, filters, bodies, i, j, ids, parts)
            }
            (false, true) => {
                Self::scan_pair_parts::<false, true>(law, filters, bodies, i, j, ids, parts)
            }
        }
        true
    }

    /// Offers `pi` and `pj` their pairs with the gathered candidates `ids`: those below
    /// `parts.0` (the shared cells') to both, then those up to `parts.1` to `pi` and those up
    /// to `parts.2` to `pj`.
    #[inline(always)]
    fn scan_pair_parts<const PERIODIC: bool, const GROW: bool>(
        law: Option<&Laws<D>>,
        filters: &[CollisionFilter],
        bodies: &[Body<D>],
        (pi, si, bi): (&Probe<D>, &Side<D>, &mut Best),
        (pj, sj, bj): (&Probe<D>, &Side<D>, &mut Best),
        ids: &[u32],
        (e0, e1, n): (usize, usize, usize),
    ) {
        Self::scan_gathered_both::<PERIODIC, GROW>(
            law,
            filters,
            bodies,
            (pi, si, &mut *bi),
            (pj, sj, &mut *bj),
            ids,
            0,
            e0,
        );
        Self::scan_gathered::<PERIODIC, GROW>(law, filters, bodies, pi, si, ids, e0, e1, bi);
        Self::scan_gathered::<PERIODIC, GROW>(law, filters, bodies, pj, sj, ids, e1, n, bj);
    }
}
