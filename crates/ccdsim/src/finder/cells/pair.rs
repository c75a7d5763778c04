//! Recomputing the two bodies of a collision in one pass over their neighbourhoods.
//!
//! After a collision of bodies `i` and `j` both are recomputed. They touch, so their cells are
//! the same or neighbours, and their 3^D blocks overlap: in 2D the union is 9 to 14 cells of
//! the 18 that two separate scans visit. [`Cells::recompute_pair`] walks the union once (the
//! table [`PairBlock`] of the grid): a body of a cell in both blocks is loaded once and
//! evaluated against `i` and against `j`, a body of a cell in one block only against that
//! block's owner, and the pair `(i, j)` itself is evaluated once and offered to both.
//!
//! # Why the records are those of two `recompute`s, bit for bit
//!
//! * *Same candidates.* `i`'s candidates are the bodies of the cells of both blocks and of
//!   `i`'s block only, that is of `i`'s block, `i` excepted; `j`, filed in a cell of both
//!   blocks, is skipped by the walk and offered up front. Likewise for `j`. Both cells are
//!   interior, so every cell of either block exists without wrapping and is seen through the
//!   zero image, as `scan_interior` sees it.
//! * *Same times.* Each candidate's time comes from [`Cells::offer_body`], the function the
//!   separate scan calls, on the same records, lower index first, with the zero shift (`+0`
//!   either way round); the pair `(i, j)` from [`Cells::pair_toi`], the same function with
//!   the same arguments. Nothing is stored between the two scans that the second one reads:
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

use super::grid::Grid;
use super::key::{Key, NONE};
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
        let zero = Vector::ZERO;
        let image = Grid::<D>::ZERO_IMAGE;
        let (mut bi, mut bj) = (Best::NONE, Best::NONE);
        // The pair itself, once, for both.
        if let Some(t) = self.pair_toi(pi, j, &pj.b, &zero) {
            let key = Key::body(t, i.min(j), i.max(j));
            bi.offer(key, image);
            bj.offer(key, image);
        }
        // Every head first, then a hint for each head's record and link (as `scan_interior`).
        let mut heads = [NONE; MAX_UNION];
        let n = block.offsets.len();
        for (h, &off) in heads.iter_mut().zip(&block.offsets) {
            *h = self.grid.first((base as isize + off) as u32);
        }
        let last = bodies.len() - 1;
        for &h in &heads[..n] {
            let h = (h as usize).min(last);
            prefetch(&bodies[h]);
            self.grid.prefetch_link(h);
        }
        let (shared, rest) = heads[..n].split_at(block.shared);
        let (only_i, only_j) = rest.split_at(block.only_first);
        if self.periodic {
            self.scan_union::<true>(bodies, pi, pj, shared, only_i, only_j, &mut bi, &mut bj);
        } else {
            self.scan_union::<false>(bodies, pi, pj, shared, only_i, only_j, &mut bi, &mut bj);
        }
        Some((bi, bj))
    }

    /// Walks the lists starting at the heads `shared` (cells of both blocks), `only_i` and
    /// `only_j` (cells of one block only), offering each body to the probes whose block holds
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
        let (i, j) = (pi.i, pj.i);
        for &h in shared {
            let mut k = h;
            while k != NONE {
                let ku = k as usize;
                if ku != i && ku != j {
                    let b = &bodies[ku];
                    Self::offer_body::<PERIODIC>(pi, ku, b, &zero, &zero, image, bi);
                    Self::offer_body::<PERIODIC>(pj, ku, b, &zero, &zero, image, bj);
                }
                k = self.grid.next_in_cell(k);
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
