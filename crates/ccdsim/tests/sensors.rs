//! Sensors (`sensors[]`): regions that report bodies entering and leaving them at the roots
//! of the contact equations, change no motion, and give the same events with every finder.

use ccdsim::generate::{box_walls, pegs, PegsConfig};
use ccdsim::gravity::Gravity;
use ccdsim::record::{RunWriter, VERSION_SENSORS};
use ccdsim::{AnyScene, BodySpec, Scene, Sensor, SensorChange, SensorEvent, Simulation, Vector};

const FINDERS: [&str; 4] = ["all-pairs", "bvh", "sedgewick", "cells"];

fn sensor(c: [f64; 2], radius: f64) -> Sensor<2> {
    Sensor {
        center: Vector(c),
        radius,
    }
}

fn table(bodies: Vec<BodySpec<2>>, sensors: Vec<Sensor<2>>) -> Scene<2> {
    Scene {
        bodies,
        walls: box_walls(Vector([10.0, 4.0])),
        sensors,
        ..Scene::default()
    }
}

fn enter(time: f64, body: usize, sensor: usize) -> SensorEvent {
    SensorEvent {
        time,
        body,
        sensor,
        change: SensorChange::Enter,
    }
}

fn leave(time: f64, body: usize, sensor: usize) -> SensorEvent {
    SensorEvent {
        change: SensorChange::Leave,
        ..enter(time, body, sensor)
    }
}

#[test]
fn a_ball_crossing_a_sensor_enters_and_leaves_at_the_roots_and_is_not_deflected() {
    for finder in FINDERS {
        // Centre at x = 1 moving at 2 m/s; sensor of radius 1 at x = 5: overlap while the
        // centre is within 1.5 m, from x = 3.5 to 6.5, t = 1.25 to 2.75; the wall at 9.5.
        let scene = table(
            vec![BodySpec::new(Vector([1.0, 2.0]), Vector([2.0, 0.0]), 0.5)],
            vec![sensor([5.0, 2.0], 1.0)],
        );
        let mut sim = Simulation::new(&scene, finder).unwrap();
        sim.run_until(2.0);
        assert_eq!(
            sim.take_sensor_events(),
            vec![enter(1.25, 0, 0)],
            "[{finder}]"
        );
        assert_eq!(sim.sensors().unwrap().bodies_in(0), vec![0]);
        let wall = sim.step_event().unwrap();
        assert_eq!(wall.event.time, 4.25, "[{finder}] not deflected");
        // The leave came before the wall collision; back through the sensor on the way back.
        sim.run_until(8.0);
        assert_eq!(
            sim.take_sensor_events(),
            vec![leave(2.75, 0, 0), enter(5.75, 0, 0), leave(7.25, 0, 0)],
            "[{finder}]"
        );
        assert_eq!(sim.sensors().unwrap().counts(0), (2, 2));
        assert!(sim.take_sensor_events().is_empty());
    }
}

#[test]
fn bodies_inside_at_the_start_or_put_there_enter_at_once() {
    let scene = table(
        vec![
            BodySpec::new(Vector([5.0, 2.0]), Vector([0.0, 0.0]), 0.5),
            BodySpec::new(Vector([1.0, 1.0]), Vector([0.0, 0.0]), 0.5),
        ],
        vec![sensor([5.0, 2.0], 0.2)],
    );
    let mut sim = Simulation::new(&scene, "cells").unwrap();
    sim.run_until(1.0);
    assert_eq!(sim.take_sensor_events(), vec![enter(0.0, 0, 0)]);
    // A teleport into the sensor enters at once; one out of it leaves at once.
    sim.set_position(0, Vector([8.0, 1.0])).unwrap();
    sim.set_position(1, Vector([5.0, 2.3])).unwrap();
    sim.run_until(2.0);
    // Simultaneous events come by body index.
    assert_eq!(
        sim.take_sensor_events(),
        vec![leave(1.0, 0, 0), enter(1.0, 1, 0)]
    );
    // At rest inside, nothing more ever happens.
    sim.run_until(100.0);
    assert!(sim.take_sensor_events().is_empty());
    assert_eq!(sim.sensors().unwrap().bodies_in(0), vec![1]);
}

#[test]
fn a_falling_ball_enters_at_the_root_of_its_parabola() {
    // Dropped from rest at y = 3.5 under g = 2: the sensor of radius 0.8 at y = 1.5 is
    // touched (centres 1.3 m apart) at y = 2.8, when t² = 0.7; the floor (y = 0.5 for the
    // centre, still 1 m from the sensor's) bounces it back at t = √3.
    let mut scene = table(
        vec![BodySpec::new(Vector([5.0, 3.5]), Vector([0.0, 0.0]), 0.5)],
        vec![sensor([5.0, 1.5], 0.8)],
    );
    scene.settings.gravity = Gravity::new(&[0.0, -2.0]);
    for finder in FINDERS {
        let mut sim = Simulation::new(&scene, finder).unwrap();
        sim.run_until(3.0);
        let events = sim.take_sensor_events();
        assert_eq!(events[0].change, SensorChange::Enter);
        assert!((events[0].time - 0.7f64.sqrt()).abs() < 1e-15, "{events:?}");
        // Elastic: back up through the sensor, out at y = 2.8 again, at 2√3 − √0.7.
        assert_eq!(events[1].change, SensorChange::Leave);
        let want = 2.0 * 3f64.sqrt() - 0.7f64.sqrt();
        assert!((events[1].time - want).abs() < 1e-14, "{events:?}");
        assert_eq!(events.len(), 2, "[{finder}] {events:?}");
        assert_eq!(sim.stats().wall_collisions, 1, "[{finder}]");
    }
}

