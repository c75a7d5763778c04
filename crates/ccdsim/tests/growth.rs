//! Growing radii (Lubachevsky–Stillinger): run files (format version 3) that `verify`
//! checks with the growth rule, scene validation, and compression to jammed packings.

use ccdsim::generate::{gas, GasConfig};
use ccdsim::growth::Growth;
use ccdsim::packing::{compress, dilute_start, CompressConfig, CompressStop, SizeMix};
use ccdsim::record::RunWriter;
use ccdsim::{Scene, SceneError, Simulation};
use replay::{records, replay};

mod replay;

fn growing<const D: usize>(n: usize, periodic: bool, rate: f64) -> Scene<D> {
    let mut scene = gas::<D>(&GasConfig {
        n,
        packing: 0.25,
        radius_min: 0.3,
        radius_max: 0.6,
        periodic,
        seed: 11,
        ..Default::default()
    })
    .unwrap();
    scene.settings.growth = Some(Growth { rate });
    scene
}

/// The run file of `events` events of `scene` with `finder`, in memory.
fn run_file<const D: usize>(scene: &Scene<D>, finder: &str, events: u64) -> Vec<u8> {
    let mut sim = Simulation::new(scene, finder).unwrap();
    let mut w = RunWriter::new(Vec::new(), finder.to_string(), scene).unwrap();
    sim.run_events_with(events, |c| w.write_event(c).unwrap());
    w.finish(sim.time()).unwrap()
}

#[test]
fn growing_runs_are_version_3_and_verify() {
    for (periodic, rate) in [(false, 0.05), (true, 0.2)] {
        let s2 = growing::<2>(200, periodic, rate);
        let bytes = run_file(&s2, "cells", 20_000);
        assert_eq!(u32::from_le_bytes(bytes[8..12].try_into().unwrap()), 3);
        let (scene, events, end) = records::<2>(&bytes);
        assert_eq!(scene.settings.growth, s2.settings.growth);
        for all_pairs in [false, true] {
            let report = replay(&scene, &events, end, all_pairs).unwrap();
            assert_eq!(report.events, 20_000);
            // Growth collisions heat the gas.
            assert!(report.kinetic_energy_end > report.kinetic_energy_start);
        }
        let s3 = growing::<3>(150, periodic, rate);
        let (scene, events, end) = records::<3>(&run_file(&s3, "cells", 10_000));
        replay(&scene, &events, end, false).unwrap();
    }
}

#[test]
fn verify_catches_runs_that_break_the_growth() {
    let s = growing::<2>(150, true, 0.2);
    let (scene, events, end) = records::<2>(&run_file(&s, "cells", 5_000));
    // Read as if radii were fixed: contacts come at distances that fixed radii never reach.
    let mut fixed = scene.clone();
    fixed.settings.growth = None;
    let err = replay(&fixed, &events, end, false).unwrap_err();
    assert!(err.contains("at a distance"), "{err}");
    // A collision that reverses the centres' approach instead of the surfaces'.
    let k = events
        .iter()
        .position(|c| c.event.kind == ccdsim::EventKind::Body)
        .unwrap();
    let mut tampered = events.clone();
    let (i, j) = (tampered[k].event.a as usize, tampered[k].event.b as usize);
    let (mi, mj) = (
        scene.bodies[i].effective_mass(),
        scene.bodies[j].effective_mass(),
    );
    // An extra impulse along the line of centres: momentum stays, the normal speed does not.
    let n = tampered[k].pos[1] - tampered[k].pos[0];
    let n = n * (1e-3 / n.norm());
    tampered[k].vel[0] -= n * (1.0 / mi);
    tampered[k].vel[1] += n * (1.0 / mj);
    let err = replay(&scene, &tampered, end, false).unwrap_err();
    assert!(err.contains("growth rule"), "{err}");
    // Radii grown faster than the run grew them: the bodies' contacts come too late.
    let mut faster = scene.clone();
    faster.settings.growth = Some(Growth { rate: 0.25 });
    assert!(replay(&faster, &events, end, false).is_err());
}

