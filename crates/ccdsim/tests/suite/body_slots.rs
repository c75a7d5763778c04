//! Bodies added to and removed from a running simulation: stable slots, refusals, sensors,
//! recorded runs that `verify` replays, and forged records it rejects.

use crate::replay;

use ccdsim::edit::Edit;
use ccdsim::generate::box_walls;
use ccdsim::record::RunWriter;
use ccdsim::{
    BodySpec, Collision, CollisionFilter, EventKind, Scene, Sensor, SensorChange, Settings,
    Simulation, Vector,
};

const FINDERS: [&str; 4] = ["all-pairs", "bvh", "sedgewick", "cells"];

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
fn an_added_body_is_met_by_every_finder_and_a_removed_one_by_none() {
    for finder in FINDERS {
        let mut sim = Simulation::new(&table(), finder).unwrap();
        sim.run_until(0.5);
        // Body 0 is at x = 1.5 moving +x; a body added at x = 5.5 is met when the gap of
        // 4 − 1 = 3 m closes, 3 s later. No slot is vacant: slots are appended.
        let k = sim
            .add_body(BodySpec::new(Vector([5.5, 1.0]), Vector::ZERO, 0.5))
            .unwrap();
        assert_eq!(k, 2, "[{finder}]");
        assert!(sim.world().len() >= 3);
        assert_eq!(sim.world().body_count(), 3);
        assert_eq!(
            sim.world().ids()[k],
            2,
            "[{finder}] the next id above the scene's"
        );
        let hit = sim.step_event().unwrap();
        assert_eq!((hit.event.a, hit.event.b), (0, 2), "[{finder}]");
        assert_eq!(hit.event.time, 3.5, "[{finder}]");
        // Removed, body 2 stops where it is: body 0, now at rest, stays at rest; body 2's
        // slot is filled again by the next body added.
        sim.remove_body(2).unwrap();
        assert!(sim.world().is_vacant(2));
        assert_eq!(sim.world().index_of(2), None);
        sim.run_until(20.0);
        assert_eq!(sim.position(0).0, [4.5, 1.0], "[{finder}]");
        let again = sim
            .add_body(BodySpec {
                id: Some(99),
                ..BodySpec::new(Vector([7.0, 1.0]), Vector([-1.0, 0.0]), 0.25)
            })
            .unwrap();
        assert_eq!(again, 2, "[{finder}] the vacant slot is filled first");
        assert_eq!(sim.world().index_of(99), Some(2));
        let hit = sim.step_event().unwrap();
        // Gap 7 − 4.5 − 0.75 = 1.75 m at 1 m/s.
        assert_eq!((hit.event.a, hit.event.b), (0, 2), "[{finder}]");
        assert_eq!(hit.event.time, 21.75, "[{finder}]");
    }
}

#[test]
fn refused_adds_and_removes_change_nothing() {
    let mut sim = Simulation::new(&table(), "cells").unwrap();
    sim.run_until(0.5);
    let before = (sim.world().len(), sim.peek_event());
    let at = |p: [f64; 2]| BodySpec::new(Vector(p), Vector::ZERO, 0.5);
    for (spec, culprit) in [
        (at([1.8, 1.2]), "overlap body 0"),
        (at([9.8, 2.0]), "cross wall"),
        (at([12.0, 2.0]), "outside the table"),
        (at([f64::NAN, 2.0]), "bodies[2].pos"),
        (
            BodySpec {
                radius: -1.0,
                ..at([5.0, 2.0])
            },
            "bodies[2].radius",
        ),
        (
            BodySpec {
                id: Some(1),
                ..at([5.0, 2.0])
            },
            "id 1 is taken by body 1",
        ),
        (
            BodySpec {
                restitution: Some(2.0),
                ..at([5.0, 2.0])
            },
            "outside [0, 1]",
        ),
    ] {
        let e = sim.add_body(spec.clone()).unwrap_err().to_string();
        assert!(e.contains(culprit), "{spec:?}: {e}");
    }
    assert_eq!((sim.world().len(), sim.peek_event()), before);
    for i in [2, 7] {
        let e = sim.remove_body(i).unwrap_err().to_string();
        assert!(e.contains("does not exist"), "{e}");
    }
    sim.remove_body(1).unwrap();
    for e in [
        sim.remove_body(1).unwrap_err(),
        sim.set_velocity(1, Vector::ZERO).unwrap_err(),
        sim.set_position(1, Vector([5.0, 2.0])).unwrap_err(),
        sim.set_collision_filter(1, CollisionFilter::DEFAULT)
            .unwrap_err(),
    ] {
        assert!(e.to_string().contains("vacant"), "{e}");
    }
    // Bodies that never collide with a body may be added on top of it.
    let ghost = BodySpec {
        group: Some(2),
        mask: Some(2),
        ..at([1.8, 1.2])
    };
    sim.add_body(ghost).unwrap();
}