#[test]
fn every_finder_reports_the_same_sensor_events_on_a_peg_board() {
    let mut board = pegs(&PegsConfig {
        rows: 5,
        balls: 40,
        ..PegsConfig::default()
    })
    .unwrap();
    // Bins along the bottom and one big region in the middle of the pegs.
    let (lo, hi) = ccdsim::wall::walls_bounds(&board.walls).unwrap();
    let width = hi[0] - lo[0];
    for k in 0..6 {
        let x = lo[0] + width * (k as f64 + 0.5) / 6.0;
        board.sensors.push(sensor([x, lo[1] + 0.5], 0.6));
    }
    board
        .sensors
        .push(sensor([0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1])], 2.0));
    let run = |finder: &str| {
        let mut sim = Simulation::new(&board, finder).unwrap();
        sim.run_until(6.0);
        sim.take_sensor_events()
    };
    let want = run("all-pairs");
    assert!(want.len() > 40, "{} events", want.len());
    assert!(want.windows(2).all(|w| w[0].time <= w[1].time));
    for finder in ["bvh", "sedgewick", "cells"] {
        assert!(run(finder) == want, "[{finder}]");
    }
}

#[test]
fn sensors_are_validated_and_runs_with_them_are_version_7() {
    let parse = |sensors: &str, rest: &str| {
        AnyScene::from_json(&format!(
            r#"{{"dim": 2, "bodies": [{{"pos": [1, 1], "vel": [0, 0], "radius": 0.5}}], "sensors": {sensors}{rest}}}"#
        ))
        .map(|_| ())
        .map_err(|e| e.to_string())
    };
    assert_eq!(parse(r#"[{"center": [5, 5], "radius": 1}]"#, ""), Ok(()));
    let e = parse(r#"[{"center": [5, 5], "radius": 0}]"#, "").unwrap_err();
    assert!(e.contains("sensors[0].radius"), "{e}");
    let e = parse(r#"[{"center": [5, 5], "radius": 1, "r": 2}]"#, "").unwrap_err();
    assert!(e.contains("sensors[0]"), "{e}");
    let e = parse(
        r#"[{"center": [5, 5], "radius": 1}]"#,
        r#", "periodic": [10, 10]"#,
    )
    .unwrap_err();
    assert!(e.contains("periodic"), "{e}");
    let scene = table(
        vec![BodySpec::new(Vector([1.0, 2.0]), Vector([2.0, 0.0]), 0.5)],
        vec![sensor([5.0, 2.0], 1.0)],
    );
    let mut sim = Simulation::new(&scene, "cells").unwrap();
    let mut w = RunWriter::new(Vec::new(), "cells".into(), &scene).unwrap();
    sim.run_until_with(10.0, |c| w.write_event(c).unwrap());
    let bytes = w.finish(10.0).unwrap();
    assert_eq!(
        u32::from_le_bytes(bytes[8..12].try_into().unwrap()),
        VERSION_SENSORS
    );
}

/// At every sample time, what the tracker says each body overlaps agrees with the geometry,
/// away from the boundary (within rounding of it either answer is right).
fn check_membership(scene: &Scene<2>, samples: usize, dt: f64) {
    let mut sim = Simulation::new(scene, "cells").unwrap();
    let mut last = 0.0;
    for k in 1..=samples {
        sim.run_until(k as f64 * dt);
        let events = sim.take_sensor_events();
        assert!(events
            .iter()
            .all(|e| e.time >= last && e.time <= sim.time()));
        last = sim.time();
        let tracker = sim.sensors().unwrap();
        for i in 0..sim.world().len() {
            let p = sim.position(i);
            for (s, sensor) in scene.sensors.iter().enumerate() {
                let sigma = sensor.radius + sim.world().radius(i);
                let d = (p - sensor.center).norm();
                if (d - sigma).abs() > 1e-9 {
                    assert_eq!(
                        tracker.is_inside(i, s),
                        d < sigma,
                        "t = {}: body {i} at distance {d} of sensor {s} (σ = {sigma})",
                        sim.time()
                    );
                }
            }
        }
    }
}

#[test]
fn membership_follows_the_geometry_in_gases_with_and_without_gravity() {
    for seed in 1..=4u64 {
        let mut scene = ccdsim::generate::gas::<2>(&ccdsim::generate::GasConfig {
            n: 80,
            packing: 0.25,
            seed,
            ..ccdsim::generate::GasConfig::default()
        })
        .unwrap();
        let (lo, hi) = ccdsim::wall::walls_bounds(&scene.walls).unwrap();
        let w = hi - lo;
        for (fx, fy, fr) in [(0.3, 0.3, 0.1), (0.6, 0.5, 0.25), (0.5, 0.5, 0.05)] {
            scene
                .sensors
                .push(sensor([lo[0] + fx * w[0], lo[1] + fy * w[1]], fr * w[0]));
        }
        check_membership(&scene, 200, 0.05);
        scene.settings.gravity = Gravity::new(&[0.0, -3.0]);
        check_membership(&scene, 200, 0.05);
    }
}
