//! The Andersen thermostat: NVT runs hold kT, every finder gives the same events (resets
//! included), run files record the resets (format version 2) and `verify` checks them.

use ccdsim::generate::{gas, GasConfig};
use ccdsim::record::RunWriter;
use ccdsim::thermostat::Thermostat;
use ccdsim::verify::Verifier;
use ccdsim::{Collision, EventKind, Scene, SceneError, Simulation, FINDER_NAMES};
use replay::records;

use crate::replay;

fn thermostatted<const D: usize>(n: usize, periodic: bool, kt: f64, rate: f64) -> Scene<D> {
    let mut scene = gas::<D>(&GasConfig {
        n,
        packing: 0.2,
        periodic,
        seed: 5,
        ..Default::default()
    })
    .unwrap();
    scene.settings.thermostat = Some(Thermostat {
        temperature: kt,
        rate,
        seed: 9,
    });
    scene
}

/// The run file of `events` events of `scene` with `finder`, in memory.
fn run_file<const D: usize>(scene: &Scene<D>, finder: &str, until: f64) -> Vec<u8> {
    let mut sim = Simulation::new(scene, finder).unwrap();
    let mut w = RunWriter::new(Vec::new(), finder.to_string(), scene).unwrap();
    sim.run_until_with(until, |c| w.write_event(c).unwrap());
    w.finish(sim.time()).unwrap()
}

#[test]
fn nvt_runs_hold_the_set_temperature() {
    // Start at kT ≈ 0.33 (the generator's speeds), thermostat at kT = 2.
    let scene = thermostatted::<2>(400, true, 2.0, 0.5);
    let mut sim = Simulation::new(&scene, "cells").unwrap();
    sim.run_until(40.0); // 20 resets per body: the initial temperature is forgotten
    let (mut sum, mut count) = (0.0, 0);
    for k in 1..=400 {
        sim.run_until(40.0 + 0.5 * f64::from(k));
        sum += ccdsim::observables::temperature(sim.world());
        count += 1;
    }
    let mean = sum / f64::from(count);
    // kT fluctuates by about kT·sqrt(2/(D N)) = 0.1 per sample; 400 samples, correlated over
    // about one reset time (2 s = 4 samples): standard error about 0.01.
    assert!((mean - 2.0).abs() < 0.04, "⟨kT⟩ = {mean}");
    assert!(sim.stats().resets > 400 * 40, "{:?}", sim.stats());
}

#[test]
fn every_finder_gives_the_same_run_file_with_resets() {
    let periodic = thermostatted::<2>(150, true, 1.0, 0.3);
    let walled = thermostatted::<3>(120, false, 1.0, 0.3);
    let reference = run_file(&periodic, "all-pairs", 15.0);
    let reference3 = run_file(&walled, "all-pairs", 15.0);
    let (_, events, _) = records::<2>(&reference);
    assert!(events.iter().any(|c| c.event.kind == EventKind::Reset));
    assert!(events.iter().any(|c| c.event.kind == EventKind::Body));
    for name in FINDER_NAMES {
        assert!(
            run_file(&periodic, name, 15.0) == reference,
            "{name} (2D periodic)"
        );
        assert!(
            run_file(&walled, name, 15.0) == reference3,
            "{name} (3D walls)"
        );
    }
}

#[test]
fn run_files_with_resets_are_version_2_and_others_stay_version_1() {
    let with = run_file(&thermostatted::<2>(50, true, 1.0, 1.0), "cells", 2.0);
    assert_eq!(u32::from_le_bytes(with[8..12].try_into().unwrap()), 2);
    let mut plain = thermostatted::<2>(50, true, 1.0, 1.0);
    plain.settings.thermostat = None;
    let without = run_file(&plain, "cells", 2.0);
    assert_eq!(u32::from_le_bytes(without[8..12].try_into().unwrap()), 1);
}

#[test]
fn verify_checks_the_resets() {
    let scene = thermostatted::<2>(100, true, 1.5, 0.5);
    let bytes = run_file(&scene, "cells", 10.0);
    let (scene, events, end) = records::<2>(&bytes);
    let verify = |events: &[Collision<2>]| {
        let mut v = Verifier::new(&scene);
        for c in events {
            v.check(c).map_err(|e| e.what)?;
        }
        v.finish(end).map_err(|e| e.what)
    };
    let report = verify(&events).unwrap();
    assert!(report.resets > 400, "{report:?}");
    assert_eq!(
        report.events,
        events.len() as u64,
        "resets are events of the run"
    );

    let k = events
        .iter()
        .position(|c| c.event.kind == EventKind::Reset)
        .unwrap();
    let mut tampered = events.clone();
    tampered[k].vel[0][0] += 1e-3;
    let err = verify(&tampered).unwrap_err();
    assert!(err.contains("thermostat reset"), "{err}");
    let mut dropped = events.clone();
    dropped.remove(k);
    let err = verify(&dropped).unwrap_err();
    assert!(err.contains("is missing"), "{err}");
    // Cutting the run before its last resets is caught at the end too.
    let last = events
        .iter()
        .rposition(|c| c.event.kind == EventKind::Reset)
        .unwrap();
    let mut v = Verifier::new(&scene);
    for c in &events[..last] {
        v.check(c).unwrap();
    }
    assert!(v.finish(end).unwrap_err().what.contains("is missing"));
}

