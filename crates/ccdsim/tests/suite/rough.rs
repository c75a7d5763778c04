//! Rough bodies: spins, inertia factors and tangential restitution (`settings.
//! tangential_restitution`, `bodies[].spin`, `bodies[].inertia`). What the scene refuses,
//! what a collision does to spins, energy and momentum, that `verify` catches a wrong
//! tangential impulse, and the file formats.

use ccdsim::generate::{box_walls, gas, GasConfig};
use ccdsim::record::{version_for, RunReader, RunWriter, VERSION_ROUGH};
use ccdsim::verify::Verifier;
use ccdsim::{AnyScene, BodySpec, Scene, SceneError, Simulation, Spin, Vector};

fn rough_gas<const D: usize>(n: usize, beta: f64, periodic: bool, seed: u64) -> Scene<D> {
    let mut scene = gas::<D>(&GasConfig {
        n,
        packing: 0.25,
        radius_min: 0.3,
        radius_max: 0.6,
        seed,
        periodic,
        temperature: Some(1.0),
        ..GasConfig::default()
    })
    .unwrap();
    scene.settings.tangential_restitution = Some(beta);
    for (k, b) in scene.bodies.iter_mut().enumerate().step_by(3) {
        b.spin = Some(Spin::of::<D>(Vector([0.5, -1.0, 2.0 + k as f64 * 0.01])));
    }
    scene
}

fn total_energy<const D: usize>(sim: &Simulation<D>) -> f64 {
    sim.world().kinetic_energy_at(sim.time()) + sim.world().rotational_energy()
}

