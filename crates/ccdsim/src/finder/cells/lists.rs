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

use super::grid::{Grid, MARGIN};
use super::predict::{Best, Probe};
use super::slots::{CellRecord, CellSlots, SLOTS};
use super::Cells;
use crate::geom::Vector;
use crate::narrow::{toi_circle_circle, toi_circle_circle_shifted, Motion};
use crate::narrow_lanes::{
    first_lanes, toi_sides, vector_lanes, Lanes, PairArgs, Side, ALL_LANES, LANES,
};
use crate::prefetch::prefetch;
use crate::world::{Body, World};
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

impl<const D: usize> Cells<D> {
    /// The list mode's structures (list mode only).
    #[inline(always)]
    fn lists(&self) -> &Lists<D> {
        self.lists.as_ref().expect("list mode")
    }

    /// The list mode's structures, mutable (list mode only).
    #[inline(always)]
    fn lists_mut(&mut self) -> &mut Lists<D> {
        self.lists.as_mut().expect("list mode")
    }

    /// Hints that the records of body `i`'s listed partners will be read soon: asked for
    /// together, their misses overlap. Not the first quad's: the scan reads those at once.
    #[inline(always)]
    pub(super) fn prefetch_partners(&self, world: &World<D>, i: usize) {
        let bodies = world.bodies();
        for &e in self.lists().list(i).get(LANES..).unwrap_or_default() {
            prefetch(&bodies[entry_body(e)]);
        }
    }

    /// Offers body `p` every pair of its neighbour list, each by the oracle's narrow phase
    /// with the oracle's arguments (see `scan_list`): the partners of higher index (listed
    /// first) with `p` first, the rest with the partner first.
    pub(super) fn scan_neighbour_list(&self, world: &World<D>, p: &Probe<D>, best: &mut Best) {
        let lists = self.lists();
        let above = lists.parts(p.i).0.len();
        let entries = lists.list(p.i);
        let bodies = world.bodies();
        if self.hints {
            self.prefetch_partners(world, p.i);
        }
        if self.periodic {
            self.scan_quads::<true>(bodies, p, entries, above, best);
        } else {
            self.scan_quads::<false>(bodies, p, entries, above, best);
        }
    }

    /// Offers body `p` the pairs of the list entries `entries`, of which the first `above`
    /// have a higher body index than `p`'s (`p` goes first in their pairs, the partner in
    /// the others'). The entries go four at a time, in list order, through the lane kernel
    /// ([`toi_sides`], each lane the scalar function's times bit for bit): `p` is put in
    /// all lanes once; a quad of one part has `p` on one side, the quad where the parts meet
    /// selects each lane's sides by its part, and the last quad is padded with copies of the
    /// last entry, whose lanes are dropped (no time, never handed to the scalar function).
    #[inline(always)]
    fn scan_quads<const PERIODIC: bool>(
        &self,
        bodies: &[Body<D>],
        p: &Probe<D>,
        entries: &[u32],
        above: usize,
        best: &mut Best,
    ) {
        let n = entries.len();
        let probe = Side::splat(&p.b.motion, p.b.radius);
        let mut k = 0;
        while k < n {
            let (quad, valid) = if let Some(q) = entries.get(k..k + LANES) {
                ([q[0], q[1], q[2], q[3]], ALL_LANES)
            } else {
                // Past the end, the last entry again (its lanes are dropped).
                let q = std::array::from_fn(|l| entries[(k + l).min(n - 1)]);
                (q, (1 << (n - k)) - 1)
            };
            if k + LANES <= above {
                self.scan_quad::<PERIODIC, 0>(bodies, p, &probe, quad, LANES, valid, best);
            } else if k >= above {
                self.scan_quad::<PERIODIC, 1>(bodies, p, &probe, quad, 0, valid, best);
            } else {
                self.scan_quad::<PERIODIC, 2>(bodies, p, &probe, quad, above - k, valid, best);
            }
            k += LANES;
        }
    }

