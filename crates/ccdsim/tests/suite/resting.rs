//! Resting and sliding contacts (`settings.rest_speed`): balls whose bounces die away come to
//! rest on floors and inclines and slide along them, the same with every finder; run files
//! mark it, `verify` checks it and rejects forged rests; the scene rules.

use crate::replay;

use ccdsim::discrete::DiscreteStepper;
use ccdsim::record::RunWriter;
use ccdsim::Gravity;
use ccdsim::{BodySpec, Halt, Scene, SceneError, Settings, Simulation, Vector, Wall};

const FINDERS: [&str; 4] = ["all-pairs", "bvh", "sedgewick", "cells"];

fn plane(point: [f64; 2], normal: [f64; 2]) -> Wall<2> {
    Wall::Plane {
        point: Vector(point),
        normal: Vector(normal),
    }
}

/// Balls dropped into a box with a floor, an incline in its left corner and side walls,
/// restitution 0.5, resting below 0.4 m/s.
fn box_with_incline(balls: usize) -> Scene<2> {
    Scene {
        settings: Settings {
            restitution: 0.5,
            gravity: Gravity::new(&[0.0, -9.81]),
            rest_speed: Some(0.4),
            ..Settings::default()
        },
        bodies: (0..balls)
            .map(|k| {
                let x = 1.0 + 1.7 * k as f64;
                let y = 2.5 + 0.9 * (k % 3) as f64;
                BodySpec::new(Vector([x, y]), Vector([0.7 - 0.3 * k as f64, 0.0]), 0.25)
            })
            .collect(),
        walls: vec![
            plane([0.0, 0.0], [0.0, 1.0]),
            plane([0.0, 0.0], [1.0, 0.0]),
            plane([12.0, 0.0], [-1.0, 0.0]),
            plane([0.0, 2.0], [1.0, 1.5]),
        ],
        ..Scene::default()
    }
}

/// Restitution `e`, gravity 10 m/s² downwards, resting below `rest_speed`.
fn falling_settings(e: f64, rest_speed: f64) -> Settings {
    Settings {
        restitution: e,
        gravity: Gravity::new(&[0.0, -10.0]),
        rest_speed: Some(rest_speed),
        ..Settings::default()
    }
}

fn recorded(scene: &Scene<2>, finder: &str, until: f64) -> (Vec<u8>, Simulation<2>) {
    let mut sim = Simulation::new(scene, finder).unwrap();
    let mut run = RunWriter::new(Vec::new(), "rest".into(), scene).unwrap();
    sim.run_until_with(until, |c| run.write_event(c).unwrap());
    (run.finish(sim.time()).unwrap(), sim)
}

#[test]
fn a_dropped_ball_comes_to_rest_on_the_floor_and_slides_on_at_its_speed() {
    // Dropped from 1.25 m (centre at 1.5, radius 0.25): it meets the floor at 5 m/s; each
    // bounce leaves with half the speed, so 5 → 2.5 → 1.25 → 0.625 and then 0.3125 ≤ 0.4: it
    // rests at the fourth contact, and its 0.5 m/s along the floor never changes.
    let scene = Scene {
        settings: falling_settings(0.5, 0.4),
        bodies: vec![BodySpec::new(Vector([0.0, 1.5]), Vector([0.5, 0.0]), 0.25)],
        walls: vec![plane([0.0, 0.0], [0.0, 1.0])],
        ..Scene::default()
    };
    for finder in FINDERS {
        let mut sim = Simulation::new(&scene, finder).unwrap();
        let mut contacts = Vec::new();
        sim.run_until_with(10.0, |c| contacts.push((c.event.time, c.rests[0])));
        assert_eq!(contacts.len(), 4, "[{finder}] {contacts:?}");
        assert!(
            contacts[..3].iter().all(|c| !c.1) && contacts[3].1,
            "{contacts:?}"
        );
        // 0.5 s to fall, then 0.5, 0.25 and 0.125 s in the air between contacts.
        let t_rest = 0.5 + 0.5 + 0.25 + 0.125;
        assert!(
            (contacts[3].0 - t_rest).abs() < 1e-12,
            "[{finder}] {contacts:?}"
        );
        assert_eq!(sim.world().support(0), Some(0));
        assert!(sim.halt().is_none(), "[{finder}] {:?}", sim.halt());
        let p = sim.position(0);
        assert!(
            (p[1] - 0.25).abs() < 1e-12,
            "[{finder}] it stays on the floor: {p:?}"
        );
        assert!((p[0] - 0.5 * 10.0).abs() < 1e-12, "[{finder}] {p:?}");
        assert_eq!(sim.world().velocity_at(0, 10.0).0, [0.5, 0.0]);
    }
}