#[test]
fn scenes_refuse_bad_rough_fields_naming_them() {
    let refused = |json: &str, field: &str| {
        let err = AnyScene::from_json(json).unwrap_err().to_string();
        assert!(err.contains(field), "{json}: {err}");
    };
    let body = |extra: &str| {
        format!(r#"{{"dim": 2, "bodies": [{{"pos": [0, 0], "vel": [0, 0], "radius": 1{extra}}}]}}"#)
    };
    refused(&body(r#", "spin": [0, 0, 1]"#), "bodies[0].spin");
    refused(&body(r#", "inertia": 0"#), "bodies[0].inertia");
    refused(&body(r#", "inertia": 1.5"#), "bodies[0].inertia");
    refused(
        &body(r#", "tangential_restitution": -1.5"#),
        "bodies[0].tangential_restitution",
    );
    refused(
        r#"{"dim": 3, "bodies": [{"pos": [0, 0, 0], "vel": [0, 0, 0], "radius": 1, "spin": 2}]}"#,
        "bodies[0].spin",
    );
    refused(
        r#"{"dim": 2, "settings": {"tangential_restitution": 2}, "bodies": []}"#,
        "settings.tangential_restitution",
    );
    // Resting contacts and spins do not mix.
    let mut scene = Scene::<2> {
        bodies: vec![BodySpec::new(Vector([2.0, 1.0]), Vector([0.0, 0.0]), 0.5)],
        walls: box_walls(Vector([4.0, 4.0])),
        ..Scene::default()
    };
    scene.settings.gravity = ccdsim::Gravity::new(&[0.0, -9.81]);
    scene.settings.rest_speed = Some(0.1);
    scene.bodies[0].spin = Some(Spin::Planar(1.0));
    assert!(matches!(
        scene.validate(),
        Err(SceneError::Unsupported { field, .. }) if field == "settings.rest_speed"
    ));
}

#[test]
fn a_program_cannot_add_a_body_whose_spin_the_run_file_would_not_hold() {
    let scene = rough_gas::<2>(10, 0.5, false, 3);
    let mut sim = Simulation::new(&scene, "cells").unwrap();
    let mut spec = BodySpec::new(Vector([0.0, 0.0]), Vector([0.0, 0.0]), 0.1);
    spec.spin = Some(Spin::Planar(1.0));
    let err = sim.add_body(spec).unwrap_err().to_string();
    assert!(err.contains("spin"), "{err}");
}

#[test]
fn smooth_scenes_keep_no_spins_and_their_run_files_keep_their_versions() {
    let mut scene = rough_gas::<3>(20, 0.5, true, 1);
    assert_eq!(version_for(&scene), VERSION_ROUGH);
    scene.settings.tangential_restitution = None;
    for b in &mut scene.bodies {
        b.spin = None;
    }
    assert_eq!(version_for(&scene), ccdsim::record::VERSION);
    let sim = Simulation::new(&scene, "cells").unwrap();
    assert!(!sim.world().is_rotational());
    assert_eq!(sim.observables().rotational_temperature, None);
}

/// Perfectly rough (β = 1) and smooth (β = −1) elastic bodies keep their total energy, in
/// walled and periodic boxes, 2D and 3D; in between, energy only goes.
#[test]
fn total_energy_is_kept_exactly_when_the_rule_says() {
    fn check<const D: usize>() {
        for periodic in [false, true] {
            for beta in [1.0, -1.0, 0.0] {
                let scene = rough_gas::<D>(60, beta, periodic, 5);
                let mut sim = Simulation::new(&scene, "cells").unwrap();
                let e0 = total_energy(&sim);
                let mut last = e0;
                for _ in 0..20 {
                    sim.run_events(200);
                    let e = total_energy(&sim);
                    if beta == 0.0 {
                        assert!(e <= last * (1.0 + 1e-13), "{D}D β {beta}: {last} → {e}");
                    }
                    last = e;
                }
                if beta.abs() == 1.0 {
                    let drift = (last - e0) / e0;
                    assert!(
                        drift.abs() < 1e-12,
                        "{D}D periodic {periodic} β {beta}: {drift}"
                    );
                } else {
                    assert!(last < 0.9 * e0, "{D}D β {beta}: {e0} → {last}");
                }
            }
        }
    }
    check::<2>();
    check::<3>();
}

/// Spins start in a run's trajectory frames and the rough rule moves energy into them: a
/// gas without spins, β = 1, heads for equipartition (T_rot ≈ T_tr).
#[test]
fn a_perfectly_rough_gas_shares_its_energy_with_the_spins() {
    let mut scene = rough_gas::<3>(300, 1.0, true, 7);
    for b in &mut scene.bodies {
        b.spin = None;
    }
    let mut sim = Simulation::new(&scene, "cells").unwrap();
    assert_eq!(sim.observables().rotational_temperature, Some(0.0));
    sim.run_events(300 * 30);
    let o = sim.observables();
    let ratio = o.rotational_temperature.unwrap() / o.temperature;
    assert!((ratio - 1.0).abs() < 0.15, "T_rot/T_tr = {ratio}");
}

/// A rough run's records verify, and a record whose tangential impulse is off (momentum still
/// kept) does not.
#[test]
fn verify_replays_spins_and_catches_a_wrong_tangential_impulse() {
    fn check<const D: usize>() {
        let scene = rough_gas::<D>(40, 0.5, false, 11);
        let mut buf = Vec::new();
        {
            let mut w = RunWriter::<_, D>::new(&mut buf, "rough".into(), &scene).unwrap();
            let mut sim = Simulation::new(&scene, "cells").unwrap();
            for _ in 0..600 {
                let Some(c) = sim.step_event() else { break };
                w.write_event(&c).unwrap();
            }
            w.finish(sim.time()).unwrap();
        }
        let mut r = RunReader::<_, D>::new(&buf[..], "rough".into()).unwrap();
        assert_eq!(r.version(), VERSION_ROUGH);
        let (events, end) = r.read_events().unwrap();
        let mut v = Verifier::new(&scene);
        for c in &events {
            v.check(c).unwrap();
        }
        let report = v.finish(end.unwrap()).unwrap();
        assert!(report.rotational_energy_end > 0.0);
        // Doctor the first body–body collision: a sideways kick to both, momentum kept.
        let k = events
            .iter()
            .position(|c| c.event.kind == ccdsim::EventKind::Body)
            .unwrap();
        let mut bad = events.clone();
        let c = &mut bad[k];
        let n = (c.pos[1] - c.pos[0]) * (1.0 / (c.pos[1] - c.pos[0]).norm());
        let mut side = Vector::<D>::ZERO;
        side[0] = -n[1];
        side[1] = n[0];
        let (ma, mb) = (
            scene.bodies[c.event.a as usize].effective_mass(),
            scene.bodies[c.event.b as usize].effective_mass(),
        );
        c.vel[0] += side * (0.01 / ma);
        c.vel[1] -= side * (0.01 / mb);
        let mut v = Verifier::new(&scene);
        let first = bad
            .iter()
            .map(|c| v.check(c))
            .find_map(Result::err)
            .expect("the doctored record fails");
        assert!(first.what.contains("tangential"), "{first}");
    }
    check::<2>();
    check::<3>();
}

#[test]
fn trajectories_carry_angular_velocities() {
    let scene = rough_gas::<2>(12, 1.0, true, 2);
    let dir = std::env::temp_dir().join(format!("ccdsim-rough-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for (name, format) in [
        ("t.xyz", ccdsim::trajectory::TrajectoryFormat::ExtendedXyz),
        ("t.gsd", ccdsim::trajectory::TrajectoryFormat::Gsd),
    ] {
        let path = dir.join(name);
        let mut sim = Simulation::new(&scene, "cells").unwrap();
        let mut w = ccdsim::trajectory::TrajectoryWriter::create_for(&path, format, true).unwrap();
        for t in [0.0, 1.0] {
            sim.run_until(t);
            w.write(&ccdsim::trajectory::Frame::of(&sim)).unwrap();
        }
        w.finish().unwrap();
        let bytes = std::fs::read(&path).unwrap();
        let text = String::from_utf8_lossy(&bytes);
        match format {
            ccdsim::trajectory::TrajectoryFormat::ExtendedXyz => {
                assert!(text.contains(":id:I:1:angvel:R:3 Time="));
                // The first body's spin, as the scene gave it: (0, 0, 2).
                let first = text.lines().nth(2).unwrap();
                assert!(first.ends_with(" 0 0 0 2"), "{first}");
            }
            ccdsim::trajectory::TrajectoryFormat::Gsd => {
                assert!(text.contains("log/particles/angular_velocity"));
            }
        }
    }
    std::fs::remove_dir_all(&dir).unwrap();
}
