//! `verify` on runs under uniform gravity: recorded runs pass (in both the grid and the
//! all-pairs modes, with kinetic plus potential energy conserved), and tampered runs fail:
//! a flipped or scaled velocity, a shifted time, a deleted collision, a header whose gravity
//! was dropped or changed, and bodies whose parabolas (but not their straight lines) cross
//! a wall.

use ccdsim::generate::{box_walls, gas, GasConfig};
use ccdsim::record::{RunReader, RunWriter};
use ccdsim::verify::VerifyReport;
use ccdsim::Gravity;
use ccdsim::{BodySpec, Collision, EventKind, Scene, Simulation, Vector, Wall};
use replay::replay;
use std::io::Cursor;

use crate::replay;

const SEEDS: [u64; 3] = [5, 17, 29];

fn falling<const D: usize>(mut scene: Scene<D>, g: [f64; D]) -> Scene<D> {
    scene.settings.gravity = Gravity::new(&g);
    scene
}

fn gas_scene<const D: usize>(n: usize, packing: f64, seed: u64) -> Scene<D> {
    gas::<D>(&GasConfig {
        n,
        packing,
        radius_min: 0.3,
        radius_max: 0.6,
        speed_max: 2.0,
        seed,
        ..GasConfig::default()
    })
    .unwrap()
}

/// A walled 2D board of short tilted pegs (segments, so their end points are hit) with balls
/// dropped from above.
fn peg_board(seed: u64) -> Scene<2> {
    let width = 12.0;
    let mut walls = box_walls(Vector([width, 16.0]));
    for row in 0..4 {
        let y = 3.0 + 1.5 * f64::from(row);
        let mut x = 1.0 + if row % 2 == 0 { 0.0 } else { 0.75 };
        while x < width - 1.0 {
            walls.push(Wall::Segment {
                a: Vector([x - 0.2, y]),
                b: Vector([x + 0.2, y + 0.1]),
            });
            x += 1.5;
        }
    }
    let mut state = seed;
    let bodies = (0..24)
        .map(|k| {
            state = state
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            let jitter = (state >> 11) as f64 / (1u64 << 53) as f64;
            let x = 0.6 + (k % 16) as f64 * 0.68 + 0.05 * jitter;
            let y = 10.0 + 0.7 * (k / 16) as f64;
            BodySpec::new(Vector([x, y]), Vector([jitter - 0.5, 0.0]), 0.25)
        })
        .collect();
    falling(
        Scene {
            bodies,
            walls,
            ..Scene::default()
        },
        [0.0, -9.81],
    )
}

fn simulate<const D: usize>(scene: &Scene<D>, events: u64) -> (Vec<Collision<D>>, f64) {
    let mut sim = Simulation::new(scene, "cells").unwrap();
    let mut out = Vec::new();
    sim.run_events_with(events, |c| out.push(*c));
    (out, sim.time())
}

/// The run file's bytes: `scene` in the header, then `events`, ended at `end`.
fn write_run<const D: usize>(scene: &Scene<D>, events: &[Collision<D>], end: f64) -> Vec<u8> {
    let mut w = RunWriter::new(Vec::new(), "memory".into(), scene).unwrap();
    for c in events {
        w.write_event(c).unwrap();
    }
    w.finish(end).unwrap()
}

/// Reads a run file's bytes and verifies it (grid mode, or every pair).
fn verify_bytes<const D: usize>(bytes: &[u8], all_pairs: bool) -> Result<VerifyReport, String> {
    let mut r = RunReader::<_, D>::new(Cursor::new(bytes), "memory".into()).unwrap();
    let scene = r.scene().clone();
    let (events, end) = r.read_events().unwrap();
    replay(&scene, &events, end.expect("an end record"), all_pairs)
}

