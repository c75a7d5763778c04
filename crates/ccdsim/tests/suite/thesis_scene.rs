//! The thesis benchmark scene honours its contract: bodies inside the table, no overlap, the
//! same body density whatever n, radii in range, and a fastest speed that crosses the diagonal
//! in one second.

use ccdsim::generate::THESIS_DURATION;
use ccdsim::generate::{thesis, ThesisConfig, THESIS_TABLE_5_1};
use ccdsim::{Scene, Simulation, Vector, Wall};

const SEEDS: [u64; 3] = [1, 2, 77];

/// Checks one scene against its configuration; returns the largest speed.
fn check<const D: usize>(cfg: &ThesisConfig, scene: &Scene<D>) -> f64 {
    scene.validate().unwrap();
    assert_eq!(scene.bodies.len(), cfg.n);
    let size: Vector<D> = cfg.table();
    // The table: aspect · w along x, w along the others, n / volume = density.
    let volume: f64 = size.0.iter().product();
    assert!((cfg.n as f64 / volume / cfg.density - 1.0).abs() < 1e-12);
    assert!((size[0] / size[1] - cfg.aspect).abs() < 1e-12);
    assert_eq!(scene.walls.len(), 2 * D);
    for wall in &scene.walls {
        match (D, wall) {
            (2, Wall::Segment { .. }) | (3, Wall::Plane { .. }) => {}
            _ => panic!("wrong wall kind {wall:?} in {D}D"),
        }
    }
    let v_max = cfg.max_speed::<D>();
    assert!((v_max - size.norm() / cfg.crossing_time).abs() <= 1e-12 * v_max);
    let mut fastest: f64 = 0.0;
    for (i, b) in scene.bodies.iter().enumerate() {
        assert!((cfg.radius_min..=cfg.radius_max).contains(&b.radius));
        for k in 0..D {
            assert!(
                b.pos[k] - b.radius > 0.0 && b.pos[k] + b.radius < size[k],
                "body {i} leaves the table along axis {k}"
            );
        }
        let speed = b.vel.norm();
        assert!(speed <= v_max * (1.0 + 1e-12), "body {i} is too fast");
        assert!(speed >= cfg.slowest * v_max * (1.0 - 1e-12));
        fastest = fastest.max(speed);
        for (j, c) in scene.bodies.iter().enumerate().skip(i + 1) {
            let gap = (c.pos - b.pos).norm() - (b.radius + c.radius);
            assert!(gap > 0.0, "bodies {i} and {j} overlap");
        }
    }
    fastest
}

#[test]
fn thesis_scene_2d_contract() {
    for &(n, ..) in &THESIS_TABLE_5_1[..8] {
        for seed in SEEDS {
            let cfg = ThesisConfig::new(n, seed);
            let scene = thesis::<2>(&cfg).unwrap();
            let fastest = check(&cfg, &scene);
            if n >= 512 {
                // Speeds are uniform up to v_max: with hundreds of bodies one comes close.
                assert!(fastest > 0.98 * cfg.max_speed::<2>(), "n = {n}: {fastest}");
            }
        }
    }
}

#[test]
fn thesis_scene_3d_contract() {
    for n in [8, 64, 500] {
        let cfg = ThesisConfig::new(n, 5);
        check(&cfg, &thesis::<3>(&cfg).unwrap());
    }
}

#[test]
fn density_is_constant_across_sizes() {
    // The number density is exact by construction (checked above); the covered fraction is
    // random but its expectation is the same for every n: π·E[r²]·density.
    let cfg = ThesisConfig::default();
    let (a, b) = (cfg.radius_min, cfg.radius_max);
    let mean_r2 = (a * a + a * b + b * b) / 3.0;
    let expected = std::f64::consts::PI * mean_r2 * cfg.density;
    let mut fractions = Vec::new();
    for n in [64, 256, 1024, 2048] {
        let cfg = ThesisConfig::new(n, 3);
        let scene = thesis::<2>(&cfg).unwrap();
        let size: Vector<2> = cfg.table();
        let covered: f64 = scene
            .bodies
            .iter()
            .map(|b| std::f64::consts::PI * b.radius * b.radius)
            .sum();
        fractions.push(covered / (size[0] * size[1]));
    }
    for (f, n) in fractions.iter().zip([64, 256, 1024, 2048]) {
        // Relative standard deviation of the mean of r² over n bodies: < 0.4/√n; allow 5σ.
        let tolerance = 5.0 * 0.4 / (n as f64).sqrt();
        assert!(
            (f / expected - 1.0).abs() < tolerance,
            "n = {n}: {f} vs {expected}"
        );
    }
}

#[test]
fn same_seed_same_scene_and_bad_parameters_refused() {
    let cfg = ThesisConfig::new(100, 9);
    assert_eq!(thesis::<2>(&cfg).unwrap(), thesis::<2>(&cfg).unwrap());
    assert_ne!(
        thesis::<2>(&cfg).unwrap(),
        thesis::<2>(&ThesisConfig::new(100, 10)).unwrap()
    );
    for bad in [
        ThesisConfig {
            density: 0.0,
            ..cfg.clone()
        },
        ThesisConfig {
            radius_min: 2.0,
            radius_max: 1.0,
            ..cfg.clone()
        },
        ThesisConfig {
            slowest: 1.5,
            ..cfg.clone()
        },
        ThesisConfig {
            aspect: 0.5,
            ..cfg.clone()
        },
        ThesisConfig {
            density: 10.0,
            ..cfg.clone()
        },
    ] {
        assert!(thesis::<2>(&bad).is_err(), "{bad:?}");
    }
}

#[test]
fn collision_counts_match_table_5_1_at_small_sizes() {
    // The calibration (docs/benchmarks.md) at the sizes a test can afford: the mean number of
    // events (body–body plus body–wall) in 5 simulated seconds over 8 seeds is within ±10 % of
    // the thesis's.
    for &(n, thesis_count, ..) in &THESIS_TABLE_5_1[3..6] {
        let mut total = 0;
        for seed in 1..=8 {
            let scene = thesis::<2>(&ThesisConfig::new(n, seed)).unwrap();
            let mut sim = Simulation::new(&scene, "sedgewick").unwrap();
            total += sim.run_until(THESIS_DURATION);
        }
        let mean = total as f64 / 8.0;
        assert!(
            (mean / thesis_count - 1.0).abs() < 0.1,
            "n = {n}: {mean} collisions, thesis {thesis_count}"
        );
    }
}