    /// Offers body `p` (in all lanes of `probe`) the pairs of the list entries `quad` whose
    /// bits are set in `valid`: `p` first in all lanes (`ORDER` 0), in none (1), or in the
    /// lanes below `first` (2).
    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    fn scan_quad<const PERIODIC: bool, const ORDER: u8>(
        &self,
        bodies: &[Body<D>],
        p: &Probe<D>,
        probe: &Side<D>,
        quad: [u32; LANES],
        first: usize,
        valid: u32,
        best: &mut Best,
    ) {
        let lists = self.lists();
        let b = quad.map(|e| &bodies[entry_body(e)]);
        let other = Side::gather(b.map(|b| &b.motion), b.map(|b| b.radius));
        // Each lane's shift as the oracle writes it for its order.
        let shift_of = |table: [&[Vector<D>; 1 << IMAGE_BITS]; LANES]| {
            if PERIODIC {
                vector_lanes(std::array::from_fn(|l| {
                    &table[l][usize::from(entry_image(quad[l]))]
                }))
            } else {
                [f64x4::ZERO; D]
            }
        };
        let lanes = match ORDER {
            0 => toi_sides::<D, PERIODIC>(probe, &other, &shift_of([&lists.shifts; LANES])),
            1 => toi_sides::<D, PERIODIC>(&other, probe, &shift_of([&lists.neg_shifts; LANES])),
            _ => {
                let mask = first_lanes(first);
                let sa = Side::select(mask, probe, &other);
                let sb = Side::select(mask, &other, probe);
                let tables = std::array::from_fn(|l| {
                    if l < first {
                        &lists.shifts
                    } else {
                        &lists.neg_shifts
                    }
                });
                toi_sides::<D, PERIODIC>(&sa, &sb, &shift_of(tables))
            }
        }
        .only(valid);
        if lanes.rare != 0 {
            self.offer_rare_quad::<PERIODIC>(bodies, p, quad, lanes, best);
            return;
        }
        let mut hits = lanes.hits;
        while hits != 0 {
            let l = hits.trailing_zeros() as usize;
            offer_entry(best, p.i, quad[l], lanes.times[l]);
            hits &= hits - 1;
        }
    }

    /// [`Cells::scan_quad`]'s offers when a lane is left to the scalar function (rare: out of
    /// line, so that the scan keeps its registers).
    #[cold]
    #[inline(never)]
    fn offer_rare_quad<const PERIODIC: bool>(
        &self,
        bodies: &[Body<D>],
        p: &Probe<D>,
        quad: [u32; LANES],
        lanes: Lanes,
        best: &mut Best,
    ) {
        lanes.each_time(
            |l, t| offer_entry(best, p.i, quad[l], t),
            |l| self.list_pair(bodies, p, quad[l]).scalar::<PERIODIC>(),
        );
    }