/// A recorded gravity run passes in both modes with the same counts, its kinetic plus
/// potential energy is conserved (elastic collisions), and gravity did work on it.
fn passes<const D: usize>(label: &str, scene: &Scene<D>, events: u64) -> (Vec<Collision<D>>, f64) {
    let (stream, end) = simulate(scene, events);
    assert!(
        stream.len() as u64 == events,
        "{label}: only {} events",
        stream.len()
    );
    let bytes = write_run(scene, &stream, end);
    assert_eq!(
        &bytes[8..12],
        &4u32.to_le_bytes(),
        "{label}: format version 4"
    );
    let grid = verify_bytes::<D>(&bytes, false).unwrap_or_else(|e| panic!("{label}: {e}"));
    let all = verify_bytes::<D>(&bytes, true).unwrap_or_else(|e| panic!("{label}: {e}"));
    assert_eq!(grid, all, "{label}");
    assert_eq!(grid.events, events);
    assert!(
        grid.wall_collisions > 0 && grid.body_collisions > 0,
        "{label}: {grid:?}"
    );
    assert!(grid.max_overlap < 1e-9, "{label}: {grid:?}");
    let scale = grid.kinetic_energy_start.abs()
        + grid.kinetic_energy_end.abs()
        + grid.potential_energy_start.abs()
        + grid.potential_energy_end.abs();
    let drift = (grid.energy_end() - grid.energy_start()).abs() / scale;
    assert!(drift < 1e-9, "{label}: energy drift {drift:e}: {grid:?}");
    assert!(
        (grid.potential_energy_end - grid.potential_energy_start).abs() > 1e-6 * scale,
        "{label}: gravity did no work? {grid:?}"
    );
    (stream, end)
}

/// The verdict on `stream` after `edit` (given the stream, returns the edited stream and end).
fn tampered<const D: usize>(
    scene: &Scene<D>,
    stream: &[Collision<D>],
    end: f64,
    edit: impl FnOnce(&mut Vec<Collision<D>>, &mut f64),
) -> Result<VerifyReport, String> {
    let mut s = stream.to_vec();
    let mut e = end;
    edit(&mut s, &mut e);
    verify_bytes::<D>(&write_run(scene, &s, e), false)
}

/// The index of the first event of `kind` from `from` on.
fn first_of<const D: usize>(s: &[Collision<D>], from: usize, kind: EventKind) -> usize {
    (from..s.len())
        .find(|&k| s[k].event.kind == kind)
        .expect("such an event")
}

fn tampering_fails<const D: usize>(
    label: &str,
    scene: &Scene<D>,
    stream: &[Collision<D>],
    end: f64,
) {
    let mid = stream.len() / 2;
    let k = first_of(stream, mid, EventKind::Body);
    // A flipped velocity breaks the pair's momentum.
    let r = tampered(scene, stream, end, |s, _| s[k].vel[0] = s[k].vel[0] * -1.0);
    assert!(r.is_err(), "{label}: flipped velocity passed: {r:?}");
    // A scaled one too, and elastic energy with it.
    let r = tampered(scene, stream, end, |s, _| s[k].vel[1] = s[k].vel[1] * 1.01);
    assert!(r.is_err(), "{label}: scaled velocity passed: {r:?}");
    // A shifted time: the recorded positions are not where the parabolas put the bodies.
    let r = tampered(scene, stream, end, |s, _| s[k].event.time += 1e-4);
    let e = r.expect_err(&format!("{label}: shifted time passed"));
    assert!(e.contains(&format!("event {k}")), "{label}: {e}");
    // A wall event's velocity flipped: energy is kept, but the body then runs into the wall
    // (or a neighbour) before its next event.
    let w = first_of(stream, mid, EventKind::Wall);
    let r = tampered(scene, stream, end, |s, _| s[w].vel[0] = s[w].vel[0] * -1.0);
    assert!(r.is_err(), "{label}: flipped wall bounce passed: {r:?}");
    // Deleted collisions, the run cut just after: the bodies pass through each other, or
    // through the wall.
    for kind in [EventKind::Body, EventKind::Wall] {
        let (d, cut) = deletable(scene, stream, mid, kind);
        let r = tampered(scene, stream, end, |s, e| {
            s.truncate(d);
            *e = cut;
        });
        let e = r.expect_err(&format!("{label}: deleted {kind:?} event {d} passed"));
        assert!(e.contains("missed collision"), "{label}: {e}");
    }
}

