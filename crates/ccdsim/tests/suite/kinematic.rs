//! Kinematic bodies (`bodies[].kinematic`): infinite mass, moved only by the velocity a
//! program gives them; they push dynamic bodies and meet no wall and no other kinematic body.

use ccdsim::generate::box_walls;
use ccdsim::record::{RunWriter, VERSION_KINEMATIC};
use ccdsim::verify::Verifier;
use ccdsim::Gravity;
use ccdsim::{AnyScene, BodySpec, Scene, Simulation, Vector};

fn paddle(pos: [f64; 2], vel: [f64; 2]) -> BodySpec<2> {
    BodySpec {
        kinematic: true,
        ..BodySpec::new(Vector(pos), Vector(vel), 0.5)
    }
}

fn table(bodies: Vec<BodySpec<2>>) -> Scene<2> {
    Scene {
        bodies,
        walls: box_walls(Vector([10.0, 4.0])),
        ..Scene::default()
    }
}

#[test]
fn a_moving_paddle_sends_a_resting_puck_off_at_twice_its_speed() {
    for finder in ["all-pairs", "bvh", "sedgewick", "cells"] {
        let scene = table(vec![
            paddle([2.0, 2.0], [1.0, 0.0]),
            BodySpec::new(Vector([5.0, 2.0]), Vector([0.0, 0.0]), 0.5),
        ]);
        let mut sim = Simulation::new(&scene, finder).unwrap();
        let hit = sim.step_event().unwrap();
        assert_eq!(hit.event.time, 2.0, "[{finder}]");
        // The paddle keeps its velocity; the puck leaves at 2 v (elastic, infinite mass).
        assert_eq!(hit.vel[0].0, [1.0, 0.0], "[{finder}]");
        assert_eq!(hit.vel[1].0, [2.0, 0.0], "[{finder}]");
        // The game stops the paddle; the puck meets the far wall at 2 + 4.5/2 s.
        sim.set_velocity(0, Vector([0.0, 0.0])).unwrap();
        let wall = sim.step_event().unwrap();
        assert_eq!((wall.event.a, wall.event.time), (1, 4.25), "[{finder}]");
        // A paddle sent up through the table's side meets no wall: it leaves the table.
        sim.set_velocity(0, Vector([0.0, 1.0])).unwrap();
        sim.run_until(10.0);
        assert!(
            (sim.position(0)[1] - 7.75).abs() < 1e-12,
            "[{finder}] {:?}",
            sim.position(0)
        );
        assert!(sim.halt().is_none());
    }
}

#[test]
fn kinematic_bodies_pass_through_each_other_and_ignore_gravity() {
    let mut scene = table(vec![
        paddle([2.0, 2.0], [1.0, 0.0]),
        paddle([8.0, 2.0], [-1.0, 0.0]),
        // A ball dropped onto a kinematic ball hanging in mid-air bounces back up, for ever.
        paddle([5.0, 1.0], [0.0, 0.0]),
        BodySpec::new(Vector([5.0, 3.0]), Vector([0.0, 0.0]), 0.4),
    ]);
    scene.bodies[0].pos = Vector([2.0, 3.0]);
    scene.bodies[1].pos = Vector([8.0, 3.2]);
    scene.settings.gravity = Gravity::new(&[0.0, -10.0]);
    let mut sim = Simulation::new(&scene, "cells").unwrap();
    let mut bounces = 0;
    sim.run_until_with(3.0, |c| {
        // Only the dynamic ball (3) meets walls, and kinematic bodies meet only it.
        match c.event.kind {
            ccdsim::EventKind::Wall => assert_eq!(c.event.a, 3, "{c:?}"),
            _ => assert_eq!(c.event.b, 3, "{c:?}"),
        }
        bounces += u32::from((c.event.a, c.event.b) == (2, 3));
    });
    assert!(bounces >= 2, "{bounces}");
    // Kinematic bodies moved in straight lines: gravity did not bend them.
    assert_eq!(sim.position(2).0, [5.0, 1.0]);
    assert!((sim.position(0)[1] - 3.0).abs() < 1e-12);
}

