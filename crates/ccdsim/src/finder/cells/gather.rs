//! Interior scans of crossing mode, four pairs at a time: the candidates of a block of cells
//! are gathered from the cells' slots without a branch per cell, then evaluated by the
//! four-lane kernel [`crate::contact::narrow_lanes::toi_sides`], each lane with its pair's balls in
//! the oracle's order.
//!
//! *Gathering.* Each cell's record is copied whole (its [`CELL_SLOTS`] slots) to the end of a
//! buffer, and the end advances by the number of used slots: the unused slots' copies are
//! overwritten by the next cell's or lie past the end. A cell holding more bodies than its
//! slots sets a flag and the caller takes the scalar path instead (rare: never at packing 0.5
//! in 2D, see `grid`). Every entry of the buffer is a valid body index (the buffer starts
//! zeroed and unused slots hold 0), so the padding lanes of a last, short quad read real
//! records and are dropped ([`Lanes::only`]).
//!
//! *The probes* are gathered too (a probe is filed in its own cell, and a collision's two
//! bodies are both in the shared cells): they are then dropped from the buffer by a pass
//! that stores every candidate and advances past the others only ([`Gathered::drop_probes`]),
//! no branch on which.
//!
//! *Exactness.* A lane holds the pair of the probe `i` and a candidate `j` with the lower
//! index's ball first (`Side::select` on `i < j`, lane by lane) and the zero shift, which is
//! what the scalar scan passes in an interior block (`+0` either way round: `0 − (+0)` is
//! `+0`): so it computes the oracle's function on the oracle's arguments, bit for bit (see
//! `narrow_lanes`), and a lane off the kernel's common path is handed to the scalar
//! [`Cells::offer_body`] on its own pair. The offers are those [`Cells::offer_body`] makes
//! (the same key and image, under the same threshold test), and [`Best`] does not depend on
//! the order of offers of distinct keys (see `pair`): the records equal those of the scalar
//! scan's.
//!
//! *Why.* The cell walks' loop exits and the scalar narrow phase's coin flips were most of the
//! 2D mispredicted branches: this costs a few per cent more instructions but a third fewer
//! mispredictions, and was faster on the clock at 2D N = 10⁴ and 10⁶, for 25 more bytes per
//! body (figures and what was tried: `bench/results/amd-epyc-2vcpu/cells-history.md`).

use super::candidate::{Best, Probe};
use super::grid::{CellBodies, Grid, CELL_SLOTS};
use super::key::{ordered, Key};
use super::Cells;
use crate::collision_filter::{colliding_lanes, CollisionFilter};
use crate::contact::narrow_lanes::{toi_sides, toi_sides_growing, Lanes, Side, ALL_LANES, LANES};
use crate::geom::Vector;
use crate::motion::Body;
use crate::motion::Laws;
use wide::{f64x4, i32x4, CmpGt};

// A cell's slots fill one quad.
const _: () = assert!(CELL_SLOTS == LANES);

/// Buffer entries for the candidates of one 2D scan: at least 14 cells (the union of two
/// blocks) of four slots, and a quad past the end.
pub(super) const GATHER_2D: usize = 64;

/// Buffer entries for the candidates of one 3D scan: 46 cells of four slots and a quad.
pub(super) const GATHER_3D: usize = 192;

/// The candidates of a block of cells, gathered from their slots.
pub(super) struct Gathered<const CAP: usize> {
    /// Body indices: the candidates in `ids[..n]`, valid indices beyond.
    pub ids: [u32; CAP],
    /// Number of candidates.
    pub n: usize,
    /// Number of bodies in the cells gathered, the overflowing ones included.
    len: usize,
}

impl<const CAP: usize> Gathered<CAP> {
    /// No candidates yet.
    #[inline(always)]
    pub fn new() -> Self {
        Gathered {
            ids: [0; CAP],
            n: 0,
            len: 0,
        }
    }

