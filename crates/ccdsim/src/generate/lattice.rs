//! Lattice starts for dense packings: hexagonal and square in 2D, face-centred cubic and
//! simple cubic in 3D.
//!
//! A lattice is laid out in a box of `cells` unit cells per axis whose shape is fixed by the
//! lattice (the hexagonal box is `n_x a` by `n_y a √3/2`); the spacing is chosen afterwards
//! from the packing fraction. When the lattice has more sites than bodies, the vacancies are
//! spread evenly over the sites.

use super::GenerateError;

/// A crystal lattice to start bodies on.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Lattice {
    /// The densest lattice of the dimension: hexagonal in 2D, face-centred cubic in 3D.
    Densest,
    /// Hexagonal (triangular) lattice, 2D: each body has six neighbours at distance `a`.
    Hexagonal,
    /// Square lattice, 2D.
    Square,
    /// Face-centred cubic lattice, 3D: four sites per cubic unit cell, twelve neighbours at
    /// distance `b/√2`; `N = 4 m³` fills `m³` unit cells exactly (10,976 = 4·14³,
    /// 97,556 = 4·29³).
    Fcc,
    /// Simple cubic lattice, 3D.
    Cubic,
}

/// Sites of a lattice in fractional coordinates of its box, and its geometry.
pub(super) struct Sites<const D: usize> {
    /// Box shape: side `d` is `shape[d] · spacing`.
    pub shape: [f64; D],
    /// Nearest-neighbour distance in units of the spacing.
    pub nearest: f64,
    /// Fractional coordinates in `[0, 1)` of the sites kept, in lattice order.
    pub points: Vec<[f64; D]>,
}

impl Lattice {
    /// The lattice meant for dimension `D`, or an error if it does not exist there.
    fn resolve<const D: usize>(self) -> Result<Lattice, GenerateError> {
        let l = match (self, D) {
            (Lattice::Densest, 2) => Lattice::Hexagonal,
            (Lattice::Densest, 3) => Lattice::Fcc,
            (l, _) => l,
        };
        let ok = matches!(
            (l, D),
            (Lattice::Hexagonal | Lattice::Square, 2) | (Lattice::Fcc | Lattice::Cubic, 3)
        );
        if ok {
            Ok(l)
        } else {
            Err(GenerateError::Param {
                param: "lattice",
                why: format!("no {self:?} lattice in {D}D"),
            })
        }
    }

    /// `n` sites of the lattice (all of them when `n` fills it exactly).
    pub(super) fn sites<const D: usize>(self, n: usize) -> Result<Sites<D>, GenerateError> {
        let n = n.max(1);
        // Unit-cell counts per axis, the basis in unit-cell coordinates, the unit cell's shape
        // in units of the spacing and the nearest-neighbour distance.
        let (counts, basis, cell, nearest): (Vec<usize>, Vec<Vec<f64>>, Vec<f64>, f64) =
            match self.resolve::<D>()? {
                Lattice::Hexagonal => {
                    let (nx, ny) = hexagonal_counts(n);
                    // Rows alternate a half-spacing shift; a unit cell is two rows.
                    (
                        vec![nx, ny / 2],
                        vec![vec![0.25, 0.25], vec![0.75, 0.75]],
                        vec![1.0, 3f64.sqrt()],
                        1.0,
                    )
                }
                Lattice::Square => {
                    let k = (n as f64).sqrt().ceil() as usize;
                    let k = if (k - 1) * (k - 1) >= n { k - 1 } else { k };
                    (vec![k, k], vec![vec![0.5, 0.5]], vec![1.0, 1.0], 1.0)
                }
                Lattice::Fcc => {
                    let m = cube_root_ceil(n.div_ceil(4));
                    let q = 0.25;
                    (
                        vec![m; 3],
                        vec![
                            vec![q, q, q],
                            vec![q + 0.5, q + 0.5, q],
                            vec![q + 0.5, q, q + 0.5],
                            vec![q, q + 0.5, q + 0.5],
                        ],
                        vec![1.0; 3],
                        0.5f64.sqrt(),
                    )
                }
                Lattice::Cubic => {
                    let m = cube_root_ceil(n);
                    (vec![m; 3], vec![vec![0.5; 3]], vec![1.0; 3], 1.0)
                }
                Lattice::Densest => unreachable!("resolved above"),
            };
        let total = counts.iter().product::<usize>() * basis.len();
        let mut points = Vec::with_capacity(n);
        for k in 0..n {
            // Evenly spread vacancies: keep site ⌊k · total / n⌋.
            let s = (k as u128 * total as u128 / n as u128) as usize;
            let b = &basis[s % basis.len()];
            let mut c = s / basis.len();
            let mut p = [0.0; D];
            for d in 0..D {
                let i = c % counts[d];
                c /= counts[d];
                p[d] = (i as f64 + b[d]) / counts[d] as f64;
            }
            points.push(p);
        }
        let mut shape = [0.0; D];
        for d in 0..D {
            shape[d] = counts[d] as f64 * cell[d];
        }
        Ok(Sites {
            shape,
            nearest,
            points,
        })
    }
}

