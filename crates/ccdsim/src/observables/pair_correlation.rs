//! The radial distribution function g(r).

use crate::contact::periodic::min_image;
use crate::geom::Vector;
use crate::trajectory::{Cell, Frame};

/// The radial distribution function accumulated over frames.
///
/// `g(r)` in a shell `[r, r + Δr)` is the number of pairs at those distances (nearest images
/// in a periodic box) divided by the number an ideal gas of the same density would have:
/// `g = 2 · pairs / (N (N − 1) / V · shell volume)`, so that `g → 1` at large `r` even for
/// a small `N` (freud's "exact" normalisation). Frames are summed before dividing. In a
/// walled box, distances are direct and `V` is the walls' bounding box: near `r_max` the
/// walls make `g` fall below 1.
///
/// Pairs are found on a grid of cells at least `r_max` wide: O(N) per frame at a fixed
/// density.
///
/// ```
/// use ccdsim::observables::PairCorrelation;
/// let g = PairCorrelation::<2>::new(2.0, 40).unwrap();
/// assert_eq!(g.bin_centres().len(), 40);
/// ```
#[derive(Clone, Debug)]
pub struct PairCorrelation<const D: usize> {
    r_max: f64,
    counts: Vec<u64>,
    /// Σ over frames of `N (N − 1) / (2 V)`: the ideal-gas pair density.
    pair_density: f64,
    frames: u64,
}

impl<const D: usize> PairCorrelation<D> {
    /// An empty histogram of `bins` shells over `[0, r_max)`, metres.
    pub fn new(r_max: f64, bins: usize) -> Result<Self, String> {
        if !(r_max.is_finite() && r_max > 0.0) {
            return Err(format!("r_max must be a positive distance, not {r_max}"));
        }
        if bins == 0 {
            return Err("g(r) needs at least one bin".to_string());
        }
        Ok(PairCorrelation {
            r_max,
            counts: vec![0; bins],
            pair_density: 0.0,
            frames: 0,
        })
    }

    /// Adds the pairs of one frame. The frame needs a cell (periodic box or walls) for its
    /// volume; in a periodic box `r_max` must not exceed half the shortest side.
    pub fn add(&mut self, frame: &Frame<D>) -> Result<(), String> {
        let Some((origin, size)) = frame.cell.origin_and_size() else {
            return Err("g(r) needs a volume: a periodic box or walls".to_string());
        };
        let periodic = matches!(frame.cell, Cell::Periodic(_));
        let shortest = (0..D).map(|d| size[d]).fold(f64::INFINITY, f64::min);
        if periodic && self.r_max > 0.5 * shortest {
            return Err(format!(
                "r_max {} exceeds half the periodic box's shortest side ({})",
                self.r_max,
                0.5 * shortest
            ));
        }
        let n = frame.len();
        let volume: f64 = (0..D).map(|d| size[d]).product();
        self.pair_density += (n as f64) * (n.saturating_sub(1) as f64) / (2.0 * volume);
        self.frames += 1;
        let bins = self.counts.len();
        let width = self.r_max / bins as f64;
        let r_max_sq = self.r_max * self.r_max;
        let mut count = |a: Vector<D>, b: Vector<D>| {
            let mut dp = a - b;
            if periodic {
                dp = min_image(dp, &size);
            }
            let r2 = dp.norm_sq();
            if r2 < r_max_sq {
                let k = ((r2.sqrt() / width) as usize).min(bins - 1);
                self.counts[k] += 1;
            }
        };
        let grid = Grid::new(&frame.positions, origin, size, self.r_max, periodic);
        match grid {
            Some(grid) => grid.for_each_pair(&frame.positions, &mut count),
            None => {
                for i in 0..n {
                    for j in i + 1..n {
                        count(frame.positions[i], frame.positions[j]);
                    }
                }
            }
        }
        Ok(())
    }

    /// Frames added so far.
    #[must_use]
    pub fn frames(&self) -> u64 {
        self.frames
    }

    /// The middle of each shell, metres.
    #[must_use]
    pub fn bin_centres(&self) -> Vec<f64> {
        let width = self.r_max / self.counts.len() as f64;
        (0..self.counts.len())
            .map(|k| (k as f64 + 0.5) * width)
            .collect()
    }