    /// Appends the bodies in the slots of `cell`, without a branch on how many there are.
    #[inline(always)]
    pub fn push(&mut self, cell: &CellBodies) {
        let n = self.n;
        self.ids[n..n + CELL_SLOTS].copy_from_slice(&cell.slots);
        self.n = n + cell.used();
        self.len += cell.len as usize;
    }

    /// Drops bodies `i` and `j` (the same body for a single probe) from the candidates
    /// gathered so far, keeping the others in order: a store and a conditional advance per
    /// candidate, no branch on which are dropped. A probe takes a lane otherwise (a quarter
    /// of a quad per probe and scan).
    #[inline(always)]
    pub fn drop_probes(&mut self, i: u32, j: u32) {
        let n = self.n;
        let mut m = 0;
        for k in 0..n {
            let id = self.ids[k];
            self.ids[m] = id;
            m += usize::from((id != i) & (id != j));
        }
        self.n = m;
        self.len -= n - m;
    }

    /// True when some cell gathered held more bodies than its slots (its overflow is not
    /// gathered).
    #[inline(always)]
    pub fn overflow(&self) -> bool {
        self.len != self.n
    }
}

/// The lane mask of the lanes of `quad` where `i` comes first (`i < j`): a compare of the
/// indices as floats, four at once (exact: indices are below 2³¹, see `key::MAX_INDEX`).
#[inline(always)]
fn probe_first(quad: [u32; LANES], i: u32) -> f64x4 {
    let q = i32x4::new(quad.map(|j| j as i32));
    f64x4::from_i32x4(q).cmp_gt(f64x4::splat(f64::from(i)))
}

/// The quad of candidates `ids[k..k + LANES]` (`k < to`), the mask of its lanes below `to`
/// (the others pad a last, short quad and are dropped), and the quad's balls.
#[inline(always)]
fn quad_at<const D: usize>(
    bodies: &[Body<D>],
    ids: &[u32],
    k: usize,
    to: usize,
) -> ([u32; LANES], u32, Side<D>) {
    let quad: [u32; LANES] = std::array::from_fn(|l| ids[k + l]);
    let valid = ALL_LANES >> (LANES - (to - k).min(LANES));
    let b = quad.map(|j| &bodies[j as usize]);
    (
        quad,
        valid,
        Side::gather(b.map(|b| &b.motion), b.map(|b| b.radius)),
    )
}

impl<const D: usize> Cells<D> {
    /// Offers body `p` (in all lanes of `probe`) its pairs with the candidates
    /// `ids[from..to]` (`to + LANES ≤ ids.len()`; `p` not among them), in quads.
    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    pub(super) fn scan_gathered<const PERIODIC: bool, const GROW: bool>(
        law: Option<&Laws<D>>,
        filters: &[CollisionFilter],
        bodies: &[Body<D>],
        p: &Probe<D>,
        probe: &Side<D>,
        ids: &[u32],
        from: usize,
        to: usize,
        best: &mut Best,
    ) {
        let mut k = from;
        while k < to {
            let (quad, valid, other) = quad_at(bodies, ids, k, to);
            Self::offer_quad::<PERIODIC, GROW>(
                law, filters, bodies, p, probe, &other, quad, valid, best,
            );
            k += LANES;
        }
    }

    /// Offers bodies `pi` and `pj` (in all lanes of `si`, `sj`) their pairs with the
    /// candidates `ids[from..to]` (`to + LANES ≤ ids.len()`; neither probe among them): each
    /// quad gathered once, evaluated for both.
    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    pub(super) fn scan_gathered_both<const PERIODIC: bool, const GROW: bool>(
        law: Option<&Laws<D>>,
        filters: &[CollisionFilter],
        bodies: &[Body<D>],
        (pi, si, bi): (&Probe<D>, &Side<D>, &mut Best),
        (pj, sj, bj): (&Probe<D>, &Side<D>, &mut Best),
        ids: &[u32],
        from: usize,
        to: usize,
    ) {
        let mut k = from;
        while k < to {
            let (quad, valid, other) = quad_at(bodies, ids, k, to);
            Self::offer_quad::<PERIODIC, GROW>(
                law, filters, bodies, pi, si, &other, quad, valid, bi,
            );
            Self::offer_quad::<PERIODIC, GROW>(
                law, filters, bodies, pj, sj, &other, quad, valid, bj,
            );
            k += LANES;
        }
    }