/// The first event of `kind` from `from` on whose deletion leaves an overlap of at least
/// `1e-6` of the contact distance by a time before the next event, and that time: the
/// contact's normal speed is read from the bounce (elastic: it flips the normal velocity).
fn deletable<const D: usize>(
    scene: &Scene<D>,
    s: &[Collision<D>],
    from: usize,
    kind: EventKind,
) -> (usize, f64) {
    for d in from..s.len() - 1 {
        let c = s[d];
        if c.event.kind != kind {
            continue;
        }
        let a = c.event.a as usize;
        let (normal_speed, sigma) = match kind {
            EventKind::Body => {
                let b = c.event.b as usize;
                let n = c.pos[1] - c.pos[0];
                let n = n * (1.0 / n.norm());
                let sigma = scene.bodies[a].radius + scene.bodies[b].radius;
                ((c.vel[1] - c.vel[0]).dot(n).abs(), sigma)
            }
            _ => {
                let wall = &scene.walls[c.event.b as usize];
                let n = ccdsim::contact::narrow::wall_normal(wall, c.pos[0]).unwrap();
                (c.vel[0].dot(n).abs(), scene.bodies[a].radius)
            }
        };
        let gap = s[d + 1].event.time - c.event.time;
        let delta = (1e-4 * sigma / normal_speed).min(0.5 * gap);
        if normal_speed * delta > 1e-6 * sigma {
            return (d, c.event.time + delta);
        }
    }
    panic!("no deletable {kind:?} event");
}

/// The run's header with its gravity dropped or changed: the records do not follow.
fn header_gravity_matters<const D: usize>(
    label: &str,
    scene: &Scene<D>,
    stream: &[Collision<D>],
    end: f64,
) {
    let mut none = scene.clone();
    none.settings.gravity = None;
    let bytes = write_run(&none, stream, end);
    assert_eq!(
        &bytes[8..12],
        &1u32.to_le_bytes(),
        "{label}: a version 1 file"
    );
    let r = verify_bytes::<D>(&bytes, false);
    assert!(
        r.is_err(),
        "{label}: the run read without gravity passed: {r:?}"
    );
    let mut other = scene.clone();
    let g: Vec<f64> = scene
        .settings
        .gravity
        .unwrap()
        .components()
        .iter()
        .map(|x| x * 0.99)
        .collect();
    other.settings.gravity = Gravity::new(&g);
    let r = verify_bytes::<D>(&write_run(&other, stream, end), false);
    assert!(
        r.is_err(),
        "{label}: the run read with 0.99 g passed: {r:?}"
    );
}

#[test]
fn gravity_runs_pass_and_tampered_ones_fail_2d() {
    for seed in SEEDS {
        let label = format!("gas 2D seed {seed}");
        let scene = falling(gas_scene::<2>(60, 0.25, seed), [0.0, -9.81]);
        let (stream, end) = passes(&label, &scene, 1500);
        tampering_fails(&label, &scene, &stream, end);
        header_gravity_matters(&label, &scene, &stream, end);
    }
    // Sideways gravity and inelastic collisions.
    let mut scene = falling(gas_scene::<2>(50, 0.2, 3), [2.0, -1.0]);
    scene.settings.restitution = 0.95;
    let (stream, end) = simulate(&scene, 800);
    let r = verify_bytes::<2>(&write_run(&scene, &stream, end), false);
    assert!(r.is_ok(), "inelastic: {r:?}");
}

#[test]
fn gravity_runs_pass_and_tampered_ones_fail_3d() {
    for seed in SEEDS {
        let label = format!("gas 3D seed {seed}");
        let scene = falling(gas_scene::<3>(50, 0.15, seed), [0.5, -1.0, -9.81]);
        let (stream, end) = passes(&label, &scene, 1200);
        tampering_fails(&label, &scene, &stream, end);
        header_gravity_matters(&label, &scene, &stream, end);
    }
}

#[test]
fn peg_boards_pass() {
    for seed in SEEDS {
        let label = format!("peg board seed {seed}");
        let scene = peg_board(seed);
        let (stream, end) = passes(&label, &scene, 1500);
        header_gravity_matters(&label, &scene, &stream, end);
    }
}

/// FNV-1a, as the run file's record checksums.
fn fnv1a(bytes: &[u8]) -> u32 {
    bytes.iter().fold(0x811c_9dc5u32, |h, &b| {
        (h ^ u32::from(b)).wrapping_mul(0x0100_0193)
    })
}