    /// The pair of body `p` and list entry `e` in the oracle's argument order.
    #[inline(always)]
    fn list_pair<'a>(&'a self, bodies: &'a [Body<D>], p: &'a Probe<D>, e: u32) -> PairArgs<'a, D> {
        let lists = self.lists();
        let j = entry_body(e);
        let image = usize::from(entry_image(e));
        let b = &bodies[j];
        if p.i < j {
            PairArgs {
                a: &p.b.motion,
                ra: p.b.radius,
                b: &b.motion,
                rb: b.radius,
                shift: &lists.shifts[image],
            }
        } else {
            PairArgs {
                a: &b.motion,
                ra: b.radius,
                b: &p.b.motion,
                rb: p.b.radius,
                shift: &lists.neg_shifts[image],
            }
        }
    }

    /// Offers body `p` the pairs of the list entries `entries`.
    #[inline(always)]
    fn scan_entries<const PERIODIC: bool>(
        &self,
        bodies: &[Body<D>],
        p: &Probe<D>,
        entries: &[u32],
        best: &mut Best,
    ) {
        let i = p.i;
        let shifts = &self.lists().shifts;
        for &e in entries {
            let j = entry_body(e);
            let image = entry_image(e);
            let b = &bodies[j];
            let probe_first = i < j;
            let (a, c) = if probe_first { (&p.b, b) } else { (b, &p.b) };
            let t = if PERIODIC {
                let shift = shifts[usize::from(image)];
                // The partner's shift as the oracle writes it: `0 − s` keeps zeros +0.
                let s = if probe_first {
                    shift
                } else {
                    Vector::ZERO - shift
                };
                toi_circle_circle_shifted(&a.motion, a.radius, &c.motion, c.radius, s)
            } else {
                toi_circle_circle(&a.motion, a.radius, &c.motion, c.radius)
            };
            if let Some(t) = t {
                let bits = super::key::ordered(t);
                if bits <= best.threshold() {
                    best.offer(super::key::Key::body_bits(bits, i.min(j), i.max(j)), image);
                }
            }
        }
    }

    /// Builds every body's list from scratch (at `init`, shell centres set).
    pub(super) fn build_all_lists(&mut self, n: usize) {
        for i in 0..n {
            let (na, nb) = self.collect_overlapping(i);
            let lists = self.lists_mut();
            let (above, below) = (
                std::mem::take(&mut lists.fresh),
                std::mem::take(&mut lists.fresh_below),
            );
            lists.set(i, &above[..na], &below[..nb]);
            lists.fresh = above;
            lists.fresh_below = below;
        }
    }

    /// Fills the scratch lists `fresh` (bodies of higher index) and `fresh_below` (lower) with
    /// every body whose shell overlaps body `i`'s, from
    /// the neighbour cells of `i`'s cell whose box comes within the overlap distance of its
    /// shell centre (see `Lists::near_cells`).
    ///
    /// The centres come from the cells' slot records ([`CellSlots`]), each cell's slots
    /// tested together, lane by lane, without a branch on any test's outcome (only a cell's
    /// overflow, rare, takes one): a first pass keeps one bit per slot and part, a second
    /// copies the kept entries. Returns the numbers of entries of higher and of lower body
    /// index (the scratch lists' lengths).
    ///
    /// The entries come in slot order, which swap-removes reshuffle: the order of a list is
    /// not the order of its bodies' filing. No result depends on it: a scan offers every
    /// entry to `Best`, which keeps the smallest keys, and keys are totally ordered, so two
    /// entries tie only when they are the same pair through two images (an axis of a single
    /// cell lists a pair once per overlapping image). Then the images' times are equal bit
    /// for bit, the event returned (time, kind, bodies) is the same whichever image is kept,
    /// and the kept image is only used to evaluate a promoted event again, to tell whether it
    /// is live: on unchanged states either image gives that same time, and otherwise the
    /// proof of the module docs holds whichever image was kept (a live key is returned, a
    /// stale one replaced by its body's live minimum), so the events returned are the same
    /// and only the `stale`/`recomputes` counters could tell.
    fn collect_overlapping(&mut self, i: usize) -> (usize, usize) {
        let mut above = std::mem::take(&mut self.lists_mut().fresh);
        let mut below = std::mem::take(&mut self.lists_mut().fresh_below);
        above.clear();
        below.clear();
        let mut near = std::mem::take(&mut self.lists_mut().near);
        let mut slot_entries = std::mem::take(&mut self.lists_mut().slot_entries);
        let lists = self.lists();
        let xi = lists.centre[i];
        let cells: &mut [(u32, u8); 27] = near.as_mut_slice().try_into().expect("27 cells");
        let count = lists.near_cells(&self.grid, &self.cached[i].coords, &xi, cells);
        if self.hints {
            for &(c, _) in &cells[..count] {
                lists.slots.prefetch_cell(c);
            }
        }
        // First pass, without a branch on any test: each cell's slot entries go to `entries`,
        // and one bit per slot (bit `SLOTS·a + k` for slot `k` of the `a`-th cell of a
        // group of 16) says whether it is kept in the part of higher body index or of lower.
        let entries: &mut [[u32; SLOTS]; 27] =
            slot_entries.as_mut_slice().try_into().expect("27 cells");
        let probe = CellProbe {
            x: std::array::from_fn(|d| f64x4::splat(xi[d])),
            me: i32x4::splat(i as i32),
            cut: f64x4::splat(lists.cut_sq),
        };
        let mut kept = [(0u64, 0u64); 2];
        let mut any_overflow = false;
        for (group, bits) in kept.iter_mut().enumerate() {
            let from = (16 * group).min(count);
            let to = (16 * group + 16).min(count);
            for (at, (&(c, image), out)) in cells[from..to]
                .iter()
                .zip(&mut entries[from..to])
                .enumerate()
            {
                let rec = lists.slots.cell(c);
                let (up, down) = lists.test_cell(rec, image, &probe, out);
                bits.0 |= u64::from(up) << (SLOTS * at);
                bits.1 |= u64::from(down) << (SLOTS * at);
                any_overflow |= rec.len as usize > SLOTS;
            }
        }
        // Second pass: the kept entries, in cell and slot order.
        for (group, &(up, down)) in kept.iter().enumerate() {
            let flat = entries[(16 * group).min(27)..].as_flattened();
            for (mut bits, part) in [(up, &mut above), (down, &mut below)] {
                while bits != 0 {
                    part.push(flat[bits.trailing_zeros() as usize]);
                    bits &= bits - 1;
                }
            }
        }
        if any_overflow {
            // Full cells: their other bodies are in their overflow lists (rare), with their
            // centres.
            for &(c, image) in &cells[..count] {
                let shift = &lists.shifts[usize::from(image) & IMAGE_MASK as usize];
                for j in lists.slots.overflow(c) {
                    let ju = j as usize;
                    if lists.overlap(&xi, &lists.centre[ju], shift) && ju != i {
                        let e = entry(ju, image);
                        if ju > i {
                            above.push(e);
                        } else {
                            below.push(e);
                        }
                    }
                }
            }
        }
        let (na, nb) = (above.len(), below.len());
        let lists = self.lists_mut();
        lists.fresh = above;
        lists.fresh_below = below;
        lists.near = near;
        lists.slot_entries = slot_entries;
        (na, nb)
    }

    /// Moves body `i`'s shell centre to its position at `t`, files it in the cell of that
    /// point and rebuilds its list, keeping the lists symmetric: `i` joins the lists of its
    /// new neighbours and leaves those of the bodies it no longer overlaps. With `best`, body
    /// `i` is offered the pairs new to its list and the walls new to its cell (the others are
    /// covered since they became responsible, see the module docs).
    pub(super) fn relist(&mut self, world: &World<D>, i: usize, t: f64, best: Option<&mut Best>) {
        let x = world.motion(i).at(t);
        let was_at = self.lists().centre[i];
        self.lists_mut().centre[i] = x;
        let from = self.grid.cell_at(&self.cached[i].coords);
        let from_border = self.grid.is_border(&self.cached[i].coords);
        let k = self.grid.coords_of_point(&x);
        self.grid.relocate(i, &mut self.cached[i].coords, k);
        let to = self.grid.cell_at(&self.cached[i].coords);
        let lists = self.lists.as_mut().expect("list mode");
        if to == from {
            lists.slots.set_centre(i, to, &x);
        } else {
            lists.slots.remove(i, from, &lists.centre);
            lists.slots.insert(i, to, &x);
        }
        let (na, nb) = self.collect_overlapping(i);
        let lists = self.lists_mut();
        let (above, below) = (
            std::mem::take(&mut lists.fresh),
            std::mem::take(&mut lists.fresh_below),
        );
        // The old list (a copy: partners' lists change below) and the new one, part by part
        // (an entry's part is fixed by its body index): entries only in the old one leave
        // their partner's list, entries only in the new one join it and go to `added`. The
        // lists equal the overlap relation on the centres before this rebuild and after it,
        // and only `i`'s centre moved, so an old entry is not in the new list exactly when its
        // partner's shell fails `Lists::overlap` with the new centre, and a new entry was not
        // in the old list exactly when it fails it with the old centre `was_at`: one test per
        // entry instead of a sweep of the other list.
        let mut old = std::mem::take(&mut lists.old);
        let (old_above, old_below) = lists.parts(i);
        let split = old_above.len();
        old.clear();
        old.extend_from_slice(old_above);
        old.extend_from_slice(old_below);
        let mut added = std::mem::take(&mut lists.added);
        added.clear();
        let parts = [(&old[..split], &above[..na]), (&old[split..], &below[..nb])];
        for (was, now) in parts {
            for &e in was {
                let (j, image) = (entry_body(e), entry_image(e));
                if !lists.overlap(&x, &lists.centre[j], &lists.shifts[usize::from(image)]) {
                    lists.remove(j, entry(i, opposite::<D>(image)));
                }
            }
            for &e in now {
                let (j, image) = (entry_body(e), entry_image(e));
                if !lists.overlap(&was_at, &lists.centre[j], &lists.shifts[usize::from(image)]) {
                    lists.push(j, entry(i, opposite::<D>(image)));
                    added.push(e);
                }
            }
        }
        let (above_new, below_new) = (&above[..na], &below[..nb]);
        lists.set(i, above_new, below_new);
        if let Some(best) = best {
            let p = Probe::of(world, i);
            if self.periodic {
                self.scan_entries::<true>(world.bodies(), &p, &added, best);
            } else {
                self.scan_entries::<false>(world.bodies(), &p, &added, best);
            }
            let walls = self
                .grid
                .walls_of(self.grid.cell_at(&self.cached[i].coords));
            if !walls.is_empty() {
                self.offer_walls(world, &p, walls, self.grid.walls_of(from), best);
            }
            if !from_border {
                self.scan_exit(world, &p, best);
            }
        }
        let lists = self.lists_mut();
        lists.fresh = above;
        lists.fresh_below = below;
        lists.old = old;
        lists.added = added;
    }

    /// Processes body `i`'s shell exit, due at `time`: its list is rebuilt around its
    /// position then, it is offered what became responsible, and its next exit is scheduled.
    #[inline(never)]
    pub(super) fn exit_shell(&mut self, world: &World<D>, i: usize, time: f64) {
        self.stats.rebuilds += 1;
        let t = time.max(self.clock);
        self.clock = t;
        let mut best = self.records(i);
        self.relist(world, i, t, Some(&mut best));
        // Like a crossing: the cached event carries over with the partner count it had.
        self.store(world, i, &best, false);
        let m = world.motion(i);
        let lists = self.lists_mut();
        lists.exit[i] = shell_exit_time(&m, &lists.centre[i], lists.half, t);
        lists.log.push((i as u32, t));
        self.schedule_listed(i);
    }

    /// True when body `i`'s stored position lies outside its shell (after a state change; a
    /// box exit moves the position by a period, far outside).
    pub(super) fn outside_shell(&self, world: &World<D>, i: usize) -> bool {
        let lists = self.lists();
        (world.position(i) - lists.centre[i]).norm_sq() > lists.half * lists.half
    }

    /// Before an update whose earliest change is at `t`: rebuilds again at `t` the lists of
    /// the bodies (other than `changed`) rebuilt after `t`, so that every body lies in its
    /// shell from `t` on, and recomputes them.
    pub(super) fn redo_rebuilds_after(&mut self, world: &World<D>, t: f64, changed: &[usize]) {
        let mut log = std::mem::take(&mut self.lists_mut().log);
        log.retain(|&(i, time)| time > t && !changed.contains(&(i as usize)));
        log.sort_unstable_by_key(|&(i, _)| i);
        log.dedup_by_key(|&mut (i, _)| i);
        for &(i, _) in &log {
            self.stats.undone += 1;
            self.relist(world, i as usize, t, None);
        }
        for &(i, _) in &log {
            self.recompute(world, i as usize);
        }
        log.clear();
        self.lists_mut().log = log;
    }

    /// Checks the list mode's structures at the finder's clock: every body within its shell
    /// (up to rounding); every list entry mirrored in its partner's list and listed once; the
    /// lists holding exactly the pairs (images included) whose shells overlap (checked
    /// against every pair and every image, not the grid); every body filed in the cell of its
    /// shell centre, in the grid and in the slot records (see `CellSlots::validate`).
    pub(super) fn validate_lists(&self, world: &World<D>) -> Result<(), String> {
        let lists = self.lists();
        let n = world.len();
        lists
            .slots
            .validate(&lists.centre, |i| self.grid.cell_at(&self.cached[i].coords))?;
        let clock = self.clock;
        for i in 0..n {
            let m = world.motion(i);
            let p = m.at(clock.max(m.time));
            let tol = 1e-9 * (1.0 + p.norm() + m.vel.norm() * (clock - m.time).abs());
            let dist = (p - lists.centre[i]).norm();
            if dist > lists.half + tol {
                return Err(format!(
                    "body {i} is {dist} from its shell centre at t = {clock} (shell radius {})",
                    lists.half
                ));
            }
            let k = self
                .grid
                .coords_of_point(&lists.centre[i])
                .map(|x| x as u32);
            if k != self.cached[i].coords {
                return Err(format!(
                    "body {i} is not filed in the cell of its shell centre"
                ));
            }
            let (above, below) = lists.parts(i);
            if above.iter().any(|&e| entry_body(e) <= i) || below.iter().any(|&e| entry_body(e) > i)
            {
                return Err(format!(
                    "body {i}: list entries of higher body index do not come first"
                ));
            }
            let list = lists.list(i);
            for (a, &e) in list.iter().enumerate() {
                if list[..a].contains(&e) {
                    return Err(format!("body {i} lists {} twice", entry_body(e)));
                }
                let j = entry_body(e);
                if j == i || j >= n {
                    return Err(format!("body {i} lists body {j}"));
                }
                if !lists
                    .list(j)
                    .contains(&entry(i, opposite::<D>(entry_image(e))))
                {
                    return Err(format!("body {i} lists {j} but not the other way round"));
                }
            }
        }
        // Every overlapping pair and image is listed, and nothing else.
        let images = 3usize.pow(D as u32);
        let mut count = 0usize;
        for a in 0..n {
            for b in a + 1..n {
                for image in 0..images {
                    if !self.periodic && image != Grid::<D>::ZERO_IMAGE as usize {
                        continue;
                    }
                    let shift = self.shifts[image];
                    let listed = lists.list(a).contains(&entry(b, image as u8));
                    let overlaps = lists.overlap(&lists.centre[a], &lists.centre[b], &shift);
                    let mirrored = lists.overlap(
                        &lists.centre[b],
                        &lists.centre[a],
                        &self.shifts[usize::from(opposite::<D>(image as u8))],
                    );
                    if overlaps != mirrored {
                        return Err(format!("bodies {a} and {b}: overlap is not symmetric"));
                    }
                    if listed != overlaps {
                        return Err(format!(
                            "bodies {a} and {b} (image {image}): listed {listed}, shells overlap \
                             {overlaps}"
                        ));
                    }
                    count += usize::from(listed);
                }
            }
        }
        let total: usize = (0..n).map(|i| lists.list(i).len()).sum();
        if total != 2 * count {
            return Err(format!(
                "{total} list entries for {count} overlapping pairs"
            ));
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests;
