//! The uniform grid of the `cells` finder: cell geometry, the bodies filed in each cell, the
//! walls each cell can reach, and cell-crossing times.
//!
//! Each cell keeps its first [`CELL_SLOTS`] bodies in a fixed record of slots ([`CellBodies`])
//! and the others, if any, in an *overflow* list linked through the bodies, whose head is the
//! link of the body in the last slot. The slots are full before anything overflows: removing
//! a body from a slot fills the hole with the first overflowing body, or else with the last
//! used slot's body (swap-remove), so the used slots are the first `min(len, CELL_SLOTS)`.
//! Unused slots hold body 0 (a valid index: a scan copies a cell's slots whole and keeps only
//! the used ones, see `gather`). Only the body of the last slot of an overflowing cell and
//! the overflowing bodies have links; every other link is `NONE`. At packing 0.5 in 2D a cell
//! holds 0.64 bodies on average and at most four (the centres of discs that do not overlap,
//! in a square as wide as their diameter), so overflow is for dilute grids' wider cells.
//!
//! Cells are at least the largest contact distance (times `1 + MARGIN`) wide along every axis.
//! In an open (non-periodic) world the grid spans the bounding box of the bodies and walls at
//! `init`, and its outermost cells extend to infinity, so every point of space is in exactly one
//! cell and two cells that are not neighbours are separated by at least one whole cell. In a
//! periodic world the grid tiles the box `[0, L)` exactly; an axis with fewer than three cells
//! becomes a single cell whose three images (−L, 0, +L) are all neighbours.

use super::key::NONE;
use crate::geom::Vector;
use crate::motion::Motion;
use crate::prefetch::prefetch;
use crate::wall::Wall;

/// Bodies kept in a cell's record; the others overflow (see the module docs).
pub(super) const CELL_SLOTS: usize = 4;

/// The bodies of one cell: the first [`CELL_SLOTS`] in slots, and how many there are.
#[derive(Clone, Copy, Debug, PartialEq)]
#[repr(C)]
pub(super) struct CellBodies {
    /// Bodies in the slots: the first `min(len, CELL_SLOTS)` are used, the others hold 0.
    pub slots: [u32; CELL_SLOTS],
    /// Number of bodies filed in the cell, the overflowing ones included.
    pub len: u32,
}

impl CellBodies {
    const EMPTY: Self = CellBodies {
        slots: [0; CELL_SLOTS],
        len: 0,
    };

    /// Number of used slots.
    #[inline(always)]
    pub fn used(&self) -> usize {
        (self.len as usize).min(CELL_SLOTS)
    }
}

/// Relative margin by which cells are wider than the largest contact distance, and by which
/// wall reach exceeds the largest radius: it absorbs the rounding of crossing times and
/// positions (see the module docs of `cells`).
pub(super) const MARGIN: f64 = 1e-6;

/// Image code of the zero shift: digit 1 (no shift) on every axis, base 3.
const fn zero_image(d: usize) -> u8 {
    ((3usize.pow(d as u32) - 1) / 2) as u8
}

/// Along one axis: up to three (coordinate, shift) choices.
#[derive(Clone, Copy)]
struct AxisChoices {
    coord: [usize; 3],
    shift: [f64; 3],
    len: usize,
}

impl AxisChoices {
    fn push(&mut self, coord: usize, shift: f64) {
        self.coord[self.len] = coord;
        self.shift[self.len] = shift;
        self.len += 1;
    }
}

/// The union of the 3^D blocks around two interior cells `c₁` and `c₂` that are neighbours
/// (or the same cell), as linear offsets from `c₁`, in a fixed order: first the cells of both
/// blocks, then those of `c₁`'s block only, then those of `c₂`'s block only.
#[derive(Clone, Debug)]
pub(super) struct PairBlock {
    /// Linear offsets from `c₁`: `shared` cells of both blocks, then `only_first` cells of
    /// `c₁`'s block only, then the cells of `c₂`'s block only.
    pub offsets: Vec<isize>,
    /// Number of cells in both blocks.
    pub shared: usize,
    /// Number of cells in the first block only.
    pub only_first: usize,
}

impl PairBlock {
    /// The union for the second cell at per-axis offset `delta` (each in −1..=1) from the
    /// first, with the linear strides `stride`.
    fn new<const D: usize>(delta: [isize; D], stride: &[usize; D]) -> Self {
        let (mut shared, mut first, mut second) = (Vec::new(), Vec::new(), Vec::new());
        // Every cell within two of the first along each axis, axis 0 fastest.
        for code in 0..5usize.pow(D as u32) {
            let mut c = code;
            let mut e = [0isize; D];
            for x in &mut e {
                *x = (c % 5) as isize - 2;
                c /= 5;
            }
            let in_first = e.iter().all(|x| x.abs() <= 1);
            let in_second = e.iter().zip(&delta).all(|(x, d)| (x - d).abs() <= 1);
            let off: isize = e.iter().zip(stride).map(|(x, &s)| x * s as isize).sum();
            match (in_first, in_second) {
                (true, true) => shared.push(off),
                (true, false) => first.push(off),
                (false, true) => second.push(off),
                (false, false) => {}
            }
        }
        let (n_shared, n_first) = (shared.len(), first.len());
        shared.extend(first);
        shared.extend(second);
        PairBlock {
            offsets: shared,
            shared: n_shared,
            only_first: n_first,
        }
    }
}

/// Geometry and contents of the grid.
#[derive(Clone, Debug)]
pub(super) struct Grid<const D: usize> {
    /// Lower corner of cell (0, …, 0) (0 in a periodic world).
    origin: [f64; D],
    /// Cell widths.
    width: [f64; D],
    /// Cells per axis.
    dims: [usize; D],
    /// Linear index strides (axis 0 fastest).
    stride: [usize; D],
    /// Box sides of a periodic world.
    period: Option<[f64; D]>,
    /// Linear offsets of the 3^D neighbours of an interior cell.
    interior: Vec<isize>,
    /// Linear offsets, from an interior cell, of the layer entered by a move along axis `a`
    /// in direction `up`: entry `2a + up`.
    layers: Vec<Vec<isize>>,
    /// The union of the blocks of two interior cells, by the offset of the second cell from
    /// the first (entry: the image code of that offset, see [`Grid::interior_pair`]).
    pairs: Vec<PairBlock>,
    /// The bodies of each cell (see the module docs).
    cells: Vec<CellBodies>,
    /// Overflow links: for the body in the last slot of an overflowing cell, the first
    /// overflowing body; for an overflowing body, the next one; else `NONE`.
    next: Vec<u32>,
    /// Walls within reach of cell `c`: `wall_ids[wall_start[c]..wall_start[c + 1]]` (empty
    /// vectors when the world has no walls).
    wall_start: Vec<u32>,
    wall_ids: Vec<u32>,
}

/// The most cells per body a grid gets: in a dilute world the cells grow beyond the largest
/// contact distance until there are this many per body.
///
/// Wider cells trade crossings (each a layer scan and a queue update) for candidates in every
/// scan. Callgrind, instructions per event against 4 cells per body: in 2D, 2.5 saves 5.5 % on
/// the thesis scene (n = 2048, 9.7 % of the area covered) and 5.9 % on the Rapier-style scene
/// (1,000 balls, 7.9 %) and is neutral on a gas at packing 0.3, where 2 costs 1.9 %; in 3D a
/// scan covers 27 cells, and 2 costs 15 % on a gas at packing 0.05, so 3D keeps 4.
fn cells_per_body(dim: usize) -> f64 {
    if dim == 2 {
        2.5
    } else {
        4.0
    }
}

