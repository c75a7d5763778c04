//! A peg board under gravity (2D): balls dropped through staggered rows of short pegs into a
//! walled box, the scene that exercises every contact gravity brings (floors, the pegs' faces
//! and their end points, balls meeting in flight).

use super::{box_walls, GenerateError};
use crate::geom::Vector;
use crate::motion::Gravity;
use crate::scene::{BodySpec, Scene};
use crate::sensor::Sensor;
use crate::wall::Wall;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// Parameters of [`pegs`].
#[derive(Clone, Debug, PartialEq)]
pub struct PegsConfig {
    /// Rows of pegs.
    pub rows: usize,
    /// Balls, dropped from above the pegs in rows of up to 16.
    pub balls: usize,
    /// Ball radius, metres.
    pub radius: f64,
    /// Gravity, metres per second squared (downwards is −y).
    pub gravity: f64,
    /// Coefficient of restitution of every collision.
    pub restitution: f64,
    /// Bins along the floor: sensors (see [`crate::sensor`]) that count the balls landing in
    /// them (for a Galton board see [`super::galton`]). Bin `k` is a disc centred on the floor under the
    /// `k`-th of `bins` equal stretches of it, its radius half the stretch less a ball's: a
    /// ball touches it when its centre is within half a stretch of the disc's, so a ball on
    /// the floor lies in exactly one bin. 0: no sensors.
    pub bins: usize,
    /// Random seed of the balls' small sideways speeds.
    pub seed: u64,
}

impl Default for PegsConfig {
    fn default() -> Self {
        PegsConfig {
            rows: 6,
            balls: 48,
            radius: 0.25,
            gravity: 9.81,
            restitution: 1.0,
            bins: 0,
            seed: 1,
        }
    }
}