#[test]
fn periodic_boxes_take_adds() {
    let periodic = Scene::<2> {
        bodies: vec![BodySpec::new(Vector([1.0, 1.0]), Vector([-1.0, 0.0]), 0.5)],
        periodic: Some(Vector([10.0, 10.0])),
        ..Scene::default()
    };
    for finder in FINDERS {
        let mut sim = Simulation::new(&periodic, finder).unwrap();
        // Body 0 leaves through the face x = 0 at t = 1, comes back at x = 10 and meets the
        // added body at x = 8 when their centres are 1 apart, at t = 2.
        let k = sim
            .add_body(BodySpec::new(Vector([8.0, 1.0]), Vector::ZERO, 0.5))
            .unwrap_or_else(|e| panic!("[{finder}] {e}"));
        assert_eq!(sim.step_event().unwrap().event.time, 2.0, "[{finder}]");
        sim.remove_body(k).unwrap();
        assert!(
            sim.step_event().is_none(),
            "[{finder}] body 0, stopped by the hit, rests alone"
        );
        let outside = BodySpec::new(Vector([12.0, 5.0]), Vector::ZERO, 0.5);
        let e = sim.add_body(outside).unwrap_err().to_string();
        assert!(e.contains("outside the periodic box"), "{e}");
        // A kinematic paddle, added, wraps round like any body: 5 + 2 · 4 = 13 ≡ 3.
        let paddle = BodySpec {
            kinematic: true,
            ..BodySpec::new(Vector([5.0, 5.0]), Vector([2.0, 0.0]), 0.5)
        };
        let k = sim.add_body(paddle).unwrap();
        sim.run_until(sim.time() + 4.0);
        assert!(
            (sim.position(k)[0] - 3.0).abs() < 1e-12,
            "[{finder}] {:?}",
            sim.position(k)
        );
    }
}

#[test]
fn a_removed_body_leaves_its_sensors_and_an_added_one_enters_them() {
    let scene = Scene::<2> {
        sensors: vec![Sensor {
            center: Vector([5.0, 1.0]),
            radius: 1.0,
        }],
        ..table()
    };
    let mut sim = Simulation::new(&scene, "cells").unwrap();
    // Body 0 (x = 1 + t) overlaps the sensor from x = 3.5: t = 2.5.
    sim.run_until(3.0);
    sim.remove_body(0).unwrap();
    let k = sim
        .add_body(BodySpec::new(Vector([5.0, 2.0]), Vector::ZERO, 0.5))
        .unwrap();
    sim.run_until(4.0);
    let got: Vec<(f64, usize, SensorChange)> = sim
        .take_sensor_events()
        .iter()
        .map(|e| (e.time, e.body, e.change))
        .collect();
    assert_eq!(
        got,
        [
            (2.5, 0, SensorChange::Enter),
            (3.0, 0, SensorChange::Leave),
            (3.0, k, SensorChange::Enter),
        ]
    );
    assert_eq!(sim.sensors().unwrap().bodies_in(0), [k]);
}

/// A steered run of a falling gas: every frame a body is removed or added (now and then, if
/// `kinematic`, a kinematic one, or one in another collision group) and now and then a
/// filter changes; every record goes to a steered run file. Returns its bytes.
/// The laws of a steered test run: gravity, or a thermostat, or growing radii.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Laws {
    Gravity,
    Thermostat,
    Growth,
}

