//! The list mode of the `cells` finder: Verlet neighbour lists with a skin, per-body shells
//! and shell exits (see the module docs of `cells` for why it is exact).
//!
//! Each body `i` has a *shell centre* `X_i`, its position when its list was last built, and
//! a shell, the ball of radius `h = s/2` around it (`s` the skin). Its list `N(i)` holds every
//! body `j` (with the image code of the shift that brings `j` next to `i`) whose shell may
//! overlap `i`'s: `|X_j − X_i + shift| ≤ σ_max + s + slack` (a bound of `r_i + r_j + s` the
//! same for all pairs), a relation symmetric bit for bit, and lists are kept equal to it:
//! when `i`'s list is rebuilt, `i` is added to the lists of its new neighbours and taken out
//! of those of the bodies it no longer overlaps. Nothing else moves a shell centre, so the
//! lists always hold exactly the overlapping pairs of the current centres.
//!
//! Lists are one flat array with a per-body stride (the first two slots of a block hold the
//! list's length and the number of its entries whose body index is above the list owner's,
//! which come first: a scan then knows which body goes first in the oracle's argument order
//! without asking per entry); when a list outgrows the stride, all lists are laid out again
//! with a stride a quarter larger (amortised: the stride grows a logarithmic number of
//! times).

use super::candidate::Best;
use super::grid::{Grid, MARGIN};
use super::slots::{CellRecord, CellSlots, SLOTS};
use crate::geom::Vector;
use crate::motion::Motion;
use crate::prefetch::prefetch;
use wide::{f64x4, i32x4, CmpEq, CmpGt, CmpLe};

/// Low bits of a list entry holding the image code (`3^3 = 27` codes fit in 5 bits).
const IMAGE_BITS: u32 = 5;
/// Header slots of a list block: the length and the number of entries of higher body index.
const HEADER: usize = 2;
/// Mask of the image code in a list entry.
const IMAGE_MASK: u32 = (1 << IMAGE_BITS) - 1;
/// Most bodies the list mode serves: an entry packs the body index above the image code.
pub(super) const MAX_LIST_BODIES: usize = 1 << (32 - IMAGE_BITS);

/// A list entry: body `j` seen through image code `image`.
#[inline(always)]
fn entry(j: usize, image: u8) -> u32 {
    ((j as u32) << IMAGE_BITS) | u32::from(image)
}

/// The body of a list entry.
#[inline(always)]
pub(super) fn entry_body(e: u32) -> usize {
    (e >> IMAGE_BITS) as usize
}

/// The image code of a list entry.
#[inline(always)]
pub(super) fn entry_image(e: u32) -> u8 {
    (e & IMAGE_MASK) as u8
}

/// Offers body `i` its pair with list entry `e`, meeting at time `t`.
#[inline(always)]
fn offer_entry(best: &mut Best, i: usize, e: u32, t: f64) {
    let bits = super::key::ordered(t);
    if bits <= best.threshold() {
        let j = entry_body(e);
        best.offer(
            super::key::Key::body_bits(bits, i.min(j), i.max(j)),
            entry_image(e),
        );
    }
}

/// The entries `above` (of higher body index than some body) and `below` (of lower) in
/// increasing order, into `out`: every entry of `below` sorts below every entry of `above`.
#[cfg(test)]
fn sorted_parts(above: &[u32], below: &[u32], out: &mut Vec<u32>) {
    out.clear();
    out.extend_from_slice(below);
    out.sort_unstable();
    out.extend_from_slice(above);
    out[below.len()..].sort_unstable();
}

/// The image code of the opposite shift (every base-3 digit `k` becomes `2 − k`).
#[inline(always)]
fn opposite<const D: usize>(image: u8) -> u8 {
    (3u8.pow(D as u32) - 1) - image
}

