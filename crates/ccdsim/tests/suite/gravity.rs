//! Uniform gravity: scene validation, analytic bounces, pairs that fall together, run files of
//! format version 4, and the halt of a ball come to rest.

use ccdsim::generate::{box_walls, pegs, PegsConfig};
use ccdsim::record::{RunReader, RunRecord, RunWriter, VERSION_GRAVITY};
use ccdsim::Gravity;
use ccdsim::{AnyScene, BodySpec, Halt, Scene, SceneError, Simulation, Vector, Wall};

/// A 3D ball dropped from height `h` (centre `h + r` above the floor) in a box.
fn dropped_ball(h: f64, restitution: f64) -> Scene<3> {
    let mut scene = Scene::<3> {
        bodies: vec![BodySpec::new(
            Vector([2.0, 2.0, 0.5 + h]),
            Vector([0.0, 0.0, 0.0]),
            0.5,
        )],
        walls: box_walls(Vector([4.0, 4.0, 40.0])),
        ..Scene::default()
    };
    scene.settings.gravity = Gravity::new(&[0.0, 0.0, -9.81]);
    scene.settings.restitution = restitution;
    scene
}

#[test]
fn an_elastic_ball_bounces_with_the_free_fall_period() {
    // Falls h = 5 m in √(2h/g), then bounces every 2√(2h/g), back to the same height.
    let h = 5.0;
    let fall = (2.0 * h / 9.81f64).sqrt();
    for finder in ["all-pairs", "bvh", "sedgewick", "cells"] {
        let mut sim = Simulation::new(&dropped_ball(h, 1.0), finder).unwrap();
        for k in 0..20 {
            let c = sim.step_event().unwrap();
            let want = fall * (1.0 + 2.0 * f64::from(k));
            assert!(
                (c.event.time - want).abs() < 1e-12 * (1.0 + want),
                "[{finder}] bounce {k} at {} not {want}",
                c.event.time
            );
            assert!((c.pos[0][2] - 0.5).abs() < 1e-12, "{:?}", c.pos[0]);
            assert!((c.vel[0][2] - (2.0 * 9.81 * h).sqrt()).abs() < 1e-10);
        }
        let w = sim.world();
        let t = sim.time();
        let total = w.kinetic_energy_at(t) + w.potential_energy_at(t);
        let start = -w.mass(0) * -9.81 * (0.5 + h);
        assert!((total - start).abs() < 1e-10 * start, "{total} vs {start}");
    }
}

#[test]
fn bodies_falling_together_meet_as_without_gravity() {
    // Relative acceleration is zero: a head-on pair meets at the same time with or without
    // gravity, whatever their reference times.
    let pair = |g: Option<Gravity>| {
        let mut scene = Scene::<2> {
            bodies: vec![
                BodySpec::new(Vector([0.0, 100.0]), Vector([1.0, 0.0]), 0.5),
                BodySpec::new(Vector([10.0, 100.0]), Vector([-1.0, 0.0]), 0.5),
            ],
            ..Scene::default()
        };
        scene.settings.gravity = g;
        Simulation::new(&scene, "cells")
            .unwrap()
            .step_event()
            .unwrap()
    };
    let plain = pair(None);
    let falling = pair(Gravity::new(&[0.0, -9.81]));
    assert_eq!(plain.event.time, 4.5);
    assert_eq!(falling.event.time, 4.5);
    assert_eq!(falling.vel[0][0], -1.0);
    // Both fell alike: 0.5·g·t² below the start.
    let drop = 0.5 * 9.81 * 4.5 * 4.5;
    assert!((falling.pos[0][1] - (100.0 - drop)).abs() < 1e-12);
}

