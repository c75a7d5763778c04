//! Random sequential placement of non-overlapping balls in a box (walled or periodic), with a
//! flat grid of cells to find the balls already placed near a candidate spot.

use super::GenerateError;
use crate::contact::periodic::min_image;
use crate::geom::Vector;
use rand::Rng;

/// Relative clearance kept between bodies and from the walls, so that rounding never makes a
/// freshly placed scene overlap.
pub(crate) const CLEARANCE: f64 = 1e-9;

/// Places balls of the given radii uniformly at random inside the box `[0, size]`, none
/// overlapping another (nor, in a walled box, a wall), larger balls first. In a `periodic`
/// box coordinates are drawn from `[0, size)` and distances are taken between nearest
/// images. Returns the centres in the order of `radii`, or [`GenerateError::Jammed`] after
/// `1000·n + 100000` failed attempts.
pub(crate) fn place_balls<const D: usize, R: Rng>(
    radii: &[f64],
    size: Vector<D>,
    periodic: bool,
    rng: &mut R,
) -> Result<Vec<Vector<D>>, GenerateError> {
    let n = radii.len();
    let r_max = radii.iter().copied().fold(0.0, f64::max);
    // Larger bodies first: they are the hardest to fit.
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by(|&a, &b| radii[b].total_cmp(&radii[a]));
    let mut grid = PlacementGrid::new(size, 2.0 * r_max * (1.0 + CLEARANCE), n, periodic);
    let mut pos = vec![Vector::<D>::ZERO; n];
    let mut attempts: u64 = 0;
    let max_attempts = 1000 * n as u64 + 100_000;
    for (placed, &i) in order.iter().enumerate() {
        let r = radii[i];
        let margin = r * (1.0 + CLEARANCE);
        if !periodic && (0..D).any(|k| 2.0 * margin > size[k]) {
            return Err(GenerateError::Param {
                param: "radius",
                why: format!("a body of radius {r} does not fit in the box"),
            });
        }
        loop {
            attempts += 1;
            if attempts > max_attempts {
                return Err(GenerateError::Jammed {
                    placed,
                    n,
                    attempts,
                });
            }
            let mut p = Vector::<D>::ZERO;
            for k in 0..D {
                p[k] = if periodic {
                    rng.random_range(0.0..size[k])
                } else {
                    rng.random_range(margin..=size[k] - margin)
                };
            }
            let cell = grid.cell_of(&p);
            let free = grid.all_near(&cell, |j| {
                let sum = (r + radii[j]) * (1.0 + CLEARANCE);
                let d = if periodic {
                    min_image(pos[j] - p, &size)
                } else {
                    pos[j] - p
                };
                d.norm_sq() >= sum * sum
            });
            if free {
                pos[i] = p;
                grid.insert(&cell, i);
                break;
            }
        }
    }
    Ok(pos)
}

/// "No ball" in the grid's lists.
const NONE: usize = usize::MAX;

/// Cells at least `reach` wide tiling the box, each with a linked list of the balls placed in
/// it: every ball within `reach` of a point lies in the point's cell or a neighbouring one.
/// At most about `4n` cells (wider ones in a dilute box), so a grid never outgrows its balls.
struct PlacementGrid<const D: usize> {
    /// Cells along each axis.
    count: [usize; D],
    /// Cell width along each axis, metres (at least the reach).
    width: [f64; D],
    periodic: bool,
    /// The last ball placed in each cell, or [`NONE`].
    head: Vec<usize>,
    /// The ball placed before each one in its cell, or [`NONE`].
    next: Vec<usize>,
}

impl<const D: usize> PlacementGrid<D> {
    fn new(size: Vector<D>, reach: f64, n: usize, periodic: bool) -> Self {
        let most = ((4 * n.max(1)) as f64).powf(1.0 / D as f64).ceil() as usize + 2;
        // `as usize` saturates: a reach of 10⁻³⁰ in a 1-metre box asks for `most`.
        let count = std::array::from_fn(|k| ((size[k] / reach).floor() as usize).clamp(1, most));
        let width = std::array::from_fn(|k| size[k] / count[k] as f64);
        PlacementGrid {
            count,
            width,
            periodic,
            head: vec![NONE; count.iter().product()],
            next: vec![NONE; n],
        }
    }