/// The board: a box 12 m wide, `rows` rows of pegs 1.5 m apart (each peg a segment 0.4 m
/// long, slightly tilted so that no ball lands on a flat top at rest), the balls above them
/// moving sideways at up to 0.5 m/s, and gravity `−gravity` along y. With a restitution
/// below 1 the scene sets the TC model's `tc` to 1 ms (see [`crate::scene::Settings::tc`]).
pub fn pegs(cfg: &PegsConfig) -> Result<Scene<2>, GenerateError> {
    let bad = |param: &'static str, why: &str| {
        Err(GenerateError::Param {
            param,
            why: why.into(),
        })
    };
    if !(cfg.radius > 0.0 && cfg.radius <= 0.3) {
        return bad("radius", "must be in (0, 0.3] m to fit between the pegs");
    }
    if !(cfg.gravity.is_finite() && cfg.gravity > 0.0) {
        return bad("gravity", "must be a positive number");
    }
    if cfg.rows > 1000 || cfg.balls > 100_000 {
        return bad("rows", "at most 1000 rows and 100000 balls");
    }
    if cfg.bins > 100 || 12.0 / cfg.bins.max(1) as f64 <= 2.0 * cfg.radius {
        return bad("bins", "at most 100 bins, each wider than a ball");
    }
    let width = 12.0;
    let top = 3.0 + 1.5 * cfg.rows as f64;
    let ball_rows = cfg.balls.div_ceil(16);
    let height = top + 2.0 + 0.7 * ball_rows as f64;
    let mut walls = box_walls(Vector([width, height]));
    for row in 0..cfg.rows {
        let y = 3.0 + 1.5 * row as f64;
        let mut x = if row % 2 == 0 { 1.0 } else { 1.75 };
        while x < width - 1.0 {
            walls.push(Wall::Segment {
                a: Vector([x - 0.2, y]),
                b: Vector([x + 0.2, y + 0.1]),
            });
            x += 1.5;
        }
    }
    let mut rng = ChaCha8Rng::seed_from_u64(cfg.seed);
    let bodies = (0..cfg.balls)
        .map(|k| {
            let x = 0.6 + (k % 16) as f64 * 0.68 + rng.random_range(0.0..0.05);
            let y = top + 1.0 + 0.7 * (k / 16) as f64;
            let vx = rng.random_range(-0.5..0.5);
            BodySpec::new(Vector([x, y]), Vector([vx, 0.0]), cfg.radius)
        })
        .collect();
    let bin = width / cfg.bins.max(1) as f64;
    let sensors = (0..cfg.bins)
        .map(|k| Sensor {
            center: Vector([(k as f64 + 0.5) * bin, 0.0]),
            radius: 0.5 * bin - cfg.radius,
        })
        .collect();
    let mut scene = Scene {
        bodies,
        walls,
        sensors,
        ..Scene::default()
    };
    scene.settings.restitution = cfg.restitution;
    // Inelastic balls would bounce ever lower, in ever shorter intervals, on pegs and floor:
    // the TC model keeps bounces under a millisecond apart elastic.
    if cfg.restitution < 1.0 {
        scene.settings.tc = Some(1e-3);
    }
    scene.settings.gravity = Gravity::new(&[0.0, -cfg.gravity]);
    scene.validate().map_err(|e| GenerateError::Param {
        param: "restitution",
        why: e.to_string(),
    })?;
    Ok(scene)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Simulation;

    #[test]
    fn balls_fall_through_the_pegs_and_stay_in_the_box() {
        let scene = pegs(&PegsConfig::default()).unwrap();
        let mut sim = Simulation::new(&scene, "cells").unwrap();
        sim.run_until(3.0);
        assert!(sim.stats().wall_collisions > 50, "{:?}", sim.stats());
        assert!(sim.stats().max_overlap <= 1e-9);
        for i in 0..sim.world().len() {
            let p = sim.position(i);
            assert!(p[0] > 0.0 && p[0] < 12.0 && p[1] > 0.0, "ball {i} at {p:?}");
        }
    }

    #[test]
    fn inelastic_boards_keep_running_under_the_tc_model() {
        let scene = pegs(&PegsConfig {
            restitution: 0.6,
            balls: 16,
            rows: 3,
            ..PegsConfig::default()
        })
        .unwrap();
        assert_eq!(scene.settings.tc, Some(1e-3));
        let mut sim = Simulation::new(&scene, "cells").unwrap();
        // Long enough for balls to land on the floor and settle into bouncing at the TC
        // model's limit (each bounce then comes about 1 ms after the last).
        sim.run_until(4.0);
        assert_eq!(sim.halt(), None);
        assert_eq!(sim.time(), 4.0);
        assert!(sim.stats().max_overlap <= 1e-9);
    }

    #[test]
    fn bins_count_the_balls_that_land_in_them() {
        let scene = pegs(&PegsConfig {
            rows: 3,
            balls: 32,
            bins: 4,
            restitution: 0.5,
            ..PegsConfig::default()
        })
        .unwrap();
        assert_eq!(scene.sensors.len(), 4);
        let mut sim = Simulation::new(&scene, "cells").unwrap();
        sim.run_until(8.0);
        // Inelastic balls come to bounce low on the floor, each in exactly one bin.
        let tracker = sim.sensors().unwrap();
        for i in 0..32 {
            let bins: Vec<usize> = (0..4).filter(|&k| tracker.is_inside(i, k)).collect();
            assert_eq!(
                bins.len(),
                1,
                "ball {i} at {:?} in bins {bins:?}",
                sim.position(i)
            );
        }
    }

    #[test]
    fn bad_parameters_are_refused() {
        for cfg in [
            PegsConfig {
                radius: 0.5,
                ..PegsConfig::default()
            },
            PegsConfig {
                gravity: f64::NAN,
                ..PegsConfig::default()
            },
            PegsConfig {
                restitution: 1.5,
                ..PegsConfig::default()
            },
        ] {
            assert!(pegs(&cfg).is_err(), "{cfg:?}");
        }
    }
}
