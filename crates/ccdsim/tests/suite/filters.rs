//! Collision groups and masks (`bodies[].group`, `bodies[].mask`): bodies whose filters keep
//! them apart pass through each other; walls still stop them.

use crate::replay;

use ccdsim::generate::box_walls;
use ccdsim::record::{RunWriter, VERSION_FILTERS};
use ccdsim::{AnyScene, BodySpec, CollisionFilter, Scene, Simulation, Vector};
use replay::{records, replay};

const FINDERS: [&str; 4] = ["all-pairs", "bvh", "sedgewick", "cells"];

fn ball(x: f64, vx: f64, group: Option<u32>, mask: Option<u32>) -> BodySpec<2> {
    BodySpec {
        group,
        mask,
        ..BodySpec::new(Vector([x, 2.0]), Vector([vx, 0.0]), 0.5)
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
fn bodies_of_groups_that_ignore_each_other_pass_through_and_still_hit_walls() {
    for finder in FINDERS {
        // Body 1 (group 2) ignores group 1; body 0 is in group 1: they pass through each
        // other and each reaches the far wall.
        let scene = table(vec![
            ball(2.0, 1.0, None, None),
            ball(8.0, -1.0, Some(2), Some(!1)),
        ]);
        let mut sim = Simulation::new(&scene, finder).unwrap();
        // Each meets its far wall at 7.5 s (9.5 − 2 and 8 − 0.5 m at 1 m/s).
        for _ in 0..2 {
            let wall = sim.step_event().unwrap();
            assert_eq!(
                (wall.event.time, wall.body_count()),
                (7.5, 1),
                "[{finder}] {wall:?}"
            );
        }
        assert_eq!(sim.stats().body_collisions, 0, "[{finder}]");
        // A third body of group 1 only (mask 1) meets body 0 but not body 1.
        let scene = table(vec![
            ball(2.0, 1.0, None, None),
            ball(5.0, 0.0, Some(1), Some(1)),
        ]);
        let hit = Simulation::new(&scene, finder)
            .unwrap()
            .step_event()
            .unwrap();
        assert_eq!((hit.event.time, hit.body_count()), (2.0, 2), "[{finder}]");
    }
}

#[test]
fn overlapping_bodies_are_allowed_only_when_they_never_collide() {
    let overlapping = |g: Option<u32>, m: Option<u32>| {
        table(vec![ball(3.0, 0.0, None, None), ball(3.5, 0.0, g, m)]).validate()
    };
    assert!(overlapping(Some(2), Some(2)).is_ok());
    assert!(overlapping(Some(0), None).is_ok());
    let e = overlapping(Some(2), None).unwrap_err().to_string();
    assert!(e.contains("overlap"), "{e}");
    // A value that is not a u32 bit set is a parse error naming the field.
    let e = AnyScene::from_json(
        r#"{"dim": 2, "bodies": [{"pos": [1, 1], "vel": [0, 0], "radius": 0.5, "mask": -1}]}"#,
    )
    .unwrap_err()
    .to_string();
    assert!(e.contains("mask") || e.contains("-1"), "{e}");
}

#[test]
fn set_collision_filter_ghosts_a_body_and_refuses_to_make_overlapping_bodies_collide() {
    for finder in FINDERS {
        // Two balls on a collision course; at t = 0.5 body 1 becomes a ghost (no group).
        let scene = table(vec![
            ball(2.0, 1.0, None, None),
            ball(6.0, -1.0, None, None),
        ]);
        let mut sim = Simulation::new(&scene, finder).unwrap();
        sim.run_until(0.5);
        let ghost = CollisionFilter { group: 0, mask: 0 };
        sim.set_collision_filter(1, ghost).unwrap();
        // At t = 2 the balls overlap (centres at 4 and 4), having passed into each other:
        // making body 1 solid is refused and changes nothing.
        sim.run_until(2.0);
        assert_eq!(sim.stats().events, 0, "[{finder}]");
        let e = sim
            .set_collision_filter(1, CollisionFilter::DEFAULT)
            .unwrap_err()
            .to_string();
        assert!(e.contains("overlaps body 0"), "[{finder}] {e}");
        assert_eq!(sim.world().filter(1), ghost, "[{finder}]");
        // Once they are apart again it is accepted, and the bodies stay apart (no contact is
        // sought back in time, when they overlapped).
        sim.run_until(3.0);
        sim.set_collision_filter(1, CollisionFilter::DEFAULT)
            .unwrap();
        let next = sim.step_event().unwrap();
        assert!(next.event.time >= 3.0, "[{finder}] {next:?}");
        assert!(
            sim.set_collision_filter(7, ghost).is_err(),
            "[{finder}] body 7"
        );
    }
}

#[test]
fn runs_with_filters_are_version_6_and_verify() {
    let mut scene = ccdsim::generate::gas::<2>(&ccdsim::generate::GasConfig {
        n: 60,
        packing: 0.3,
        ..ccdsim::generate::GasConfig::default()
    })
    .unwrap();
    for (k, b) in scene.bodies.iter_mut().enumerate() {
        if k % 3 == 0 {
            b.group = Some(2);
            b.mask = Some(2);
        }
    }
    let mut sim = Simulation::new(&scene, "cells").unwrap();
    let mut w = RunWriter::new(Vec::new(), "cells".into(), &scene).unwrap();
    sim.run_events_with(3000, |c| w.write_event(c).unwrap());
    let bytes = w.finish(sim.time()).unwrap();
    assert_eq!(
        u32::from_le_bytes(bytes[8..12].try_into().unwrap()),
        VERSION_FILTERS
    );
    let (read, events, end) = records::<2>(&bytes);
    assert_eq!(read, scene);
    replay(&read, &events, end, false).unwrap();
    replay(&read, &events, end, true).unwrap();
    // The same events are wrong for a scene whose filters keep a colliding pair apart.
    let c = events
        .iter()
        .find(|c| c.body_count() == 2)
        .expect("a body collision");
    let mut tampered = read.clone();
    for k in [c.event.a, c.event.b] {
        tampered.bodies[k as usize].group = Some(16);
        tampered.bodies[k as usize].mask = Some(16);
    }
    tampered.bodies[c.event.b as usize].mask = Some(32);
    let e = replay(&tampered, &events, end, false).unwrap_err();
    assert!(e.contains("collision filters keep them apart"), "{e}");
}