#[test]
fn a_ball_at_rest_on_an_incline_slides_down_it_at_g_sin_alpha() {
    // A 30° incline through the origin; a ball put on it at rest... dropped a hair above it
    // with rest_speed above any bounce: it rests at the first contact and slides with
    // acceleration g sin 30° = 5 m/s² along the incline.
    let (s, c) = (0.5f64, 0.75f64.sqrt());
    let normal = [s, c];
    let r = 0.5;
    let start = [0.0 + normal[0] * (r + 1e-3), 0.0 + normal[1] * (r + 1e-3)];
    let scene = Scene {
        settings: falling_settings(0.5, 1.0),
        bodies: vec![BodySpec::new(Vector(start), Vector([0.0, 0.0]), r)],
        walls: vec![plane([0.0, 0.0], normal)],
        ..Scene::default()
    };
    for finder in FINDERS {
        let mut sim = Simulation::new(&scene, finder).unwrap();
        let first = sim.step_event().unwrap();
        assert!(first.rests[0], "[{finder}]");
        let t0 = first.event.time;
        let p0 = first.pos[0];
        let v0 = first.vel[0];
        sim.advance(2.0);
        let t = sim.time() - t0;
        // Down the slope: direction (c, −s); the slide starts with v0 along it.
        let down = Vector([c, -s]);
        let along = v0.dot(down);
        assert!(v0.dot(Vector(normal)).abs() < 1e-15, "[{finder}] {v0:?}");
        let expect = p0 + down * (along * t + 0.5 * 5.0 * t * t);
        let got = sim.position(0);
        assert!(
            (got - expect).norm() < 1e-9,
            "[{finder}] {got:?} vs {expect:?}"
        );
        // Still touching the incline: centre at r from the plane.
        assert!(
            (got.dot(Vector(normal)) - r).abs() < 1e-9,
            "[{finder}] {got:?}"
        );
    }
}

#[test]
fn every_finder_writes_the_oracle_run_file_and_verify_accepts_it() {
    let scene = box_with_incline(7);
    let (oracle, sim) = recorded(&scene, "all-pairs", 6.0);
    let (_, events, end) = replay::records::<2>(&oracle);
    let rests = events.iter().filter(|c| c.rests[0] || c.rests[1]).count();
    assert!(rests >= 5, "bodies come to rest: {rests} rest flags");
    assert!(
        (0..7).filter(|&i| sim.world().support(i).is_some()).count() >= 3,
        "several balls rest at the end"
    );
    for finder in &FINDERS[1..] {
        let (bytes, _) = recorded(&scene, finder, 6.0);
        assert!(
            bytes == oracle,
            "[{finder}] run file differs from the oracle's"
        );
    }
    for all_pairs in [false, true] {
        let report = replay::replay(&scene, &events, end, all_pairs).unwrap();
        assert!(report.max_overlap < 1e-9, "{report:?}");
    }
    assert_eq!(ccdsim::record::version_for(&scene), 11);
}

#[test]
fn verify_rejects_a_forged_rest() {
    let scene = box_with_incline(7);
    let (bytes, _) = recorded(&scene, "cells", 6.0);
    let (_, events, end) = replay::records::<2>(&bytes);
    let first_rest = events.iter().position(|c| c.rests[0]).unwrap();
    // A bounce marked as a rest: the body would sink through the floor on its slide.
    let bounce = events
        .iter()
        .position(|c| c.event.kind == ccdsim::EventKind::Wall && !c.rests[0])
        .unwrap();
    let mut forged = events.clone();
    forged[bounce].rests[0] = true;
    let err = replay::replay(&scene, &forged, end, false).unwrap_err();
    assert!(err.contains("rests on wall"), "{err}");
    // A rest taken out: the body would fall through the floor it rests on.
    let mut forged = events.clone();
    forged[first_rest].rests[0] = false;
    assert!(replay::replay(&scene, &forged, end, false).is_err());
}

