//! The uniform grid of the `cells` finder: cell geometry, one linked list of bodies per cell,
//! the walls each cell can reach, and cell-crossing times.
//!
//! Cells are at least the largest contact distance (times `1 + MARGIN`) wide along every axis.
//! In an open (non-periodic) world the grid spans the bounding box of the bodies and walls at
//! `init`, and its outermost cells extend to infinity, so every point of space is in exactly one
//! cell and two cells that are not neighbours are separated by at least one whole cell. In a
//! periodic world the grid tiles the box `[0, L)` exactly; an axis with fewer than three cells
//! becomes a single cell whose three images (−L, 0, +L) are all neighbours.

use super::queue::NONE;
use crate::geom::Vector;
use crate::narrow::Motion;
use crate::scene::Wall;

/// Relative margin by which cells are wider than the largest contact distance, and by which
/// wall reach exceeds the largest radius: it absorbs the rounding of crossing times and
/// positions (see the module docs of `cells`).
pub(super) const MARGIN: f64 = 1e-6;

/// Most neighbour cells of a cell: 3^D for D ≤ 3.
pub(super) const MAX_NEIGHBOURS: usize = 27;

/// A neighbour cell and the image shift to add to the displacement of its bodies.
#[derive(Clone, Copy, Debug)]
pub(super) struct Neighbour<const D: usize> {
    /// Linear cell index.
    pub cell: u32,
    /// Displacement of the image of the cell's bodies that lies next to the centre cell (zero
    /// except across periodic boundaries).
    pub shift: Vector<D>,
}

/// A fixed-capacity list of neighbour cells.
pub(super) struct Neighbours<const D: usize> {
    items: [Neighbour<D>; MAX_NEIGHBOURS],
    len: usize,
}

impl<const D: usize> Neighbours<D> {
    fn new() -> Self {
        Neighbours {
            items: [Neighbour {
                cell: 0,
                shift: Vector::ZERO,
            }; MAX_NEIGHBOURS],
            len: 0,
        }
    }

    /// The neighbours found.
    pub fn as_slice(&self) -> &[Neighbour<D>] {
        &self.items[..self.len]
    }
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
    /// First body of each cell, or `NONE`.
    head: Vec<u32>,
    /// Next body in the same cell, or `NONE`.
    next: Vec<u32>,
    /// Cell of each body.
    cell: Vec<u32>,
    /// Walls within reach of cell `c`: `wall_ids[wall_start[c]..wall_start[c + 1]]` (empty
    /// vectors when the world has no walls).
    wall_start: Vec<u32>,
    wall_ids: Vec<u32>,
}

impl<const D: usize> Grid<D> {
    /// A grid for `n` bodies whose cells are at least `min_width` wide, spanning `lo..hi` (open
    /// worlds) or the periodic box `period`, with at most about `4n + 64` cells.
    pub fn new(
        n: usize,
        min_width: f64,
        lo: Vector<D>,
        hi: Vector<D>,
        period: Option<Vector<D>>,
    ) -> Self {
        let cap = 4.0 * n as f64 + 64.0;
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
        let mut interior = Vec::with_capacity(MAX_NEIGHBOURS);
        for code in 0..3usize.pow(D as u32) {
            let mut c = code;
            let mut off = 0isize;
            for st in stride {
                off += ((c % 3) as isize - 1) * st as isize;
                c /= 3;
            }
            interior.push(off);
        }
        Grid {
            origin,
            width,
            dims,
            stride,
            period: period.map(|p| p.0),
            interior,
            head: vec![NONE; s],
            next: vec![NONE; n],
            cell: vec![NONE; n],
            wall_start: Vec::new(),
            wall_ids: Vec::new(),
        }
    }

    /// Number of cells.
    pub fn cell_count(&self) -> usize {
        self.head.len()
    }

    /// Cells per axis.
    pub fn dims(&self) -> [usize; D] {
        self.dims
    }

