//! Live edits of a running simulation: `set_position` (teleports) next to `set_velocity`.

use ccdsim::generate::box_walls;
use ccdsim::{BodySpec, Scene, Simulation, Vector};

fn table() -> Scene<2> {
    Scene {
        bodies: vec![
            BodySpec::new(Vector([1.0, 1.0]), Vector([1.0, 0.0]), 0.5),
            BodySpec::new(Vector([8.0, 3.0]), Vector([0.0, 0.0]), 0.5),
        ],
        walls: box_walls(Vector([10.0, 4.0])),
        ..Scene::default()
    }
}

#[test]
fn a_teleported_body_is_met_where_it_now_is_by_every_finder() {
    for finder in ["all-pairs", "bvh", "sedgewick", "cells"] {
        let mut sim = Simulation::new(&table(), finder).unwrap();
        sim.run_until(0.5);
        // Body 1 appears in front of body 0 (at x = 1.5, moving +x at 1 m/s): they touch
        // when the gap of 4 − 1 = 3 m is closed, 3 s later.
        sim.set_position(1, Vector([5.5, 1.0])).unwrap();
        assert_eq!(sim.position(1).0, [5.5, 1.0]);
        let hit = sim.step_event().unwrap();
        assert_eq!((hit.event.a, hit.event.b), (0, 1), "[{finder}]");
        assert_eq!(hit.event.time, 3.5, "[{finder}]");
    }
}

#[test]
fn teleports_into_bodies_walls_or_nowhere_are_refused_and_change_nothing() {
    let mut sim = Simulation::new(&table(), "cells").unwrap();
    sim.run_until(0.5);
    let before = (sim.position(1), sim.peek_event());
    for (pos, culprit) in [
        ([1.8, 1.2], "overlap body 0"),
        ([9.8, 2.0], "cross wall"),
        ([12.0, 2.0], "outside the table"),
        ([f64::NAN, 2.0], "not finite"),
    ] {
        let e = sim.set_position(1, Vector(pos)).unwrap_err().to_string();
        assert!(e.contains(culprit), "{pos:?}: {e}");
    }
    let e = sim
        .set_position(5, Vector([2.0, 2.0]))
        .unwrap_err()
        .to_string();
    assert!(e.contains("does not exist"), "{e}");
    assert_eq!((sim.position(1), sim.peek_event()), before);
}
