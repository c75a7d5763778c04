//! Sensors (`sensors[]`): regions that report bodies entering and leaving them at the roots
//! of the contact equations, change no motion, and give the same events with every finder.

use ccdsim::contact::periodic::min_image;
use ccdsim::generate::{box_walls, pegs, PegsConfig};
use ccdsim::generate::{gas, GasConfig};
use ccdsim::record::{RunWriter, VERSION_SENSORS};
use ccdsim::Gravity;
use ccdsim::Growth;
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
fn a_falling_growing_ball_enters_when_its_parabola_meets_the_grown_sphere() {
    // As above, dropped from y = 3.4 (clear of the ceiling at 4, which the growing ball
    // would touch at once from 3.5), the radius 0.5 growing at 0.2 per second (0.1 m/s): the
    // centres, 1.9 − t² apart, meet the contact distance 1.3 + 0.1·t at the root of
    // t² + 0.1·t − 0.6. (The ceiling's gap, 0.1 − 0.1·t + t², never closes.)
    let mut scene = table(
        vec![BodySpec::new(Vector([5.0, 3.4]), Vector([0.0, 0.0]), 0.5)],
        vec![sensor([5.0, 1.5], 0.8)],
    );
    scene.settings.gravity = Gravity::new(&[0.0, -2.0]);
    scene.settings.growth = Some(Growth { rate: 0.2 });
    let want = (-0.1 + (0.01f64 + 2.4).sqrt()) / 2.0;
    for finder in FINDERS {
        let mut sim = Simulation::new(&scene, finder).unwrap();
        sim.run_until(1.0);
        let events = sim.take_sensor_events();
        assert_eq!(events.len(), 1, "[{finder}] {events:?}");
        assert_eq!(events[0].change, SensorChange::Enter);
        assert!((events[0].time - want).abs() < 1e-14, "{events:?} {want}");
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
    assert_eq!(
        parse(
            r#"[{"center": [5, 5], "radius": 1}]"#,
            r#", "periodic": [10, 10]"#
        ),
        Ok(())
    );
    assert_eq!(
        parse(
            r#"[{"center": [5, 5], "radius": 1}]"#,
            r#", "settings": {"growth": {"rate": 0.1}}"#
        ),
        Ok(())
    );
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

// ---------------------------------------------------------------------------------------
// Periodic boxes and growing radii.

/// A scene in the periodic box `[0, 10) × [0, 8)` without collisions to speak of.
fn periodic_box(bodies: Vec<BodySpec<2>>, sensors: Vec<Sensor<2>>) -> Scene<2> {
    Scene {
        bodies,
        periodic: Some(Vector([10.0, 8.0])),
        sensors,
        ..Scene::default()
    }
}

#[test]
fn a_body_crossing_the_box_inside_a_straddling_sensor_neither_leaves_nor_enters_there() {
    for finder in FINDERS {
        // Sensor of radius 1 at x = 0.3 straddles the face x = 0 (its image at x = 10.3).
        // The body (radius 0.2) from x = 8 at +1 m/s: in at x = 9.1 (t = 1.1), through the
        // face at t = 2, out at x = 1.5 (t = 3.5); round the box again, in at t = 11.1.
        let scene = periodic_box(
            vec![BodySpec::new(Vector([8.0, 4.0]), Vector([1.0, 0.0]), 0.2)],
            vec![sensor([0.3, 4.0], 1.0)],
        );
        let mut sim = Simulation::new(&scene, finder).unwrap();
        sim.run_until(2.5);
        assert_eq!(sim.stats().exits, 1, "[{finder}]");
        let events = sim.take_sensor_events();
        assert_eq!(events.len(), 1, "[{finder}] {events:?}");
        assert_eq!(events[0].change, SensorChange::Enter);
        assert!((events[0].time - 1.1).abs() < 1e-14, "{events:?}");
        assert_eq!(sim.sensors().unwrap().bodies_in(0), vec![0]);
        sim.run_until(12.0);
        let events = sim.take_sensor_events();
        let kinds: Vec<_> = events.iter().map(|e| e.change).collect();
        assert_eq!(
            kinds,
            [SensorChange::Leave, SensorChange::Enter],
            "[{finder}] {events:?}"
        );
        assert!((events[0].time - 3.5).abs() < 1e-14, "{events:?}");
        assert!((events[1].time - 11.1).abs() < 1e-13, "{events:?}");
        assert_eq!(sim.stats().exits, 2, "[{finder}]");
    }
}

#[test]
fn a_body_crossing_a_corner_inside_a_sensor_on_the_corner_stays_inside() {
    // 2D: the sensor sits on the corner (0, 0); a body moving diagonally through the corner
    // crosses both faces inside it.
    for finder in FINDERS {
        let scene = periodic_box(
            vec![BodySpec::new(Vector([7.0, 5.0]), Vector([1.0, 1.0]), 0.25)],
            vec![sensor([0.0, 0.0], 2.0)],
        );
        let mut sim = Simulation::new(&scene, finder).unwrap();
        sim.run_until(6.0);
        assert_eq!(sim.stats().exits, 2, "[{finder}]");
        let events = sim.take_sensor_events();
        // At the corner at t = 3: in when √2·(3 − t) = 2.25, out when √2·(t − 3) = 2.25.
        let d = 2.25 / 2f64.sqrt();
        assert_eq!(events.len(), 2, "[{finder}] {events:?}");
        assert_eq!(
            (events[0].change, events[1].change),
            (SensorChange::Enter, SensorChange::Leave)
        );
        assert!((events[0].time - (3.0 - d)).abs() < 1e-14, "{events:?}");
        assert!((events[1].time - (3.0 + d)).abs() < 1e-14, "{events:?}");
    }
    // 3D: the same through the corner of a cube, all three faces at once.
    for finder in FINDERS {
        let scene = Scene::<3> {
            bodies: vec![BodySpec::new(
                Vector([3.0, 3.0, 3.0]),
                Vector([1.0, 1.0, 1.0]),
                0.25,
            )],
            periodic: Some(Vector([6.0, 6.0, 6.0])),
            sensors: vec![Sensor {
                center: Vector([0.0, 0.0, 0.0]),
                radius: 2.0,
            }],
            ..Scene::default()
        };
        let mut sim = Simulation::new(&scene, finder).unwrap();
        sim.run_until(6.0);
        assert_eq!(sim.stats().exits, 3, "[{finder}]");
        let events = sim.take_sensor_events();
        let d = 2.25 / 3f64.sqrt();
        assert_eq!(events.len(), 2, "[{finder}] {events:?}");
        assert_eq!(
            (events[0].change, events[1].change),
            (SensorChange::Enter, SensorChange::Leave)
        );
        assert!((events[0].time - (3.0 - d)).abs() < 1e-14, "{events:?}");
        assert!((events[1].time - (3.0 + d)).abs() < 1e-14, "{events:?}");
    }
}

#[test]
fn a_growing_body_enters_a_sensor_it_grows_into_and_leaves_only_if_it_outruns_it() {
    for finder in FINDERS {
        // Radius 0.5 growing at Γ = 0.5 (σ̇ = 0.25), sensor of radius 1 whose centre is
        // 3 m away: 1 + 0.5·(1 + 0.5·t) = 3 at t = 6.
        let mut scene = table(
            vec![
                BodySpec::new(Vector([2.0, 2.0]), Vector([0.0, 0.0]), 0.5),
                // At the centre of sensor 1, moving away at 0.2 m/s: the sphere
                // (σ = 1.5 + 0.25·t) keeps it.
                BodySpec::new(Vector([8.0, 2.0]), Vector([0.2, 0.0]), 0.5),
                // Radius 0.1 (σ = 1.1 + 0.05·t), 0.8 m off the centre of sensor 1 and moving
                // away at 1 m/s: out when 0.8 + t = σ, at 0.3/0.95, and never back.
                BodySpec::new(Vector([8.0, 1.2]), Vector([0.0, -1.0]), 0.1),
            ],
            vec![sensor([5.0, 2.0], 1.0), sensor([8.0, 2.0], 1.0)],
        );
        scene.walls = box_walls(Vector([20.0, 20.0]));
        for b in &mut scene.bodies {
            b.pos += Vector([5.0, 5.0]);
        }
        for s in &mut scene.sensors {
            s.center += Vector([5.0, 5.0]);
        }
        scene.settings.growth = Some(Growth { rate: 0.5 });
        let mut sim = Simulation::new(&scene, finder).unwrap();
        sim.run_until(5.0);
        let events = sim.take_sensor_events();
        let of = |b: usize, k: usize| -> Vec<(SensorChange, f64)> {
            events
                .iter()
                .filter(|e| e.body == b && e.sensor == k)
                .map(|e| (e.change, e.time))
                .collect()
        };
        assert_eq!(of(1, 1), vec![(SensorChange::Enter, 0.0)], "[{finder}]");
        let out = of(2, 1);
        assert_eq!(out.len(), 2, "[{finder}] {out:?}");
        assert_eq!(out[0], (SensorChange::Enter, 0.0));
        assert_eq!(out[1].0, SensorChange::Leave);
        assert!((out[1].1 - 0.3 / 0.95).abs() < 1e-15, "{out:?}");
        assert!(of(0, 0).is_empty(), "[{finder}]");
        sim.run_until(10.0);
        let events = sim.take_sensor_events();
        let first: Vec<_> = events.iter().filter(|e| e.body == 0).collect();
        assert_eq!(first.len(), 1, "[{finder}] {events:?}");
        assert_eq!((first[0].change, first[0].sensor), (SensorChange::Enter, 0));
        assert!((first[0].time - 6.0).abs() < 1e-14, "{first:?}");
        assert!(sim.sensors().unwrap().is_inside(1, 1));
    }
}

/// Each body's path as pieces `(from, position, velocity)`, from the scene and the
/// collisions of a run (box exits move no body in space, so they start no piece).
type Paths<const D: usize> = Vec<Vec<(f64, Vector<D>, Vector<D>)>>;

/// Runs `scene` with `finder` to `until`, returning the sensor events and the paths.
fn run_with_paths<const D: usize>(
    scene: &Scene<D>,
    finder: &str,
    until: f64,
) -> (Vec<SensorEvent>, Paths<D>) {
    let mut paths: Paths<D> = scene
        .bodies
        .iter()
        .map(|b| vec![(scene.start_time, b.pos, b.vel)])
        .collect();
    let mut sim = Simulation::new(scene, finder).unwrap();
    sim.run_until_with(until, |c| {
        for k in 0..c.body_count() {
            let i = if k == 0 { c.event.a } else { c.event.b } as usize;
            paths[i].push((c.event.time, c.pos[k], c.vel[k]));
        }
    });
    (sim.take_sensor_events(), paths)
}

/// The independent reference: a body's distance to the nearest image of a sensor (the
/// minimum image) less the contact distance at `t`, on its path.
fn gap_at<const D: usize>(
    scene: &Scene<D>,
    path: &[(f64, Vector<D>, Vector<D>)],
    i: usize,
    k: usize,
    t: f64,
) -> f64 {
    let piece = path.iter().rev().find(|p| p.0 <= t).unwrap_or(&path[0]);
    let x = piece.1 + piece.2 * (t - piece.0);
    let sensor = &scene.sensors[k];
    let dp = match &scene.periodic {
        Some(size) => min_image(x - sensor.center, size),
        None => x - sensor.center,
    };
    let r = scene.bodies[i].radius;
    let r = match &scene.settings.growth {
        Some(g) => r * (1.0 + g.rate * (t - scene.start_time)),
        None => r,
    };
    dp.norm() - (sensor.radius + r)
}

/// The reference events of body `i` and sensor `k` up to `until`: the sign changes of
/// [`gap_at`] sampled every `h` seconds at most along each piece, each narrowed by bisection.
fn reference_events<const D: usize>(
    scene: &Scene<D>,
    path: &[(f64, Vector<D>, Vector<D>)],
    i: usize,
    k: usize,
    until: f64,
    h: f64,
) -> Vec<(SensorChange, f64)> {
    let g = |t: f64| gap_at(scene, path, i, k, t);
    let mut out = Vec::new();
    let mut t = scene.start_time;
    let mut inside = g(t) < 0.0;
    if inside {
        out.push((SensorChange::Enter, t));
    }
    let mut ends: Vec<f64> = path.iter().skip(1).map(|p| p.0).collect();
    ends.push(until);
    for end in ends {
        let steps = ((end - t) / h).ceil().max(1.0) as usize;
        let start = t;
        for s in 1..=steps {
            let next = if s == steps {
                end
            } else {
                start + (end - start) * s as f64 / steps as f64
            };
            // Sample just inside the piece: its end belongs to the next one.
            if (g(next) < 0.0) != inside {
                let (mut lo, mut hi) = (t, next);
                for _ in 0..200 {
                    let mid = 0.5 * (lo + hi);
                    if mid <= lo || mid >= hi {
                        break;
                    }
                    if (g(mid) < 0.0) == inside {
                        lo = mid;
                    } else {
                        hi = mid;
                    }
                }
                inside = !inside;
                let change = if inside {
                    SensorChange::Enter
                } else {
                    SensorChange::Leave
                };
                out.push((change, hi));
            }
            t = next;
        }
    }
    out
}

/// Checks every body's and sensor's events against the reference: each reference event has
/// one of the same kind at the same time (within 1e-9 s, or where the reference's gap is
/// within rounding of zero, for crossings at a grazing angle); events the sampling missed
/// must be enter–leave pairs shorter than two samples with an overlap in between.
fn check_against_reference<const D: usize>(
    scene: &Scene<D>,
    events: &[SensorEvent],
    paths: &Paths<D>,
    until: f64,
) -> usize {
    let h = 2e-3;
    let mut matched = 0;
    for (i, path) in paths.iter().enumerate() {
        for k in 0..scene.sensors.len() {
            let got: Vec<(SensorChange, f64)> = events
                .iter()
                .filter(|e| e.body == i && e.sensor == k)
                .map(|e| (e.change, e.time))
                .collect();
            let want = reference_events(scene, path, i, k, until, h);
            let g = |t: f64| gap_at(scene, path, i, k, t);
            let close =
                |a: f64, b: f64| (a - b).abs() <= 1e-9 * (1.0 + a.abs()) || g(a).abs() <= 1e-10;
            let (mut a, mut b) = (0, 0);
            while a < got.len() || b < want.len() {
                if a < got.len()
                    && b < want.len()
                    && got[a].0 == want[b].0
                    && close(got[a].1, want[b].1)
                {
                    a += 1;
                    b += 1;
                    matched += 1;
                    continue;
                }
                // A brief overlap between two samples.
                let brief = a + 1 < got.len()
                    && got[a].0 == SensorChange::Enter
                    && got[a + 1].0 == SensorChange::Leave
                    && got[a + 1].1 - got[a].1 < 2.0 * h
                    && g(0.5 * (got[a].1 + got[a + 1].1)) < 1e-10;
                assert!(
                    brief,
                    "body {i}, sensor {k}: got {:?}, the reference has {:?}",
                    &got[a.min(got.len())..],
                    &want[b.min(want.len())..]
                );
                a += 2;
            }
        }
    }
    matched
}

/// A gas of `n` bodies (radii 0.3 to 0.6), periodic or walled, with sensors: in a periodic
/// box one straddling a face, one on a corner, one in the middle and one as large as the box
/// allows; in a walled one three inside.
fn gas_with_sensors<const D: usize>(n: usize, periodic: bool, seed: u64) -> Scene<D> {
    let mut scene = gas::<D>(&GasConfig {
        n,
        packing: 0.2,
        radius_min: 0.3,
        radius_max: 0.6,
        periodic,
        seed,
        ..GasConfig::default()
    })
    .unwrap();
    let (lo, size) = match scene.periodic {
        Some(size) => (Vector::ZERO, size),
        None => {
            let (lo, hi) = ccdsim::wall::walls_bounds(&scene.walls).unwrap();
            (lo, hi - lo)
        }
    };
    let side = (0..D).map(|d| size[d]).fold(f64::INFINITY, f64::min);
    let at = |f: [f64; 3]| {
        let mut c = lo;
        for d in 0..D {
            c[d] += f[d] * size[d];
        }
        c
    };
    let r_max = scene.bodies.iter().map(|b| b.radius).fold(0.0, f64::max);
    let mut add = |center: Vector<D>, radius: f64| scene.sensors.push(Sensor { center, radius });
    add(at([0.5, 0.5, 0.5]), 0.15 * side);
    if periodic {
        add(at([0.02, 0.4, 0.6]), 0.2 * side);
        add(at([0.0, 0.0, 0.0]), 0.1 * side);
        // As large as allowed: growth soon lets a body overlap two of its images.
        add(at([0.7, 0.9, 0.3]), 0.5 * side - r_max - 1e-3);
    } else {
        add(at([0.2, 0.25, 0.3]), 0.1 * side);
        add(at([0.75, 0.7, 0.6]), 0.2 * side);
    }
    scene
}

/// Runs `scene` with every finder: the same sensor events with each, matching the reference.
fn check_every_finder<const D: usize>(scene: &Scene<D>, until: f64) {
    let (want, paths) = run_with_paths(scene, "all-pairs", until);
    assert!(want.len() > 20, "{} events", want.len());
    assert!(want.windows(2).all(|w| w[0].time <= w[1].time));
    let matched = check_against_reference(scene, &want, &paths, until);
    assert!(
        matched * 10 >= want.len() * 9,
        "{matched} of {}",
        want.len()
    );
    for finder in ["bvh", "sedgewick", "cells"] {
        let (got, _) = run_with_paths(scene, finder, until);
        assert!(got == want, "[{finder}] differs from all-pairs");
    }
}

#[test]
fn periodic_sensor_events_match_the_minimum_image_reference_in_2d() {
    for seed in 1..=3 {
        let scene = gas_with_sensors::<2>(60, true, seed);
        check_every_finder(&scene, 6.0);
    }
}

#[test]
fn periodic_sensor_events_match_the_minimum_image_reference_in_3d() {
    for seed in 1..=2 {
        let scene = gas_with_sensors::<3>(60, true, seed);
        check_every_finder(&scene, 4.0);
    }
}

#[test]
fn growing_sensor_events_match_the_reference_with_walls_and_in_a_periodic_box() {
    for (periodic, seed) in [(false, 1), (false, 2), (true, 3), (true, 4)] {
        let mut scene = gas_with_sensors::<2>(60, periodic, seed);
        scene.settings.growth = Some(Growth { rate: 0.05 });
        check_every_finder(&scene, 5.0);
        let mut scene = gas_with_sensors::<3>(50, periodic, seed);
        scene.settings.growth = Some(Growth { rate: 0.05 });
        check_every_finder(&scene, 3.0);
    }
}

#[test]
fn periodic_sensors_must_lie_in_the_box_and_fit_it() {
    let parse = |sensors: &str| {
        AnyScene::from_json(&format!(
            r#"{{"dim": 2, "periodic": [10, 8], "bodies": [{{"pos": [1, 1], "vel": [0, 0], "radius": 0.5}}], "sensors": {sensors}}}"#
        ))
        .map(|_| ())
        .map_err(|e| e.to_string())
    };
    assert_eq!(parse(r#"[{"center": [9.9, 0], "radius": 3.4}]"#), Ok(()));
    // 2·(3.5 + 0.5) = 8: the side along y.
    let e = parse(r#"[{"center": [5, 4], "radius": 3.5}]"#).unwrap_err();
    assert!(
        e.contains("sensors[0].radius") && e.contains("half the periodic box's side 8"),
        "{e}"
    );
    let e = parse(r#"[{"center": [5, 4], "radius": 1}, {"center": [10, 4], "radius": 1}]"#)
        .unwrap_err();
    assert!(
        e.contains("sensors[1].center") && e.contains("outside the periodic box"),
        "{e}"
    );
    let e = parse(r#"[{"center": [5, -0.5], "radius": 1}]"#).unwrap_err();
    assert!(e.contains("sensors[0].center"), "{e}");
    // 3D: the smallest side decides.
    let e = AnyScene::from_json(
        r#"{"dim": 3, "periodic": [10, 10, 4], "bodies": [{"pos": [1, 1, 1], "vel": [0, 0, 0], "radius": 0.5}], "sensors": [{"center": [5, 5, 2], "radius": 1.5}]}"#,
    )
    .unwrap_err()
    .to_string();
    assert!(
        e.contains("sensors[0].radius") && e.contains("axis 2"),
        "{e}"
    );
}

#[test]
fn a_body_too_large_for_a_periodic_sensor_cannot_be_added() {
    let scene = periodic_box(
        vec![BodySpec::new(Vector([1.0, 1.0]), Vector([1.0, 0.0]), 0.5)],
        vec![sensor([5.0, 4.0], 3.0)],
    );
    let mut sim = Simulation::new(&scene, "cells").unwrap();
    // 2·(3 + 1) = 8 reaches the side 8.
    let e = sim
        .add_body(BodySpec::new(Vector([5.0, 7.0]), Vector::ZERO, 1.0))
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("add_body: sensors[0]") && e.contains("half the periodic box's side"),
        "{e}"
    );
    assert_eq!(sim.world().body_count(), 1);
    // One just small enough is added, and enters the sensor it starts in.
    let i = sim
        .add_body(BodySpec::new(Vector([5.0, 7.5]), Vector::ZERO, 0.9))
        .unwrap();
    sim.run_until(0.5);
    assert_eq!(sim.take_sensor_events(), vec![enter(0.0, i, 0)]);
}

#[test]
fn a_body_reaching_a_sensor_just_as_it_crosses_the_face_enters_once() {
    // The path y = 4 + dy meets the image (x = 10.3) of the sensor at x = 0.3 exactly on the
    // face x = 10: the body is on the sensor's sphere at its box exit. Rounding of the wrap
    // must not make it leave and enter again there. Many neighbouring paths, float by float.
    let sigma: f64 = 1.2;
    let dy0 = (sigma * sigma - 0.09).sqrt();
    let mut cases = 0;
    for finder in FINDERS {
        let mut dy = dy0;
        for _ in 0..40 {
            dy = f64::from_bits(dy.to_bits() - 1);
        }
        for _ in 0..80 {
            dy = f64::from_bits(dy.to_bits() + 1);
            let scene = periodic_box(
                vec![BodySpec::new(
                    Vector([8.0, 2.0 + dy]),
                    Vector([1.0, 0.0]),
                    0.2,
                )],
                vec![sensor([0.3, 2.0], 1.0)],
            );
            let mut sim = Simulation::new(&scene, finder).unwrap();
            sim.run_until(3.0);
            let events = sim.take_sensor_events();
            let kinds: Vec<_> = events.iter().map(|e| e.change).collect();
            assert_eq!(
                kinds,
                [SensorChange::Enter, SensorChange::Leave],
                "[{finder}] dy = {dy:e}: {events:?}"
            );
            assert!((events[0].time - 2.0).abs() < 1e-9, "{events:?}");
            assert!((events[1].time - 2.6).abs() < 1e-9, "{events:?}");
            cases += 1;
        }
    }
    assert_eq!(cases, 320);
}

#[test]
fn a_growing_body_handed_from_a_sensor_to_its_image_never_leaves() {
    // Box 10 × 10, sensor at x = 2 of radius 4.3 (its image at x = 12); the body, radius 0.5
    // growing at Γ = 0.5 (σ = 4.8 + 0.25·t), from x = 5.5 at +1 m/s. It is in the image's
    // sphere from t = 1.7/1.25 on, before it would leave the sensor's (at 1.3/0.75): inside
    // one or the other all along, it never leaves (once σ > L/2 the two overlap).
    for finder in FINDERS {
        let mut scene = Scene::<2> {
            bodies: vec![BodySpec::new(Vector([5.5, 5.0]), Vector([1.0, 0.0]), 0.5)],
            periodic: Some(Vector([10.0, 10.0])),
            sensors: vec![sensor([2.0, 5.0], 4.3)],
            ..Scene::default()
        };
        scene.settings.growth = Some(Growth { rate: 0.5 });
        let mut sim = Simulation::new(&scene, finder).unwrap();
        sim.run_until(8.0);
        assert!(sim.stats().exits >= 1, "[{finder}]");
        assert_eq!(
            sim.take_sensor_events(),
            vec![enter(0.0, 0, 0)],
            "[{finder}]"
        );
        assert!(sim.sensors().unwrap().is_inside(0, 0));
    }
}

#[test]
fn rebuilding_the_finder_reports_no_sensor_events_of_the_past() {
    // The body entered the sensor at 1.25, after its motion began (at 0). Adding a body
    // that needs new slots re-initialises the finder and recomputes every body's sensor
    // events: from now, not from the motion's start (where the body was still outside).
    for finder in FINDERS {
        let scene = table(
            vec![BodySpec::new(Vector([1.0, 2.0]), Vector([2.0, 0.0]), 0.5)],
            vec![sensor([5.0, 2.0], 1.0)],
        );
        let mut sim = Simulation::new(&scene, finder).unwrap();
        sim.run_until(2.0);
        assert_eq!(sim.take_sensor_events(), vec![enter(1.25, 0, 0)]);
        sim.add_body(BodySpec::new(Vector([1.0, 1.0]), Vector::ZERO, 0.2))
            .unwrap();
        sim.run_until(3.0);
        assert_eq!(
            sim.take_sensor_events(),
            vec![leave(2.75, 0, 0)],
            "[{finder}]"
        );
    }
}

#[test]
fn stopping_the_growth_or_cooling_reports_no_sensor_events_of_the_past() {
    // Growing at Γ = 0.5, the body of radius 0.5 at rest 3 m from the sensor's centre
    // (σ = 1.5 + 0.25·t) enters at 6. Body 2, 2 m from it and moving away at 0.5 m/s, stays
    // out (2 + 0.5·t > σ), though with the radius of t = 7 it would have been in where its
    // motion began. Stopping the growth at 7 (and cooling) must not find it there.
    for finder in FINDERS {
        let mut scene = table(
            vec![
                BodySpec::new(Vector([7.0, 10.0]), Vector([0.0, 0.0]), 0.5),
                BodySpec::new(Vector([14.0, 10.0]), Vector([0.0, 0.0]), 0.25),
                BodySpec::new(Vector([10.0, 8.0]), Vector([0.0, -0.5]), 0.5),
            ],
            vec![sensor([10.0, 10.0], 1.0)],
        );
        // Room for the radii to grow to 2.25 m and 1.125 m without meeting the walls.
        scene.walls = box_walls(Vector([20.0, 20.0]));
        scene.settings.growth = Some(Growth { rate: 0.5 });
        let mut sim = Simulation::new(&scene, finder).unwrap();
        sim.run_until(7.0);
        let events = sim.take_sensor_events();
        assert_eq!(events.len(), 1, "[{finder}] {events:?}");
        assert_eq!((events[0].body, events[0].change), (0, SensorChange::Enter));
        assert!((events[0].time - 6.0).abs() < 1e-14, "{events:?}");
        sim.stop_growth().unwrap();
        sim.run_until(10.0);
        assert_eq!(sim.take_sensor_events(), vec![], "[{finder}]");
        sim.rescale_velocities(2.0).unwrap();
        // Body 2 (radius 2.25 now, at y = 3 moving down at 1 m/s) bounces off the floor at
        // 10.75, far from the sensor.
        sim.run_until(11.0);
        assert_eq!(sim.take_sensor_events(), vec![], "[{finder}]");
        assert_eq!(sim.sensors().unwrap().bodies_in(0), vec![0]);
    }
}