#[test]
fn a_time_changed_in_the_file_fails() {
    let scene = falling(gas_scene::<2>(40, 0.25, 9), [0.0, -9.81]);
    let (stream, end) = simulate(&scene, 600);
    let mut bytes = write_run(&scene, &stream, end);
    assert!(verify_bytes::<2>(&bytes, false).is_ok());
    // Record 300's time, at offset 9 in the record, moved later (halfway to record 301's,
    // so that times still never go backwards); checksum recomputed so that the reader accepts
    // the record and the verifier has to catch it.
    let len = ccdsim::record::record_len(2);
    let start = bytes.len() - len * (stream.len() + 1 - 300);
    let later = 0.5 * (stream[300].event.time + stream[301].event.time);
    assert!(later > stream[300].event.time);
    let nudge = |bytes: &mut Vec<u8>, t: f64| {
        let rec = &mut bytes[start..start + len];
        rec[9..17].copy_from_slice(&t.to_le_bytes());
        let sum = fnv1a(&rec[..len - 4]);
        rec[len - 4..].copy_from_slice(&sum.to_le_bytes());
    };
    nudge(&mut bytes, later);
    let e = verify_bytes::<2>(&bytes, false).unwrap_err();
    assert!(e.contains("event 300"), "{e}");
    // Moved past record 301's time, it makes that record go back in time: the reader
    // refuses the file, naming the record.
    nudge(&mut bytes, stream[301].event.time + 1e-3);
    let mut r = RunReader::<_, 2>::new(Cursor::new(&bytes[..]), "memory".into()).unwrap();
    let e = r.read_events().unwrap_err().to_string();
    assert!(
        e.contains("record 301") && e.contains("goes backwards"),
        "{e}"
    );
}

#[test]
fn walls_are_checked_along_the_parabola() {
    // A ball thrown up beside a horizontal segment arcs over and comes down through it: its
    // straight line from the start never comes near. No event is recorded.
    let seg = Wall::Segment {
        a: Vector([0.0, 0.0]),
        b: Vector([4.0, 0.0]),
    };
    let ball = BodySpec::new(Vector([-1.0, 1.0]), Vector([1.5, 8.0]), 0.1);
    let scene = falling(
        Scene {
            bodies: vec![ball],
            walls: vec![seg],
            ..Scene::default()
        },
        [0.0, -10.0],
    );
    let e = replay(&scene, &[], 2.0, false).unwrap_err();
    assert!(e.contains("crosses wall 0"), "{e}");
    // Stopped before it comes down: fine.
    assert!(replay(&scene, &[], 1.0, false).is_ok());

    // A floor plane in 3D: a ball thrown up comes back down through it.
    let floor = Wall::Plane {
        point: Vector([0.0, 0.0, 0.0]),
        normal: Vector([0.0, 0.0, 1.0]),
    };
    let ball = BodySpec::new(Vector([0.0, 0.0, 1.0]), Vector([0.0, 1.0, 3.0]), 0.5);
    let scene = falling(
        Scene {
            bodies: vec![ball],
            walls: vec![floor],
            ..Scene::default()
        },
        [0.0, 0.0, -10.0],
    );
    // Rises to 1.45 at t = 0.3, back to 0.5 (touching) at t = 0.3 + √0.19.
    assert!(replay(&scene, &[], 0.7, false).is_ok());
    let e = replay(&scene, &[], 0.8, false).unwrap_err();
    assert!(e.contains("crosses wall 0"), "{e}");
}

#[test]
fn pairs_falling_together_are_checked_from_their_states() {
    // Two balls falling alike, one thrown up at the other: they pass through each other
    // unless a collision is recorded. Their relative motion is linear, so the pair check sees
    // it from their states.
    // Both start at t = 1 (a scene's start time), 10 apart, closing at 8 m/s while falling.
    let later = falling(
        Scene {
            bodies: vec![
                BodySpec::new(Vector([0.0, 9.0]), Vector([0.0, -2.0]), 0.5),
                BodySpec::new(Vector([0.0, -1.0]), Vector([0.0, 6.0]), 0.5),
            ],
            start_time: 1.0,
            ..Scene::default()
        },
        [0.0, -2.0],
    );
    // Gap 10 − 1 closing at 8: contact at t = 1 + 9/8.
    assert!(replay(&later, &[], 2.0, false).is_ok());
    for all in [false, true] {
        let e = replay(&later, &[], 2.2, all).unwrap_err();
        assert!(e.contains("bodies 0 and 1"), "{e}");
    }
}