/// Face code of no face (never returned).
const NO_FACE: u8 = u8::MAX;

impl<const D: usize> Grid<D> {
    /// Image code of the zero shift.
    pub const ZERO_IMAGE: u8 = zero_image(D);

    /// A grid for `n` bodies whose cells are at least `min_width` wide, spanning `lo..hi` (open
    /// worlds) or the periodic box `period`, with at most about `CELLS_PER_BODY · n + 64`
    /// cells.
    pub fn new(
        n: usize,
        min_width: f64,
        lo: Vector<D>,
        hi: Vector<D>,
        period: Option<Vector<D>>,
    ) -> Self {
        let cap = cells_per_body(D) * n as f64 + 64.0;
        let mut w = min_width;
        let (origin, extent) = match period {
            Some(p) => ([0.0; D], p.0),
            None => (lo.0, (hi - lo).0),
        };
        let mut dims = [1usize; D];
        loop {
            let mut total = 1.0;
            for d in 0..D {
                let k = (extent[d] / w).floor();
                dims[d] = if k.is_finite() && k >= 1.0 {
                    k as usize
                } else {
                    1
                };
                // A periodic axis needs three distinct neighbour cells; with fewer it is one
                // cell whose three images are searched.
                if period.is_some() && dims[d] < 3 {
                    dims[d] = 1;
                }
                total *= dims[d] as f64;
            }
            if total <= cap {
                break;
            }
            w *= (total / cap).powf(1.0 / D as f64).max(1.0 + 1e-9);
        }
        let mut width = [0.0; D];
        let mut stride = [0usize; D];
        let mut s = 1usize;
        for d in 0..D {
            width[d] = if dims[d] > 1 {
                extent[d] / dims[d] as f64
            } else {
                extent[d].max(min_width)
            };
            stride[d] = s;
            s *= dims[d];
        }
        let mut interior = Vec::with_capacity(3usize.pow(D as u32));
        for code in 0..3usize.pow(D as u32) {
            let mut c = code;
            let mut off = 0isize;
            for st in stride {
                off += ((c % 3) as isize - 1) * st as isize;
                c /= 3;
            }
            interior.push(off);
        }
        let layers = (0..2 * D)
            .map(|code| {
                let (axis, up) = (code / 2, code % 2 == 1);
                let mut offs = Vec::new();
                for other in 0..3usize.pow(D as u32 - 1) {
                    let mut c = other;
                    let mut off = 0isize;
                    for (d, &st) in stride.iter().enumerate() {
                        let step = if d == axis {
                            if up {
                                1
                            } else {
                                -1
                            }
                        } else {
                            let s = (c % 3) as isize - 1;
                            c /= 3;
                            s
                        };
                        off += step * st as isize;
                    }
                    offs.push(off);
                }
                offs
            })
            .collect();
        let pairs = (0..3usize.pow(D as u32))
            .map(|code| {
                let mut c = code;
                let delta = std::array::from_fn(|_| {
                    let x = (c % 3) as isize - 1;
                    c /= 3;
                    x
                });
                PairBlock::new::<D>(delta, &stride)
            })
            .collect();
        Grid {
            layers,
            pairs,
            origin,
            width,
            dims,
            stride,
            period: period.map(|p| p.0),
            interior,
            cells: vec![CellBodies::EMPTY; s],
            next: vec![NONE; n],
            wall_start: Vec::new(),
            wall_ids: Vec::new(),
        }
    }

    /// Number of cells.
    pub fn cell_count(&self) -> usize {
        self.cells.len()
    }

    /// Cells per axis.
    pub fn dims(&self) -> [usize; D] {
        self.dims
    }

    /// Bytes held (payload).
    pub fn bytes(&self) -> usize {
        std::mem::size_of::<CellBodies>() * self.cells.capacity()
            + 4 * (self.next.capacity() + self.wall_start.capacity() + self.wall_ids.capacity())
            + std::mem::size_of::<isize>() * (self.interior.capacity() + 3usize.pow(D as u32))
            + self
                .pairs
                .iter()
                .map(|p| std::mem::size_of::<isize>() * p.offsets.capacity())
                .sum::<usize>()
    }

    /// Cell coordinates of the point `p` (outer cells of open worlds extend to infinity;
    /// periodic coordinates are clamped into the box, since stored positions are in it up to
    /// rounding).
    pub fn coords_of_point(&self, p: &Vector<D>) -> [usize; D] {
        let mut k = [0usize; D];
        for d in 0..D {
            // Truncation is the floor for the non-negative quotients it is used on.
            let x = (p[d] - self.origin[d]) / self.width[d];
            k[d] = if x >= (self.dims[d] - 1) as f64 {
                self.dims[d] - 1
            } else if x >= 0.0 {
                x as usize
            } else {
                0
            };
        }
        k
    }

    /// Linear index of cell coordinates.
    #[inline]
    pub fn linear(&self, k: &[usize; D]) -> u32 {
        k.iter()
            .zip(&self.stride)
            .map(|(k, s)| k * s)
            .sum::<usize>() as u32
    }

    /// Cell coordinates of a linear index.
    #[inline]
    pub fn coords(&self, c: u32) -> [usize; D] {
        let c = c as usize;
        std::array::from_fn(|d| (c / self.stride[d]) % self.dims[d])
    }

    /// Linear index of the cell of coordinates `k`.
    #[inline]
    pub fn cell_at(&self, k: &[u32; D]) -> u32 {
        self.linear_u32(k)
    }

    /// True when the cell of coordinates `k` is first or last along some axis: in a periodic
    /// world only a body filed in such a cell can reach a face of the box before it leaves its
    /// cell (every other cell is at least one whole cell away from every face).
    #[inline]
    pub fn is_border(&self, k: &[u32; D]) -> bool {
        (0..D).any(|d| k[d] == 0 || k[d] as usize + 1 == self.dims[d])
    }

    #[inline]
    fn linear_u32(&self, k: &[u32; D]) -> u32 {
        k.iter()
            .zip(&self.stride)
            .map(|(&k, s)| k as usize * s)
            .sum::<usize>() as u32
    }

    /// Files body `i` (not filed anywhere) in the cell of coordinates `k`, and returns the
    /// coordinates the caller must keep for it (the grid does not store them: the finder
    /// keeps them beside its prediction, which whoever reads them also reads).
    pub fn insert(&mut self, i: usize, k: [usize; D]) -> [u32; D] {
        let k = k.map(|x| x as u32);
        let c = self.linear_u32(&k) as usize;
        self.file(i, c);
        k
    }

    /// Takes body `i` out of its cell, of coordinates `k`.
    pub fn remove(&mut self, i: usize, k: &[u32; D]) {
        let c = self.linear_u32(k) as usize;
        self.unfile(i, c);
    }

