//! The verifier's own broad phase: which pairs of bodies may have come within touching
//! distance, so that a replay checks a few neighbours per event instead of every body.
//!
//! It shares no code with the simulator's finders. Time is cut into *slabs* `[T, T_end]`. In
//! each slab every body is filed, in a hash grid of box-shaped cells, in the cells that the box
//! swept by its current motion over `[max(t_i, T), T_end]`, grown by its radius, covers.
//!
//! **Why no close pair is missed.** If bodies `i` and `j` came within their contact distance
//! `r_i + r_j` at a time `s` in the slab, while both moved as filed, each centre at `s` lies
//! in its own swept box, and the two points are closer than `r_i + r_j` on every axis, so the
//! boxes grown by `r_i` and `r_j` overlap, and share a cell. A body whose motion changes at an
//! event is filed again from that time; the motion it leaves was checked, at that event,
//! against every body sharing a cell with it. At a slab's end every pair sharing a cell is
//! checked over the rest of the slab. So every stretch of time during which two bodies kept
//! their motions is checked exactly once, by the closed-form closest approach, for every
//! pair whose boxes overlap, and pairs whose boxes never overlap were never close.
//!
//! Under gravity a body's path in a slab is a parabola: along each axis its coordinate is
//! extreme at the ends of its stretch or at the vertex, so the box of those (up to three)
//! points holds the whole arc, and the argument above stands.
//!
//! In a periodic box the cells tile the box and their indices wrap around, so a body is
//! filed in the cells of every image its box reaches (a box as long as the box covers all).
//! A body whose box would cover more than [`WIDE_CELLS`] cells (a fast body in a long slab)
//! is kept on a list of *wide* bodies instead, which every body counts as a neighbour.

/// Most cells a body is filed in; a body whose box covers more is a wide body.
const WIDE_CELLS: i64 = 4096;

use crate::geom::Vector;
use crate::motion::Motion;
use std::collections::{HashMap, HashSet};

/// Where a body is filed: the range of cell indices its grown swept box covers, per axis.
#[derive(Clone, Copy, Debug)]
struct Filed<const D: usize> {
    lo: [i64; D],
    hi: [i64; D],
}

/// The slab hash grid.
#[derive(Clone, Debug)]
pub(super) struct Proximity<const D: usize> {
    /// Cell side per axis, metres (at least `2 r_max`; in a periodic box, a whole fraction
    /// of the box's side, so that indices wrap with the box).
    cell: [f64; D],
    /// Periodic worlds: cells per axis (indices wrap modulo these).
    wrap: Option<[i64; D]>,
    /// Bodies filed in each non-empty cell.
    cells: HashMap<[i64; D], Vec<u32>>,
    /// Where each body is filed.
    filed: Vec<Filed<D>>,
    /// Wide bodies (see the module docs), each also marked in `is_wide`.
    wide: Vec<u32>,
    is_wide: Vec<bool>,
    /// Start of the current slab, seconds.
    pub(super) start: f64,
    /// End of the current slab, seconds.
    pub(super) end: f64,
}

impl<const D: usize> Proximity<D> {
    /// A grid with cells of `2 · r_max` (at least), for a world whose periodic box, if any,
    /// is `period`; no body filed yet (each is filed with its own acceleration).
    pub(super) fn new(radii: &[f64], period: Option<Vector<D>>, start: f64) -> Self {
        let r_max = radii.iter().fold(0.0f64, |m, &r| m.max(r));
        let side = (2.0 * r_max).max(f64::MIN_POSITIVE);
        let mut cell = [side; D];
        let wrap = period.map(|size| {
            // Whole cells per side, at least one, each at least `2 r_max` wide.
            let k: [i64; D] =
                std::array::from_fn(|d| ((size[d] / side).floor() as i64).clamp(1, 1 << 20));
            for d in 0..D {
                cell[d] = size[d] / k[d] as f64;
            }
            k
        });
        Proximity {
            cell,
            wrap,
            cells: HashMap::new(),
            filed: vec![
                Filed {
                    lo: [0; D],
                    hi: [-1; D]
                };
                radii.len()
            ],
            wide: Vec::new(),
            is_wide: vec![false; radii.len()],
            start,
            end: start,
        }
    }

    /// Makes room for `n` bodies (bodies added during a run), none of the new ones filed.
    pub(super) fn resize(&mut self, n: usize) {
        self.filed.resize(
            n,
            Filed {
                lo: [0; D],
                hi: [-1; D],
            },
        );
        self.is_wide.resize(n, false);
    }

    /// The cell index range of a grown box, per axis; `None` when the box is not finite or
    /// covers more than [`WIDE_CELLS`] cells. Counted in floating point before any index is
    /// formed, so that no size of box (a slab of 10¹⁷⁰ s, a corrupt time) can overflow an
    /// index or a count.
    fn range(&self, lo: Vector<D>, hi: Vector<D>) -> Option<Filed<D>> {
        let mut f = Filed {
            lo: [0; D],
            hi: [0; D],
        };
        let mut count = 1.0f64;
        for d in 0..D {
            let (a, b) = (
                (lo[d] / self.cell[d]).floor(),
                (hi[d] / self.cell[d]).floor(),
            );
            // Beyond 2⁵² cells from the origin indices are no longer exact: wide.
            let limit = 4_503_599_627_370_496.0;
            if !(a.abs() <= limit && b.abs() <= limit && a <= b) {
                return None;
            }
            let (mut a, mut b) = (a as i64, b as i64);
            if let Some(k) = self.wrap {
                if b - a + 1 >= k[d] {
                    (a, b) = (0, k[d] - 1);
                }
            }
            count *= (b - a + 1) as f64;
            (f.lo[d], f.hi[d]) = (a, b);
        }
        (count <= WIDE_CELLS as f64).then_some(f)
    }

