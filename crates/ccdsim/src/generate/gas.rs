//! Gases of non-overlapping bodies in a walled or periodic box: random or lattice starts,
//! uniform-speed or Maxwell velocities.

use super::place::place_balls;
use super::{box_walls, random_direction, GenerateError, Lattice};
use crate::geom::{ball_volume, Vector};
use crate::scene::{BodySpec, Scene, MAX_MAGNITUDE};

/// The smallest radius [`gas`] takes, metres: its mass `r^D` stays far above underflow.
const MIN_RADIUS: f64 = 1e-30;
/// The largest radius [`gas`] takes, metres: its mass `r^D` and the box stay far inside `f64`.
const MAX_RADIUS: f64 = 1e30;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rand_distr::StandardNormal;

/// Parameters of [`gas`]. The defaults of the fields added after the first release
/// (`periodic`, `lattice`, `temperature`) keep the original behaviour.
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
    /// Ignored when `temperature` is set.
    pub speed_min: f64,
    /// See `speed_min`.
    pub speed_max: f64,
    /// Seed of the random generator (ChaCha8, so scenes are the same on every platform).
    pub seed: u64,
    /// A periodic box (no walls) instead of a walled one.
    pub periodic: bool,
    /// Start on a lattice instead of at random positions (needed for dense packings, where
    /// random placement jams). The box takes the lattice's shape (the hexagonal one is not
    /// square).
    pub lattice: Option<Lattice>,
    /// Maxwell–Boltzmann velocities at this temperature `kT` (joules, k = 1; masses are the
    /// bodies' unit-density masses) with zero total momentum, scaled so that the kinetic
    /// temperature `2K / (D N)` is exactly `kT`; instead of uniform speeds.
    pub temperature: Option<f64>,
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
            lattice: None,
            temperature: None,
        }
    }
}

fn bad<T>(param: &'static str, why: &str) -> Result<T, GenerateError> {
    Err(GenerateError::Param {
        param,
        why: why.to_string(),
    })
}