#[test]
fn scenes_with_gravity_are_validated() {
    let text = |settings: &str, extra: &str| {
        format!(
            r#"{{"dim": 2, "settings": {settings}, "bodies": [{{"pos": [1, 1], "vel": [0, 0], "radius": 0.5}}]{extra}}}"#
        )
    };
    let scene = AnyScene::from_json(&text(r#"{"gravity": [0, -9.81]}"#, "")).unwrap();
    let AnyScene::D2(s) = scene else { panic!("2D") };
    assert_eq!(s.gravity(), Some(Vector([0.0, -9.81])));
    let err = |settings: &str, extra: &str| {
        AnyScene::from_json(&text(settings, extra))
            .unwrap_err()
            .to_string()
    };
    let e = err(r#"{"gravity": [0, -9.81, 0]}"#, "");
    assert!(
        e.contains("settings.gravity") && e.contains("3 components"),
        "{e}"
    );
    let e = err(r#"{"gravity": [1]}"#, "");
    assert!(
        e.contains("settings.gravity") && e.contains("1 components"),
        "{e}"
    );
    let e = err(r#"{"gravity": "down"}"#, "");
    assert!(e.contains("settings.gravity"), "{e}");
    let e = err(r#"{"gravity": [0, -1]}"#, r#", "periodic": [10, 10]"#);
    assert!(e.contains("periodic box"), "{e}");
    // Gravity combines with growing radii (sedimented packings, see `ccdsim::contact::falling_growth`);
    // resting contacts do not: a resting body would have to move off its wall as it grows.
    let scene = AnyScene::from_json(&text(
        r#"{"gravity": [0, -1], "growth": {"rate": 0.1}}"#,
        "",
    ));
    let AnyScene::D2(s) = scene.unwrap() else {
        panic!("2D")
    };
    assert_eq!(s.settings.growth.map(|g| g.rate), Some(0.1));
    let e = err(
        r#"{"gravity": [0, -1], "growth": {"rate": 0.1}, "rest_speed": 0.1}"#,
        "",
    );
    assert!(
        e.contains("settings.rest_speed") && e.contains("settings.growth"),
        "{e}"
    );
    // NaN cannot be written in JSON; through the API it is refused too.
    let mut s = dropped_ball(1.0, 1.0);
    s.settings.gravity = Gravity::new(&[0.0, f64::NAN, 0.0]);
    assert_eq!(
        s.validate(),
        Err(SceneError::NonFinite("settings.gravity".into()))
    );
    // Segments in 3D (rods) are served under gravity, static and moving (see `tests/rods.rs`).
    let mut s = dropped_ball(1.0, 1.0);
    s.walls.push(Wall::Segment {
        a: Vector([1.0, 1.0, 30.0]),
        b: Vector([3.0, 1.0, 30.0]),
    });
    s.moving_walls.push(ccdsim::MovingWall {
        wall: Wall::Segment {
            a: Vector([1.0, 3.0, 20.0]),
            b: Vector([3.0, 3.0, 20.0]),
        },
        velocity: Vector([0.0, 0.0, -1.0]),
    });
    assert_eq!(s.validate(), Ok(()));
    let text = r#"{"dim": 3, "settings": {"gravity": [0, 0, -9.81]},
        "bodies": [{"pos": [1, 1, 5], "vel": [0, 0, 0], "radius": 0.5}],
        "walls": [{"a": [0, 1, 1], "b": [2, 1, 1]}],
        "moving_walls": [{"a": [0, 3, 1], "b": [2, 3, 1], "velocity": [0, 0, 1]}]}"#;
    assert!(AnyScene::from_json(text).is_ok());
    // With growing radii too: rods meet growing balls as well.
    s.settings.growth = Some(ccdsim::Growth { rate: 0.1 });
    assert_eq!(s.validate(), Ok(()));
}

#[test]
fn run_files_of_gravity_scenes_are_version_4_and_read_back() {
    let scene = pegs(&PegsConfig {
        balls: 16,
        rows: 3,
        ..PegsConfig::default()
    })
    .unwrap();
    let mut sim = Simulation::new(&scene, "cells").unwrap();
    let mut w = RunWriter::new(Vec::new(), "cells".into(), &scene).unwrap();
    let mut events = Vec::new();
    sim.run_events_with(300, |c| {
        w.write_event(c).unwrap();
        events.push(*c);
    });
    let bytes = w.finish(sim.time()).unwrap();
    assert_eq!(
        u32::from_le_bytes(bytes[8..12].try_into().unwrap()),
        VERSION_GRAVITY
    );
    let mut r = RunReader::<_, 2>::new(&bytes[..], "run".into()).unwrap();
    assert_eq!(r.scene().gravity(), Some(Vector([0.0, -9.81])));
    let mut read = Vec::new();
    while let Some(RunRecord::Event(c)) = r.next_record().unwrap() {
        read.push(c);
    }
    assert_eq!(read, events);
}

#[test]
fn run_files_of_growing_scenes_under_gravity_are_version_4_read_back_and_verify() {
    // Gravity's version (it comes after growth's): the header carries both settings, and a
    // build that predates the combination refuses the scene when it reads the header.
    let mut scene = pegs(&PegsConfig {
        balls: 16,
        rows: 3,
        ..PegsConfig::default()
    })
    .unwrap();
    scene.settings.growth = Some(ccdsim::Growth { rate: 0.05 });
    let mut sim = Simulation::new(&scene, "bvh").unwrap();
    let mut w = RunWriter::new(Vec::new(), "bvh".into(), &scene).unwrap();
    let mut events = Vec::new();
    sim.run_events_with(400, |c| {
        w.write_event(c).unwrap();
        events.push(*c);
    });
    assert_eq!(events.len(), 400);
    // The radii have grown, and the frames' radii are the grown ones.
    assert!(sim.radius(0) > scene.bodies[0].radius);
    let bytes = w.finish(sim.time()).unwrap();
    assert_eq!(
        u32::from_le_bytes(bytes[8..12].try_into().unwrap()),
        VERSION_GRAVITY
    );
    let mut r = RunReader::<_, 2>::new(&bytes[..], "run".into()).unwrap();
    assert_eq!(r.scene().gravity(), Some(Vector([0.0, -9.81])));
    assert_eq!(r.scene().settings.growth.map(|g| g.rate), Some(0.05));
    let (read, end) = r.read_events().unwrap();
    assert_eq!(read, events);
    let mut v = ccdsim::verify::Verifier::new(&scene);
    for c in &read {
        v.check(c).unwrap();
    }
    v.finish(end.unwrap()).unwrap();
    // A collision that breaks the growth rule is caught: a wall bounce whose velocity after
    // is the one before (no bounce at all).
    let k = read
        .iter()
        .position(|c| c.event.kind == ccdsim::EventKind::Wall)
        .unwrap();
    let mut bad = read.clone();
    bad[k].vel[0] = bad[k].vel[0] * -1.0;
    let mut v = ccdsim::verify::Verifier::new(&scene);
    let failed = bad.iter().try_for_each(|c| v.check(c));
    assert!(
        failed.is_err(),
        "a bounce against the growth rule passes verify"
    );
}

#[test]
fn a_ball_that_comes_to_rest_halts_the_run_at_the_same_event_with_every_finder() {
    // Restitution 0.5: the bounces die away geometrically (a Zeno sequence), until the ball
    // touches the floor with no normal speed; resting contacts are not simulated yet, so the
    // run stops there, saying so, instead of looping at one instant.
    let mut ends = Vec::new();
    for finder in ["all-pairs", "bvh", "sedgewick", "cells"] {
        let mut sim = Simulation::new(&dropped_ball(1.0, 0.5), finder).unwrap();
        let n = sim.run_events(100_000);
        assert!(n < 100_000, "[{finder}] the run must stop");
        let Some(Halt::Resting { body, wall, time }) = sim.halt() else {
            panic!("[{finder}] expected a resting halt, got {:?}", sim.halt());
        };
        assert_eq!((body, wall), (0, 4), "[{finder}] the floor is wall 4");
        // The Zeno time of the bounces: t₁ (1 + 2e/(1 − e)) with t₁ the first fall.
        let t1 = (2.0 / 9.81f64).sqrt();
        assert!((time - t1 * 3.0).abs() < 1e-6, "[{finder}] rests at {time}");
        ends.push((n, time.to_bits()));
        // It stays halted: run_until does not move the clock past the rest.
        sim.run_until(time + 1.0);
        assert_eq!(sim.time().to_bits(), time.to_bits());
    }
    assert!(ends.windows(2).all(|w| w[0] == w[1]), "{ends:?}");
}

#[test]
fn bounces_the_clock_quantises_into_a_fixed_point_halt_the_run_too() {
    // A ball of restitution 0.9 dropped on a floor (2D): its bounces die away until each
    // hop lasts a few ulps of time, where rounding the flight to whole ulps feeds back as
    // much speed as the restitution takes: 1.65e-14 m/s, 4 ulps a hop, at t ≈ 7.23 s, for
    // ever. Such hops rise 1e-29 m, far below the resolution of the ball: the run halts,
    // at the same event with every finder, instead of creeping on a few ulps an event.
    let scene = Scene {
        bodies: vec![BodySpec::new(
            Vector([2.9993153025651473, 1.1852748539049491]),
            Vector([0.07641747911227026, -0.9279602241779514]),
            0.5,
        )],
        walls: vec![Wall::Plane {
            point: Vector([0.0, 0.0]),
            normal: Vector([0.0, 1.0]),
        }],
        settings: ccdsim::Settings {
            restitution: 0.9,
            gravity: Gravity::new(&[0.0, -9.81]),
            ..ccdsim::Settings::default()
        },
        ..Scene::default()
    };
    let mut ends = Vec::new();
    for finder in ["all-pairs", "bvh", "sedgewick", "cells"] {
        let mut sim = Simulation::new(&scene, finder).unwrap();
        let mut w = RunWriter::new(Vec::new(), finder.into(), &scene).unwrap();
        let mut events = Vec::new();
        // Capped: without the halt the clock creeps on for ever.
        sim.run_events_with(5_000, |c| {
            w.write_event(c).unwrap();
            events.push(*c);
        });
        assert!(events.len() < 5_000, "[{finder}] {} events", events.len());
        let Some(Halt::Resting { body, wall, time }) = sim.halt() else {
            panic!("[{finder}] expected a resting halt, got {:?}", sim.halt());
        };
        assert_eq!((body, wall), (0, 0), "[{finder}]");
        assert!((time - 7.231_067_016_5).abs() < 1e-9, "[{finder}] {time}");
        // The last thousand bounces are the unresolved ones: each comes less than 2e-5 s
        // (the longest hop under 5e-10 of the radius) after the one before.
        let last = &events[events.len() - ccdsim::sim::WEDGED_AFTER as usize..];
        assert!(last
            .windows(2)
            .all(|p| p[1].event.time - p[0].event.time < 2e-5));
        let mut v = ccdsim::verify::Verifier::new(&scene);
        events.iter().try_for_each(|c| v.check(c)).unwrap();
        v.finish(time).unwrap();
        ends.push(w.finish(time).unwrap());
    }
    assert!(ends.windows(2).all(|w| w[0] == w[1]));
}