    /// Offers body `p` its pairs with the bodies `quad` (balls in `other`) of the lanes in
    /// `valid`: the kernel on each lane's pair in the oracle's order, with the zero shift (its
    /// growing form when `GROW`, with the growth law `law`).
    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    fn offer_quad<const PERIODIC: bool, const GROW: bool>(
        law: Option<&Laws<D>>,
        filters: &[CollisionFilter],
        bodies: &[Body<D>],
        p: &Probe<D>,
        probe: &Side<D>,
        other: &Side<D>,
        quad: [u32; LANES],
        valid: u32,
        best: &mut Best,
    ) {
        let mask = probe_first(quad, p.i as u32);
        let sa = Side::select(mask, probe, other);
        let sb = Side::select(mask, other, probe);
        let zero = [f64x4::ZERO; D];
        // Collision filters drop the lanes of pairs that pass through each other.
        let valid = if GROW && law.is_some_and(|l| l.filtered) {
            valid & colliding_lanes(filters, p.i, quad)
        } else {
            valid
        };
        let lanes = match (GROW, law) {
            (
                true,
                Some(Laws {
                    growth: Some(growth),
                    gravity: None,
                    kinematic: false,
                    ..
                }),
            ) => toi_sides_growing::<D, PERIODIC>(&sa, &sb, &zero, growth),
            // Collision filters alone: the straight-line kernel, on the lanes left.
            (
                true,
                Some(Laws {
                    growth: None,
                    gravity: None,
                    kinematic: false,
                    ..
                }),
            ) => toi_sides::<D, PERIODIC>(&sa, &sb, &zero),
            // Gravity: every lane goes to the scalar falling function.
            (true, Some(_)) => Lanes::all_rare(),
            _ => toi_sides::<D, PERIODIC>(&sa, &sb, &zero),
        }
        .only(valid);
        if lanes.rare != 0 {
            Self::offer_rare_lanes::<PERIODIC>(
                if GROW { law } else { None },
                filters,
                bodies,
                p,
                quad,
                lanes,
                best,
            );
            return;
        }
        let mut hits = lanes.hits;
        while hits != 0 {
            let l = hits.trailing_zeros() as usize;
            offer_time(
                best,
                p.i,
                quad[l] as usize,
                lanes.times[l],
                Grid::<D>::ZERO_IMAGE,
            );
            hits &= hits - 1;
        }
    }

    /// [`Cells::offer_quad`]'s offers when a lane is left to the scalar function (rare: out
    /// of line, so that the scan keeps its registers).
    #[cold]
    #[inline(never)]
    fn offer_rare_lanes<const PERIODIC: bool>(
        law: Option<&Laws<D>>,
        filters: &[CollisionFilter],
        bodies: &[Body<D>],
        p: &Probe<D>,
        quad: [u32; LANES],
        lanes: Lanes,
        best: &mut Best,
    ) {
        let zero = Vector::ZERO;
        for (l, &j) in quad.iter().enumerate() {
            let j = j as usize;
            if lanes.rare >> l & 1 != 0 {
                let image = Grid::<D>::ZERO_IMAGE;
                Self::offer_body::<PERIODIC>(
                    law, filters, p, j, &bodies[j], &zero, &zero, image, best,
                );
            } else if lanes.hits >> l & 1 != 0 {
                offer_time(best, p.i, j, lanes.times[l], Grid::<D>::ZERO_IMAGE);
            }
        }
    }
}

/// Offers body `i` its pair with body `j` meeting at time `t` (image code `image`), as
/// [`Cells::offer_body`] does.
#[inline(always)]
pub(super) fn offer_time(best: &mut Best, i: usize, j: usize, t: f64, image: u8) {
    let bits = ordered(t);
    if bits <= best.threshold() {
        best.offer(Key::body_bits(bits, i.min(j), i.max(j)), image);
    }
}