    /// The cell holding `p` (a point of the box; rounding at its far faces is clamped in).
    fn cell_of(&self, p: &Vector<D>) -> [usize; D] {
        std::array::from_fn(|k| ((p[k] / self.width[k]).floor() as usize).min(self.count[k] - 1))
    }

    fn index(&self, cell: &[usize; D]) -> usize {
        cell.iter()
            .zip(&self.count)
            .rev()
            .fold(0, |at, (&c, &count)| at * count + c)
    }

    fn insert(&mut self, cell: &[usize; D], ball: usize) {
        let at = self.index(cell);
        self.next[ball] = self.head[at];
        self.head[at] = ball;
    }

    /// Whether `test` holds for every ball in `cell` and the cells around it (stops at the
    /// first that fails). In a periodic box with fewer than three cells along an axis a cell
    /// may be visited twice.
    fn all_near(&self, cell: &[usize; D], mut test: impl FnMut(usize) -> bool) -> bool {
        'codes: for code in 0..3usize.pow(D as u32) {
            let mut near = *cell;
            let mut c = code;
            for (k, slot) in near.iter_mut().enumerate() {
                let step = c % 3;
                c /= 3;
                let count = self.count[k];
                *slot = match (step, self.periodic) {
                    (0, true) => (*slot + count - 1) % count,
                    (2, true) => (*slot + 1) % count,
                    (0, false) if *slot == 0 => continue 'codes,
                    (0, false) => *slot - 1,
                    (2, false) if *slot + 1 == count => continue 'codes,
                    (2, false) => *slot + 1,
                    _ => *slot,
                };
            }
            let mut ball = self.head[self.index(&near)];
            while ball != NONE {
                if !test(ball) {
                    return false;
                }
                ball = self.next[ball];
            }
        }
        true
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::SeedableRng;
    use rand_chacha::ChaCha8Rng;

    /// Every pair of placed balls, all images in a periodic box, apart by their radii and the
    /// clearance; walled boxes keep every ball inside. Checked against all pairs, for dense and
    /// very dilute boxes (whose grids are capped and wider than the reach), in 2D and 3D.
    fn check<const D: usize>(n: usize, r: (f64, f64), side: f64, periodic: bool, seed: u64) {
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let radii: Vec<f64> = (0..n).map(|_| rng.random_range(r.0..=r.1)).collect();
        let size = Vector::<D>::splat(side);
        let pos = place_balls(&radii, size, periodic, &mut rng).unwrap();
        for i in 0..n {
            for &x in &pos[i].0 {
                if periodic {
                    assert!((0.0..side).contains(&x));
                } else {
                    assert!(x >= radii[i] && x <= side - radii[i]);
                }
            }
            for j in 0..i {
                let d = if periodic {
                    min_image(pos[j] - pos[i], &size)
                } else {
                    pos[j] - pos[i]
                };
                let sum = (radii[i] + radii[j]) * (1.0 + CLEARANCE);
                assert!(d.norm_sq() >= sum * sum, "{i} and {j} overlap");
            }
        }
    }

    #[test]
    fn placed_balls_never_overlap() {
        for periodic in [false, true] {
            check::<2>(400, (0.5, 0.5), 25.0, periodic, 1);
            check::<2>(300, (0.1, 0.9), 30.0, periodic, 2);
            check::<2>(50, (1e-3, 1e-3), 1.0, periodic, 3);
            check::<3>(300, (0.5, 0.5), 9.0, periodic, 4);
            check::<3>(200, (0.2, 0.7), 10.0, periodic, 5);
            check::<3>(1, (0.5, 0.5), 2.0, periodic, 6);
        }
    }

    #[test]
    fn a_box_too_full_is_refused_and_a_ball_too_large_for_it_too() {
        let mut rng = ChaCha8Rng::seed_from_u64(7);
        let radii = vec![0.5; 200];
        assert!(matches!(
            place_balls(&radii, Vector::<2>::splat(10.0), false, &mut rng),
            Err(GenerateError::Jammed { .. })
        ));
        assert!(matches!(
            place_balls(&[2.0], Vector::<2>::splat(3.0), false, &mut rng),
            Err(GenerateError::Param { .. })
        ));
    }
}
