//! A Galton board (2D): a funnel above the centre releases balls one at a time onto a
//! triangle of round pegs; below it, walled bins collect them, and the scene's
//! [`Histogram`] counts what each bin holds at the end.
//!
//! The geometry makes each row one left-or-right choice. The pegs (kinematic bodies of the
//! balls' radius, so perfectly round) stand on a triangular lattice whose gaps are 1.2 ball
//! diameters wide: a ball that passes a gap of one row lands on the peg below it and must
//! pass one of that peg's two neighbouring gaps, so after `rows` rows it is in one of
//! `rows + 1` bins, bin `k` reached by `C(rows, k)` paths. Walls along the triangle's sides
//! (behind a column of guard pegs) keep balls from going round it. Balls lose most of their
//! bounce (restitution 0.3; the TC model keeps bounces under 1 ms apart elastic, so balls
//! settling in a bin bounce on at that limit instead of collapsing) and each arrives at rest
//! at a random place across the funnel's mouth, a quarter of a second after the one before,
//! so balls rarely meet on the pegs: the counts follow the binomial distribution
//! `B(rows, 1/2)` (`docs/galton.md` tests it).

use super::GenerateError;
use crate::geom::Vector;
use crate::histogram::Histogram;
use crate::motion::Gravity;
use crate::scene::arrival::Arrival;
use crate::scene::{BodySpec, Scene};
use crate::wall::Wall;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// Parameters of [`galton`].
#[derive(Clone, Debug, PartialEq)]
pub struct GaltonConfig {
    /// Rows of pegs; the board has `rows + 1` bins.
    pub rows: usize,
    /// Balls released.
    pub balls: usize,
    /// Seconds between one ball's release and the next, at least 0.25.
    pub interval: f64,
    /// Coefficient of restitution of every collision, in `[0, 1)`.
    pub restitution: f64,
    /// Random seed of the places the balls are released at.
    pub seed: u64,
}

impl Default for GaltonConfig {
    fn default() -> Self {
        GaltonConfig {
            rows: 12,
            balls: 500,
            interval: 0.25,
            restitution: 0.3,
            seed: 1,
        }
    }
}

/// Ball radius, metres; every length of the board is a multiple of it.
const RADIUS: f64 = 0.05;
/// Distance between neighbouring pegs of a row, in radii: gaps of 2.4 radii.
const SPACING: f64 = 4.4;
/// Width of the funnel's neck, in radii: one ball at a time.
const NECK: f64 = 2.6;

