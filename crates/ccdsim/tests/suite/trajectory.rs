//! Frames sampled from runs: unwrapped positions follow the bodies through a periodic box,
//! and the files hold every frame.

use ccdsim::trajectory::{Frame, SampleTimes, TrajectoryFormat, TrajectoryWriter};
use ccdsim::{BodySpec, Scene, Simulation, Vector};

#[test]
fn a_lone_body_unwraps_across_many_box_lengths() {
    let scene = Scene::<2> {
        bodies: vec![BodySpec::new(Vector([1.0, 1.0]), Vector([3.0, -2.0]), 0.25)],
        periodic: Some(Vector([2.0, 2.0])),
        ..Scene::default()
    };
    let mut sim = Simulation::new(&scene, "cells").unwrap();
    for t in SampleTimes::new(0.0, 0.5, 10.0).unwrap() {
        sim.run_until(t);
        let f = Frame::of(&sim);
        let u = f.unwrapped_positions()[0];
        assert!((u[0] - (1.0 + 3.0 * t)).abs() < 1e-12, "{t}: {u:?}");
        assert!((u[1] - (1.0 - 2.0 * t)).abs() < 1e-12, "{t}: {u:?}");
        assert!((0.0..2.0).contains(&f.positions[0][0]));
        assert!((0.0..2.0).contains(&f.positions[0][1]));
    }
    // 30 m travelled in x: fifteen box lengths.
    assert_eq!(sim.image(0)[0], 15);
}

#[test]
fn unwrapped_displacements_match_the_velocities_between_collisions() {
    // A gas: between two frames without a collision for body i, its unwrapped displacement is
    // its velocity times the interval, whatever box faces it crossed.
    let scene = ccdsim::generate::gas::<3>(&ccdsim::generate::GasConfig {
        n: 200,
        packing: 0.2,
        periodic: true,
        seed: 4,
        ..Default::default()
    })
    .unwrap();
    let mut sim = Simulation::new(&scene, "cells").unwrap();
    let dt = 0.01;
    let mut before = Frame::of(&sim);
    let mut checked = 0;
    for t in SampleTimes::new(0.0, dt, 3.0).unwrap().skip(1) {
        let hits = sim.advance(t - sim.time());
        let after = Frame::of(&sim);
        let (u0, u1) = (before.unwrapped_positions(), after.unwrapped_positions());
        for i in 0..after.len() {
            let touched = hits.iter().any(|c| {
                c.event.a as usize == i || (c.body_count() == 2 && c.event.b as usize == i)
            });
            if !touched {
                let d = u1[i] - u0[i];
                let expect = after.velocities[i] * (after.time - before.time);
                assert!((d - expect).norm() < 1e-9, "body {i} at {t}");
                checked += 1;
            }
        }
        before = after;
    }
    assert!(checked > 10_000, "{checked}");
}

#[test]
fn files_of_either_format_are_written_whole() {
    let dir = tempfile::Builder::new()
        .prefix("ccdsim-traj-")
        .tempdir()
        .unwrap();
    let scene = ccdsim::generate::gas::<2>(&ccdsim::generate::GasConfig {
        n: 50,
        packing: 0.3,
        periodic: true,
        seed: 2,
        ..Default::default()
    })
    .unwrap();
    for name in ["t.xyz", "t.gsd"] {
        let path = dir.path().join(name);
        let format = TrajectoryFormat::from_path(&path).unwrap();
        let mut w = TrajectoryWriter::create(&path, format).unwrap();
        let mut sim = Simulation::new(&scene, "cells").unwrap();
        for t in SampleTimes::new(0.0, 0.1, 1.0).unwrap() {
            sim.run_until(t);
            w.write(&Frame::of(&sim)).unwrap();
        }
        w.finish().unwrap();
        let bytes = std::fs::read(&path).unwrap();
        if name.ends_with("xyz") {
            let text = String::from_utf8(bytes).unwrap();
            assert_eq!(text.lines().count(), 11 * 52);
            assert!(text.lines().nth(52 + 1).unwrap().contains("Time=0.1 "));
        } else {
            assert_eq!(&bytes[..8], &0x65DF_65DF_65DF_65DFu64.to_le_bytes());
        }
    }
    assert!(TrajectoryFormat::from_path(std::path::Path::new("t.dcd")).is_err());
}

#[test]
fn every_finder_writes_the_same_trajectory_bytes() {
    // Exactness carries over to sampled frames: the files are byte-identical across finders.
    let scene = ccdsim::generate::gas::<3>(&ccdsim::generate::GasConfig {
        n: 60,
        packing: 0.3,
        periodic: true,
        seed: 11,
        ..Default::default()
    })
    .unwrap();
    let files: Vec<(&str, Vec<u8>)> = ccdsim::FINDER_NAMES
        .iter()
        .map(|name| {
            let mut sim = Simulation::new(&scene, name).unwrap();
            let mut w = ccdsim::trajectory::XyzWriter::new(Vec::new());
            for t in SampleTimes::new(0.0, 0.2, 4.0).unwrap() {
                sim.run_until(t);
                w.write(&Frame::of(&sim)).unwrap();
            }
            (*name, w.finish().unwrap())
        })
        .collect();
    for (name, bytes) in &files[1..] {
        assert!(bytes == &files[0].1, "{name} differs from {}", files[0].0);
    }
}

/// In a sheared box a body that crossed a y face has slid with its layer: a frame's
/// unwrapped positions carry that strain, as `Simulation::unwrapped_position` does, and
/// follow each body's continuous path.
#[test]
fn sheared_frames_unwrap_with_the_strain() {
    let mut scene = ccdsim::generate::gas::<2>(&ccdsim::generate::GasConfig {
        n: 200,
        packing: 0.3,
        periodic: true,
        temperature: Some(1.0),
        seed: 4,
        ..Default::default()
    })
    .unwrap();
    scene.settings.shear_rate = Some(0.2);
    let mut sim = ccdsim::Simulation::new(&scene, "cells").unwrap();
    // Over short stretches no unwrapped path jumps (a wrong strain would move it by up to a
    // box length), though bodies cross the sliding faces (the layer speed is about 5 m/s
    // here; a body a layer or two up moves that much faster).
    let mut crossed = 0;
    for k in 1..=600 {
        let before: Vec<_> = (0..200)
            .map(|i| (sim.unwrapped_position(i), sim.image(i)))
            .collect();
        sim.run_until(0.05 * k as f64);
        for (i, (p, image)) in before.iter().enumerate() {
            let moved = (sim.unwrapped_position(i) - *p).norm();
            assert!(moved < 3.0, "body {i} jumps {moved} at t = {}", sim.time());
            crossed += usize::from(sim.image(i)[1] != image[1]);
        }
    }
    assert!(crossed > 50, "{crossed} crossings of the sliding faces");
    let frame = ccdsim::trajectory::Frame::of(&sim);
    assert!(frame.strain > 0.0);
    assert!(
        frame.images.iter().any(|k| k[1] != 0),
        "no body crossed a y face"
    );
    for (i, u) in frame.unwrapped_positions().iter().enumerate() {
        let want = sim.unwrapped_position(i);
        assert!(
            (*u - want).norm() < 1e-9 * (1.0 + want.norm()),
            "{i}: {u:?} {want:?}"
        );
    }
}
