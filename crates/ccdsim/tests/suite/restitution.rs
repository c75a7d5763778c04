//! Per-body restitution and the TC model of inelastic collapse (`settings.tc`).

use ccdsim::generate::box_walls;
use ccdsim::Gravity;
use ccdsim::{AnyScene, BodySpec, Scene, Simulation, Vector};

fn ball(pos: [f64; 2], vel: [f64; 2], restitution: Option<f64>) -> BodySpec<2> {
    BodySpec {
        restitution,
        ..BodySpec::new(Vector(pos), Vector(vel), 0.5)
    }
}

#[test]
fn bodies_bounce_with_their_own_restitution_and_pairs_with_the_mean() {
    let scene = Scene::<2> {
        bodies: vec![
            ball([2.0, 2.0], [-1.0, 0.0], Some(0.5)),
            ball([6.0, 2.0], [1.0, 0.0], None),
        ],
        walls: box_walls(Vector([8.0, 4.0])),
        ..Scene::default()
    };
    let mut sim = Simulation::new(&scene, "cells").unwrap();
    // Both reach their side walls at t = 1.5: body 0 keeps half its speed, body 1 all of it.
    let a = sim.step_event().unwrap();
    let b = sim.step_event().unwrap();
    assert_eq!((a.event.a, b.event.a), (0, 1));
    assert_eq!(a.vel[0].0, [0.5, 0.0]);
    assert_eq!(b.vel[0].0, [-1.0, 0.0]);
    // They meet head on: e = (0.5 + 1)/2 = 0.75 between equal masses.
    let c = sim.step_event().unwrap();
    let closing = 1.5;
    let parting = c.vel[1][0] - c.vel[0][0];
    assert!((parting - 0.75 * closing).abs() < 1e-12, "{:?}", c.vel);
}

#[test]
fn the_tc_model_turns_a_zeno_collapse_into_lasting_small_bounces() {
    // A ball bouncing on a floor with restitution 0.5 under gravity would stop after finitely
    // many bounces in finite time (the run halts, see tests/gravity.rs); with tc = 1 ms its
    // bounces become elastic once they come closer than 1 ms apart, so it keeps bouncing,
    // about 5 mm high, and the run goes on with every finder alike.
    let mut scene = Scene::<2> {
        bodies: vec![ball([2.0, 1.5], [0.0, 0.0], None)],
        walls: box_walls(Vector([4.0, 4.0])),
        ..Scene::default()
    };
    scene.settings.restitution = 0.5;
    scene.settings.gravity = Gravity::new(&[0.0, -9.81]);
    scene.settings.tc = Some(1e-3);
    let mut runs = Vec::new();
    for finder in ["all-pairs", "bvh", "sedgewick", "cells"] {
        let mut sim = Simulation::new(&scene, finder).unwrap();
        let mut log = Vec::new();
        sim.run_until_with(3.0, |c| log.push((c.event.time.to_bits(), c.vel[0].0)));
        assert!(sim.halt().is_none(), "[{finder}] {:?}", sim.halt());
        assert_eq!(sim.time(), 3.0);
        let p = sim.position(0);
        assert!(p[1] >= 0.5 - 1e-9 && p[1] < 0.52, "[{finder}] at {p:?}");
        runs.push(log);
    }
    assert!(runs[0].len() > 100);
    assert!(runs.windows(2).all(|w| w[0] == w[1]));
}