#[test]
fn a_thermostat_keeps_a_gas_without_collisions_going() {
    // One body in a periodic box: no collision ever; resets still come, one after another.
    let mut scene = thermostatted::<2>(10, true, 1.0, 2.0);
    scene.bodies.truncate(1);
    let mut sim = Simulation::new(&scene, "cells").unwrap();
    let n = sim.run_until(10.0);
    assert!(n > 5, "{n}");
    assert_eq!(sim.stats().resets, n);
    assert!(sim.halt().is_none());
}

#[test]
fn bad_thermostat_settings_are_refused() {
    for (field, thermostat) in [
        ("temperature", r#"{"temperature": 0, "rate": 1}"#),
        ("rate", r#"{"temperature": 1, "rate": -1}"#),
    ] {
        let json = format!(
            r#"{{"dim": 2, "settings": {{"thermostat": {thermostat}}},
               "bodies": [{{"pos": [0, 0], "vel": [0, 0], "radius": 1}}]}}"#
        );
        let err = Scene::<2>::from_json(&json).unwrap_err();
        assert_eq!(
            err,
            SceneError::NonPositive(format!("settings.thermostat.{field}"))
        );
    }
    let json = r#"{"dim": 2, "settings": {"thermostat": {"temperature": 1, "rate": 1, "speed": 2}},
                  "bodies": []}"#;
    assert!(Scene::<2>::from_json(json).is_err());
}

#[test]
fn kinematic_bodies_and_removed_ones_take_no_resets_and_the_others_keep_their_rate() {
    // 400 bodies in walls; every fourth held still as a kinematic obstacle, and a hundred of
    // the others removed at the start: 200 bodies move freely.
    let mut scene = thermostatted::<2>(400, false, 2.0, 0.5);
    for (k, b) in scene.bodies.iter_mut().enumerate() {
        if k % 4 == 0 {
            b.kinematic = true;
            b.vel = ccdsim::Vector::ZERO;
        }
    }
    let removed: Vec<usize> = (0..400).filter(|k| k % 4 == 1).take(100).collect();
    for finder in ["all-pairs", "cells"] {
        let mut sim = Simulation::new(&scene, finder).unwrap();
        for &i in &removed {
            sim.remove_body(i).unwrap();
        }
        let mut per_body = vec![0u32; 400];
        let (mut sum, mut samples) = (0.0, 0);
        for k in 1..=160 {
            sim.run_until_with(0.25 * f64::from(k), |c| {
                if c.event.kind == EventKind::Reset {
                    per_body[c.event.a as usize] += 1;
                }
            });
            if k > 40 {
                sum += ccdsim::observables::temperature(sim.world());
                samples += 1;
            }
        }
        for (k, &resets) in per_body.iter().enumerate() {
            if k % 4 == 0 || removed.contains(&k) {
                assert_eq!(resets, 0, "[{finder}] body {k} was reset");
            }
        }
        // ν · 200 bodies · 40 s = 4000 resets, standard deviation 63.
        let total: u32 = per_body.iter().sum();
        assert!((3800..=4200).contains(&total), "[{finder}] {total} resets");
        // The temperature is that of the bodies that move, held at the set kT.
        let mean = sum / f64::from(samples);
        assert!((mean - 2.0).abs() < 0.1, "[{finder}] ⟨kT⟩ = {mean}");
    }
}

#[test]
fn a_world_of_kinematic_bodies_waits_for_one_that_moves() {
    // Only kinematic bodies: every draw is void, so no event ever comes; an added free body
    // takes resets from the moment it is added.
    let mut scene = thermostatted::<2>(10, false, 1.0, 2.0);
    for b in &mut scene.bodies {
        b.kinematic = true;
        b.vel = ccdsim::Vector::ZERO;
    }
    let mut sim = Simulation::new(&scene, "cells").unwrap();
    assert!(sim.step_event().is_none());
    assert_eq!(sim.run_until(5.0), 0);
    let spare = scene.bodies[0].pos + ccdsim::Vector([0.0, 3.0 * scene.bodies[0].radius]);
    let i = (0..40)
        .find_map(|k| {
            let pos = spare + ccdsim::Vector([0.1 * f64::from(k), 0.0]);
            let spec = ccdsim::BodySpec::new(pos, ccdsim::Vector::ZERO, 0.1);
            sim.add_body(spec).ok()
        })
        .expect("room for a small body");
    let first = sim.step_event().unwrap();
    assert_eq!(first.event.kind, EventKind::Reset);
    assert_eq!(first.event.a as usize, i);
    assert!(first.event.time > 5.0);
}