/// Columns and (even) rows of a hexagonal lattice of at least `n` sites: an exact fit if one
/// gives a box within a factor 2 of square, else the most nearly square box.
fn hexagonal_counts(n: usize) -> (usize, usize) {
    let aspect = |nx: usize, ny: usize| (ny as f64 * 3f64.sqrt() / 2.0 / nx as f64).ln().abs();
    let mut best: Option<(bool, f64, usize, usize)> = None;
    let mut ny = 2;
    while ny <= 2 * ((n as f64).sqrt() as usize + 2) {
        let nx = n.div_ceil(ny);
        let inexact = nx * ny != n || aspect(nx, ny) > 2f64.ln();
        let cand = (inexact, aspect(nx, ny), nx, ny);
        if best.is_none_or(|b| (cand.0, cand.1) < (b.0, b.1)) {
            best = Some(cand);
        }
        ny += 2;
    }
    let (_, _, nx, ny) = best.expect("at least one candidate");
    (nx, ny)
}

/// Smallest `m` with `m³ ≥ n`.
fn cube_root_ceil(n: usize) -> usize {
    let mut m = (n as f64).cbrt().round() as usize;
    while m * m * m < n {
        m += 1;
    }
    while m > 1 && (m - 1) * (m - 1) * (m - 1) >= n {
        m -= 1;
    }
    m.max(1)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn exact_fits() {
        assert_eq!(hexagonal_counts(10_000), (100, 100));
        assert_eq!(hexagonal_counts(62_500), (250, 250));
        assert_eq!(hexagonal_counts(1_000_000), (1000, 1000));
        assert_eq!(cube_root_ceil(10_976 / 4), 14);
        assert_eq!(cube_root_ceil(97_556 / 4), 29);
        let s = Lattice::Fcc.sites::<3>(10_976).unwrap();
        assert_eq!(s.points.len(), 10_976);
        assert_eq!(s.shape, [14.0; 3]);
    }

    #[test]
    fn sites_are_distinct_and_spaced() {
        for (lattice, n) in [
            (Lattice::Hexagonal, 37),
            (Lattice::Square, 50),
            (Lattice::Hexagonal, 1000),
        ] {
            let s = lattice.sites::<2>(n).unwrap();
            assert_eq!(s.points.len(), n);
            let min = min_distance(&s.points, &s.shape);
            assert!(min >= s.nearest * (1.0 - 1e-12), "{lattice:?} {n}: {min}");
        }
        for (lattice, n) in [
            (Lattice::Fcc, 100),
            (Lattice::Cubic, 30),
            (Lattice::Fcc, 256),
        ] {
            let s = lattice.sites::<3>(n).unwrap();
            assert_eq!(s.points.len(), n);
            let min = min_distance(&s.points, &s.shape);
            assert!(min >= s.nearest * (1.0 - 1e-12), "{lattice:?} {n}: {min}");
        }
        assert!(Lattice::Fcc.sites::<2>(10).is_err());
        assert!(Lattice::Hexagonal.sites::<3>(10).is_err());
    }

    /// Smallest distance between sites in a periodic box of the lattice's shape.
    fn min_distance<const D: usize>(points: &[[f64; D]], shape: &[f64; D]) -> f64 {
        let mut min = f64::INFINITY;
        for (i, p) in points.iter().enumerate() {
            for q in &points[..i] {
                let mut d2 = 0.0;
                for d in 0..D {
                    let mut x = (p[d] - q[d]) * shape[d];
                    x -= shape[d] * (x / shape[d]).round();
                    d2 += x * x;
                }
                min = min.min(d2.sqrt());
            }
        }
        min
    }
}