#[test]
fn restitution_and_tc_are_validated() {
    let scene = |body: &str, settings: &str| {
        AnyScene::from_json(&format!(
            r#"{{"dim": 2, "settings": {settings}, "bodies": [{{"pos": [1, 1], "vel": [0, 0], "radius": 0.5{body}}}]}}"#
        ))
        .map(|_| ())
        .map_err(|e| e.to_string())
    };
    assert_eq!(scene(r#", "restitution": 0.3"#, r#"{"tc": 0.01}"#), Ok(()));
    let e = scene(r#", "restitution": 1.5"#, "{}").unwrap_err();
    assert!(
        e.contains("bodies[0].restitution") && e.contains("outside [0, 1]"),
        "{e}"
    );
    let e = scene("", r#"{"tc": 0}"#).unwrap_err();
    assert!(e.contains("settings.tc"), "{e}");
    // Growth collisions take the pair's restitution too (see tests/growth.rs).
    assert_eq!(
        scene(r#", "restitution": 0.3"#, r#"{"growth": {"rate": 0.1}}"#),
        Ok(())
    );
}

#[test]
fn verify_takes_each_collision_restitution_as_the_simulation_chose_it() {
    // An elastic scene with one inelastic body, and an inelastic one under the TC model:
    // the inelastic body's bounces lose energy, the others' keep it, and `verify` checks
    // each with the restitution the simulation used (it once held every collision of an
    // elastic scene to conservation).
    let walls = box_walls(Vector([8.0, 4.0]));
    let mut scenes = vec![Scene::<2> {
        bodies: vec![
            ball([2.0, 2.0], [-1.0, 0.3], Some(0.5)),
            ball([6.0, 2.0], [1.0, 0.2], None),
            ball([4.0, 1.0], [0.1, -0.7], Some(1.0)),
        ],
        walls: walls.clone(),
        ..Scene::default()
    }];
    let mut tc = scenes[0].clone();
    tc.settings.restitution = 0.8;
    tc.settings.tc = Some(0.05);
    tc.settings.gravity = Gravity::new(&[0.0, -9.81]);
    scenes.push(tc);
    for scene in &scenes {
        let mut sim = Simulation::new(scene, "cells").unwrap();
        let mut w = ccdsim::record::RunWriter::new(Vec::new(), "cells".into(), scene).unwrap();
        sim.run_until_with(100.0, |c| w.write_event(c).unwrap());
        let bytes = w.finish(sim.time()).unwrap();
        let mut r = ccdsim::record::RunReader::<_, 2>::new(&bytes[..], "run".into()).unwrap();
        let (events, end) = r.read_events().unwrap();
        assert!(events.len() > 20);
        let mut v = ccdsim::verify::Verifier::new(scene);
        for c in &events {
            v.check(c).unwrap();
        }
        let report = v.finish(end.unwrap()).unwrap();
        assert!(report.energy_end() < report.energy_start());
        // Read as if every body bounced elastically, the losses are violations.
        let mut elastic = scene.clone();
        elastic.settings.restitution = 1.0;
        elastic.settings.tc = None;
        for b in &mut elastic.bodies {
            b.restitution = None;
        }
        let mut v = ccdsim::verify::Verifier::new(&elastic);
        let err = events.iter().find_map(|c| v.check(c).err()).unwrap();
        assert!(err.to_string().contains("kinetic energy"), "{err}");
    }
}

/// A restitution-0 gas without gravity and without `settings.tc` collapses: collisions pile
/// up at one instant (it once wrote 3.1 GB in 90 s). The run halts, naming the cure, at the
/// same event for every finder; with the TC model the same gas runs on.
#[test]
fn an_inelastic_collapse_halts_the_same_for_every_finder_and_tc_cures_it() {
    use ccdsim::generate::{gas, GasConfig};
    use ccdsim::Halt;
    let mut scene: Scene<2> = gas(&GasConfig {
        n: 300,
        packing: 0.3,
        seed: 1,
        ..GasConfig::default()
    })
    .unwrap();
    scene.settings.restitution = 0.0;
    let mut runs = Vec::new();
    for finder in ["all-pairs", "bvh", "sedgewick", "cells"] {
        let mut sim = Simulation::new(&scene, finder).unwrap();
        let mut log = Vec::new();
        sim.run_until_with(100.0, |c| {
            log.push((c.event.time.to_bits(), c.event.a, c.event.b))
        });
        let halt = sim.halt();
        let Some(Halt::InelasticCollapse {
            time, collisions, ..
        }) = halt
        else {
            panic!("[{finder}] {halt:?}")
        };
        assert!(halt.unwrap().to_string().contains("settings.tc"));
        // The clock stays where the run stopped, and no event comes after it.
        assert_eq!(sim.time(), time, "[{finder}]");
        assert!(sim.step_event().is_none());
        assert!(
            collisions >= 1000 && log.len() < 100_000,
            "[{finder}] {}",
            log.len()
        );
        runs.push((log, halt));
    }
    assert!(runs.windows(2).all(|w| w[0] == w[1]));
    // The TC model: collisions closer than tc apart are elastic, and the gas runs on.
    let collapsed_at = runs[0].1.map(|h| match h {
        Halt::InelasticCollapse { time, .. } => time,
        _ => unreachable!(),
    });
    scene.settings.tc = Some(1e-3);
    let mut sim = Simulation::new(&scene, "cells").unwrap();
    let until = 2.0 * collapsed_at.unwrap();
    sim.run_until(until);
    assert!(sim.halt().is_none(), "{:?}", sim.halt());
    assert_eq!(sim.time(), until);
}