    /// Files body `i` (not filed anywhere) in cell `c`: in the first free slot, else at the
    /// head of the overflow list.
    #[inline]
    fn file(&mut self, i: usize, c: usize) {
        let cell = &mut self.cells[c];
        let len = cell.len as usize;
        if len < CELL_SLOTS {
            cell.slots[len] = i as u32;
        } else {
            let last = cell.slots[CELL_SLOTS - 1] as usize;
            self.next[i] = self.next[last];
            self.next[last] = i as u32;
        }
        cell.len += 1;
    }

    /// Takes body `i` out of cell `c`, where it is filed, keeping the slots full before the
    /// overflow (see the module docs).
    #[inline]
    fn unfile(&mut self, i: usize, c: usize) {
        let cell = &mut self.cells[c];
        let len = cell.len as usize;
        cell.len -= 1;
        let used = len.min(CELL_SLOTS);
        // Cells hold a handful of bodies: a search is cheaper than a slot index per body.
        match cell.slots[..used].iter().position(|&b| b == i as u32) {
            Some(k) if len > CELL_SLOTS => {
                // The first overflowing body takes the hole; the rest of the overflow hangs
                // from whichever body is in the last slot afterwards.
                let o = self.next[cell.slots[CELL_SLOTS - 1] as usize];
                let rest = self.next[o as usize];
                cell.slots[k] = o;
                self.next[i] = NONE;
                self.next[o as usize] = NONE;
                self.next[cell.slots[CELL_SLOTS - 1] as usize] = rest;
            }
            Some(k) => {
                cell.slots[k] = cell.slots[used - 1];
                cell.slots[used - 1] = 0;
            }
            None => {
                // An overflowing body: unlink it (the list starts at the last slot's link).
                let mut at = cell.slots[CELL_SLOTS - 1] as usize;
                while self.next[at] != i as u32 {
                    at = self.next[at] as usize;
                    debug_assert!(at != NONE as usize, "body {i} not in its cell {c}");
                }
                self.next[at] = self.next[i];
                self.next[i] = NONE;
            }
        }
    }

    /// True when the point `p` lies in the closed box of the cell of coordinates `k` (see
    /// [`Grid::cell_box`]): a few comparisons, where finding the cell of a point takes a
    /// division and a conversion per axis.
    #[inline]
    pub fn holds(&self, k: &[u32; D], p: &Vector<D>) -> bool {
        let open = self.period.is_none();
        for d in 0..D {
            let kd = k[d] as usize;
            let lo = if open && kd == 0 {
                f64::NEG_INFINITY
            } else {
                self.origin[d] + kd as f64 * self.width[d]
            };
            let hi = if open && kd + 1 == self.dims[d] {
                f64::INFINITY
            } else {
                self.origin[d] + (kd + 1) as f64 * self.width[d]
            };
            if !(p[d] >= lo && p[d] <= hi) {
                return false;
            }
        }
        true
    }

    /// Moves body `i`, filed at coordinates `coords`, to the cell of coordinates `k`, and
    /// updates `coords`.
    pub fn relocate(&mut self, i: usize, coords: &mut [u32; D], k: [usize; D]) {
        if *coords != k.map(|x| x as u32) {
            self.remove(i, coords);
            *coords = self.insert(i, k);
        }
    }

    /// Moves body `i`, filed at coordinates `coords`, one cell along `axis` (`up` or down),
    /// and updates `coords`; that cell must exist without wrapping around a periodic box.
    #[inline(always)]
    pub fn step(&mut self, i: usize, coords: &mut [u32; D], axis: usize, up: bool) {
        let c = self.linear_u32(coords) as usize;
        self.unfile(i, c);
        let kd = &mut coords[axis];
        let c = if up {
            *kd += 1;
            c + self.stride[axis]
        } else {
            *kd -= 1;
            c - self.stride[axis]
        };
        self.file(i, c);
    }

    /// The record of cell `c`.
    #[inline(always)]
    pub fn cell(&self, c: u32) -> &CellBodies {
        &self.cells[c as usize]
    }