/// Time at which a body with motion `m`, inside the shell of radius `h` around `centre` at
/// time `t_ref`, reaches the shell's surface on its way out: the later root of
/// `|m.at(t) − centre| = h`, solved from `t_ref` without cancellation; infinity for a body at
/// rest. Between `t_ref` and that time the body is within `h` of `centre` (up to rounding).
/// A body already outside the shell and moving away gets a time at or before `t_ref`.
#[must_use]
pub(super) fn shell_exit_time<const D: usize>(
    m: &Motion<D>,
    centre: &Vector<D>,
    h: f64,
    t_ref: f64,
) -> f64 {
    let a = m.vel.norm_sq();
    if a == 0.0 {
        return f64::INFINITY;
    }
    let d = m.at(t_ref) - *centre;
    let b = d.dot(m.vel);
    let c = d.norm_sq() - h * h;
    let disc = b * b - a * c;
    if disc.is_nan() || disc < 0.0 {
        // The path misses the shell: only possible for a body already outside it.
        return t_ref;
    }
    let root = disc.sqrt();
    let tau = if b <= 0.0 {
        (root - b) / a
    } else {
        -c / (b + root)
    };
    t_ref + tau
}

/// The neighbour lists, shell centres and shell exit times of every body.
#[derive(Clone, Debug)]
pub(super) struct Lists<const D: usize> {
    /// The shell radius `h = s/2`, metres.
    pub half: f64,
    /// Square of the overlap distance `σ_max + s + slack` (slack against rounding).
    cut_sq: f64,
    /// Margin taken off the gaps between a shell centre and the cells around its own when
    /// cells are skipped at a rebuild (rounding of positions and cell faces).
    prune_margin: f64,
    /// Slots per body block: the length, the number of entries of higher body index, then
    /// up to `stride − HEADER` entries, those of higher body index first.
    stride: usize,
    /// The blocks.
    entries: Vec<u32>,
    /// Image shift of each image code, padded to 32 codes (entries hold 5-bit codes, so a
    /// lookup needs no bounds check).
    shifts: [Vector<D>; 1 << IMAGE_BITS],
    /// The shift of each image code as the oracle writes it for a partner listed first,
    /// `0 − shift` (zero components stay +0).
    neg_shifts: [Vector<D>; 1 << IMAGE_BITS],
    /// Each axis of each image shift in all four lanes (for the slot tests of a rebuild).
    shift_lanes: [[f64x4; D]; 1 << IMAGE_BITS],
    /// Shell centre of each body.
    pub centre: Vec<Vector<D>>,
    /// Shell exit time of each body (infinity: never).
    pub exit: Vec<f64>,
    /// Lists rebuilt since the last `update`: body, time.
    pub log: Vec<(u32, f64)>,
    /// Scratch: a list being built, its entries of higher body index.
    fresh: Vec<u32>,
    /// Scratch: a list being built, its entries of lower body index.
    fresh_below: Vec<u32>,
    /// Scratch: a copy of the list being replaced, above part first.
    old: Vec<u32>,
    /// Scratch: the entries new to the list being replaced.
    added: Vec<u32>,
    /// The shell centres again, filed by cell (read by rebuilds).
    pub slots: CellSlots<D>,
    /// Scratch of a rebuild: the cells near the shell (27 places, kept, never initialised
    /// again).
    near: Vec<(u32, u8)>,
    /// Scratch of a rebuild: the list entries of each near cell's slots (27 places).
    slot_entries: Vec<[u32; SLOTS]>,
}

/// A shell centre being tested against cells' slot records, in lanes: its coordinates and
/// body index splatted, and the squared overlap distance.
struct CellProbe<const D: usize> {
    x: [f64x4; D],
    me: i32x4,
    cut: f64x4,
}