#[test]
fn runs_with_kinematic_bodies_are_version_5_and_verify_with_and_without_gravity() {
    let scene = table(vec![
        paddle([1.0, 1.0], [2.0, 0.5]),
        BodySpec::new(Vector([5.0, 2.0]), Vector([-1.0, 0.3]), 0.5),
        BodySpec::new(Vector([7.0, 1.0]), Vector([0.5, 1.0]), 0.4),
    ]);
    let mut sim = Simulation::new(&scene, "cells").unwrap();
    let mut w = RunWriter::new(Vec::new(), "cells".into(), &scene).unwrap();
    let mut v = Verifier::new(&scene);
    let mut n = 0;
    sim.run_until_with(30.0, |c| {
        w.write_event(c).unwrap();
        v.check(c).unwrap();
        n += 1;
    });
    assert!(n > 10);
    v.finish(30.0).unwrap();
    let bytes = w.finish(30.0).unwrap();
    assert_eq!(
        u32::from_le_bytes(bytes[8..12].try_into().unwrap()),
        VERSION_KINEMATIC
    );
    // Under gravity the paddle keeps its straight line while the balls fall: verify checks
    // both (a kinematic body's contacts with falling ones are parabolas seen from a line),
    // and catches a paddle recorded as if it fell.
    let mut falling = scene.clone();
    falling.settings.gravity = Gravity::new(&[0.0, -1.0]);
    let mut sim = Simulation::new(&falling, "cells").unwrap();
    let mut events = Vec::new();
    sim.run_until_with(30.0, |c| events.push(*c));
    let paddle_hits = events
        .iter()
        .filter(|c| c.event.kind == ccdsim::EventKind::Body && c.event.a == 0)
        .count();
    assert!(
        events.len() > 10 && paddle_hits > 0,
        "{} {paddle_hits}",
        events.len()
    );
    for all_pairs in [false, true] {
        let mut v = if all_pairs {
            Verifier::all_pairs(&falling)
        } else {
            Verifier::new(&falling)
        };
        for c in &events {
            v.check(c).unwrap();
        }
        v.finish(30.0).unwrap();
    }
    let k = events
        .iter()
        .position(|c| c.event.kind == ccdsim::EventKind::Body && c.event.a == 0)
        .unwrap();
    let mut forged = events.clone();
    let dt = forged[k].event.time;
    forged[k].pos[0][1] -= 0.5 * dt * dt; // fallen under g = 1 since t = 0
    let mut v = Verifier::new(&falling);
    let e = forged
        .iter()
        .try_for_each(|c| v.check(c))
        .unwrap_err()
        .to_string();
    assert!(e.contains("body 0 recorded at"), "{e}");
}

