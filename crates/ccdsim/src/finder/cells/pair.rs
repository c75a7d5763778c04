//! Recomputing the two bodies of a collision in one pass over their neighbourhoods.
//!
//! After a collision of bodies `i` and `j` both are recomputed. They touch, so their cells are
//! the same or neighbours, and their 3^D blocks overlap: in 2D the union is 9 to 14 cells of
//! the 18 that two separate scans visit. [`Cells::recompute_pair`] walks the union once (the
//! table `PairBlock` of the grid): a body of a cell in both blocks is loaded once and
//! evaluated against `i` and against `j`, a body of a cell in one block only against that
//! block's owner. Empty cells are left out before the walk, without a branch each, and the
//! walk of the shared cells has no branch on whether a body is `i` or `j` (half the bodies
//! there are): callgrind, 2D N = 10⁴ at packing 0.5, the branch mispredictions per
//! collision fall from 43.7 (two scans) to 33.4 and the instructions from 3,743 to 3,666. (A
//! plain union walk, with those branches, took 3,562 instructions and 38.9 mispredictions;
//! a two-lane SIMD kernel for the shared cells, `i` and `j` in the lanes, 3,636 and 41.6:
//! shared cells hold about two other bodies per scan.)
//!
//! # Why the records are those of two `recompute`s, bit for bit
//!
//! * *Same candidates.* `i`'s candidates are the bodies of the cells of both blocks and of
//!   `i`'s block only, that is of `i`'s block, `i` excepted: the walk of the shared cells
//!   computes a time for `i` with itself too, and drops it whatever it is, before offering
//!   (see `offer_other`). `j`, filed in a cell of both blocks, is met there. Likewise for
//!   `j`. Both cells are interior, so every cell of either block exists without wrapping and
//!   is seen through the zero image, as `scan_interior` sees it.
//! * *Same times.* Each candidate's time comes from the function the separate scan calls
//!   ([`Cells::scan_list`] for the cells of one block, the same code in `offer_other` for the
//!   shared ones), on the same records, lower index first, with the zero shift (`+0` either
//!   way round): the pair `(i, j)` gets the same time whether it is met from `i`'s side or
//!   from `j`'s. Nothing is stored between the two scans that the second one reads: a scan
//!   reads the world (unchanged) and the grid (unchanged), and `store` writes only the
//!   records of the body it stores.
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

use super::grid::Grid;
use super::key::{ordered, Key, NONE};
use super::predict::{Best, Probe};
use super::Cells;
use crate::geom::Vector;
use crate::prefetch::prefetch;
use crate::world::{Body, World};

/// Most cells in the union of two 3^D blocks (two 3D blocks meeting at a corner: 27 + 27 − 8).
const MAX_UNION: usize = 46;

impl<const D: usize> Cells<D> {
    /// Recomputes bodies `i` and `j` (both changed, at the same state of the world) as
    /// `recompute(i)` then `recompute(j)` would, in one scan of their neighbourhoods, when
    /// that applies: crossing mode, two distinct bodies filed in interior cells that are the
    /// same or neighbours. Returns false, having done nothing, otherwise.
    pub(super) fn recompute_pair(&mut self, world: &World<D>, i: usize, j: usize) -> bool {
        if self.lists.is_some() || i == j {
            return false;
        }
        let (pi, pj) = (Probe::of(world, i), Probe::of(world, j));
        let Some((mut bi, mut bj)) = self.scan_pair(world, &pi, &pj) else {
            return false;
        };
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

    /// The body candidates of `pi` and of `pj` (see the module docs), if their cells are
    /// interior and the same or neighbours.
    #[inline(always)]
    fn scan_pair(&self, world: &World<D>, pi: &Probe<D>, pj: &Probe<D>) -> Option<(Best, Best)> {
        let (i, j) = (pi.i, pj.i);
        let (base, block) = self
            .grid
            .interior_pair(&self.cached[i].coords, &self.cached[j].coords)?;
        let bodies = world.bodies();
        let (mut bi, mut bj) = (Best::NONE, Best::NONE);
        // Every head first, the empty cells' left out (a branch per cell on whether it is
        // empty mispredicts about as often as not), then a hint for each head's record and
        // link, as `scan_interior` gives.
        let mut heads = [NONE; MAX_UNION];
        let mut n = 0;
        let mut ends = [0usize; 3];
        let sections = [
            &block.offsets[..block.shared],
            &block.offsets[block.shared..block.shared + block.only_first],
            &block.offsets[block.shared + block.only_first..],
        ];
        for (end, offsets) in ends.iter_mut().zip(sections) {
            for &off in offsets {
                let h = self.grid.first((base as isize + off) as u32);
                heads[n] = h;
                n += usize::from(h != NONE);
            }
            *end = n;
        }
        for &h in &heads[..n] {
            prefetch(&bodies[h as usize]);
            self.grid.prefetch_link(h as usize);
        }
        let shared = &heads[..ends[0]];
        let only_i = &heads[ends[0]..ends[1]];
        let only_j = &heads[ends[1]..ends[2]];
        if self.periodic {
            self.scan_union::<true>(bodies, pi, pj, shared, only_i, only_j, &mut bi, &mut bj);
        } else {
            self.scan_union::<false>(bodies, pi, pj, shared, only_i, only_j, &mut bi, &mut bj);
        }
        Some((bi, bj))
    }

    /// Offers body `p` its pair with body `j` (record `bj`) of a shared cell, unless `j` is
    /// `p` itself: as [`Cells::offer_body`] with the zero shift, except that the time is
    /// computed before asking whether `j` is `p` (whatever it is for `p` with itself, it is
    /// dropped), so that the walk has no branch on it: half the bodies of the shared cells
    /// are the probes themselves.
    #[inline(always)]
    fn offer_other<const PERIODIC: bool>(p: &Probe<D>, j: usize, bj: &Body<D>, best: &mut Best) {
        let i = p.i;
        let zero = Vector::ZERO;
        if let Some(t) = Self::body_time::<PERIODIC>(p, j, bj, &zero, &zero) {
            let bits = ordered(t);
            if bits <= best.threshold() && j != i {
                best.offer(
                    Key::body_bits(bits, i.min(j), i.max(j)),
                    Grid::<D>::ZERO_IMAGE,
                );
            }
        }
    }

    /// Walks the lists starting at the heads `shared` (cells of both blocks), `only_i` and
    /// `only_j` (cells of one block only), none of them empty, offering each body to the probes whose block holds
    /// its cell.
    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    fn scan_union<const PERIODIC: bool>(
        &self,
        bodies: &[Body<D>],
        pi: &Probe<D>,
        pj: &Probe<D>,
        shared: &[u32],
        only_i: &[u32],
        only_j: &[u32],
        bi: &mut Best,
        bj: &mut Best,
    ) {
        let zero = Vector::ZERO;
        let image = Grid::<D>::ZERO_IMAGE;
        // Cells that are not empty: each list has a first body.
        for &h in shared {
            let mut k = h;
            loop {
                let ku = k as usize;
                let b = &bodies[ku];
                Self::offer_other::<PERIODIC>(pi, ku, b, bi);
                Self::offer_other::<PERIODIC>(pj, ku, b, bj);
                k = self.grid.next_in_cell(k);
                if k == NONE {
                    break;
                }
            }
        }
        for &h in only_i {
            self.scan_list::<PERIODIC>(bodies, pi, h, &zero, image, bi);
        }
        for &h in only_j {
            self.scan_list::<PERIODIC>(bodies, pj, h, &zero, image, bj);
        }
    }
}