    /// The bodies of cell `c`: its used slots, then its overflow list.
    #[inline]
    pub fn bodies_in(&self, c: u32) -> impl Iterator<Item = u32> + '_ {
        let cell = &self.cells[c as usize];
        let mut at = if cell.len as usize > CELL_SLOTS {
            self.next[cell.slots[CELL_SLOTS - 1] as usize]
        } else {
            NONE
        };
        let over = std::iter::from_fn(move || {
            (at != NONE).then(|| {
                let j = at;
                at = self.next[j as usize];
                j
            })
        });
        cell.slots[..cell.used()].iter().copied().chain(over)
    }

    /// Hints that the heads of the 3^D block around the cell of coordinates `k` will be
    /// read soon (interior cells only: the others are rare).
    #[inline(always)]
    pub fn prefetch_block(&self, k: &[u32; D]) {
        if self.is_interior(k) {
            let c = self.linear_u32(k) as isize;
            for &off in &self.interior {
                prefetch(&self.cells[(c + off) as usize]);
            }
        }
    }

    /// Walls within reach of cell `c`.
    #[inline]
    pub fn walls_of(&self, c: u32) -> &[u32] {
        if self.wall_start.is_empty() {
            return &[];
        }
        let c = c as usize;
        &self.wall_ids[self.wall_start[c] as usize..self.wall_start[c + 1] as usize]
    }

    /// The choices along axis `d` around coordinate `k`: the cell before, the cell itself and
    /// the cell after, as they exist, with their periodic shifts.
    fn axis_choices(&self, d: usize, k: usize) -> AxisChoices {
        let mut a = AxisChoices {
            coord: [0; 3],
            shift: [0.0; 3],
            len: 0,
        };
        let n = self.dims[d];
        match self.period {
            Some(p) if n == 1 => {
                a.push(0, -p[d]);
                a.push(0, 0.0);
                a.push(0, p[d]);
            }
            Some(p) => {
                if k == 0 {
                    a.push(n - 1, -p[d]);
                } else {
                    a.push(k - 1, 0.0);
                }
                a.push(k, 0.0);
                if k + 1 == n {
                    a.push(0, p[d]);
                } else {
                    a.push(k + 1, 0.0);
                }
            }
            None => {
                if k > 0 {
                    a.push(k - 1, 0.0);
                }
                a.push(k, 0.0);
                if k + 1 < n {
                    a.push(k + 1, 0.0);
                }
            }
        }
        a
    }

    /// The one layer entered along axis `axis` in direction `up` from coordinate `k` (the cell
    /// beyond `k`), if it exists.
    fn layer_choice(&self, axis: usize, k: usize, up: bool) -> AxisChoices {
        let mut a = AxisChoices {
            coord: [0; 3],
            shift: [0.0; 3],
            len: 0,
        };
        let n = self.dims[axis];
        let p = self.period.map_or(0.0, |p| p[axis]);
        if up {
            if k + 1 < n {
                a.push(k + 1, 0.0);
            } else if self.period.is_some() {
                a.push(0, p);
            }
        } else if k > 0 {
            a.push(k - 1, 0.0);
        } else if self.period.is_some() {
            a.push(n - 1, -p);
        }
        a
    }

    /// Calls `f(cell, shift, image)` for every combination of the axes' choices; `image` is
    /// the shift's code, one base-3 digit per axis (0: −L, 1: none, 2: +L).
    #[inline]
    fn visit_product(&self, axes: &[AxisChoices; D], f: &mut impl FnMut(u32, &Vector<D>, u8)) {
        if axes.iter().any(|a| a.len == 0) {
            return;
        }
        let mut idx = [0usize; D];
        loop {
            let mut c = 0;
            let mut image = 0u8;
            let mut shift = Vector::<D>::ZERO;
            let mut pow = 1u8;
            for d in 0..D {
                c += axes[d].coord[idx[d]] * self.stride[d];
                let s = axes[d].shift[idx[d]];
                shift[d] = s;
                let digit = if s < 0.0 {
                    0
                } else if s > 0.0 {
                    2
                } else {
                    1
                };
                image += digit * pow;
                pow *= 3;
            }
            f(c as u32, &shift, image);
            let mut d = 0;
            loop {
                idx[d] += 1;
                if idx[d] < axes[d].len {
                    break;
                }
                idx[d] = 0;
                d += 1;
                if d == D {
                    return;
                }
            }
        }
    }

    /// True for a cell with a neighbour on both sides along every axis, without wrapping.
    #[inline]
    fn is_interior(&self, k: &[u32; D]) -> bool {
        (0..D).all(|d| k[d] >= 1 && k[d] as usize + 2 <= self.dims[d])
    }

    /// The neighbour cells of a body filed at coordinates `k` when they are the plain 3^D
    /// block around it (no border, no wrapping, zero image shift), else `None`.
    #[inline(always)]
    pub fn interior_neighbours(
        &self,
        k: &[u32; D],
    ) -> Option<impl Iterator<Item = u32> + Clone + '_> {
        if !self.is_interior(k) {
            return None;
        }
        let c = self.linear_u32(k) as isize;
        Some(self.interior.iter().map(move |&off| (c + off) as u32))
    }

    /// When the cells of coordinates `k1` and `k2` are both interior and neighbours (or the
    /// same cell): the linear index of `k1`'s cell and the union of their blocks (plain 3^D
    /// blocks, zero image shift), else `None`.
    #[inline(always)]
    pub fn interior_pair(&self, k1: &[u32; D], k2: &[u32; D]) -> Option<(u32, &PairBlock)> {
        if !self.is_interior(k1) || !self.is_interior(k2) {
            return None;
        }
        let mut code = 0usize;
        let mut pow = 1usize;
        for d in 0..D {
            let delta = k2[d] as isize - k1[d] as isize;
            if !(-1..=1).contains(&delta) {
                return None;
            }
            code += (delta + 1) as usize * pow;
            pow *= 3;
        }
        Some((self.linear_u32(k1), &self.pairs[code]))
    }

    /// The cells entered by a move into the cell of coordinates `k` along `axis` in direction
    /// `up` when that cell is interior (zero image shift), else `None`.
    #[inline(always)]
    pub fn interior_entered_layer(
        &self,
        k: &[u32; D],
        axis: usize,
        up: bool,
    ) -> Option<impl Iterator<Item = u32> + Clone + '_> {
        if !self.is_interior(k) {
            return None;
        }
        let c = self.linear_u32(k) as isize;
        Some(
            self.layers[2 * axis + usize::from(up)]
                .iter()
                .map(move |&off| (c + off) as u32),
        )
    }

    /// Calls `f(cell, shift, image)` for every cell whose bodies can touch a body filed at
    /// coordinates `k` before it leaves its cell: the 3^D block around it (fewer at the border
    /// of an open world), with the image shift to add to their displacement and its code.
    #[inline]
    pub fn visit_neighbours(&self, k: &[u32; D], mut f: impl FnMut(u32, &Vector<D>, u8)) {
        if self.is_interior(k) {
            let c = self.linear_u32(k) as isize;
            let zero = Vector::ZERO;
            for &off in &self.interior {
                f((c + off) as u32, &zero, Self::ZERO_IMAGE);
            }
            return;
        }
        let axes: [AxisChoices; D] = std::array::from_fn(|d| self.axis_choices(d, k[d] as usize));
        self.visit_product(&axes, &mut f);
    }

    /// Calls `f(cell, shift, image)` for the cells that became neighbours of a body that
    /// moved into the cell of coordinates `k` along `axis` in direction `up`: the layer of
    /// the block beyond it.
    #[inline]
    pub fn visit_entered_layer(
        &self,
        k: &[u32; D],
        axis: usize,
        up: bool,
        mut f: impl FnMut(u32, &Vector<D>, u8),
    ) {
        if self.is_interior(k) {
            let c = self.linear_u32(k) as isize;
            let zero = Vector::ZERO;
            for &off in &self.layers[2 * axis + usize::from(up)] {
                f((c + off) as u32, &zero, Self::ZERO_IMAGE);
            }
            return;
        }
        let axes: [AxisChoices; D] = std::array::from_fn(|d| {
            if d == axis {
                self.layer_choice(d, k[d] as usize, up)
            } else {
                self.axis_choices(d, k[d] as usize)
            }
        });
        self.visit_product(&axes, &mut f);
    }

    /// The shift of image code `image` (see [`Grid::visit_neighbours`]).
    pub fn shift_of(&self, image: u8) -> Vector<D> {
        let mut shift = Vector::ZERO;
        let mut code = image;
        if let Some(p) = self.period {
            for d in 0..D {
                shift[d] = match code % 3 {
                    0 => -p[d],
                    2 => p[d],
                    _ => 0.0,
                };
                code /= 3;
            }
        }
        shift
    }

    /// The next time a body with motion `m` filed at coordinates `k` leaves its cell through a face
    /// between two cells, with the face's code `2·axis + up`: faces of the outer cells of an
    /// open world towards infinity, and the faces of a periodic box (box exits are real
    /// events) are not crossings. Ties go to the lower axis.
    #[inline(always)]
    pub fn next_crossing(&self, k: &[u32; D], m: &Motion<D>) -> Option<(f64, u8)> {
        // Every axis is evaluated and the choices are selects: whether a body moves up or
        // down an axis, and which axis it leaves by first, are coin flips a branch
        // predictor cannot learn. The time is the same expression either way.
        let (mut best_t, mut best_code, mut found) = (f64::INFINITY, NO_FACE, false);
        for (d, &kd) in k.iter().enumerate() {
            let kd = kd as usize;
            let v = m.vel[d];
            let up = v > 0.0;
            let valid = (up & (kd + 1 < self.dims[d])) | ((v < 0.0) & (kd > 0));
            let bound = self.origin[d] + (kd + usize::from(up)) as f64 * self.width[d];
            let t = m.time + (bound - m.pos[d]) / v;
            let take = valid & (!found | (t < best_t));
            // A mask, not `if`: the code generator turns an `if` on floats into a branch.
            let mask = u64::from(take).wrapping_neg();
            best_t = f64::from_bits((t.to_bits() & mask) | (best_t.to_bits() & !mask));
            best_code = if take {
                (2 * d) as u8 | u8::from(up)
            } else {
                best_code
            };
            found |= valid;
        }
        found.then_some((best_t, best_code))
    }

    /// [`Grid::next_crossing`] for a body falling under the acceleration `g` (see
    /// [`crate::contact::gravity`]): along each axis with a component of `g` the body crosses the
    /// lower face where its coordinate falls through it and the upper face where it rises
    /// through it, at the root of the face's quadratic, taken only when it lies at or after
    /// `after` (the time from which the body is known to lie in its cell: it may have left
    /// through that face and come back before). A face the parabola only grazes from inside
    /// the cell (equal or disordered roots after rounding) is not crossed. A parabola that
    /// opens away from the cell (a lower face the body falls towards) is left whatever the
    /// roots say: at its later root, or at `after` when that root lies before it or there is
    /// none (a body filed on the face at rest: `x = bound`, `v = 0` makes a double root, which
    /// once counted as a graze and let the body fall through the grid unseen). Both cells
    /// sharing a face compute the same two roots from the same bound, and the cell below sees
    /// that parabola open towards it, so a body never bounces between them at one time.
    /// Axes without gravity cross as in [`Grid::next_crossing`]. Ties go to the lower axis.
    #[inline(never)]
    pub fn next_crossing_falling(
        &self,
        k: &[u32; D],
        m: &Motion<D>,
        g: &Vector<D>,
        after: f64,
    ) -> Option<(f64, u8)> {
        let mut best: Option<(f64, u8)> = None;
        for (d, &kd) in k.iter().enumerate() {
            let kd = kd as usize;
            let (x, v, a) = (m.pos[d], m.vel[d], 0.5 * g[d]);
            let lower = (kd > 0).then(|| self.origin[d] + kd as f64 * self.width[d]);
            let upper =
                (kd + 1 < self.dims[d]).then(|| self.origin[d] + (kd + 1) as f64 * self.width[d]);
            let mut offer = |t: f64, up: bool| {
                if best.is_none_or(|(bt, _)| t < bt) {
                    best = Some((t, (2 * d) as u8 | u8::from(up)));
                }
            };
            if a == 0.0 {
                if let (true, Some(bound)) = (v > 0.0, upper) {
                    offer(m.time + (bound - x) / v, true);
                } else if let (true, Some(bound)) = (v < 0.0, lower) {
                    offer(m.time + (bound - x) / v, false);
                }
                continue;
            }
            for (bound, up) in [(lower, false), (upper, true)] {
                let Some(bound) = bound else { continue };
                // Seen from inside the cell, the body's height over this face is a parabola
                // that either opens away from the cell (the lower face with `a < 0`, the upper
                // with `a > 0`): the body is inside only between the two roots and leaves for
                // good at the later one; or opens towards it: the body leaves at the earlier
                // root and comes back at the later one.
                let leaves_for_good = if up { a > 0.0 } else { a < 0.0 };
                match crate::contact::quadratic::face_roots(x - bound, v, a) {
                    Some((falls, rises)) => {
                        let t = m.time + if up { rises } else { falls };
                        if !t.is_finite() {
                            continue;
                        }
                        if !leaves_for_good && t == m.time + if up { falls } else { rises } {
                            // Out and back within one instant (roots closer than the time's
                            // rounding, as for a body on the face moving off it at a speed
                            // rounding left behind): no crossing, or it would be crossed out
                            // of the other cell at that same instant, back and forth for ever.
                            continue;
                        }
                        if t >= after {
                            offer(t, up);
                        } else if leaves_for_good {
                            // Filed here, yet past its way out by rounding: it leaves now.
                            offer(after, up);
                        }
                    }
                    // No crossing root on a parabola that opens away from the cell: the body
                    // is outside but for one instant, the one it is filed here at (a body at
                    // rest on the face, `x = bound`, `v = 0`). It leaves now; had it waited for
                    // a root, it would have fallen through the floor unseen.
                    None if leaves_for_good => offer(after, up),
                    None => {}
                }
            }
        }
        best
    }

    /// The closed box of cell coordinates `k` (outer cells of open worlds are unbounded).
    pub fn cell_box(&self, k: &[usize; D]) -> (Vector<D>, Vector<D>) {
        let mut lo = Vector::<D>::ZERO;
        let mut hi = Vector::<D>::ZERO;
        for d in 0..D {
            let open = self.period.is_none();
            lo[d] = if open && k[d] == 0 {
                f64::NEG_INFINITY
            } else {
                self.origin[d] + k[d] as f64 * self.width[d]
            };
            hi[d] = if open && k[d] + 1 == self.dims[d] {
                f64::INFINITY
            } else {
                self.origin[d] + (k[d] + 1) as f64 * self.width[d]
            };
        }
        (lo, hi)
    }

    /// The box of cell coordinates `k` as laid out, without extending outer cells (for
    /// drawing).
    pub fn nominal_box(&self, k: &[usize; D]) -> (Vector<D>, Vector<D>) {
        let mut lo = Vector::<D>::ZERO;
        let mut hi = Vector::<D>::ZERO;
        for d in 0..D {
            lo[d] = self.origin[d] + k[d] as f64 * self.width[d];
            hi[d] = lo[d] + self.width[d];
        }
        (lo, hi)
    }

    /// Lists, for every cell, the walls that come within `reach` of it.
    pub fn file_walls(&mut self, walls: &[Wall<D>], reach: f64) {
        self.wall_start.clear();
        self.wall_ids.clear();
        if walls.is_empty() {
            return;
        }
        let mut pairs: Vec<(u32, u32)> = Vec::new();
        let all = [0usize; D];
        let last: [usize; D] = std::array::from_fn(|d| self.dims[d] - 1);
        for (w, wall) in walls.iter().enumerate() {
            let (from, to) = match *wall {
                Wall::Segment { a, b } => {
                    let e = Vector::splat(reach);
                    (
                        self.coords_of_point(&(a.min(b) - e)),
                        self.coords_of_point(&(a.max(b) + e)),
                    )
                }
                Wall::Plane { .. } => (all, last),
            };
            let mut k = from;
            loop {
                let (lo, hi) = self.cell_box(&k);
                let near = match *wall {
                    Wall::Segment { a, b } => {
                        segment_box_distance_sq(a, b, lo, hi) <= reach * reach
                    }
                    Wall::Plane { point, normal } => {
                        plane_box_min_distance(point, normal, lo, hi) <= reach
                    }
                };
                if near {
                    pairs.push((self.linear(&k), w as u32));
                }
                let mut d = 0;
                loop {
                    if k[d] < to[d] {
                        k[d] += 1;
                        break;
                    }
                    k[d] = from[d];
                    d += 1;
                    if d == D {
                        break;
                    }
                }
                if d == D {
                    break;
                }
            }
        }
        pairs.sort_unstable();
        self.wall_start = vec![0; self.cell_count() + 1];
        for &(c, _) in &pairs {
            self.wall_start[c as usize + 1] += 1;
        }
        for c in 0..self.cell_count() {
            self.wall_start[c + 1] += self.wall_start[c];
        }
        self.wall_ids = pairs.into_iter().map(|(_, w)| w).collect();
    }

    /// Checks the cells: every body filed once, in the cell of the coordinates `coords(i)`
    /// recorded for it; slots full before any overflow, unused slots 0, and links only where
    /// the module docs put them.
    pub fn validate(&self, coords: impl Fn(usize) -> [u32; D]) -> Result<(), String> {
        let mut seen = vec![false; self.next.len()];
        let mut linked = 0;
        for (c, cell) in self.cells.iter().enumerate() {
            if cell.slots[cell.used()..].iter().any(|&b| b != 0) {
                return Err(format!("cell {c}: an unused slot is not 0"));
            }
            let mut count = 0;
            for i in self.bodies_in(c as u32) {
                let i = i as usize;
                if i >= seen.len() || seen[i] {
                    return Err(format!("body {i} filed twice or unknown"));
                }
                seen[i] = true;
                count += 1;
                if self.linear_u32(&coords(i)) != c as u32 {
                    return Err(format!(
                        "body {i} in cell {c} but recorded in {:?}",
                        coords(i)
                    ));
                }
            }
            if count != cell.len as usize {
                return Err(format!("cell {c}: length {} but {count} bodies", cell.len));
            }
            linked += cell.len.saturating_sub(CELL_SLOTS as u32) as usize;
        }
        if self.next.iter().filter(|&&l| l != NONE).count() != linked {
            return Err("a link outside the overflow lists".into());
        }
        match seen.iter().position(|s| !s) {
            Some(i) => Err(format!("body {i} is in no cell")),
            None => Ok(()),
        }
    }
}

