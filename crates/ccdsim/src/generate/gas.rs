//! Random gases of non-overlapping bodies in a walled box.

use super::{box_walls, random_direction, GenerateError};
use crate::geom::{ball_volume, Vector};
use crate::scene::{BodySpec, Scene};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::collections::HashMap;

/// Parameters of [`gas`].
#[derive(Clone, Debug, PartialEq)]
pub struct GasConfig {
    /// Number of bodies.
    pub n: usize,
    /// Fraction of the box's area (2D) or volume (3D) covered by bodies, in `(0, 1)`.
    pub packing: f64,
    /// Radii are uniform in `[radius_min, radius_max]`, metres.
    pub radius_min: f64,
    /// See `radius_min`.
    pub radius_max: f64,
    /// Speeds are uniform in `[speed_min, speed_max]`, metres per second; directions uniform.
    pub speed_min: f64,
    /// See `speed_min`.
    pub speed_max: f64,
    /// Seed of the random generator (ChaCha8, so scenes are the same on every platform).
    pub seed: u64,
    /// A periodic box (no walls) instead of a walled one.
    pub periodic: bool,
}

impl Default for GasConfig {
    fn default() -> Self {
        GasConfig {
            n: 1000,
            packing: 0.2,
            radius_min: 0.5,
            radius_max: 0.5,
            speed_min: 0.0,
            speed_max: 1.0,
            seed: 1,
            periodic: false,
        }
    }
}

/// A cubic (square) box with walls, or a periodic one, holding `n` random non-overlapping
/// bodies at the given packing fraction. The box side is chosen from the bodies' volume.
pub fn gas<const D: usize>(cfg: &GasConfig) -> Result<Scene<D>, GenerateError> {
    let bad = |param, why: &str| {
        Err(GenerateError::Param {
            param,
            why: why.to_string(),
        })
    };
    if !(cfg.packing > 0.0 && cfg.packing < 1.0) {
        return bad("packing", "must be in (0, 1)");
    }
    if !(cfg.radius_min > 0.0 && cfg.radius_min <= cfg.radius_max && cfg.radius_max.is_finite()) {
        return bad("radius", "need 0 < radius_min ≤ radius_max");
    }
    if !(cfg.speed_min >= 0.0 && cfg.speed_min <= cfg.speed_max && cfg.speed_max.is_finite()) {
        return bad("speed", "need 0 ≤ speed_min ≤ speed_max");
    }
    let mut rng = ChaCha8Rng::seed_from_u64(cfg.seed);
    let radii: Vec<f64> = (0..cfg.n)
        .map(|_| rng.random_range(cfg.radius_min..=cfg.radius_max))
        .collect();
    let volume: f64 = radii.iter().map(|&r| ball_volume::<D>(r)).sum();
    let side = (volume / cfg.packing)
        .powf(1.0 / D as f64)
        .max(2.0 * cfg.radius_max * 1.000001);
    let size = Vector::<D>::splat(side);
    if cfg.periodic && side <= 4.0 * cfg.radius_max {
        return bad(
            "packing",
            "a periodic box must be wider than 4·radius_max: use more bodies or a lower packing",
        );
    }
    // Larger bodies first: they are the hardest to fit.
    let mut order: Vec<usize> = (0..cfg.n).collect();
    order.sort_by(|&a, &b| radii[b].total_cmp(&radii[a]));
    // Cells at least 2·r_max wide; in a periodic box they tile it and keys wrap around.
    let cells = ((side / (2.0 * cfg.radius_max)).floor() as i64).max(1);
    let cell = if cfg.periodic {
        side / cells as f64
    } else {
        2.0 * cfg.radius_max
    };
    let wrap = |k: i64| if cfg.periodic { k.rem_euclid(cells) } else { k };
    let key = |p: Vector<D>| p.0.map(|x| wrap((x / cell).floor() as i64));
    let mut grid: HashMap<[i64; D], Vec<usize>> = HashMap::new();
    let mut pos = vec![Vector::<D>::ZERO; cfg.n];
    let mut attempts: u64 = 0;
    let max_attempts = 1000 * cfg.n as u64 + 100_000;
    for (placed, &i) in order.iter().enumerate() {
        let r = radii[i];
        loop {
            attempts += 1;
            if attempts > max_attempts {
                return Err(GenerateError::Jammed {
                    placed,
                    n: cfg.n,
                    attempts,
                });
            }
            let mut p = Vector::<D>::ZERO;
            for k in 0..D {
                p[k] = if cfg.periodic {
                    rng.random_range(0.0..side)
                } else {
                    // A hair of clearance keeps rounding from putting a body into a wall.
                    rng.random_range(r * (1.0 + 1e-9)..=side - r * (1.0 + 1e-9))
                };
            }
            let k = key(p);
            let mut free = true;
            'scan: for code in 0..3usize.pow(D as u32) {
                let mut nk = k;
                let mut c = code;
                for slot in nk.iter_mut() {
                    *slot = wrap(*slot + (c % 3) as i64 - 1);
                    c /= 3;
                }
                if let Some(list) = grid.get(&nk) {
                    for &j in list {
                        let sum = (r + radii[j]) * (1.0 + 1e-9);
                        let dp = if cfg.periodic {
                            crate::periodic::min_image(pos[j] - p, &size)
                        } else {
                            pos[j] - p
                        };
                        if dp.norm_sq() < sum * sum {
                            free = false;
                            break 'scan;
                        }
                    }
                }
            }
            if free {
                pos[i] = p;
                grid.entry(k).or_default().push(i);
                break;
            }
        }
    }
    let bodies = (0..cfg.n)
        .map(|i| {
            let speed = rng.random_range(cfg.speed_min..=cfg.speed_max);
            let dir: Vector<D> = random_direction(&mut rng);
            BodySpec::new(pos[i], dir * speed, radii[i])
        })
        .collect();
    if cfg.periodic {
        return Ok(Scene {
            bodies,
            periodic: Some(size),
            ..Scene::default()
        });
    }
    Ok(Scene {
        bodies,
        walls: box_walls(size),
        ..Scene::default()
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn gas_is_valid_and_deterministic() {
        let cfg = GasConfig {
            n: 300,
            packing: 0.3,
            radius_min: 0.3,
            radius_max: 0.7,
            seed: 7,
            ..GasConfig::default()
        };
        let a: Scene<2> = gas(&cfg).unwrap();
        a.validate().unwrap();
        assert_eq!(a, gas(&cfg).unwrap());
        let b: Scene<3> = gas(&GasConfig {
            n: 200,
            ..cfg.clone()
        })
        .unwrap();
        b.validate().unwrap();
        assert_eq!(b.walls.len(), 6);
        let covered: f64 = a.bodies.iter().map(|b| ball_volume::<2>(b.radius)).sum();
        let crate::scene::Wall::Segment { b: corner, .. } = a.walls[0] else {
            panic!()
        };
        assert!((covered / (corner[0] * corner[0]) - 0.3).abs() < 1e-9);
    }

    #[test]
    fn refuses_bad_parameters() {
        assert!(gas::<2>(&GasConfig {
            packing: 1.5,
            ..GasConfig::default()
        })
        .is_err());
        assert!(gas::<2>(&GasConfig {
            radius_min: 2.0,
            radius_max: 1.0,
            ..GasConfig::default()
        })
        .is_err());
        assert!(matches!(
            gas::<2>(&GasConfig {
                packing: 0.85,
                n: 400,
                ..GasConfig::default()
            }),
            Err(GenerateError::Jammed { .. })
        ));
    }
}