fn steered_run(finder: &str, kinematic: bool, laws: Laws) -> Vec<u8> {
    let settings = match laws {
        Laws::Gravity => Settings {
            gravity: ccdsim::Gravity::new(&[0.0, -9.81]),
            ..Settings::default()
        },
        Laws::Thermostat => Settings {
            thermostat: Some(ccdsim::thermostat::Thermostat {
                temperature: 2.0,
                rate: 0.4,
                seed: 11,
            }),
            ..Settings::default()
        },
        Laws::Growth => Settings {
            growth: Some(ccdsim::Growth { rate: 0.01 }),
            ..Settings::default()
        },
    };
    let scene = Scene::<2> {
        bodies: (0..24)
            .map(|k| {
                let (x, y) = (1.0 + 1.5 * (k % 8) as f64, 1.0 + 1.5 * (k / 8) as f64);
                let v = Vector([f64::from(k % 5) - 2.0, f64::from(k % 3)]);
                BodySpec::new(Vector([x, y]), v, 0.5)
            })
            .collect(),
        walls: box_walls(Vector([13.0, 9.0])),
        settings,
        ..Scene::default()
    };
    let mut sim = Simulation::new(&scene, finder).unwrap();
    let mut run = RunWriter::new_steered(Vec::new(), "slots".into(), &scene).unwrap();
    sim.record_edits(true);
    for frame in 0..240u32 {
        let w = sim.world();
        let live: Vec<usize> = (0..w.len()).filter(|&i| !w.is_vacant(i)).collect();
        if frame % 3 == 0 && live.len() > 12 {
            sim.remove_body(live[(frame as usize * 7) % live.len()])
                .unwrap();
        } else {
            let x = 1.0 + f64::from(frame * 37 % 110) / 10.0;
            let spec = BodySpec {
                kinematic: kinematic && frame % 11 == 0,
                group: (frame % 7 == 0).then_some(2),
                mask: (frame % 7 == 0).then_some(2),
                ..BodySpec::new(Vector([x, 7.5]), Vector([0.5, -1.0]), 0.3)
            };
            let _ = sim.add_body(spec); // refused where it would overlap: not recorded
        }
        if frame % 13 == 5 {
            let i = live[frame as usize % live.len()];
            let _ = sim.set_collision_filter(i, CollisionFilter { group: 4, mask: 4 });
        }
        for record in sim.take_edits().iter().chain(&sim.advance(1.0 / 30.0)) {
            run.write_event(record).unwrap();
        }
    }
    run.finish(sim.time()).unwrap()
}

#[test]
fn runs_that_add_and_remove_bodies_record_them_and_verify() {
    let cases = [
        (Laws::Gravity, true),
        (Laws::Gravity, false),
        (Laws::Thermostat, true),
        (Laws::Thermostat, false),
        (Laws::Growth, true),
        (Laws::Growth, false),
    ];
    for (laws, kinematic) in cases {
        let case = format!("{laws:?}, kinematic bodies: {kinematic}");
        let want = steered_run("all-pairs", kinematic, laws);
        assert_eq!(
            u32::from_le_bytes(want[8..12].try_into().unwrap()),
            ccdsim::record::VERSION_SLOTS
        );
        for finder in ["bvh", "sedgewick", "cells"] {
            assert!(
                steered_run(finder, kinematic, laws) == want,
                "[{finder}] {case}: run files differ"
            );
        }
        let (scene, events, end) = replay::records::<2>(&want);
        let count = |code: u32| {
            events
                .iter()
                .filter(|c| c.event.kind == EventKind::Edit && c.event.b == code)
                .count()
        };
        let (adds, removes, filters) = (count(1), count(3), count(4));
        assert!(
            adds >= 50 && removes >= 50 && filters >= 10,
            "{case}: {adds} {removes} {filters}"
        );
        assert_eq!(count(2), adds, "each add has its id record");
        let of_kind = |kind: EventKind| events.iter().filter(|c| c.event.kind == kind).count();
        let body_events = of_kind(EventKind::Body);
        // Without gravity the bodies added at the top do not fall into the crowd.
        let least = if laws == Laws::Gravity { 100 } else { 20 };
        assert!(body_events > least, "{case}: {body_events} collisions");
        let resets = of_kind(EventKind::Reset);
        if laws == Laws::Thermostat {
            // About 0.4 resets per body per second, 12 to 24 bodies, 8 s.
            assert!((30..=120).contains(&resets), "{case}: {resets} resets");
        }
        for all_pairs in [false, true] {
            let report = replay::replay(&scene, &events, end, all_pairs)
                .unwrap_or_else(|v| panic!("{case}: {v}"));
            assert_eq!(report.edits as usize, adds + removes + filters);
            assert_eq!(report.resets as usize, resets);
            if !kinematic && laws == Laws::Gravity {
                // Elastic collisions keep the energy; only the edits move it: a removed body
                // takes its energy with it, an added one brings its own. (Kinematic bodies
                // push others without keeping it; resets and growth change it.)
                let balance = report.energy_start() + report.edit_energy - report.energy_end();
                assert!(
                    balance.abs() < 1e-9 * report.energy_start().abs().max(1.0),
                    "energy off by {balance}"
                );
            }
        }
    }
}