    /// Every cell key of a range (wrapped in periodic worlds).
    fn keys(&self, f: &Filed<D>) -> Vec<[i64; D]> {
        let mut out = Vec::new();
        if (0..D).any(|d| f.hi[d] < f.lo[d]) {
            return out;
        }
        let mut k = f.lo;
        loop {
            let mut key = k;
            if let Some(w) = self.wrap {
                for d in 0..D {
                    key[d] = key[d].rem_euclid(w[d]);
                }
            }
            out.push(key);
            let mut d = 0;
            loop {
                if d == D {
                    return out;
                }
                if k[d] < f.hi[d] {
                    k[d] += 1;
                    break;
                }
                k[d] = f.lo[d];
                d += 1;
            }
        }
    }

    /// Files body `i`, moving as `m` with radius `r` and accelerating at `acc` (the grid's
    /// gravity, a resting body's slide, or none for a kinematic body), for the rest of the
    /// slab from `from`, replacing where it was filed.
    pub(super) fn file(
        &mut self,
        i: usize,
        m: &Motion<D>,
        r: f64,
        from: f64,
        acc: Option<Vector<D>>,
    ) {
        self.unfile(i);
        let end = self.end.max(from);
        let gravity = acc;
        let (a, b, lo, hi) = match &gravity {
            None => {
                let (a, b) = (m.at(from), m.at(end));
                (a, b, a.min(b), a.max(b))
            }
            Some(g) => {
                let (a, b) = (m.falling_at(from, g), m.falling_at(end, g));
                let (mut lo, mut hi) = (a.min(b), a.max(b));
                for d in 0..D {
                    if g[d] != 0.0 {
                        let vertex = m.time - m.vel[d] / g[d];
                        if vertex > from && vertex < end {
                            let x = m.falling_at(vertex, g)[d];
                            lo[d] = lo[d].min(x);
                            hi[d] = hi[d].max(x);
                        }
                    }
                }
                (a, b, lo, hi)
            }
        };
        // Grown by the radius and a hair for the rounding of positions (of their terms,
        // under gravity, which may be much larger than the positions they add up to).
        let dt = (end - m.time).abs().max((from - m.time).abs());
        let (mut lo, mut hi) = (lo, hi);
        for d in 0..D {
            let terms = a[d].abs()
                + b[d].abs()
                + gravity.map_or(0.0, |g| (m.vel[d].abs() + g[d].abs() * dt) * dt);
            let grow = r * (1.0 + 1e-6) + 1e-12 * terms;
            lo[d] -= grow;
            hi[d] += grow;
        }
        let Some(f) = self.range(lo, hi) else {
            self.wide.push(i as u32);
            self.is_wide[i] = true;
            return;
        };
        for key in self.keys(&f) {
            self.cells.entry(key).or_default().push(i as u32);
        }
        self.filed[i] = f;
    }

    fn unfile(&mut self, i: usize) {
        if self.is_wide[i] {
            self.is_wide[i] = false;
            if let Some(k) = self.wide.iter().position(|&j| j as usize == i) {
                self.wide.swap_remove(k);
            }
            return;
        }
        let f = self.filed[i];
        for key in self.keys(&f) {
            if let Some(list) = self.cells.get_mut(&key) {
                if let Some(k) = list.iter().position(|&j| j as usize == i) {
                    list.swap_remove(k);
                }
                if list.is_empty() {
                    self.cells.remove(&key);
                }
            }
        }
        self.filed[i] = Filed {
            lo: [0; D],
            hi: [-1; D],
        };
    }

    /// The bodies other than `i` that share a cell with it, in index order, once each.
    pub(super) fn neighbours(&self, i: usize) -> Vec<usize> {
        if self.is_wide[i] {
            return (0..self.filed.len()).filter(|&j| j != i).collect();
        }
        let mut out: Vec<usize> = self
            .keys(&self.filed[i])
            .iter()
            .filter_map(|key| self.cells.get(key))
            .flatten()
            .chain(&self.wide)
            .map(|&j| j as usize)
            .filter(|&j| j != i)
            .collect();
        out.sort_unstable();
        out.dedup();
        out
    }

    /// Every pair `(i, j)`, `i < j`, of bodies filed in cells (neither of them wide)
    /// sharing a cell, once each, in order. Pairs with a wide body are not listed (there may
    /// be `n` times as many): see [`Proximity::wide`].
    pub(super) fn pairs(&self) -> Vec<(usize, usize)> {
        let mut seen = HashSet::new();
        for list in self.cells.values() {
            for (k, &a) in list.iter().enumerate() {
                for &b in &list[k + 1..] {
                    seen.insert((a.min(b) as usize, a.max(b) as usize));
                }
            }
        }
        let mut out: Vec<(usize, usize)> = seen.into_iter().collect();
        out.sort_unstable();
        out
    }

    /// The wide bodies, in index order: each is a neighbour of every body.
    pub(super) fn wide(&self) -> Vec<usize> {
        let mut out: Vec<usize> = self.wide.iter().map(|&w| w as usize).collect();
        out.sort_unstable();
        out
    }

    /// True when body `i` is wide.
    pub(super) fn is_wide(&self, i: usize) -> bool {
        self.is_wide[i]
    }

    /// Starts the slab `[start, end]`, emptying the grid (the caller files every body again).
    pub(super) fn start_slab(&mut self, start: f64, end: f64) {
        self.cells.clear();
        self.wide.clear();
        self.is_wide.fill(false);
        for f in &mut self.filed {
            *f = Filed {
                lo: [0; D],
                hi: [-1; D],
            };
        }
        self.start = start;
        self.end = end;
    }
}