/// The board of [`GaltonConfig`]: walls (floor, bins, funnel, the triangle's sides and a box
/// around it all), the pegs as kinematic bodies, the balls as arrivals, the bins as the
/// scene's histogram (along x, the bins' walls as edges), gravity 9.81 m/s² along −y and the
/// TC model at 1 ms. The last ball arrives at `(balls − 1) · interval` s; [`galton_duration`]
/// adds the time it takes to settle.
pub fn galton(cfg: &GaltonConfig) -> Result<Scene<2>, GenerateError> {
    let bad = |param: &'static str, why: &str| {
        Err(GenerateError::Param {
            param,
            why: why.into(),
        })
    };
    if !(1..=40).contains(&cfg.rows) {
        return bad("rows", "must be 1 to 40");
    }
    if !(1..=100_000).contains(&cfg.balls) {
        return bad("balls", "must be 1 to 100000");
    }
    if !(cfg.interval.is_finite() && cfg.interval >= 0.25) {
        return bad(
            "interval",
            "must be at least 0.25 s: balls released closer together meet on the pegs, and \
             the counts spread wider than the binomial",
        );
    }
    if !(0.0..1.0).contains(&cfg.restitution) {
        return bad("restitution", "must be in [0, 1): the balls must settle");
    }
    let r = RADIUS;
    let s = SPACING * r;
    let h = s * 3f64.sqrt() / 2.0;
    let rows = cfg.rows;
    let bins = rows + 1;
    let half = bins as f64 / 2.0 * s;
    // The most a bin may hold, with some to spare: the binomial's mode plus five standard
    // deviations, two balls abreast, stacked a diameter apart.
    let p_mode = binomial_mode_probability(rows);
    let n = cfg.balls as f64;
    let most = n * p_mode + 5.0 * (n * p_mode).sqrt() + 2.0;
    let bin_height = (most / 2.0).ceil() * 2.0 * r + 6.0 * r;
    // Peg rows: the last just above the bins' walls (which stop 0.2 radii below its pegs).
    let peg_radius = r;
    let y_last = bin_height + 0.2 * r + peg_radius;
    let y_top = y_last + (rows - 1) as f64 * h;
    let mut walls = vec![Wall::Segment {
        a: Vector([-half, 0.0]),
        b: Vector([half, 0.0]),
    }];
    for k in 0..=bins {
        let x = (k as f64 - bins as f64 / 2.0) * s;
        walls.push(Wall::Segment {
            a: Vector([x, 0.0]),
            b: Vector([x, bin_height]),
        });
    }
    // Row i's pegs at (j − i/2)·s, j = 0..=i, and a guard peg beyond each end.
    let mut pegs = Vec::new();
    for i in 0..rows {
        let y = y_top - i as f64 * h;
        for j in -1..=(i as i64 + 1) {
            let x = (j as f64 - i as f64 / 2.0) * s;
            pegs.push(BodySpec {
                kinematic: true,
                ..BodySpec::new(Vector([x, y]), Vector([0.0, 0.0]), peg_radius)
            });
        }
    }
    // The triangle's sides, just outside the guard pegs (0.1 radii clear of them, measured
    // across the slanted line).
    let slant = (0.5 * s / h).atan();
    let side = (peg_radius + 0.1 * r) / slant.cos();
    for sign in [-1.0, 1.0] {
        walls.push(Wall::Segment {
            a: Vector([sign * (s + side), y_top]),
            b: Vector([sign * ((rows as f64 / 2.0 + 0.5) * s + side), y_last]),
        });
    }
    // The funnel: its neck 6 radii above the top peg, 2 radii long; its sides rise at 50°
    // for 10 radii; a roof from the neck to the first guard pegs.
    let neck = NECK * r;
    let y_neck = y_top + 6.0 * r;
    let neck_top = y_neck + 2.0 * r;
    let rise = 10.0 * r;
    let spread = rise / 50f64.to_radians().tan();
    let mouth = neck_top + rise;
    for sign in [-1.0, 1.0] {
        walls.push(Wall::Segment {
            a: Vector([sign * neck / 2.0, y_neck]),
            b: Vector([sign * neck / 2.0, neck_top]),
        });
        walls.push(Wall::Segment {
            a: Vector([sign * neck / 2.0, neck_top]),
            b: Vector([sign * (neck / 2.0 + spread), mouth]),
        });
        walls.push(Wall::Segment {
            a: Vector([sign * neck / 2.0, y_neck]),
            b: Vector([sign * s, y_top + side]),
        });
    }
    // The box around it all.
    let x_box = half.max(neck / 2.0 + spread) + 10.0 * r;
    let y_box = mouth + 10.0 * r;
    for (a, b) in [
        ([-x_box, 0.0], [x_box, 0.0]),
        ([x_box, 0.0], [x_box, y_box]),
        ([x_box, y_box], [-x_box, y_box]),
        ([-x_box, y_box], [-x_box, 0.0]),
    ] {
        walls.push(Wall::Segment {
            a: Vector(a),
            b: Vector(b),
        });
    }
    // Each ball appears at rest just inside the funnel's mouth, at least two radii from its
    // sides.
    let reach = neck / 2.0 + spread - 0.2 * r / 50f64.to_radians().tan() - 2.0 * r;
    let mut rng = ChaCha8Rng::seed_from_u64(cfg.seed);
    let arrivals = (0..cfg.balls)
        .map(|k| Arrival {
            time: k as f64 * cfg.interval,
            body: BodySpec::new(
                Vector([rng.random_range(-reach..reach), mouth - 0.2 * r]),
                Vector([0.0, 0.0]),
                r,
            ),
        })
        .collect();
    let mut scene = Scene {
        bodies: pegs,
        walls,
        arrivals,
        histogram: Some(Histogram {
            axis: 0,
            edges: (0..=bins)
                .map(|k| (k as f64 - bins as f64 / 2.0) * s)
                .collect(),
        }),
        ..Scene::default()
    };
    scene.settings.restitution = cfg.restitution;
    scene.settings.tc = Some(1e-3);
    scene.settings.gravity = Gravity::new(&[0.0, -9.81]);
    scene.validate().map_err(|e| GenerateError::Param {
        param: "rows",
        why: e.to_string(),
    })?;
    Ok(scene)
}

/// Seconds to simulate a board of `cfg` for: until the last ball has arrived, plus 10 s for
/// it to fall through the pegs and settle in its bin.
#[must_use]
pub fn galton_duration(cfg: &GaltonConfig) -> f64 {
    cfg.balls.saturating_sub(1) as f64 * cfg.interval + 10.0
}