#[test]
fn kinematic_bodies_are_validated() {
    let scene = |body: &str, rest: &str| {
        AnyScene::from_json(&format!(
            r#"{{"dim": 2, "bodies": [{{"pos": [1, 1], "vel": [0, 0], "radius": 0.5{body}}}]{rest}}}"#
        ))
        .map(|_| ())
        .map_err(|e| e.to_string())
    };
    assert_eq!(scene(r#", "kinematic": true"#, ""), Ok(()));
    let e = scene(r#", "kinematic": true, "mass": 2"#, "").unwrap_err();
    assert!(
        e.contains("bodies[0].kinematic") && e.contains("mass"),
        "{e}"
    );
    assert_eq!(
        scene(r#", "kinematic": true"#, r#", "periodic": [10, 10]"#),
        Ok(())
    );
    let e = scene(r#", "kinematic": 1"#, "").unwrap_err();
    assert!(e.contains("kinematic"), "{e}");
    // Growing radii take kinematic bodies (see tests/growth.rs), and so does a thermostat,
    // which does not reset them (see tests/thermostat.rs).
    let growth = r#", "settings": {"growth": {"rate": 0.1}}"#;
    assert_eq!(scene(r#", "kinematic": true"#, growth), Ok(()));
    let thermostat = r#", "settings": {"thermostat": {"temperature": 1, "rate": 1}}"#;
    assert_eq!(scene(r#", "kinematic": true"#, thermostat), Ok(()));
}

#[test]
fn in_a_periodic_box_a_paddle_wraps_round_and_meets_bodies_across_the_faces() {
    // A 10 m box. The paddle at x = 9 moves right at 1 m/s, leaves through x = 10 at t = 1 and
    // comes back at x = 0; the puck at x = 1.5 rests. Centres 1 m apart when the paddle is at
    // x = 0.5 (image 10.5): at t = 1.5, across the face. The second paddle, moving left,
    // passes through the first one without a collision.
    let scene = Scene::<2> {
        bodies: vec![
            paddle([9.0, 5.0], [1.0, 0.0]),
            BodySpec::new(Vector([1.5, 5.0]), Vector([0.0, 0.0]), 0.5),
            paddle([5.0, 5.0], [-3.0, 0.0]),
        ],
        periodic: Some(Vector([10.0, 10.0])),
        ..Scene::default()
    };
    for finder in ["all-pairs", "bvh", "sedgewick", "cells"] {
        let mut sim = Simulation::new(&scene, finder).unwrap();
        let mut run = RunWriter::new(Vec::new(), finder.into(), &scene).unwrap();
        let mut hits = Vec::new();
        sim.run_until_with(3.0, |c| {
            run.write_event(c).unwrap();
            hits.push((c.event.time, c.event.a, c.event.b));
        });
        // The second paddle meets the puck first, their centres 1 m apart when it is at
        // x = 2.5: t = 5/6.
        let (t, a, b) = hits[0];
        assert!(
            (t - 2.5 / 3.0).abs() < 1e-12 && (a, b) == (1, 2),
            "[{finder}] {hits:?}"
        );
        assert!(hits.len() >= 3, "[{finder}] {hits:?}");
        // The puck leaves at −6 m/s (twice the paddle's speed), wraps and meets the first
        // paddle; every hit is with a paddle, never between the paddles.
        assert!(
            hits.iter().all(|&(_, a, b)| (a, b) != (0, 2)),
            "[{finder}] {hits:?}"
        );
        let bytes = run.finish(sim.time()).unwrap();
        let mut reader = ccdsim::record::RunReader::<_, 2>::new(&bytes[..], "run".into()).unwrap();
        let (events, end) = reader.read_events().unwrap();
        let mut v = Verifier::new(&scene);
        for c in &events {
            v.check(c).unwrap_or_else(|e| panic!("[{finder}] {e}"));
        }
        v.finish(end.unwrap()).unwrap();
    }
}

#[test]
fn verify_holds_a_kinematic_collision_to_the_bounce_off_a_moving_wall() {
    // The paddle (1 m/s) meets the puck at rest at t = 2: the puck leaves at 2 m/s, the
    // paddle keeps its velocity. A record where the paddle slows down, or where the puck
    // leaves at the paddle's speed (relative normal velocity 1 becoming 0, not −1), or
    // swerves, is rejected, with and without restitution of its own.
    for restitution in [None, Some(0.5)] {
        let mut puck = BodySpec::new(Vector([5.0, 2.0]), Vector([0.0, 0.0]), 0.5);
        puck.restitution = restitution;
        let scene = table(vec![paddle([2.0, 2.0], [1.0, 0.0]), puck]);
        let mut sim = Simulation::new(&scene, "cells").unwrap();
        let mut events = Vec::new();
        // Before the paddle, which passes through walls, squeezes the puck on the far one.
        sim.run_until_with(3.0, |c| events.push(*c));
        assert_eq!(events.len(), 1);
        let mut v = Verifier::new(&scene);
        events.iter().try_for_each(|c| v.check(c)).unwrap();
        v.finish(3.0).unwrap();
        // e is the pair's mean: (1 + 0.5)/2 = 0.75 with the puck's own restitution.
        let e = restitution.map_or(1.0, |r| (1.0 + r) / 2.0);
        assert_eq!(events[0].vel[1].0, [1.0 + e, 0.0]);
        let forge = |k: usize, vel: [f64; 2]| {
            let mut forged = events.clone();
            forged[0].vel[k] = Vector(vel);
            let mut v = Verifier::new(&scene);
            v.check(&forged[0]).unwrap_err().to_string()
        };
        let err = forge(0, [0.9, 0.0]);
        assert!(err.contains("kinematic body 0 changes velocity"), "{err}");
        let err = forge(1, [1.0, 0.0]);
        assert!(err.contains("restitution rule"), "{err}");
        let err = forge(1, [1.0 + e, 0.1]);
        assert!(err.contains("restitution rule"), "{err}");
    }
}
