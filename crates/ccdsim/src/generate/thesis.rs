//! The benchmark scene of the thesis's §5.2: a walled rectangular table whose size grows with the
//! number of bodies so that their density stays constant, random radii, and random velocities
//! whose fastest crosses the table's diagonal in one second.
//!
//! The thesis does not give its constants. Ours are calibrated so that the number of collisions
//! (body–body plus body–wall) in 5 simulated seconds matches its Table 5.1 within ±10 % for
//! n = 64 … 2048; see `docs/benchmarks.md` for the method and the resulting table.

use super::place::place_balls;
use super::{box_walls, random_direction, GenerateError};
use crate::geom::Vector;
use crate::scene::{BodySpec, Scene};
use crate::wall::Wall;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// Parameters of [`thesis`]. [`ThesisConfig::default`] holds the calibrated constants.
#[derive(Clone, Debug, PartialEq)]
pub struct ThesisConfig {
    /// Number of bodies.
    pub n: usize,
    /// Seed of the random generator (ChaCha8, so scenes are the same on every platform).
    pub seed: u64,
    /// Bodies per unit of table area (2D, m⁻²) or volume (3D, m⁻³); the table is sized so that
    /// `n / area` is exactly this, whatever `n`.
    pub density: f64,
    /// Radii are uniform in `[radius_min, radius_max]`, metres.
    pub radius_min: f64,
    /// See `radius_min`.
    pub radius_max: f64,
    /// Speeds are uniform in `[slowest · v_max, v_max]` with uniformly random directions, where
    /// `v_max` crosses the table's diagonal in `crossing_time`; in `[0, 1]`.
    pub slowest: f64,
    /// Time the fastest possible body takes to cross the table's diagonal, seconds (thesis: 1).
    pub crossing_time: f64,
    /// Table length over width (a billiard table is 2); in 3D the box is
    /// `aspect · w × w × w`.
    pub aspect: f64,
    /// In 2D, each side of the table is this many collinear segments of equal length (1: the
    /// thesis's four walls; more make a table of many walls with the same bodies, to measure
    /// what walls cost a finder). 3D tables are planes and need 1.
    pub wall_pieces: usize,
}

/// The thesis's Table 5.1: number of bodies, mean number of collisions in 5 simulated seconds,
/// and mean running times in seconds of the all-pairs check and of the thesis's broad phase
/// (Intel i7-2630QM, 100 runs each, 10 at n = 2048).
pub const THESIS_TABLE_5_1: [(usize, f64, f64, f64); 9] = [
    (8, 52.28, 0.000193307, 0.000337453),
    (16, 213.15, 0.001134925, 0.000512313),
    (32, 628.46, 0.009495239, 0.005448446),
    (64, 1700.78, 0.091004501, 0.032925012),
    (128, 4670.91, 1.009229282, 0.172442404),
    (256, 12138.45, 9.716522560, 1.101287737),
    (512, 33332.82, 105.5300373, 6.773387463),
    (1024, 89060.59, 1273.946865, 46.33965052),
    (2048, 246636.2, 13085.64345, 264.8951511),
];

/// The thesis's Table 5.2 at n = 1024: time step (`None` for the continuous method), mean
/// running time in seconds and mean number of missed collisions.
pub const THESIS_TABLE_5_2: [(Option<f64>, f64, f64); 7] = [
    (None, 46.33965052, 0.0),
    (Some(0.001), 236.7274949, 0.17),
    (Some(0.005), 57.51156817, 1.93),
    (Some(0.01), 29.52776001, 32.87),
    (Some(0.03), 13.82739977, 156.06),
    (Some(0.1), 5.480592384, 3416.14),
    (Some(1.0), 1.893161469, 87281.33),
];

/// Largest [`ThesisConfig::wall_pieces`].
pub const MAX_WALL_PIECES: usize = 1_000_000;

/// Simulated duration of every thesis benchmark run, seconds.
pub const THESIS_DURATION: f64 = 5.0;

impl Default for ThesisConfig {
    fn default() -> Self {
        ThesisConfig {
            n: 256,
            seed: 1,
            density: 0.055,
            radius_min: 0.5,
            radius_max: 1.0,
            slowest: 0.0,
            crossing_time: 1.0,
            aspect: 2.0,
            wall_pieces: 1,
        }
    }
}

impl ThesisConfig {
    /// The default (calibrated) scene with `n` bodies and the given seed.
    #[must_use]
    pub fn new(n: usize, seed: u64) -> Self {
        ThesisConfig {
            n,
            seed,
            ..ThesisConfig::default()
        }
    }

    /// The table's extents for dimension `D`, metres: `aspect · w` along x and `w` along the
    /// other axes, with `n / volume = density`.
    #[must_use]
    pub fn table<const D: usize>(&self) -> Vector<D> {
        let volume = self.n.max(1) as f64 / self.density;
        let w = (volume / self.aspect).powf(1.0 / D as f64);
        let mut size = Vector::<D>::splat(w);
        size[0] = self.aspect * w;
        size
    }