#[test]
fn verify_rejects_forged_slot_records() {
    let want = steered_run("cells", true, Laws::Gravity);
    let (scene, events, end) = replay::records::<2>(&want);
    let first_add = events.iter().position(Edit::starts_add).unwrap();
    let forge = |f: &dyn Fn(&mut Vec<Collision<2>>)| {
        let mut forged = events.clone();
        f(&mut forged);
        replay::replay(&scene, &forged, end, false).unwrap_err()
    };
    // An add whose id record went missing.
    let e = forge(&|v| {
        v.remove(first_add + 1);
    });
    assert!(e.contains("id record"), "{e}");
    // The same body added twice in its slot, then once more in a fresh slot on top of it.
    let pair = [events[first_add], events[first_add + 1]];
    let e = forge(&|v| {
        v.splice(first_add + 2..first_add + 2, pair);
    });
    assert!(e.contains("which holds one"), "{e}");
    let e = forge(&|v| {
        let mut twin = pair;
        for c in &mut twin {
            c.event.a = 1000;
        }
        v.splice(first_add + 2..first_add + 2, twin);
    });
    assert!(e.contains("into body"), "{e}");
    // A removed body that keeps moving.
    let first_remove = events
        .iter()
        .position(|c| c.event.kind == EventKind::Edit && c.event.b == 3)
        .unwrap();
    let e = forge(&|v| v[first_remove].vel[0] = Vector([1.0, 0.0]));
    assert!(e.contains("keeps moving"), "{e}");
}

#[test]
fn version_8_steered_files_still_read_and_verify() {
    // A steered run that only moves bodies is what a version 8 file held.
    let scene = table();
    let mut sim = Simulation::new(&scene, "cells").unwrap();
    let mut run = RunWriter::new_steered(Vec::new(), "v8".into(), &scene).unwrap();
    sim.record_edits(true);
    for frame in 0..60 {
        sim.set_velocity(0, Vector([1.0 + f64::from(frame % 3), 0.5]))
            .unwrap();
        for record in sim.take_edits().iter().chain(&sim.advance(0.1)) {
            run.write_event(record).unwrap();
        }
    }
    let mut bytes = run.finish(sim.time()).unwrap();
    bytes[8..12].copy_from_slice(&ccdsim::record::VERSION_EDITS.to_le_bytes());
    let (scene, events, end) = replay::records::<2>(&bytes);
    let report = replay::replay(&scene, &events, end, false).unwrap();
    assert_eq!(report.edits, 60);
}

#[test]
fn exports_name_added_and_removed_bodies_by_id() {
    let bytes = steered_run("cells", true, Laws::Gravity);
    let mut r = ccdsim::record::RunReader::<_, 2>::new(&bytes[..], "slots".into()).unwrap();
    let mut out = Vec::new();
    ccdsim::record::export_jsonl(&mut r, &mut out).unwrap();
    let text = String::from_utf8(out).unwrap();
    let lines: Vec<serde_json::Value> = text
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    assert_eq!(lines[0]["version"], ccdsim::record::VERSION_SLOTS);
    let kind = |k: &str| lines.iter().filter(|l| l["kind"] == k).count();
    let (_, events, _) = replay::records::<2>(&bytes);
    // An added body's two records make one line.
    assert_eq!(lines.len() - 1 + kind("add"), events.len());
    assert!(kind("add") > 0 && kind("remove") > 0 && kind("filter") > 0);
    let add = lines.iter().find(|l| l["kind"] == "add").unwrap();
    assert_eq!(add["radius"], 0.3);
    assert!(add["slot"].as_u64().is_some() && add["a"].as_u64().unwrap() >= 24);
    // Ids never repeat among the adds.
    let mut ids: Vec<u64> = lines
        .iter()
        .filter(|l| l["kind"] == "add")
        .map(|l| l["a"].as_u64().unwrap())
        .collect();
    let n = ids.len();
    ids.dedup();
    assert_eq!(ids.len(), n);
    assert!(lines
        .iter()
        .any(|l| l["kind"] == "add" && l["kinematic"] == true));
}