/// Squared distance between the segment `[a, b]` and the closed box `[lo, hi]` (whose bounds
/// may be infinite). The squared distance is a convex piecewise quadratic function of the
/// segment parameter, with breaks where a coordinate crosses a box bound; each piece is
/// minimised exactly.
pub(super) fn segment_box_distance_sq<const D: usize>(
    a: Vector<D>,
    b: Vector<D>,
    lo: Vector<D>,
    hi: Vector<D>,
) -> f64 {
    let u = b - a;
    let mut breaks = [0.0f64; 8];
    let mut nb = 0;
    breaks[nb] = 0.0;
    nb += 1;
    breaks[nb] = 1.0;
    nb += 1;
    for d in 0..D {
        if u[d] != 0.0 {
            for bound in [lo[d], hi[d]] {
                if bound.is_finite() {
                    let s = (bound - a[d]) / u[d];
                    if s > 0.0 && s < 1.0 && nb < breaks.len() {
                        breaks[nb] = s;
                        nb += 1;
                    }
                }
            }
        }
    }
    let breaks = &mut breaks[..nb];
    breaks.sort_unstable_by(f64::total_cmp);
    let dist_sq = |s: f64| {
        let mut acc = 0.0;
        for d in 0..D {
            let x = a[d] + u[d] * s;
            let e = if x < lo[d] {
                lo[d] - x
            } else if x > hi[d] {
                x - hi[d]
            } else {
                0.0
            };
            acc += e * e;
        }
        acc
    };
    let mut best = f64::INFINITY;
    for w in breaks.windows(2) {
        let (s0, s1) = (w[0], w[1]);
        best = best.min(dist_sq(s0)).min(dist_sq(s1));
        // Inside the piece each axis is below, inside or above the box throughout: the
        // distance is a quadratic q(s) = Σ (a_d + u_d s − bound_d)², minimal at its vertex.
        let mid = 0.5 * (s0 + s1);
        let (mut num, mut den) = (0.0, 0.0);
        for d in 0..D {
            let x = a[d] + u[d] * mid;
            let bound = if x < lo[d] {
                lo[d]
            } else if x > hi[d] {
                hi[d]
            } else {
                continue;
            };
            num += (bound - a[d]) * u[d];
            den += u[d] * u[d];
        }
        if den > 0.0 {
            let s = num / den;
            if s > s0 && s < s1 {
                best = best.min(dist_sq(s));
            }
        }
    }
    best
}