#[test]
fn growth_settings_are_validated() {
    for (text, field) in [
        (r#"{"rate": 0}"#, "settings.growth.rate"),
        (r#"{"rate": -1}"#, "settings.growth.rate"),
        (r#"{"speed": 1}"#, "unknown field"),
    ] {
        let json = format!(
            r#"{{"dim": 2, "settings": {{"growth": {text}}}, "bodies": [{{"pos": [0, 0], "vel": [1, 0], "radius": 1}}]}}"#
        );
        let err = Scene::<2>::from_json(&json).unwrap_err();
        assert!(err.to_string().contains(field), "{text}: {err}");
        if field.starts_with("settings") {
            assert!(matches!(err, SceneError::NonPositive(_)), "{err:?}");
        }
    }
}

#[test]
fn a_binary_mixture_compresses_past_0_7_in_2d() {
    // DynamO's issue 76: compression of a 2D binary mixture fails near φ = 0.7. Here it jams
    // near 0.84, the random close packing of the 1:1.4 mixture.
    let scene = dilute_start::<2>(400, 0.3, SizeMix::Bidisperse(1.4), true, 7).unwrap();
    let config = CompressConfig {
        rate: 0.02,
        until_pressure: 1e9,
        ..CompressConfig::default()
    };
    let mut blocks = 0;
    let mut last = 0.0;
    let packed = compress(&scene, "cells", &config, |b| {
        assert!(
            b.packing_fraction >= last,
            "the packing fraction only grows"
        );
        last = b.packing_fraction;
        blocks += 1;
    })
    .unwrap();
    assert_eq!(packed.stop, CompressStop::Pressure);
    assert!(packed.reduced_pressure >= 1e9);
    assert!(
        (0.82..0.86).contains(&packed.packing_fraction),
        "{}",
        packed.packing_fraction
    );
    assert!(blocks > 10);
    // Jammed: most bodies are held by at least D + 1 contacts, about 2D on average.
    assert!(
        packed.contacts.rattlers.len() < 400 / 5,
        "{:?}",
        packed.contacts.rattlers.len()
    );
    assert!(
        (3.6..=4.0).contains(&packed.contacts.mean_contacts),
        "{}",
        packed.contacts.mean_contacts
    );
    // The packing reads back as a valid scene, its radii fixed and its pressure high: a short
    // run keeps every pair apart and collides often.
    let text = packed.scene.to_json();
    let back = Scene::<2>::from_json(&text).unwrap();
    assert!(back.settings.growth.is_none());
    let mut sim = Simulation::new(&back, "cells").unwrap();
    assert_eq!(sim.run_events(10_000), 10_000);
    assert!(sim.stats().max_overlap < 1e-9);
}

#[test]
fn every_finder_compresses_to_the_same_packing() {
    let scene = dilute_start::<3>(60, 0.2, SizeMix::Polydisperse(0.2), false, 3).unwrap();
    let config = CompressConfig {
        rate: 0.05,
        until_pressure: 1e5,
        ..CompressConfig::default()
    };
    let reference = compress(&scene, "all-pairs", &config, |_| {}).unwrap();
    assert_eq!(reference.stop, CompressStop::Pressure);
    for name in ["bvh", "sedgewick", "cells"] {
        let packed = compress(&scene, name, &config, |_| {}).unwrap();
        assert_eq!(packed, reference, "{name}");
    }
}

#[test]
fn bad_compressions_are_refused() {
    let scene = dilute_start::<2>(20, 0.2, SizeMix::Monodisperse, true, 1).unwrap();
    for config in [
        CompressConfig {
            rate: 0.0,
            ..CompressConfig::default()
        },
        CompressConfig {
            until_pressure: 0.5,
            ..CompressConfig::default()
        },
        CompressConfig {
            temperature: f64::NAN,
            ..CompressConfig::default()
        },
    ] {
        assert!(
            compress(&scene, "cells", &config, |_| {}).is_err(),
            "{config:?}"
        );
    }
    let mut open = scene.clone();
    open.periodic = None;
    let err = compress(&open, "cells", &CompressConfig::default(), |_| {}).unwrap_err();
    assert!(err.to_string().contains("volume"), "{err}");
}

/// A periodic growing packing in which, every 0.1 s, a body is taken out and a body of its
/// current radius put back where it was, moving the other way: the run file of `finder`.
fn refilled_run(finder: &str) -> (Vec<u8>, Vec<(f64, f64, f64)>) {
    let scene = growing::<2>(60, true, 0.05);
    let mut sim = Simulation::new(&scene, finder).unwrap();
    let mut run = RunWriter::new_steered(Vec::new(), finder.into(), &scene).unwrap();
    sim.record_edits(true);
    let mut radii = Vec::new();
    for frame in 0..30u32 {
        for c in sim.advance(0.1) {
            run.write_event(&c).unwrap();
        }
        let i = (frame as usize * 7) % 60;
        let (pos, vel, r) = (
            sim.position(i),
            sim.world().velocity_at(i, sim.time()),
            sim.radius(i),
        );
        sim.remove_body(i).unwrap();
        let spec = ccdsim::BodySpec::new(pos, -vel, r);
        assert_eq!(
            sim.add_body(spec).unwrap(),
            i,
            "the slot just vacated is filled"
        );
        radii.push((sim.time(), r, sim.radius(i)));
        for c in sim.take_edits() {
            run.write_event(&c).unwrap();
        }
    }
    let end = sim.time();
    for c in sim.advance(0.5) {
        run.write_event(&c).unwrap();
    }
    let last = sim.radius(29 * 7 % 60);
    radii.push((end, last, sim.radius(29 * 7 % 60)));
    (run.finish(sim.time()).unwrap(), radii)
}

#[test]
fn bodies_added_to_a_growing_packing_grow_with_it_and_every_finder_agrees() {
    let (want, radii) = refilled_run("all-pairs");
    for &(t, given, now) in &radii[..radii.len() - 1] {
        // The added body's radius is the one given, up to the rounding of the stored one.
        assert!(
            (now - given).abs() <= 4.0 * f64::EPSILON * given,
            "{t}: {given} {now}"
        );
    }
    // From then on it grows with every other: by the growth factor 1 + 0.05 t, relatively.
    let &(t1, r1, _) = &radii[radii.len() - 2];
    let &(t2, _, r2) = radii.last().unwrap();
    let ratio = (1.0 + 0.05 * (t2 + 0.5)) / (1.0 + 0.05 * t1);
    assert!((r2 / r1 - ratio).abs() < 1e-12, "{} vs {ratio}", r2 / r1);
    for finder in ["bvh", "sedgewick", "cells"] {
        assert!(
            refilled_run(finder).0 == want,
            "[{finder}] run files differ"
        );
    }
    let (scene, events, end) = records::<2>(&want);
    let adds = events
        .iter()
        .filter(|c| c.event.kind == ccdsim::EventKind::Edit && c.event.b == 1)
        .count();
    assert_eq!(adds, 30);
    for all_pairs in [false, true] {
        replay(&scene, &events, end, all_pairs).unwrap();
    }
}