impl<const D: usize> Lists<D> {
    /// Lists for `n` bodies with the skin `skin`, listing pairs whose centres are at most
    /// `cut` apart, on a grid of `cells` cells (all empty, centres at the origin, no body
    /// filed).
    pub fn new(n: usize, skin: f64, cut: f64, cells: usize) -> Self {
        let stride = 8;
        Lists {
            half: 0.5 * skin,
            cut_sq: cut * cut,
            prune_margin: 2.0 * MARGIN * cut,
            shifts: [Vector::ZERO; 1 << IMAGE_BITS],
            neg_shifts: [Vector::ZERO; 1 << IMAGE_BITS],
            shift_lanes: [[f64x4::ZERO; D]; 1 << IMAGE_BITS],
            stride,
            entries: vec![0; n * stride],
            centre: vec![Vector::ZERO; n],
            exit: vec![f64::INFINITY; n],
            log: Vec::new(),
            fresh: Vec::new(),
            fresh_below: Vec::new(),
            old: Vec::new(),
            added: Vec::new(),
            slots: CellSlots::new(cells, n),
            near: vec![(0, 0); 27],
            slot_entries: vec![[0; SLOTS]; 27],
        }
    }

    /// Sets the image shift of each image code (`shifts[code]`, at most 32 codes).
    pub fn set_shifts(&mut self, shifts: &[Vector<D>]) {
        self.shifts[..shifts.len()].copy_from_slice(shifts);
        for (neg, s) in self.neg_shifts.iter_mut().zip(shifts) {
            *neg = Vector::ZERO - *s;
        }
        for (lanes, s) in self.shift_lanes.iter_mut().zip(shifts) {
            *lanes = std::array::from_fn(|d| f64x4::splat(s[d]));
        }
    }

    /// Bytes held (payload).
    pub fn bytes(&self) -> usize {
        4 * (self.entries.capacity()
            + self.fresh.capacity()
            + self.fresh_below.capacity()
            + self.old.capacity()
            + self.added.capacity())
            + std::mem::size_of::<Vector<D>>() * self.centre.capacity()
            + 8 * self.exit.capacity()
            + std::mem::size_of::<(u32, f64)>() * self.log.capacity()
            + self.slots.bytes()
            + std::mem::size_of::<(u32, u8)>() * self.near.capacity()
            + std::mem::size_of::<[u32; SLOTS]>() * self.slot_entries.capacity()
    }

    /// Longest list the layout holds.
    #[cfg(test)]
    pub fn capacity(&self) -> usize {
        self.stride - HEADER
    }

    /// Body `i`'s list.
    #[inline(always)]
    pub fn list(&self, i: usize) -> &[u32] {
        let at = i * self.stride;
        let len = self.entries[at] as usize;
        &self.entries[at + HEADER..at + HEADER + len]
    }

    /// Hints that body `i`'s list block will be read soon (its first two cache lines).
    #[inline(always)]
    pub fn prefetch_list(&self, i: usize) {
        let at = i * self.stride;
        prefetch(&self.entries[at]);
        prefetch(&self.entries[(at + 16).min(self.entries.len() - 1)]);
    }

    /// Body `i`'s list in two parts: the entries whose body index is above `i`, then the
    /// others.
    #[inline(always)]
    pub fn parts(&self, i: usize) -> (&[u32], &[u32]) {
        let at = i * self.stride;
        let len = self.entries[at] as usize;
        let above = (self.entries[at + 1] as usize).min(len);
        self.entries[at + HEADER..at + HEADER + len].split_at(above)
    }

    /// Lays all lists out again so that one of `len` entries fits, in place (the array
    /// grows, then blocks move up from the last one down: a block's new place is never below
    /// its old one, so no block is overwritten before it moves), so that the peak memory is
    /// the new array only (large reallocations extend in place or are remapped).
    fn grow(&mut self, len: usize) {
        let old = self.stride;
        let stride = (len + HEADER).max(old + old / 4 + 1);
        let n = self.centre.len();
        self.entries.resize(n * stride, 0);
        for i in (1..n).rev() {
            let used = HEADER + self.entries[i * old] as usize;
            self.entries
                .copy_within(i * old..i * old + used, i * stride);
        }
        self.stride = stride;
    }

