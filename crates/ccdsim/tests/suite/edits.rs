//! Live edits of a running simulation: `set_position` (teleports) next to `set_velocity`.

use crate::replay;

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

/// A steered run of `table()`: every frame body 0 gets a new velocity, every fifth a body is
/// teleported; every record goes to a steered run file. Returns its bytes.
fn steered_run(finder: &str) -> Vec<u8> {
    use ccdsim::record::RunWriter;
    let scene = table();
    let mut sim = Simulation::new(&scene, finder).unwrap();
    let mut run = RunWriter::new_steered(Vec::new(), "steered".into(), &scene).unwrap();
    sim.record_edits(true);
    for frame in 0..240 {
        let angle = 0.1 * frame as f64;
        sim.set_velocity(0, Vector([2.0 * angle.cos(), 2.0 * angle.sin()]))
            .unwrap();
        if frame % 5 == 0 {
            let spot = Vector([2.0 + (frame % 7) as f64, 1.0 + (frame % 3) as f64]);
            let _ = sim.set_position(1, spot); // refused where it would overlap: not recorded
        }
        for record in sim.take_edits().iter().chain(&sim.advance(1.0 / 30.0)) {
            run.write_event(record).unwrap();
        }
    }
    run.finish(sim.time()).unwrap()
}

#[test]
fn steered_runs_record_their_edits_and_verify() {
    let want = steered_run("all-pairs");
    assert_eq!(
        u32::from_le_bytes(want[8..12].try_into().unwrap()),
        ccdsim::record::VERSION_SLOTS
    );
    for finder in ["bvh", "sedgewick", "cells"] {
        assert!(steered_run(finder) == want, "[{finder}] run files differ");
    }
    let (scene, events, end) = replay::records::<2>(&want);
    let edits = events
        .iter()
        .filter(|c| c.event.kind == ccdsim::EventKind::Edit)
        .count();
    assert!(edits >= 240, "{edits} edits");
    assert!(events
        .iter()
        .any(|c| c.event.kind != ccdsim::EventKind::Edit));
    for all_pairs in [false, true] {
        let report = replay::replay(&scene, &events, end, all_pairs).unwrap();
        assert_eq!(report.edits as usize, edits);
        // Elastic collisions keep the energy: what changed it is the edits.
        let drift = report.kinetic_energy_end - report.kinetic_energy_start - report.edit_energy;
        assert!(drift.abs() < 1e-9, "{drift}");
    }
    // Without its edits the run is wrong: the recorded collisions no longer follow.
    let unsteered: Vec<_> = events
        .iter()
        .filter(|c| c.event.kind != ccdsim::EventKind::Edit)
        .copied()
        .collect();
    assert!(replay::replay(&scene, &unsteered, end, false).is_err());
    // An edit that puts a body into another is caught.
    let mut tampered = events.clone();
    let k = tampered
        .iter()
        .position(|c| c.event.kind == ccdsim::EventKind::Edit && c.event.a == 1)
        .unwrap();
    let t = tampered[k].event.time;
    let other = replay::records::<2>(&want).1[..k]
        .iter()
        .rev()
        .find(|c| c.event.a == 0 || (c.body_count() == 2 && c.event.b == 0))
        .map(|c| {
            let s = usize::from(c.event.a != 0);
            c.pos[s] + c.vel[s] * (t - c.event.time)
        })
        .unwrap_or(scene.bodies[0].pos + scene.bodies[0].vel * t);
    tampered[k].pos[0] = other + Vector([0.3, 0.0]);
    let e = replay::replay(&scene, &tampered, end, false).unwrap_err();
    assert!(e.contains("an edit puts body 1 into body 0"), "{e}");
}

#[test]
fn edits_need_a_steered_run_file_and_an_edit_journal() {
    use ccdsim::record::RunWriter;
    let scene = table();
    let mut sim = Simulation::new(&scene, "cells").unwrap();
    // The journal is off by default: edits leave no records.
    sim.set_velocity(0, Vector([0.0, 1.0])).unwrap();
    assert!(sim.take_edits().is_empty());
    sim.record_edits(true);
    sim.set_velocity(0, Vector([1.0, 1.0])).unwrap();
    let edits = sim.take_edits();
    assert_eq!(edits.len(), 1);
    let mut plain = RunWriter::new(Vec::new(), "plain".into(), &scene).unwrap();
    let e = plain.write_event(&edits[0]).unwrap_err().to_string();
    assert!(e.contains("steered run file"), "{e}");
}

#[test]
fn exports_name_edits_and_old_versions_refuse_them() {
    let bytes = steered_run("cells");
    let mut r = ccdsim::record::RunReader::<_, 2>::new(&bytes[..], "steered".into()).unwrap();
    assert_eq!(r.version(), ccdsim::record::VERSION_SLOTS);
    let mut out = Vec::new();
    ccdsim::record::export_jsonl(&mut r, &mut out).unwrap();
    let text = String::from_utf8(out).unwrap();
    assert!(text.contains(r#""kind":"edit""#), "{}", &text[..300]);
    // The same records under a version-7 header: the edits are refused by name.
    let mut old = bytes.clone();
    old[8..12].copy_from_slice(&7u32.to_le_bytes());
    let mut r = ccdsim::record::RunReader::<_, 2>::new(&old[..], "old".into()).unwrap();
    let e = r.read_events().unwrap_err().to_string();
    assert!(e.contains("edit record") && e.contains("version 7"), "{e}");
}