/// Smallest signed distance from the plane through `point` with normal `normal` to a point of
/// the closed box `[lo, hi]` (negative behind the plane; −∞ for unbounded boxes reaching
/// behind it).
pub(super) fn plane_box_min_distance<const D: usize>(
    point: Vector<D>,
    normal: Vector<D>,
    lo: Vector<D>,
    hi: Vector<D>,
) -> f64 {
    let mut s = 0.0;
    for d in 0..D {
        let n = normal[d];
        if n > 0.0 {
            s += (lo[d] - point[d]) * n;
        } else if n < 0.0 {
            s += (hi[d] - point[d]) * n;
        }
    }
    s / normal.norm()
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// Cells of a grid over `n` bodies in the open box `[0, side]^D`, at least `min` wide.
    fn cells_of<const D: usize>(n: usize, min: f64, side: f64) -> (usize, [usize; D]) {
        let g = Grid::<D>::new(n, min, Vector::ZERO, Vector([side; D]), None);
        for d in 0..D {
            assert!(
                g.width[d] >= min,
                "cells narrower than asked: {:?}",
                g.width
            );
        }
        (g.cell_count(), g.dims())
    }

    /// `Grid::next_crossing` as first written, with a branch per axis: the model the
    /// branch-free version must match bit for bit.
    fn next_crossing_model<const D: usize>(
        g: &Grid<D>,
        k: &[u32; D],
        m: &Motion<D>,
    ) -> Option<(f64, u8)> {
        let mut best: Option<(f64, u8)> = None;
        for (d, &kd) in k.iter().enumerate() {
            let kd = kd as usize;
            let v = m.vel[d];
            let bound = if v > 0.0 && kd + 1 < g.dims[d] {
                g.origin[d] + (kd + 1) as f64 * g.width[d]
            } else if v < 0.0 && kd > 0 {
                g.origin[d] + kd as f64 * g.width[d]
            } else {
                continue;
            };
            let t = m.time + (bound - m.pos[d]) / v;
            if best.is_none_or(|(bt, _)| t < bt) {
                best = Some((t, (2 * d + usize::from(v > 0.0)) as u8));
            }
        }
        best
    }

    /// A velocity component: often exactly zero (either sign) or tiny, so that axes are
    /// skipped, tie or overflow.
    fn velocity_component() -> impl Strategy<Value = f64> {
        prop_oneof![
            Just(0.0),
            Just(-0.0),
            Just(1e-300),
            Just(-1e-300),
            Just(1.0),
            -10.0..10.0f64,
        ]
    }

    fn check_next_crossing<const D: usize>(
        periodic: bool,
        fractions: &[f64],
        vel: &[f64],
        time: f64,
    ) -> Result<(), TestCaseError> {
        let side = 10.0;
        let period = periodic.then_some(Vector([side; D]));
        let g = Grid::<D>::new(40, 1.3, Vector::ZERO, Vector([side; D]), period);
        let mut pos = Vector::<D>::ZERO;
        let mut v = Vector::<D>::ZERO;
        for d in 0..D {
            pos[d] = fractions[d] * side;
            v[d] = vel[d];
        }
        let m = Motion { pos, vel: v, time };
        let k = g.coords_of_point(&pos).map(|c| c as u32);
        let got = g.next_crossing(&k, &m);
        let want = next_crossing_model(&g, &k, &m);
        prop_assert_eq!(
            got.map(|(t, c)| (t.to_bits(), c)),
            want.map(|(t, c)| (t.to_bits(), c)),
            "cell {:?} of dims {:?}, motion {:?}",
            k,
            g.dims,
            m
        );
        Ok(())
    }

    proptest! {
        #[test]
        fn next_crossing_matches_the_branching_model(
            periodic in any::<bool>(),
            fractions in prop::collection::vec(prop_oneof![Just(0.0), Just(0.999), 0.0..1.0f64], 3),
            vel in prop::collection::vec(velocity_component(), 3),
            time in prop_oneof![Just(0.0), 0.0..100.0f64],
        ) {
            check_next_crossing::<2>(periodic, &fractions, &vel, time)?;
            check_next_crossing::<3>(periodic, &fractions, &vel, time)?;
        }
    }

    /// A body filed in its cell at `m.time` under gravity `g` never lies outside that cell
    /// (beyond rounding) before the crossing `next_crossing_falling` names, and is on the
    /// named face then. Positions are drawn on the grid's faces and on round numbers, with
    /// zero and axis-aligned velocities, where a body on a face at rest once never crossed.
    fn check_falling_crossing<const D: usize>(
        ticks: &[u8],
        vel: &[f64],
        g: &[f64],
    ) -> Result<(), TestCaseError> {
        let side = 12.0;
        let grid = Grid::<D>::new(40, 1.0, Vector::ZERO, Vector([side; D]), None);
        let mut pos = Vector::<D>::ZERO;
        let mut v = Vector::<D>::ZERO;
        let mut acc = Vector::<D>::ZERO;
        for d in 0..D {
            // Quarter-cell ticks: every fourth one lies exactly on a face.
            pos[d] = f64::from(ticks[d]) * grid.width[d] / 4.0;
            v[d] = vel[d];
            acc[d] = g[d];
        }
        let m = Motion {
            pos,
            vel: v,
            time: 1.0,
        };
        let k = grid.coords_of_point(&pos);
        let k32 = k.map(|c| c as u32);
        let (lo, hi) = grid.cell_box(&k);
        let crossing = grid.next_crossing_falling(&k32, &m, &acc, m.time);
        let at = |t: f64| {
            let dt = t - m.time;
            Vector::<D>(std::array::from_fn(|d| {
                m.pos[d] + m.vel[d] * dt + 0.5 * acc[d] * dt * dt
            }))
        };
        let end = crossing.map_or(m.time + 20.0, |(t, _)| t);
        prop_assert!(end >= m.time, "crossing at {end} before the body's time");
        let tol = 1e-9;
        for step in 0..=1000 {
            let t = m.time + (end - m.time) * f64::from(step) / 1000.0;
            let p = at(t);
            for d in 0..D {
                prop_assert!(
                    p[d] >= lo[d] - tol && p[d] <= hi[d] + tol,
                    "at t = {t} the body is at {:?}, outside its cell {:?}..{:?}; crossing {:?}",
                    p.0,
                    lo.0,
                    hi.0,
                    crossing
                );
            }
        }
        if let Some((t, code)) = crossing {
            let (axis, up) = ((code >> 1) as usize, code & 1 == 1);
            let face = if up { hi[axis] } else { lo[axis] };
            prop_assert!(
                (at(t)[axis] - face).abs() <= 1e-9 * (1.0 + face.abs()),
                "the crossing at {t} is not on its face"
            );
        }
        Ok(())
    }

    proptest! {
        #[test]
        fn falling_bodies_cross_before_leaving_their_cell(
            ticks in prop::collection::vec(0u8..48, 3),
            vel in prop::collection::vec(prop_oneof![Just(0.0), Just(1.0), Just(-2.0), -3.0..3.0f64], 3),
            g in prop::collection::vec(prop_oneof![2 => Just(0.0), 2 => Just(-9.81), 1 => Just(4.0), 1 => -10.0..10.0f64], 3),
        ) {
            check_falling_crossing::<2>(&ticks, &vel, &g)?;
            check_falling_crossing::<3>(&ticks, &vel, &g)?;
        }
    }

    #[test]
    fn a_body_at_rest_on_a_face_falls_out_of_its_cell_at_once() {
        let grid = Grid::<2>::new(100, 1.0, Vector::ZERO, Vector([12.0; 2]), None);
        // A face at y = 9 (12 cells of 1 m): the body is filed in the cell above it.
        let m = Motion {
            pos: Vector([5.0, 9.0]),
            vel: Vector([1.0, 0.0]),
            time: 0.0,
        };
        let k = grid.coords_of_point(&m.pos).map(|c| c as u32);
        assert_eq!(grid.cell_box(&k.map(|c| c as usize)).0[1], 9.0);
        let crossing = grid.next_crossing_falling(&k, &m, &Vector([0.0, -9.81]), 0.0);
        // Down through the lower y face (code 2·1 + 0), now.
        assert_eq!(crossing, Some((0.0, 2)));
    }

    #[test]
    fn a_body_leaving_a_face_for_an_instant_is_not_crossed_back_and_forth() {
        let grid = Grid::<2>::new(100, 1.0, Vector::ZERO, Vector([12.0; 2]), None);
        // On the face at y = 9, moving up at a speed rounding left (5e-16 m/s) and falling:
        // above the face for 1e-16 s, less than the time's rounding at t = 1.25 s.
        let g = Vector([0.0, -9.81]);
        let m = Motion {
            pos: Vector([5.5, 9.0]),
            vel: Vector([0.0, 5.307e-16]),
            time: 1.25,
        };
        let above = [5u32, 9];
        let below = [5u32, 8];
        // From the cell above it falls out now, through its lower face (code 2).
        assert_eq!(
            grid.next_crossing_falling(&above, &m, &g, 1.25),
            Some((1.25, 2))
        );
        // From the cell below it does not go up again at that instant: it next leaves that
        // cell through its lower face, at y = 8, 0.45 s later.
        let (t, code) = grid.next_crossing_falling(&below, &m, &g, 1.25).unwrap();
        assert_eq!(code, 2);
        assert!((t - (1.25 + (1.0 / 4.905f64).sqrt())).abs() < 1e-12, "{t}");
    }

    #[test]
    fn dilute_grids_get_a_bounded_number_of_cells_per_body() {
        // 1,000 bodies in a 1000-wide square: unit cells would be 1,000 per body.
        let (cells, _) = cells_of::<2>(1000, 1.0, 1000.0);
        assert!(cells as f64 <= 2.5 * 1000.0 + 64.0, "{cells} cells");
        assert!(
            cells as f64 > 0.5 * 2.5 * 1000.0,
            "{cells} cells: cells grew too far"
        );
        let (cells, _) = cells_of::<3>(1000, 1.0, 1000.0);
        assert!(cells as f64 <= 4.0 * 1000.0 + 64.0, "{cells} cells");
        assert!(
            cells as f64 > 0.3 * 4.0 * 1000.0,
            "{cells} cells: cells grew too far"
        );
        // Dense: the smallest width already gives fewer cells than the bound.
        assert_eq!(cells_of::<2>(10_000, 1.0, 100.0), (10_000, [100, 100]));
        assert_eq!(cells_of::<3>(10_000, 1.0, 20.0), (8_000, [20, 20, 20]));
    }

    /// The union of two blocks: both blocks' cells, each once, shared ones first.
    fn check_pair_blocks<const D: usize>(g: &Grid<D>, sizes: &[usize]) {
        let k1 = [2u32; D];
        let c1 = g.linear_u32(&k1) as isize;
        let block = |k: &[u32; D]| {
            let mut cells = Vec::new();
            g.visit_neighbours(k, |c, _, _| cells.push(c as isize));
            cells
        };
        for code in 0..3usize.pow(D as u32) {
            let mut c = code;
            let k2: [u32; D] = std::array::from_fn(|d| {
                let x = k1[d] + (c % 3) as u32 - 1;
                c /= 3;
                x
            });
            let (base, p) = g.interior_pair(&k1, &k2).unwrap();
            assert_eq!(base as isize, c1);
            let cells: Vec<isize> = p.offsets.iter().map(|o| c1 + o).collect();
            let (b1, b2) = (block(&k1), block(&k2));
            let (shared, rest) = cells.split_at(p.shared);
            let (first, second) = rest.split_at(p.only_first);
            assert!(shared.iter().all(|c| b1.contains(c) && b2.contains(c)));
            assert!(first.iter().all(|c| b1.contains(c) && !b2.contains(c)));
            assert!(second.iter().all(|c| !b1.contains(c) && b2.contains(c)));
            let mut sorted = cells.clone();
            sorted.sort_unstable();
            sorted.dedup();
            let mut union = [b1, b2].concat();
            union.sort_unstable();
            union.dedup();
            assert_eq!(sorted, union, "offset code {code}");
            assert_eq!(cells.len(), union.len());
            assert!(sizes.contains(&cells.len()));
        }
        // Cells two apart, or a border cell: no union.
        let mut far = k1;
        far[0] += 2;
        assert!(g.interior_pair(&k1, &far).is_none());
        assert!(g.interior_pair(&[0; D], &[1; D]).is_none());
    }

    #[test]
    fn pair_blocks_are_unions_of_blocks() {
        let g = Grid::<2>::new(64, 1.0, Vector::ZERO, Vector([6.0; 2]), None);
        check_pair_blocks(&g, &[9, 12, 14]);
        let g = Grid::<3>::new(400, 1.0, Vector::ZERO, Vector([6.0; 3]), None);
        check_pair_blocks(&g, &[27, 36, 42, 46]);
    }

    proptest! {
        /// Filing, stepping and removing bodies in a grid of few cells, so that cells
        /// overflow their slots and drain again: after every move each body is filed once,
        /// in its cell, slots full before any overflow (`validate`), and each cell's bodies
        /// are the set a model keeps.
        #[test]
        fn slots_and_overflow_stay_exact(
            moves in prop::collection::vec((0..12usize, 0..4usize, any::<bool>()), 1..200),
        ) {
            let n = 12;
            let mut g = Grid::<2>::new(n, 1.0, Vector::ZERO, Vector([3.0; 2]), None);
            prop_assert_eq!(g.dims(), [3, 3]);
            let mut coords = vec![[0u32; 2]; n];
            for (i, c) in coords.iter_mut().enumerate() {
                *c = g.insert(i, [1, i % 3]);
            }
            for &(i, axis, up) in &moves {
                let axis = axis % 2;
                let k = coords[i][axis];
                let up = if k == 0 { true } else if k == 2 { false } else { up };
                if axis == 1 && i % 4 == 0 {
                    // A remove and insert instead of a step, as `relocate` does.
                    let mut k = coords[i].map(|x| x as usize);
                    k[1] = if up { k[1] + 1 } else { k[1] - 1 };
                    g.relocate(i, &mut coords[i], k);
                } else {
                    g.step(i, &mut coords[i], axis, up);
                }
                let r = g.validate(|b| coords[b]);
                prop_assert!(r.is_ok(), "{:?}", r);
                for c in 0..g.cell_count() as u32 {
                    let mut got: Vec<u32> = g.bodies_in(c).collect();
                    got.sort_unstable();
                    let want: Vec<u32> = (0..n as u32)
                        .filter(|&b| g.cell_at(&coords[b as usize]) == c)
                        .collect();
                    prop_assert_eq!(got, want);
                }
            }
        }
    }

    #[test]
    fn segment_box_distances() {
        let lo = Vector([0.0, 0.0]);
        let hi = Vector([1.0, 1.0]);
        // Crossing the box.
        let d = segment_box_distance_sq(Vector([-1.0, 0.5]), Vector([2.0, 0.5]), lo, hi);
        assert_eq!(d, 0.0);
        // Parallel above it.
        let d = segment_box_distance_sq(Vector([-1.0, 3.0]), Vector([2.0, 3.0]), lo, hi);
        assert!((d - 4.0).abs() < 1e-12);
        // Diagonal past the corner (2,2)-(1,1) direction: closest point to corner (1,1).
        let d = segment_box_distance_sq(Vector([3.0, 1.0]), Vector([1.0, 3.0]), lo, hi);
        assert!((d - 2.0).abs() < 1e-12, "{d}");
        // Unbounded box.
        let d = segment_box_distance_sq(
            Vector([5.0, 5.0]),
            Vector([6.0, 9.0]),
            Vector([f64::NEG_INFINITY, 0.0]),
            Vector([1.0, f64::INFINITY]),
        );
        assert!((d - 16.0).abs() < 1e-12);
    }

    #[test]
    fn plane_box_distances() {
        let d = plane_box_min_distance(
            Vector([0.0, 0.0, 0.0]),
            Vector([0.0, 0.0, 2.0]),
            Vector([0.0, 0.0, 1.0]),
            Vector([1.0, 1.0, 3.0]),
        );
        assert_eq!(d, 1.0);
        let d = plane_box_min_distance(
            Vector([0.0, 0.0, 0.0]),
            Vector([0.0, 0.0, 1.0]),
            Vector([0.0, 0.0, f64::NEG_INFINITY]),
            Vector([1.0, 1.0, 3.0]),
        );
        assert_eq!(d, f64::NEG_INFINITY);
    }

    fn collect<const D: usize>(
        g: &Grid<D>,
        visit: impl FnOnce(&mut dyn FnMut(u32, &Vector<D>, u8)),
    ) -> Vec<([usize; D], [f64; D], u8)> {
        let mut out = Vec::new();
        visit(&mut |c, s, i| out.push((g.coords(c), s.0, i)));
        out
    }

    #[test]
    fn neighbours_and_layers() {
        let g = Grid::<2>::new(4, 1.0, Vector([0.0, 0.0]), Vector([5.0, 5.0]), None);
        assert_eq!(g.dims(), [5, 5]);
        let count = |k: [u32; 2]| collect(&g, |f| g.visit_neighbours(&k, f)).len();
        assert_eq!(count([2, 2]), 9);
        assert_eq!(count([0, 0]), 4);
        assert_eq!(count([0, 2]), 6);
        let layer = collect(&g, |f| g.visit_entered_layer(&[1, 2], 0, true, f));
        let cells: Vec<[usize; 2]> = layer.iter().map(|x| x.0).collect();
        assert_eq!(cells, vec![[2, 1], [2, 2], [2, 3]]);
        assert!(collect(&g, |f| g.visit_entered_layer(&[4, 2], 0, true, f)).is_empty());
        let p = Grid::<2>::new(4, 1.0, Vector::ZERO, Vector::ZERO, Some(Vector([5.0, 2.5])));
        assert_eq!(p.dims(), [5, 1]);
        let nb = collect(&p, |f| p.visit_neighbours(&[0, 0], f));
        assert_eq!(nb.len(), 9);
        let corner = nb
            .iter()
            .find(|x| x.0 == [4, 0] && x.1 == [-5.0, 2.5])
            .unwrap();
        assert_eq!(p.shift_of(corner.2).0, corner.1);
        for (_, shift, image) in collect(&p, |f| p.visit_neighbours(&[2, 0], f)) {
            assert_eq!(p.shift_of(image).0, shift);
        }
    }
}
