//! The discrete-time stepper and its miss counter.

use ccdsim::discrete::DiscreteStepper;
use ccdsim::generate::{thesis, ThesisConfig};
use ccdsim::{BodySpec, Scene, Vector};

/// A small body (r = 0.01 m) flying at 100 m/s straight at a resting body of radius 0.05 m one
/// metre ahead: they overlap only while the small body's centre is within 0.06 m of the other's
/// centre, a 0.12 m gap in its path that it crosses in 1.2 ms.
fn bullet_and_target() -> Scene<2> {
    Scene {
        bodies: vec![
            BodySpec::new(Vector([0.0, 0.0]), Vector([100.0, 0.0]), 0.01),
            BodySpec::new(Vector([1.0, 0.0]), Vector([0.0, 0.0]), 0.05),
        ],
        ..Scene::default()
    }
}

fn run(scene: &Scene<2>, dt: f64, until: f64) -> ccdsim::discrete::DiscreteStats {
    let mut s = DiscreteStepper::new(scene).unwrap();
    s.set_count_misses(true);
    s.run_until(until, dt);
    *s.stats()
}

#[test]
fn a_fast_body_crossing_a_thin_gap_is_one_miss_at_large_dt_and_none_at_small_dt() {
    let scene = bullet_and_target();
    for dt in [0.1, 0.02, 0.007] {
        // Frames 0.7 m or more apart: one before the target, the next past it.
        let s = run(&scene, dt, 0.5);
        assert_eq!((s.body_misses, s.body_contacts), (1, 0), "dt = {dt}");
    }
    for dt in [0.001, 0.0001] {
        // Frames 0.1 m or less apart: one of them falls inside the 0.12 m gap.
        let s = run(&scene, dt, 0.5);
        assert_eq!((s.body_misses, s.body_contacts), (0, 1), "dt = {dt}");
        assert_eq!(s.wall_misses, 0);
    }
}

#[test]
fn a_detected_hit_bounces_like_the_exact_one() {
    // At small dt the stepper's impulse is the exact simulation's: the small body comes back.
    let mut s = DiscreteStepper::new(&bullet_and_target()).unwrap();
    s.run_until(0.5, 0.0001);
    assert!(s.world().velocity(0)[0] < -90.0);
    assert!(s.world().velocity(1)[0] > 0.0);
}

#[test]
fn bodies_never_leave_the_table_and_energy_is_kept() {
    let cfg = ThesisConfig::new(128, 4);
    let scene = thesis::<2>(&cfg).unwrap();
    let size: Vector<2> = cfg.table();
    for dt in [1.0, 0.1, 0.01] {
        let mut s = DiscreteStepper::new(&scene).unwrap();
        let e0 = s.world().kinetic_energy();
        s.run_until(5.0, dt);
        assert_eq!(s.time(), 5.0);
        let w = s.world();
        for i in 0..w.len() {
            let (p, r) = (w.position(i), w.radius(i));
            for k in 0..2 {
                assert!(
                    p[k] >= r * (1.0 - 1e-9) && p[k] <= size[k] - r * (1.0 - 1e-9),
                    "dt = {dt}: body {i} at {p:?}"
                );
            }
        }
        let e1 = w.kinetic_energy();
        assert!((e1 / e0 - 1.0).abs() < 1e-9, "dt = {dt}: {e0} → {e1}");
    }
}

#[test]
fn misses_grow_with_the_time_step_and_counting_them_changes_nothing() {
    let scene = thesis::<2>(&ThesisConfig::new(128, 2)).unwrap();
    let mut misses = Vec::new();
    for dt in [0.001, 0.03, 0.3] {
        let mut counted = DiscreteStepper::new(&scene).unwrap();
        counted.set_count_misses(true);
        counted.run_until(2.0, dt);
        let mut plain = DiscreteStepper::new(&scene).unwrap();
        plain.run_until(2.0, dt);
        assert_eq!(counted.world().bodies(), plain.world().bodies());
        assert_eq!(plain.stats().misses(), 0);
        misses.push(counted.stats().misses());
    }
    assert!(misses[0] < misses[1] && misses[1] < misses[2], "{misses:?}");
}

#[test]
fn works_in_3d() {
    let scene = thesis::<3>(&ThesisConfig::new(100, 3)).unwrap();
    let mut s = DiscreteStepper::new(&scene).unwrap();
    s.set_count_misses(true);
    assert_eq!(s.run_until(1.0, 0.01), 100);
    assert!(s.stats().body_contacts > 0 && s.stats().wall_contacts > 0);
}