#[test]
fn a_ball_landing_for_ever_on_a_resting_one_halts_the_same_with_every_finder() {
    // Two balls stacked on a floor: the upper one's bounces on the lower, resting one die
    // away (the lower one passes its push on to the floor), until they touch without
    // normal speed under gravity: the run stops there, the same for every finder.
    let scene = Scene {
        settings: falling_settings(0.5, 0.4),
        bodies: vec![
            BodySpec::new(Vector([0.0, 0.5]), Vector([0.0, 0.0]), 0.5),
            BodySpec::new(Vector([0.0, 2.0]), Vector([0.0, 0.0]), 0.5),
        ],
        walls: vec![plane([0.0, 0.0], [0.0, 1.0])],
        ..Scene::default()
    };
    let mut halts = Vec::new();
    for finder in FINDERS {
        let mut sim = Simulation::new(&scene, finder).unwrap();
        sim.run_until(5.0);
        halts.push(sim.halt());
    }
    assert!(
        matches!(halts[0], Some(Halt::RestingOnBody { a: 0, b: 1, .. })),
        "{halts:?}"
    );
    assert!(halts.iter().all(|h| *h == halts[0]), "{halts:?}");
}

#[test]
fn rest_speed_needs_gravity_and_a_positive_speed() {
    let mut scene = box_with_incline(2);
    scene.settings.gravity = None;
    let err = scene.validate().unwrap_err();
    assert!(matches!(err, SceneError::Unsupported { .. }), "{err}");
    assert!(err.to_string().contains("settings.rest_speed"), "{err}");
    let mut scene = box_with_incline(2);
    scene.settings.rest_speed = Some(0.0);
    assert!(matches!(scene.validate(), Err(SceneError::NonPositive(_))));
    scene.settings.rest_speed = Some(f64::NAN);
    assert!(matches!(scene.validate(), Err(SceneError::NonFinite(_))));
    let err = DiscreteStepper::new(&box_with_incline(2)).unwrap_err();
    assert!(err.to_string().contains("rest"), "{err}");
    // Read from a scene file.
    let json = r#"{"settings": {"gravity": [0, -9.81], "rest_speed": 0.2}, "bodies": []}"#;
    let scene: Scene<2> = serde_json::from_str(json).unwrap();
    assert_eq!(scene.settings.rest_speed, Some(0.2));
}

#[test]
fn a_ball_landing_on_a_resting_one_pushes_it_along_the_floor_not_into_it() {
    // Ball 0 lands on the floor at once and rests (rest_speed above its speed); ball 1 falls
    // onto it off-centre. The floor takes the normal part of ball 0's push: ball 0 slides
    // off sideways, still resting, and the pair parts at e times its closing speed.
    let e = 0.5;
    let scene = Scene {
        settings: falling_settings(e, 1.0),
        bodies: vec![
            BodySpec::new(Vector([0.0, 0.5 + 1e-6]), Vector([0.0, 0.0]), 0.5),
            BodySpec::new(Vector([-0.6, 3.0]), Vector([0.0, 0.0]), 0.5),
        ],
        walls: vec![plane([0.0, 0.0], [0.0, 1.0])],
        ..Scene::default()
    };
    for finder in FINDERS {
        let mut sim = Simulation::new(&scene, finder).unwrap();
        let landing = sim.step_event().unwrap();
        assert!(
            landing.rests[0] && landing.event.b == 0,
            "[{finder}] {landing:?}"
        );
        let t = sim.peek_event().unwrap().time;
        let (v0, v1) = (sim.world().velocity_at(0, t), sim.world().velocity_at(1, t));
        let hit = sim.step_event().unwrap();
        assert_eq!(hit.event.kind, ccdsim::EventKind::Body, "[{finder}]");
        assert_eq!(
            hit.rests,
            [true, false],
            "[{finder}] ball 0 stays on the floor"
        );
        assert_eq!(sim.world().support(0), Some(0));
        let (w0, w1) = (hit.vel[0], hit.vel[1]);
        assert_eq!(w0[1], 0.0, "[{finder}] along the floor: {w0:?}");
        assert!(w0[0] > 0.0, "[{finder}] pushed away from ball 1: {w0:?}");
        // Equal masses: momentum along the floor is kept.
        assert!((w0[0] + w1[0] - v0[0] - v1[0]).abs() < 1e-12, "[{finder}]");
        // Normal speed reversed times e.
        let n = hit.pos[0] - hit.pos[1];
        let n = n * (1.0 / n.norm());
        let (before, after) = ((v0 - v1).dot(n), (w0 - w1).dot(n));
        assert!(
            (after + e * before).abs() < 1e-12,
            "[{finder}] {before} -> {after}"
        );
    }
    let (bytes, _) = recorded(&scene, "cells", 3.0);
    let (_, events, end) = replay::records::<2>(&bytes);
    replay::replay(&scene, &events, end, false).unwrap();
}