/// The largest probability of `B(rows, 1/2)`, that of its middle bin.
fn binomial_mode_probability(rows: usize) -> f64 {
    let k = rows / 2;
    // C(rows, k) / 2^rows, as a product that stays in range.
    (1..=k).fold(0.5f64.powi((rows - k) as i32), |p, j| {
        p * (rows - k + j) as f64 / j as f64 * 0.5
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_middle_bin_takes_its_binomial_share() {
        assert!((binomial_mode_probability(12) - 924.0 / 4096.0).abs() < 1e-15);
        assert!((binomial_mode_probability(1) - 0.5).abs() < 1e-15);
        assert!((binomial_mode_probability(3) - 0.375).abs() < 1e-15);
    }

    #[test]
    fn a_board_has_its_pegs_bins_and_arrivals() {
        let cfg = GaltonConfig {
            balls: 10,
            ..GaltonConfig::default()
        };
        let scene = galton(&cfg).unwrap();
        // 12 rows of i + 1 pegs and two guards each.
        assert_eq!(scene.bodies.len(), (1..=12).sum::<usize>() + 24);
        assert_eq!(scene.arrivals.len(), 10);
        assert_eq!(scene.histogram.as_ref().unwrap().edges.len(), 14);
        assert_eq!(scene.arrivals[9].time, 2.25);
        assert_eq!(galton_duration(&cfg), 12.25);
    }

    /// Pearson's χ² of `counts` against `B(rows, 1/2)`, the end bins pooled inwards until
    /// each expects at least 5 balls, and its degrees of freedom.
    fn chi_square(counts: &[u64], rows: usize) -> (f64, usize) {
        let n: u64 = counts.iter().sum();
        let mut cells: Vec<(f64, f64)> = counts
            .iter()
            .enumerate()
            .map(|(k, &c)| {
                let p = (0..k).fold(0.5f64.powi(rows as i32), |p, j| {
                    p * (rows - j) as f64 / (j + 1) as f64
                });
                (c as f64, n as f64 * p)
            })
            .collect();
        while cells.len() > 2 && cells[0].1 < 5.0 {
            let (c, e) = cells.remove(0);
            cells[0].0 += c;
            cells[0].1 += e;
        }
        while cells.len() > 2 && cells[cells.len() - 1].1 < 5.0 {
            let (c, e) = cells.pop().unwrap();
            let last = cells.len() - 1;
            cells[last].0 += c;
            cells[last].1 += e;
        }
        let chi2 = cells.iter().map(|(c, e)| (c - e) * (c - e) / e).sum();
        (chi2, cells.len() - 1)
    }

    #[test]
    fn a_small_board_fills_its_bins_binomially() {
        let cfg = GaltonConfig {
            rows: 6,
            balls: 60,
            ..GaltonConfig::default()
        };
        let scene = galton(&cfg).unwrap();
        let mut sim = crate::Simulation::new(&scene, "cells").unwrap();
        sim.run_until(galton_duration(&cfg));
        assert_eq!(sim.halt(), None);
        assert_eq!(sim.stats().arrivals, 60);
        assert!(sim.stats().max_overlap <= 1e-9);
        let held = sim.histogram(scene.histogram.as_ref().unwrap());
        assert_eq!(held.outside, 0, "{held:?}");
        // Every ball is in a bin, below the pegs.
        let top = scene
            .bodies
            .iter()
            .map(|b| b.pos[1])
            .fold(f64::INFINITY, f64::min);
        for i in scene.bodies.len()..sim.world().len() {
            if !sim.world().is_vacant(i) {
                assert!(
                    sim.position(i)[1] < top,
                    "ball {i} at {:?}",
                    sim.position(i)
                );
            }
        }
        let (chi2, dof) = chi_square(&held.counts, cfg.rows);
        // The χ² distribution's 99th percentile for 4 degrees of freedom.
        assert_eq!(dof, 4, "{held:?}");
        assert!(chi2 < 13.277, "χ² {chi2} on {dof} dof: {held:?}");
    }

    #[test]
    fn the_chi_square_of_a_perfect_histogram_is_zero() {
        let (chi2, dof) = chi_square(&[1, 4, 6, 4, 1].map(|c| c * 16), 4);
        assert!(chi2.abs() < 1e-12);
        assert_eq!(dof, 4);
    }

    #[test]
    fn bad_parameters_are_refused() {
        for cfg in [
            GaltonConfig {
                rows: 0,
                ..GaltonConfig::default()
            },
            GaltonConfig {
                balls: 0,
                ..GaltonConfig::default()
            },
            GaltonConfig {
                interval: 0.2,
                ..GaltonConfig::default()
            },
            GaltonConfig {
                restitution: 1.0,
                ..GaltonConfig::default()
            },
        ] {
            assert!(galton(&cfg).is_err(), "{cfg:?}");
        }
    }
}
