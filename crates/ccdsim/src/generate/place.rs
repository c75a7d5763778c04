//! Random sequential placement of non-overlapping balls in a box, with a uniform grid to find
//! neighbours.

use super::GenerateError;
use crate::geom::Vector;
use rand::Rng;
use std::collections::HashMap;

/// Relative clearance kept between bodies and from the walls, so that rounding never makes a
/// freshly placed scene overlap.
pub(crate) const CLEARANCE: f64 = 1e-9;

/// Places balls of the given radii uniformly at random inside the box `[0, size]`, none
/// overlapping another or a wall, larger balls first. Returns the centres in the order of
/// `radii`, or [`GenerateError::Jammed`] after `1000·n + 100000` failed attempts.
pub(crate) fn place_balls<const D: usize, R: Rng>(
    radii: &[f64],
    size: Vector<D>,
    rng: &mut R,
) -> Result<Vec<Vector<D>>, GenerateError> {
    let n = radii.len();
    let r_max = radii.iter().copied().fold(0.0, f64::max);
    // Larger bodies first: they are the hardest to fit.
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by(|&a, &b| radii[b].total_cmp(&radii[a]));
    let cell = (2.0 * r_max).max(f64::MIN_POSITIVE);
    let key = |p: Vector<D>| p.0.map(|x| (x / cell).floor() as i64);
    let mut grid: HashMap<[i64; D], Vec<usize>> = HashMap::with_capacity(n);
    let mut pos = vec![Vector::<D>::ZERO; n];
    let mut attempts: u64 = 0;
    let max_attempts = 1000 * n as u64 + 100_000;
    for (placed, &i) in order.iter().enumerate() {
        let r = radii[i];
        let margin = r * (1.0 + CLEARANCE);
        if (0..D).any(|k| 2.0 * margin > size[k]) {
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
                p[k] = rng.random_range(margin..=size[k] - margin);
            }
            let k = key(p);
            let free = (0..3usize.pow(D as u32)).all(|code| {
                let mut nk = k;
                let mut c = code;
                for slot in nk.iter_mut() {
                    *slot += (c % 3) as i64 - 1;
                    c /= 3;
                }
                grid.get(&nk).is_none_or(|list| {
                    list.iter().all(|&j| {
                        let sum = (r + radii[j]) * (1.0 + CLEARANCE);
                        (pos[j] - p).norm_sq() >= sum * sum
                    })
                })
            });
            if free {
                pos[i] = p;
                grid.entry(k).or_default().push(i);
                break;
            }
        }
    }
    Ok(pos)
}