    /// Bytes held (payload).
    pub fn bytes(&self) -> usize {
        4 * (self.head.capacity()
            + self.next.capacity()
            + self.cell.capacity()
            + self.wall_start.capacity()
            + self.wall_ids.capacity())
            + std::mem::size_of::<isize>() * self.interior.capacity()
    }

    /// Cell coordinates of the point `p` (outer cells of open worlds extend to infinity;
    /// periodic coordinates are clamped into the box, since stored positions are in it up to
    /// rounding).
    pub fn coords_of_point(&self, p: &Vector<D>) -> [usize; D] {
        let mut k = [0usize; D];
        for d in 0..D {
            let x = ((p[d] - self.origin[d]) / self.width[d]).floor();
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
        k.iter().zip(&self.stride).map(|(k, s)| k * s).sum::<usize>() as u32
    }

    /// Cell coordinates of a linear index.
    #[inline]
    pub fn coords(&self, c: u32) -> [usize; D] {
        let c = c as usize;
        std::array::from_fn(|d| (c / self.stride[d]) % self.dims[d])
    }

    /// The cell body `i` is filed in.
    #[inline]
    pub fn cell_of(&self, i: usize) -> u32 {
        self.cell[i]
    }

    /// Files body `i` (not filed anywhere) in cell `c`.
    pub fn insert(&mut self, i: usize, c: u32) {
        self.next[i] = self.head[c as usize];
        self.head[c as usize] = i as u32;
        self.cell[i] = c;
    }

    /// Takes body `i` out of its cell.
    pub fn remove(&mut self, i: usize) {
        let c = self.cell[i] as usize;
        let mut at = self.head[c];
        if at == i as u32 {
            self.head[c] = self.next[i];
        } else {
            // Cells hold a handful of bodies: a scan is cheaper than a second link per body.
            while self.next[at as usize] != i as u32 {
                at = self.next[at as usize];
                debug_assert!(at != NONE, "body {i} not in its cell {c}");
            }
            self.next[at as usize] = self.next[i];
        }
        self.next[i] = NONE;
        self.cell[i] = NONE;
    }

    /// Moves body `i` to cell `c`.
    pub fn relocate(&mut self, i: usize, c: u32) {
        if self.cell[i] != c {
            self.remove(i);
            self.insert(i, c);
        }
    }

    /// First body of cell `c`, or `NONE`.
    #[inline]
    pub fn first(&self, c: u32) -> u32 {
        self.head[c as usize]
    }

    /// Body after `i` in its cell, or `NONE`.
    #[inline]
    pub fn after(&self, i: u32) -> u32 {
        self.next[i as usize]
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

    fn product(&self, axes: &[AxisChoices; D], out: &mut Neighbours<D>) {
        let mut idx = [0usize; D];
        if axes.iter().any(|a| a.len == 0) {
            return;
        }
        loop {
            let mut c = 0;
            let mut shift = Vector::<D>::ZERO;
            for d in 0..D {
                c += axes[d].coord[idx[d]] * self.stride[d];
                shift[d] = axes[d].shift[idx[d]];
            }
            out.items[out.len] = Neighbour {
                cell: c as u32,
                shift,
            };
            out.len += 1;
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

    /// The cells whose bodies can touch a body filed in cell `c` before it leaves `c`: the 3^D
    /// block around it (fewer at the border of an open world), with periodic image shifts.
    pub fn neighbours(&self, c: u32) -> Neighbours<D> {
        let k = self.coords(c);
        let mut out = Neighbours::new();
        if (0..D).all(|d| k[d] >= 1 && k[d] + 2 <= self.dims[d]) {
            for &off in &self.interior {
                out.items[out.len] = Neighbour {
                    cell: (c as isize + off) as u32,
                    shift: Vector::ZERO,
                };
                out.len += 1;
            }
            return out;
        }
        let axes: [AxisChoices; D] = std::array::from_fn(|d| self.axis_choices(d, k[d]));
        self.product(&axes, &mut out);
        out
    }

    /// The cells that become neighbours when a body moves into cell `c` along `axis` in
    /// direction `up`: the layer of the block beyond `c`.
    pub fn entered_layer(&self, c: u32, axis: usize, up: bool) -> Neighbours<D> {
        let k = self.coords(c);
        let mut out = Neighbours::new();
        let axes: [AxisChoices; D] = std::array::from_fn(|d| {
            if d == axis {
                self.layer_choice(d, k[d], up)
            } else {
                self.axis_choices(d, k[d])
            }
        });
        self.product(&axes, &mut out);
        out
    }

    /// The cell next to `c` along `axis` (`up` or down); it must exist and not wrap.
    pub fn step(&self, c: u32, axis: usize, up: bool) -> u32 {
        if up {
            c + self.stride[axis] as u32
        } else {
            c - self.stride[axis] as u32
        }
    }

    /// The next time a body with motion `m` filed in cell `c` leaves it through a face
    /// between two cells, with the face's code `2·axis + up`: faces of the outer cells of an
    /// open world towards infinity, and the faces of a periodic box (box exits are real
    /// events) are not crossings. Ties go to the lower axis.
    #[inline]
    pub fn next_crossing(&self, c: u32, m: &Motion<D>) -> Option<(f64, u8)> {
        let k = self.coords(c);
        let mut best: Option<(f64, u8)> = None;
        for (d, &kd) in k.iter().enumerate() {
            let v = m.vel[d];
            let bound = if v > 0.0 && kd + 1 < self.dims[d] {
                self.origin[d] + (kd + 1) as f64 * self.width[d]
            } else if v < 0.0 && kd > 0 {
                self.origin[d] + kd as f64 * self.width[d]
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

    /// Checks the lists: every body filed once, in the cell recorded for it.
    pub fn validate(&self) -> Result<(), String> {
        let mut seen = vec![false; self.cell.len()];
        for c in 0..self.head.len() {
            let mut at = self.head[c];
            while at != NONE {
                let i = at as usize;
                if seen[i] {
                    return Err(format!("body {i} filed twice"));
                }
                seen[i] = true;
                if self.cell[i] != c as u32 {
                    return Err(format!(
                        "body {i} in cell {c} but recorded in {}",
                        self.cell[i]
                    ));
                }
                at = self.next[i];
            }
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

    #[test]
    fn neighbours_and_layers() {
        let g = Grid::<2>::new(4, 1.0, Vector([0.0, 0.0]), Vector([5.0, 5.0]), None);
        assert_eq!(g.dims(), [5, 5]);
        assert_eq!(g.neighbours(g.linear(&[2, 2])).as_slice().len(), 9);
        assert_eq!(g.neighbours(g.linear(&[0, 0])).as_slice().len(), 4);
        assert_eq!(g.neighbours(g.linear(&[0, 2])).as_slice().len(), 6);
        let layer = g.entered_layer(g.linear(&[1, 2]), 0, true);
        let cells: Vec<[usize; 2]> = layer.as_slice().iter().map(|n| g.coords(n.cell)).collect();
        assert_eq!(cells, vec![[2, 1], [2, 2], [2, 3]]);
        assert!(g
            .entered_layer(g.linear(&[4, 2]), 0, true)
            .as_slice()
            .is_empty());
        let p = Grid::<2>::new(4, 1.0, Vector::ZERO, Vector::ZERO, Some(Vector([5.0, 2.5])));
        assert_eq!(p.dims(), [5, 1]);
        let nb = p.neighbours(p.linear(&[0, 0]));
        assert_eq!(nb.as_slice().len(), 9);
        assert!(nb
            .as_slice()
            .iter()
            .any(|n| p.coords(n.cell) == [4, 0] && n.shift.0 == [-5.0, 2.5]));
    }
}
