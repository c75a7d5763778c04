//! Recomputing the two bodies of a collision in one pass over their neighbourhoods.
//!
//! After a collision of bodies `i` and `j` both are recomputed. They touch, so their cells are
//! the same or neighbours, and their 3^D blocks overlap: in 2D the union is 9 to 14 cells of
//! the 18 that two separate scans visit. [`Cells::recompute_pair`] walks the union once (the
//! table `PairBlock` of the grid): a body of a cell in both blocks is loaded once and
//! evaluated against `i` and against `j`, a body of a cell in one block only against that
//! block's owner, and the pair `(i, j)` itself is evaluated once and offered to both. Empty
//! cells are left out before the walk, without a branch each, and the walk of the shared
//! cells steps over `i` and `j` by selects on their links rather than by a test per body
//! (half the bodies there are the probes). Callgrind, 2D N = 10⁴ at packing 0.5,
//! instructions and branch mispredictions per collision: two scans 3,196 and 36.9; this
//! 3,308 and 34.6, faster on the clock (session 6's results README). Measured on a base
//! that still gave every scan prefetch hints (two scans 3,743 and 43.7, this 3,604 and
//! 34.6; the simulated predictor's count moves by a mispredict or two with code layout
//! alone: the same walk with bounds-checked gathering took 3,636 and 32.9, and the
//! unchanged queue code's own count moved by 0.3 between the two). Tried: a plain union
//! walk with those branches, 3,562 and 38.9; the time of each probe with itself computed
//! and dropped instead of the steps, 3,666 and 33.4; the steps by arithmetic masks (the
//! code generator makes the selects branches), 3,727 and 34.0; a two-lane SIMD kernel for
//! the shared cells, `i` and `j` in the lanes, 3,636 and 41.6 (shared cells hold about two
//! other bodies per scan).
//!
//! # Why the records are those of two `recompute`s, bit for bit
//!
//! * *Same candidates.* `i`'s candidates are the bodies of the cells of both blocks and of
//!   `i`'s block only, that is of `i`'s block, `i` excepted; `j`, filed in a cell of both
//!   blocks, is stepped over by the walk and offered up front. Likewise for `j`. (A list
//!   holds each body once, so stepping over `i`, then `j`, then `i` again from any link
//!   leaves neither: see `probe_skipper`.) Both cells are interior, so every cell of either
//!   block exists without wrapping and is seen through the zero image, as `scan_interior`
//!   sees it.
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

/// Slots for the heads of the union of two 3^D blocks, a power of two: at least the most
/// cells such a union has (two 3D blocks meeting at a corner: 27 + 27 − 8 = 46).
const HEAD_SLOTS: usize = 64;

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
        // The pair itself, once, for both (the walk skips `i` and `j`).
        let zero = Vector::ZERO;
        if let Some(t) = self.pair_toi(pi, j, &pj.b, &zero) {
            let key = Key::body(t, i.min(j), i.max(j));
            bi.offer(key, Grid::<D>::ZERO_IMAGE);
            bj.offer(key, Grid::<D>::ZERO_IMAGE);
        }
        // Every head first, the empty cells' left out (a branch per cell on whether it is
        // empty mispredicts about as often as not), then, in large worlds, a hint for each
        // head's record, as `scan_interior` gives.
        let mut heads = [NONE; HEAD_SLOTS];
        let mut n = 0;
        let skip = self.probe_skipper(i, j);
        let first = |off: isize| self.grid.first((base as isize + off) as u32);
        let (shared, rest) = block.offsets.split_at(block.shared);
        let (only_i, only_j) = rest.split_at(block.only_first);
        for &off in shared {
            push_head(&mut heads, &mut n, skip(first(off)));
        }
        let e0 = n;
        for &off in only_i {
            push_head(&mut heads, &mut n, first(off));
        }
        let e1 = n;
        for &off in only_j {
            push_head(&mut heads, &mut n, first(off));
        }
        if self.hints {
            for &h in &heads[..n] {
                prefetch(&bodies[h as usize]);
            }
        }
        let (shared, only_i, only_j) = (&heads[..e0], &heads[e0..e1], &heads[e1..n]);
        if self.periodic {
            self.scan_union::<true>(bodies, pi, pj, shared, only_i, only_j, &mut bi, &mut bj);
        } else {
            self.scan_union::<false>(bodies, pi, pj, shared, only_i, only_j, &mut bi, &mut bj);
        }
        Some((bi, bj))
    }

    /// A map from a link of a cell list (a body or `NONE`) to the first link from there on
    /// that is neither `i` nor `j`, from the two probes' links read once: it replaces a test
    /// per body of whether it is a probe (half the bodies of the shared cells are). A list
    /// holds each body once, so from a link at most the probes `i, j` or `j, i` follow in a
    /// row: checking for `i`, then `j`, then `i` again is enough. (The code generator makes
    /// branches of the selects, on the walk's chain of loads; they mispredict about twice a
    /// collision in callgrind's model, the selects forced by arithmetic cost more, see the
    /// module docs.)
    #[inline(always)]
    fn probe_skipper(&self, i: usize, j: usize) -> impl Fn(u32) -> u32 {
        let (i, j) = (i as u32, j as u32);
        let (after_i, after_j) = (self.grid.next_in_cell(i), self.grid.next_in_cell(j));
        move |k| {
            let k = if k == i { after_i } else { k };
            let k = if k == j { after_j } else { k };
            if k == i {
                after_i
            } else {
                k
            }
        }
    }

    /// Walks the lists starting at the heads `shared` (cells of both blocks, `i` and `j`
    /// stepped over), `only_i` and `only_j` (cells of one block only), none of them empty,
    /// offering each body to the probes whose block holds its cell.
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
        // Cells that are not empty: each list has a first body. The probes are skipped.
        let skip = self.probe_skipper(pi.i, pj.i);
        for &h in shared {
            let mut k = h;
            loop {
                let ku = k as usize;
                let b = &bodies[ku];
                Self::offer_body::<PERIODIC>(pi, ku, b, &zero, &zero, image, bi);
                Self::offer_body::<PERIODIC>(pj, ku, b, &zero, &zero, image, bj);
                k = skip(self.grid.next_in_cell(k));
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

/// Appends the head `h` to `heads[..*n]` unless it is `NONE` (an empty cell), without a
/// branch. `*n` stays below the slots (a union has at most 46 cells): the mask only spares
/// the bounds check.
#[inline(always)]
fn push_head(heads: &mut [u32; HEAD_SLOTS], n: &mut usize, h: u32) {
    heads[*n & (HEAD_SLOTS - 1)] = h;
    *n += usize::from(h != NONE);
}