    /// Adds `e` to body `i`'s list (in the part of its body index).
    fn push(&mut self, i: usize, e: u32) {
        let len = self.list(i).len();
        if len + HEADER >= self.stride {
            self.grow(len + 1);
        }
        let at = i * self.stride;
        let block = &mut self.entries[at..at + HEADER + len + 1];
        if entry_body(e) > i {
            // The first entry of the lower part moves to the end to make room.
            let split = HEADER + block[1] as usize;
            block[HEADER + len] = block[split];
            block[split] = e;
            block[1] += 1;
        } else {
            block[HEADER + len] = e;
        }
        block[0] += 1;
    }

    /// Takes `e` out of body `i`'s list, where it is.
    fn remove(&mut self, i: usize, e: u32) {
        let at = i * self.stride;
        let len = self.entries[at] as usize;
        let above = self.entries[at + 1] as usize;
        let block = &mut self.entries[at + HEADER..at + HEADER + len];
        let k = block.iter().position(|&x| x == e);
        debug_assert!(k.is_some(), "entry {e} not in the list of body {i}");
        if let Some(k) = k {
            if k < above {
                // The last entry of the upper part fills the hole, the last entry of the
                // list fills its place.
                block[k] = block[above - 1];
                block[above - 1] = block[len - 1];
                self.entries[at + 1] -= 1;
            } else {
                block[k] = block[len - 1];
            }
            self.entries[at] -= 1;
        }
    }

    /// Replaces body `i`'s list by the entries `above` (of higher body index) and `below`
    /// (of lower).
    fn set(&mut self, i: usize, above: &[u32], below: &[u32]) {
        let len = above.len() + below.len();
        if len + HEADER > self.stride {
            self.grow(len);
        }
        let at = i * self.stride;
        let block = &mut self.entries[at..at + HEADER + len];
        block[0] = len as u32;
        block[1] = above.len() as u32;
        let (first, second) = block[HEADER..].split_at_mut(above.len());
        first.copy_from_slice(above);
        second.copy_from_slice(below);
    }

    /// The entries of body `i`'s list in increasing order, into `out`: the entries of lower
    /// body index sort below the others, so each part is sorted on its own.
    #[cfg(test)]
    fn sorted_list(&self, i: usize, out: &mut Vec<u32>) {
        let (above, below) = self.parts(i);
        sorted_parts(above, below, out);
    }

    /// Fills `out` with the cells (and image codes) of the 3^D block around the cell of
    /// coordinates `k` (where a body with shell centre `x` is filed) whose box comes within
    /// the overlap distance of `x`, and returns how many there are: the others hold no body
    /// whose shell overlaps. A body of a cell lies in the cell's box up to rounding, and
    /// along each axis the box of the cell before (after) `k`, with its image shift, ends
    /// where `k`'s own begins (ends), so the per-axis gaps from `x` to those faces, less
    /// `prune_margin` for rounding, bound the distance from below. An axis of a single cell
    /// (its three images) is not pruned.
    #[inline]
    fn near_cells(
        &self,
        grid: &Grid<D>,
        k: &[u32; D],
        x: &Vector<D>,
        out: &mut [(u32, u8); 27],
    ) -> usize {
        let dims = grid.dims();
        let (lo, hi) = grid.nominal_box(&k.map(|c| c as usize));
        // Per axis and offset (before, same, after): the linear index part, the image code
        // part and the squared gap.
        let mut part = [[0u32; 3]; D];
        let mut code = [[0u8; 3]; D];
        let mut gap = [[0.0f64; 3]; D];
        let mut stride = 1u32;
        let mut pow = 1u8;
        for d in 0..D {
            let n = dims[d] as u32;
            let kd = k[d];
            if n == 1 {
                part[d] = [0; 3];
                code[d] = [0, pow, 2 * pow];
            } else {
                let (before, wrap_before) = if kd == 0 { (n - 1, 0) } else { (kd - 1, 1) };
                let (after, wrap_after) = if kd + 1 == n { (0, 2) } else { (kd + 1, 1) };
                part[d] = [before * stride, kd * stride, after * stride];
                code[d] = [wrap_before * pow, pow, wrap_after * pow];
                let below = (x[d] - lo[d] - self.prune_margin).max(0.0);
                let above = (hi[d] - x[d] - self.prune_margin).max(0.0);
                gap[d] = [below * below, 0.0, above * above];
            }
            stride *= n;
            pow *= 3;
        }
        // Axes beyond `D` (2D) have the one offset "same", adding nothing.
        let reach = |d: usize| if d < D { 3 } else { 1 };
        let at = |t: &[[u32; 3]; D], d: usize, o: usize| if d < D { t[d][o] } else { 0 };
        let code_at = |d: usize, o: usize| if d < D { code[d][o] } else { 0 };
        let gap_at = |d: usize, o: usize| if d < D { gap[d][o] } else { 0.0 };
        let mut count = 0;
        for o2 in 0..reach(2) {
            let g2 = gap_at(2, o2);
            for o1 in 0..reach(1) {
                let g1 = g2 + gap_at(1, o1);
                let row = at(&part, 2, o2) + at(&part, 1, o1);
                let row_code = code_at(2, o2) + code_at(1, o1);
                // Branch-free: every cell is written to the next slot, which is kept when the
                // cell is near (gaps are never negative, so a far row keeps none).
                for o0 in 0..3 {
                    out[count] = (row + part[0][o0], row_code + code[0][o0]);
                    count += usize::from(g1 + gap[0][o0] <= self.cut_sq);
                }
            }
        }
        count
    }