#[test]
fn a_rebuilt_world_takes_the_supports_a_record_gives() {
    // A tool rebuilding a world from a run file (the viewer) sets each body's state, which
    // lifts it off its wall, and then its support: the body then slides as the simulation's.
    let scene = box_with_incline(2);
    let mut sim = Simulation::new(&scene, "all-pairs").unwrap();
    sim.run_until(3.0);
    let resting: Vec<usize> = (0..2)
        .filter(|&i| sim.world().support(i).is_some())
        .collect();
    assert!(!resting.is_empty(), "a ball rests by 3 s");
    let mut world = ccdsim::World::from_scene(&scene).unwrap();
    for i in 0..2 {
        world.set_motion(i, sim.world().motion(i));
        assert_eq!(world.support(i), None);
        assert!(world.set_support(i, sim.world().support(i)));
        assert_eq!(world.support(i), sim.world().support(i));
        assert_eq!(world.acceleration(i), sim.world().acceleration(i));
        assert_eq!(world.position_at(i, 3.5), sim.world().position_at(i, 3.5));
    }
    // The side walls hold no resting body, and there is no body 2.
    assert!(!world.set_support(0, Some(1)));
    assert!(!world.set_support(2, Some(0)));
    assert!(world.set_support(resting[0], None));
    assert_eq!(world.support(resting[0]), None);
    assert_eq!(world.acceleration(resting[0]), Vector([0.0, -9.81]));
}

#[test]
fn a_body_added_with_its_own_restitution_rests_as_verify_expects() {
    // The scene's restitution is 0.9; a ball added with its own 0.1 meets the floor at
    // √(2·10·0.5) ≈ 3.16 m/s and leaves at 0.32 ≤ rest_speed 0.4: it rests at once, which
    // verify accepts only if it counts the added body's restitution.
    let scene = Scene {
        settings: falling_settings(0.9, 0.4),
        bodies: vec![BodySpec::new(Vector([5.0, 0.3]), Vector([0.0, 0.0]), 0.25)],
        walls: vec![plane([0.0, 0.0], [0.0, 1.0])],
        ..Scene::default()
    };
    let mut sim = Simulation::new(&scene, "cells").unwrap();
    let mut run = RunWriter::new_steered(Vec::new(), "added".into(), &scene).unwrap();
    sim.record_edits(true);
    let mut ball = BodySpec::new(Vector([0.0, 0.75]), Vector([0.0, 0.0]), 0.25);
    ball.restitution = Some(0.1);
    let i = sim.add_body(ball).unwrap();
    for record in sim.take_edits().iter().chain(&sim.advance(2.0)) {
        run.write_event(record).unwrap();
    }
    assert_eq!(sim.world().support(i), Some(0), "the added ball rests");
    let bytes = run.finish(sim.time()).unwrap();
    let (_, events, end) = replay::records::<2>(&bytes);
    replay::replay(&scene, &events, end, false).unwrap();
}