/// A box with walls, or a periodic one, holding `n` non-overlapping bodies at the given
/// packing fraction, at random positions or on a lattice. The box's volume is the bodies'
/// volume over the packing fraction; it is a cube (square) for random starts.
pub fn gas<const D: usize>(cfg: &GasConfig) -> Result<Scene<D>, GenerateError> {
    if !(cfg.packing > 0.0 && cfg.packing < 1.0) {
        return bad("packing", "must be in (0, 1)");
    }
    if !(cfg.radius_min > 0.0 && cfg.radius_min <= cfg.radius_max && cfg.radius_max.is_finite()) {
        return bad("radius", "need 0 < radius_min ≤ radius_max");
    }
    if cfg.lattice.is_none() {
        check_random_packing::<D>(cfg)?;
    } else if cfg.packing > densest_lattice_packing::<D>() {
        return Err(GenerateError::Param {
            param: "packing",
            why: format!(
                "{} is denser than any lattice of discs (spheres) can be: at most {} in {D}D",
                cfg.packing,
                densest_lattice_packing::<D>()
            ),
        });
    }
    if !(cfg.speed_min >= 0.0 && cfg.speed_min <= cfg.speed_max && cfg.speed_max.is_finite()) {
        return bad("speed", "need 0 ≤ speed_min ≤ speed_max");
    }
    if cfg
        .temperature
        .is_some_and(|t| !(t.is_finite() && t >= 0.0))
    {
        return bad("temperature", "must be finite and ≥ 0");
    }
    // Within what f64 can simulate (see `scene::MAX_MAGNITUDE`): masses are volumes `r^D`,
    // so radii stay within 1e±30; speeds and temperatures within the largest magnitude.
    if !(MIN_RADIUS..=MAX_RADIUS).contains(&cfg.radius_min)
        || !(MIN_RADIUS..=MAX_RADIUS).contains(&cfg.radius_max)
    {
        return bad("radius", "radii must lie in [1e-30, 1e30] m");
    }
    if cfg.speed_max > MAX_MAGNITUDE {
        return bad("speed", "speeds must stay within 1e100 m/s");
    }
    if cfg.temperature.is_some_and(|t| t > MAX_MAGNITUDE) {
        return bad("temperature", "must stay within 1e100");
    }
    let mut rng = ChaCha8Rng::seed_from_u64(cfg.seed);
    let radii: Vec<f64> = (0..cfg.n)
        .map(|_| rng.random_range(cfg.radius_min..=cfg.radius_max))
        .collect();
    let volume: f64 = radii.iter().map(|&r| ball_volume::<D>(r)).sum::<f64>() / cfg.packing;
    // The box's side against the bodies: beyond 1e15 diameters, a grid of cells a diameter
    // wide has more cells per axis than an i64 counts (and no gas is that dilute).
    let side = volume.powf(1.0 / D as f64);
    if !(side <= MAX_MAGNITUDE && side <= 1e15 * 2.0 * cfg.radius_max) {
        return bad(
            "packing",
            "too dilute: the box would be more than 1e15 diameters wide",
        );
    }
    let (size, pos) = match cfg.lattice {
        Some(lattice) => lattice_positions::<D>(cfg, lattice, volume)?,
        None => random_positions::<D>(cfg, &radii, volume, &mut rng)?,
    };
    if cfg.periodic && (0..D).any(|d| size[d] <= 4.0 * cfg.radius_max) {
        return bad(
            "packing",
            "a periodic box must be wider than 4·radius_max: use more bodies or a lower packing",
        );
    }
    let vel = match cfg.temperature {
        Some(kt) => maxwell_velocities::<D>(&radii, kt, &mut rng),
        None => (0..cfg.n)
            .map(|_| {
                let speed = rng.random_range(cfg.speed_min..=cfg.speed_max);
                let dir: Vector<D> = random_direction(&mut rng);
                dir * speed
            })
            .collect(),
    };
    let bodies = pos
        .into_iter()
        .zip(vel)
        .zip(radii)
        .map(|((p, v), r)| BodySpec::new(p, v, r))
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

/// The densest packing of equal discs (spheres) on a lattice: hexagonal in 2D, `π/(2√3) ≈
/// 0.9069`; face-centred cubic in 3D, `π/(3√2) ≈ 0.7405`.
#[must_use]
pub fn densest_lattice_packing<const D: usize>() -> f64 {
    if D == 2 {
        std::f64::consts::PI / (2.0 * 3f64.sqrt())
    } else {
        std::f64::consts::PI / (3.0 * 2f64.sqrt())
    }
}

/// The densest packing that random placement of equal discs (spheres) reaches: random
/// sequential addition, which [`gas`] does (each body at a uniformly random free position, never
/// moved again), jams at the saturation coverage `0.5472` in 2D (Hinrichsen, Feder & Jøssang
/// 1986) and `0.3841` in 3D (Talbot, Schaaf & Tarjus 1991); past it no free position is left
/// for the next body, and the approach to it is slow (the coverage missing falls as
/// `attempts^(−1/D)`). Walls lower it further (bodies keep a radius from them).
#[must_use]
pub fn random_packing_limit<const D: usize>() -> f64 {
    if D == 2 {
        0.5472
    } else {
        0.3841
    }
}

/// Refuses, at once, a packing that random placement of equal bodies cannot reach (instead of
/// spending its whole budget of attempts first: minutes for 10⁵ bodies). Mixed radii are left to
/// the attempt budget: placed largest first, they jam later.
fn check_random_packing<const D: usize>(cfg: &GasConfig) -> Result<(), GenerateError> {
    let limit = random_packing_limit::<D>();
    if cfg.radius_min == cfg.radius_max && cfg.packing > limit {
        return Err(GenerateError::Param {
            param: "packing",
            why: format!(
                "{} is beyond what random placement reaches ({limit} in {D}D, where it jams, and \
                 less in practice): start on a lattice (`--lattice`, up to {:.4})",
                cfg.packing,
                densest_lattice_packing::<D>()
            ),
        });
    }
    Ok(())
}

/// Positions on a lattice filling a box of the given volume: in a periodic box the lattice
/// tiles it; in a walled box it is stretched to keep `radius_max` from the walls.
fn lattice_positions<const D: usize>(
    cfg: &GasConfig,
    lattice: Lattice,
    volume: f64,
) -> Result<(Vector<D>, Vec<Vector<D>>), GenerateError> {
    let sites = lattice.sites::<D>(cfg.n)?;
    let spacing = (volume / sites.shape.iter().product::<f64>()).powf(1.0 / D as f64);
    let size = Vector(sites.shape.map(|s| s * spacing));
    let need = 2.0 * cfg.radius_max * (1.0 + 1e-9);
    let too_dense = || {
        bad(
            "packing",
            "too dense for this lattice and these radii (neighbours would overlap)",
        )
    };
    if cfg.periodic {
        if sites.nearest * spacing < need {
            return too_dense();
        }
        let pos = sites
            .points
            .iter()
            .map(|p| Vector(std::array::from_fn(|d| p[d] * size[d])))
            .collect();
        return Ok((size, pos));
    }
    let margin = cfg.radius_max * (1.0 + 1e-9);
    let (mut lo, mut hi) = ([f64::INFINITY; D], [f64::NEG_INFINITY; D]);
    for p in &sites.points {
        for d in 0..D {
            lo[d] = lo[d].min(p[d]);
            hi[d] = hi[d].max(p[d]);
        }
    }
    // Fractional extent of the sites along each axis mapped onto [margin, L − margin]; the
    // nearest distance shrinks at most by the smallest of these stretches.
    let mut stretch = f64::INFINITY;
    let mut scale = [0.0; D];
    for d in 0..D {
        let span = hi[d] - lo[d];
        scale[d] = if span > 0.0 {
            (size[d] - 2.0 * margin) / span
        } else {
            0.0
        };
        if span > 0.0 {
            stretch = stretch.min(scale[d] / size[d]);
        }
    }
    if size.0.iter().any(|&s| s <= 2.0 * margin)
        || (stretch.is_finite() && sites.nearest * spacing * stretch < need)
    {
        return too_dense();
    }
    let pos = sites
        .points
        .iter()
        .map(|p| {
            Vector(std::array::from_fn(|d| {
                if scale[d] > 0.0 {
                    margin + (p[d] - lo[d]) * scale[d]
                } else {
                    0.5 * size[d]
                }
            }))
        })
        .collect();
    Ok((size, pos))
}

/// Random sequential placement in a cubic box of the given volume (see [`place_balls`]).
fn random_positions<const D: usize>(
    cfg: &GasConfig,
    radii: &[f64],
    volume: f64,
    rng: &mut ChaCha8Rng,
) -> Result<(Vector<D>, Vec<Vector<D>>), GenerateError> {
    let side = volume
        .powf(1.0 / D as f64)
        .max(2.0 * cfg.radius_max * 1.000001);
    let size = Vector::<D>::splat(side);
    Ok((size, place_balls(radii, size, cfg.periodic, rng)?))
}

/// Maxwell–Boltzmann velocities at temperature `kt` for unit-density bodies of the given
/// radii, with zero total momentum and kinetic temperature exactly `kt` (up to rounding).
fn maxwell_velocities<const D: usize>(
    radii: &[f64],
    kt: f64,
    rng: &mut ChaCha8Rng,
) -> Vec<Vector<D>> {
    let mass: Vec<f64> = radii.iter().map(|&r| ball_volume::<D>(r)).collect();
    let mut vel: Vec<Vector<D>> = mass
        .iter()
        .map(|&m| {
            let s = (kt / m).sqrt();
            Vector(std::array::from_fn(|_| {
                rng.sample::<f64, _>(StandardNormal) * s
            }))
        })
        .collect();
    let total: f64 = mass.iter().sum();
    let momentum = vel
        .iter()
        .zip(&mass)
        .fold(Vector::<D>::ZERO, |acc, (v, &m)| acc + *v * m);
    let drift = momentum * (1.0 / total.max(f64::MIN_POSITIVE));
    let mut kinetic = 0.0;
    for (v, &m) in vel.iter_mut().zip(&mass) {
        *v -= drift;
        kinetic += 0.5 * m * v.norm_sq();
    }
    let now = 2.0 * kinetic / (D as f64 * radii.len().max(1) as f64);
    if now > 0.0 {
        let scale = (kt / now).sqrt();
        for v in &mut vel {
            *v = *v * scale;
        }
    }
    vel
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
        let crate::wall::Wall::Segment { b: corner, .. } = a.walls[0] else {
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
        // Below the saturation coverage but beyond what the attempt budget reaches in a small
        // walled box: random placement tries and gives up.
        assert!(matches!(
            gas::<2>(&GasConfig {
                packing: 0.54,
                n: 400,
                ..GasConfig::default()
            }),
            Err(GenerateError::Jammed { .. })
        ));
    }

    #[test]
    fn options_beyond_f64_are_refused() {
        for (cfg, param) in [
            (
                GasConfig {
                    radius_min: 1e-40,
                    ..GasConfig::default()
                },
                "radius",
            ),
            (
                GasConfig {
                    radius_min: 1e40,
                    radius_max: 1e40,
                    ..GasConfig::default()
                },
                "radius",
            ),
            (
                GasConfig {
                    speed_max: 1e200,
                    ..GasConfig::default()
                },
                "speed",
            ),
            (
                GasConfig {
                    temperature: Some(1e300),
                    ..GasConfig::default()
                },
                "temperature",
            ),
            (
                GasConfig {
                    n: 10,
                    packing: 1e-250,
                    ..GasConfig::default()
                },
                "packing",
            ),
        ] {
            match gas::<2>(&cfg) {
                Err(GenerateError::Param { param: p, .. }) => assert_eq!(p, param),
                other => panic!("{param}: {other:?}"),
            }
        }
        // The largest allowed options make a scene that validates.
        let s: Scene<3> = gas(&GasConfig {
            n: 50,
            radius_min: 1e30,
            radius_max: 1e30,
            speed_max: 1e100,
            ..GasConfig::default()
        })
        .unwrap();
        s.validate().unwrap();
    }

    #[test]
    fn packings_beyond_reach_are_refused_at_once() {
        let start = std::time::Instant::now();
        for packing in [0.55, 0.85, 0.95] {
            let e = gas::<2>(&GasConfig {
                packing,
                n: 100_000,
                ..GasConfig::default()
            })
            .unwrap_err();
            let GenerateError::Param { param, why } = &e else {
                panic!("{e}")
            };
            assert_eq!(*param, "packing");
            assert!(why.contains("--lattice") && why.contains("0.5472"), "{why}");
        }
        let e = gas::<3>(&GasConfig {
            packing: 0.4,
            n: 100_000,
            ..GasConfig::default()
        })
        .unwrap_err();
        assert!(e.to_string().contains("0.3841"), "{e}");
        // Lattices reach further, up to the densest packing and no further.
        for (packing, ok) in [(0.9, true), (0.91, false), (0.95, false)] {
            let r = gas::<2>(&GasConfig {
                packing,
                n: 100,
                periodic: true,
                lattice: Some(Lattice::Densest),
                ..GasConfig::default()
            });
            assert_eq!(r.is_ok(), ok, "{packing}: {r:?}");
        }
        let e = gas::<3>(&GasConfig {
            packing: 0.75,
            lattice: Some(Lattice::Densest),
            ..GasConfig::default()
        })
        .unwrap_err();
        assert!(e.to_string().contains("0.7404"), "{e}");
        // Refusals come before any body is placed: no budget of 10⁸ attempts spent first.
        assert!(start.elapsed() < std::time::Duration::from_secs(5));
    }
}

#[cfg(test)]
mod lattice_tests {
    use super::*;
    use crate::world::World;

    #[test]
    fn dense_periodic_lattices_with_maxwell_velocities() {
        let cfg = GasConfig {
            n: 10_000,
            packing: 0.5,
            periodic: true,
            lattice: Some(Lattice::Densest),
            temperature: Some(1.0),
            ..GasConfig::default()
        };
        let s: Scene<2> = gas(&cfg).unwrap();
        s.validate().unwrap();
        assert_eq!(s.bodies.len(), 10_000);
        let size = s.periodic.unwrap();
        let covered: f64 = s.bodies.iter().map(|b| ball_volume::<2>(b.radius)).sum();
        assert!((covered / (size[0] * size[1]) - 0.5).abs() < 1e-12);
        let w = World::from_scene(&s).unwrap();
        assert!(w.momentum().norm() < 1e-9);
        assert!((crate::observables::temperature(&w) - 1.0).abs() < 1e-12);
        let cfg3 = GasConfig {
            n: 10_976,
            packing: 0.45,
            ..cfg.clone()
        };
        let s: Scene<3> = gas(&cfg3).unwrap();
        s.validate().unwrap();
        let size = s.periodic.unwrap();
        assert_eq!(size[0], size[1]);
        let covered: f64 = s.bodies.iter().map(|b| ball_volume::<3>(b.radius)).sum();
        assert!((covered / (size[0] * size[1] * size[2]) - 0.45).abs() < 1e-12);
        // Beyond close packing the lattice refuses.
        assert!(gas::<3>(&GasConfig {
            n: 500,
            packing: 0.75,
            ..cfg3
        })
        .is_err());
    }

    #[test]
    fn walled_and_polydisperse_lattices() {
        for lattice in [Lattice::Hexagonal, Lattice::Square] {
            let s: Scene<2> = gas(&GasConfig {
                n: 500,
                packing: 0.5,
                radius_min: 0.4,
                radius_max: 0.5,
                lattice: Some(lattice),
                ..GasConfig::default()
            })
            .unwrap();
            s.validate().unwrap();
            assert_eq!(s.walls.len(), 4);
        }
        for lattice in [Lattice::Fcc, Lattice::Cubic] {
            let s: Scene<3> = gas(&GasConfig {
                n: 300,
                packing: 0.3,
                lattice: Some(lattice),
                temperature: Some(2.0),
                ..GasConfig::default()
            })
            .unwrap();
            s.validate().unwrap();
        }
        assert!(gas::<2>(&GasConfig {
            lattice: Some(Lattice::Fcc),
            ..GasConfig::default()
        })
        .is_err());
    }
}