    /// Tests the bodies of the slot record `rec` of a cell seen through image `image`
    /// against the shell of `probe`'s body: returns the slot bits of those kept with a body
    /// index above the probe's and of those kept below it, and writes each slot's list entry
    /// to `out`. Each slot's test is `Lists::overlap`'s, the same operations in the same
    /// order (the displacement `(x_j − x_i) + shift`, then its squared norm summed from 0
    /// axis by axis), so its outcome is the same bit for bit; one slot per lane of a four-lane
    /// vector (the `SLOTS` slots of an axis lie together), and unused slots (at infinity)
    /// never pass.
    #[inline(always)]
    fn test_cell(
        &self,
        rec: &CellRecord<D>,
        image: u8,
        probe: &CellProbe<D>,
        out: &mut [u32; SLOTS],
    ) -> (u32, u32) {
        let shift = &self.shift_lanes[usize::from(image) & IMAGE_MASK as usize];
        let mut sq = f64x4::ZERO;
        for ((p, &x), &s) in rec.pos.iter().zip(&probe.x).zip(shift) {
            let t = (f64x4::new(*p) - x) + s;
            sq += t * t;
        }
        let near = sq.cmp_le(probe.cut).move_mask() as u32;
        // Body indices are below 2^27: signed lanes compare them as they are.
        let bodies = i32x4::new(rec.body.map(|j| j as i32));
        let not_self = !bodies.cmp_eq(probe.me).move_mask() as u32;
        let up = bodies.cmp_gt(probe.me).move_mask() as u32;
        let keep = near & not_self;
        let e = (bodies << IMAGE_BITS as i32) | i32x4::splat(i32::from(image));
        *out = e.to_array().map(|e| e as u32);
        (keep & up, keep & !up)
    }

    /// True when the shells of two bodies with centres `xa` and `xb` may overlap through the
    /// shift `shift` added to `b`'s displacement: `|xb − xa + shift| ≤ σ_max + s + slack`, a
    /// bound of `r_a + r_b + s` the same for every pair. Seen from `b` (centres swapped, the
    /// opposite shift, which is the exact negation) the displacement is the exact negation
    /// of this one (rounding to nearest is symmetric), so both sides agree bit for bit.
    #[inline(always)]
    pub fn overlap(&self, xa: &Vector<D>, xb: &Vector<D>, shift: &Vector<D>) -> bool {
        let d = (*xb - *xa) + *shift;
        d.norm_sq() <= self.cut_sq
    }
}

mod finder;
#[cfg(test)]
mod tests;