    /// Pairs counted per shell over all frames.
    #[must_use]
    pub fn pair_counts(&self) -> &[u64] {
        &self.counts
    }

    /// g(r) per shell (zeros before any frame).
    #[must_use]
    pub fn values(&self) -> Vec<f64> {
        let width = self.r_max / self.counts.len() as f64;
        self.counts
            .iter()
            .enumerate()
            .map(|(k, &c)| {
                let shell =
                    ball_volume::<D>((k + 1) as f64 * width) - ball_volume::<D>(k as f64 * width);
                if self.pair_density > 0.0 {
                    c as f64 / (self.pair_density * shell)
                } else {
                    0.0
                }
            })
            .collect()
    }
}

/// Volume of a ball of radius `r` in `D` dimensions (area in 2D), by the recurrence
/// `V_D = 2π/D · r² · V_{D−2}` from `V_0 = 1` and `V_1 = 2r`.
pub(crate) fn ball_volume<const D: usize>(r: f64) -> f64 {
    let mut v = if D % 2 == 0 { 1.0 } else { 2.0 * r };
    let mut d = if D % 2 == 0 { 2 } else { 3 };
    while d <= D {
        v *= 2.0 * std::f64::consts::PI / d as f64 * r * r;
        d += 2;
    }
    v
}

/// Bodies binned in cells at least `r_max` wide, so that pairs within `r_max` lie in
/// neighbouring cells.
struct Grid<const D: usize> {
    dims: [usize; D],
    periodic: bool,
    /// Bodies by cell: `start[c] .. start[c + 1]` index `order`.
    start: Vec<usize>,
    order: Vec<usize>,
    cell_of: Vec<usize>,
}

impl<const D: usize> Grid<D> {
    /// The grid, or `None` where it would not pay or not be exact: fewer than three cells
    /// along some axis (neighbour cells would repeat), or bodies far outside the cell.
    fn new(
        positions: &[Vector<D>],
        origin: Vector<D>,
        size: Vector<D>,
        r_max: f64,
        periodic: bool,
    ) -> Option<Self> {
        let mut lo = origin;
        let mut hi = origin + size;
        if !periodic {
            for p in positions {
                for d in 0..D {
                    lo[d] = lo[d].min(p[d]);
                    hi[d] = hi[d].max(p[d]);
                }
            }
        }
        let mut dims = [0usize; D];
        for d in 0..D {
            let cells = ((hi[d] - lo[d]) / r_max).floor();
            if !(3.0..=1e6).contains(&cells) {
                return None;
            }
            dims[d] = cells as usize;
        }
        let total: usize = dims.iter().product();
        if total > 4 * positions.len() + 64 {
            return None;
        }
        let cell_of: Vec<usize> = positions
            .iter()
            .map(|p| {
                let mut c = 0;
                for d in (0..D).rev() {
                    let x = ((p[d] - lo[d]) / (hi[d] - lo[d]) * dims[d] as f64).floor();
                    c = c * dims[d] + (x.max(0.0) as usize).min(dims[d] - 1);
                }
                c
            })
            .collect();
        let mut start = vec![0usize; total + 1];
        for &c in &cell_of {
            start[c + 1] += 1;
        }
        for c in 0..total {
            start[c + 1] += start[c];
        }
        let mut fill = start.clone();
        let mut order = vec![0; positions.len()];
        for (i, &c) in cell_of.iter().enumerate() {
            order[fill[c]] = i;
            fill[c] += 1;
        }
        Some(Grid {
            dims,
            periodic,
            start,
            order,
            cell_of,
        })
    }