    /// The fastest possible speed, metres per second: the table's diagonal over
    /// `crossing_time`.
    #[must_use]
    pub fn max_speed<const D: usize>(&self) -> f64 {
        self.table::<D>().norm() / self.crossing_time
    }

    fn check(&self) -> Result<(), GenerateError> {
        let bad = |param, why: &str| {
            Err(GenerateError::Param {
                param,
                why: why.to_string(),
            })
        };
        if !(self.density > 0.0 && self.density.is_finite()) {
            return bad("density", "must be positive and finite");
        }
        if !(self.radius_min > 0.0
            && self.radius_min <= self.radius_max
            && self.radius_max.is_finite())
        {
            return bad("radius", "need 0 < radius_min ≤ radius_max");
        }
        if !(0.0..=1.0).contains(&self.slowest) {
            return bad("slowest", "must be in [0, 1]");
        }
        if !(self.crossing_time > 0.0 && self.crossing_time.is_finite()) {
            return bad("crossing_time", "must be positive and finite");
        }
        if !(self.aspect >= 1.0 && self.aspect.is_finite()) {
            return bad("aspect", "must be at least 1 and finite");
        }
        if self.wall_pieces == 0 || self.wall_pieces > MAX_WALL_PIECES {
            return bad("wall_pieces", "must be in 1 ..= 1,000,000");
        }
        Ok(())
    }
}

/// The thesis benchmark scene: `n` random non-overlapping bodies on a walled table (4 segments
/// in 2D, 6 inward planes in 3D) of constant density, with speeds uniform in
/// `[slowest · v_max, v_max]` and uniform directions.
pub fn thesis<const D: usize>(cfg: &ThesisConfig) -> Result<Scene<D>, GenerateError> {
    cfg.check()?;
    if D != 2 && cfg.wall_pieces != 1 {
        return Err(GenerateError::Param {
            param: "wall_pieces",
            why: "a 3D table is six planes; only a 2D table's sides can be cut".to_string(),
        });
    }
    let mut rng = ChaCha8Rng::seed_from_u64(cfg.seed);
    let radii: Vec<f64> = (0..cfg.n)
        .map(|_| rng.random_range(cfg.radius_min..=cfg.radius_max))
        .collect();
    let size = cfg.table::<D>();
    let pos = place_balls(&radii, size, false, &mut rng)?;
    let v_max = cfg.max_speed::<D>();
    let bodies = (0..cfg.n)
        .map(|i| {
            let speed = v_max * rng.random_range(cfg.slowest..=1.0);
            let dir: Vector<D> = random_direction(&mut rng);
            BodySpec::new(pos[i], dir * speed, radii[i])
        })
        .collect();
    Ok(Scene {
        bodies,
        walls: cut_walls(box_walls(size), cfg.wall_pieces),
        ..Scene::default()
    })
}

/// Each segment of `walls` as `pieces` collinear segments of equal length, in order, the end
/// of one piece the start of the next (bit for bit) and the last ending at the segment's end.
fn cut_walls<const D: usize>(walls: Vec<Wall<D>>, pieces: usize) -> Vec<Wall<D>> {
    if pieces == 1 {
        return walls;
    }
    let point = |a: Vector<D>, b: Vector<D>, k: usize| {
        if k == pieces {
            b
        } else {
            a + (b - a) * (k as f64 / pieces as f64)
        }
    };
    walls
        .into_iter()
        .flat_map(|w| match w {
            Wall::Segment { a, b } => (0..pieces)
                .map(|k| Wall::Segment {
                    a: point(a, b, k),
                    b: point(a, b, k + 1),
                })
                .collect(),
            plane @ Wall::Plane { .. } => vec![plane],
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cut_sides_tile_the_table_with_the_same_bodies() {
        let whole = thesis::<2>(&ThesisConfig::new(50, 4)).unwrap();
        let cfg = ThesisConfig {
            wall_pieces: 7,
            ..ThesisConfig::new(50, 4)
        };
        let cut = thesis::<2>(&cfg).unwrap();
        cut.validate().unwrap();
        assert_eq!(cut.bodies, whole.bodies);
        assert_eq!(cut.walls.len(), 4 * 7);
        for (side, pieces) in whole.walls.iter().zip(cut.walls.chunks(7)) {
            let (
                Wall::Segment { a, b },
                Wall::Segment { a: first, .. },
                Wall::Segment { b: last, .. },
            ) = (side, pieces[0], pieces[6])
            else {
                panic!("2D tables have segments");
            };
            assert_eq!((first, last), (*a, *b));
            for w in pieces.windows(2) {
                let (Wall::Segment { b: end, .. }, Wall::Segment { a: start, .. }) = (w[0], w[1])
                else {
                    panic!("2D tables have segments");
                };
                assert_eq!(end, start, "pieces meet");
            }
        }
        let bad = ThesisConfig {
            wall_pieces: 0,
            ..ThesisConfig::new(50, 4)
        };
        assert!(thesis::<2>(&bad).is_err());
        assert!(thesis::<3>(&cfg).is_err(), "3D tables are planes");
    }
}