    /// Calls `f` once for every unordered pair of bodies in the same or neighbouring cells.
    fn for_each_pair(&self, positions: &[Vector<D>], f: &mut impl FnMut(Vector<D>, Vector<D>)) {
        let offsets = 3usize.pow(D as u32);
        for (i, &c) in self.cell_of.iter().enumerate() {
            let mut coord = [0usize; D];
            let mut rest = c;
            for (x, &dim) in coord.iter_mut().zip(&self.dims) {
                *x = rest % dim;
                rest /= dim;
            }
            'offsets: for o in 0..offsets {
                let mut code = o;
                let mut neighbour = 0;
                let mut stride = 1;
                for (&at, &dim) in coord.iter().zip(&self.dims) {
                    let step = (code % 3) as isize - 1;
                    code /= 3;
                    let mut x = at as isize + step;
                    if x < 0 || x >= dim as isize {
                        if !self.periodic {
                            continue 'offsets;
                        }
                        x = x.rem_euclid(dim as isize);
                    }
                    neighbour += x as usize * stride;
                    stride *= dim;
                }
                for &j in &self.order[self.start[neighbour]..self.start[neighbour + 1]] {
                    if j > i {
                        f(positions[i], positions[j]);
                    }
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn frame<const D: usize>(n: usize, side: f64, periodic: bool, seed: u64) -> Frame<D> {
        let mut state = seed;
        let mut next = || {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        let positions: Vec<Vector<D>> = (0..n)
            .map(|_| {
                let mut p = Vector([0.0; D]);
                for d in 0..D {
                    p[d] = next() * side;
                }
                p
            })
            .collect();
        Frame {
            time: 0.0,
            cell: if periodic {
                Cell::Periodic(Vector([side; D]))
            } else {
                Cell::Walls {
                    lo: Vector([0.0; D]),
                    hi: Vector([side; D]),
                }
            },
            ids: (0..n as u64).collect(),
            images: vec![[0; D]; n],
            strain: 0.0,
            velocities: vec![Vector([0.0; D]); n],
            radii: vec![0.1; n],
            masses: vec![1.0; n],
            positions,
            spins: None,
        }
    }

    /// All pairs, directly.
    fn brute<const D: usize>(f: &Frame<D>, r_max: f64, bins: usize) -> Vec<u64> {
        let mut counts = vec![0; bins];
        let (_, size) = f.cell.origin_and_size().unwrap();
        for i in 0..f.len() {
            for j in i + 1..f.len() {
                let mut dp = f.positions[i] - f.positions[j];
                if matches!(f.cell, Cell::Periodic(_)) {
                    dp = min_image(dp, &size);
                }
                let r = dp.norm();
                if r < r_max {
                    counts[((r / (r_max / bins as f64)) as usize).min(bins - 1)] += 1;
                }
            }
        }
        counts
    }

    #[test]
    fn the_grid_counts_every_pair_once() {
        for periodic in [true, false] {
            for seed in 1..4 {
                let f2 = frame::<2>(400, 10.0, periodic, seed);
                let mut g2 = PairCorrelation::new(2.5, 25).unwrap();
                g2.add(&f2).unwrap();
                assert_eq!(g2.pair_counts(), brute(&f2, 2.5, 25).as_slice());
                let f3 = frame::<3>(400, 10.0, periodic, seed);
                let mut g3 = PairCorrelation::new(3.0, 30).unwrap();
                g3.add(&f3).unwrap();
                assert_eq!(g3.pair_counts(), brute(&f3, 3.0, 30).as_slice());
            }
        }
    }

    #[test]
    fn an_ideal_gas_has_g_near_one() {
        let mut g = PairCorrelation::<3>::new(2.0, 10).unwrap();
        for seed in 0..20 {
            g.add(&frame::<3>(1000, 10.0, true, seed)).unwrap();
        }
        for v in g.values() {
            assert!((v - 1.0).abs() < 0.1, "{v}");
        }
    }

    #[test]
    fn ball_volumes() {
        use std::f64::consts::PI;
        assert_eq!(ball_volume::<1>(3.0), 6.0);
        assert!((ball_volume::<2>(3.0) - PI * 9.0).abs() < 1e-12);
        assert!((ball_volume::<3>(3.0) - 4.0 / 3.0 * PI * 27.0).abs() < 1e-12);
        assert!((ball_volume::<4>(3.0) - PI * PI / 2.0 * 81.0).abs() < 1e-9);
    }

    #[test]
    fn bad_requests_are_refused() {
        assert!(PairCorrelation::<2>::new(0.0, 10).is_err());
        assert!(PairCorrelation::<2>::new(1.0, 0).is_err());
        let mut g = PairCorrelation::<2>::new(6.0, 10).unwrap();
        assert!(g.add(&frame::<2>(10, 10.0, true, 1)).is_err());
        let mut open = frame::<2>(10, 10.0, true, 1);
        open.cell = Cell::Open;
        assert!(g.add(&open).is_err());
    }
}
