//! The verifier's broad phase against its all-pairs mode: the same verdicts on whole runs, and
//! the same missed collision named when a collision is deleted from a run (issue 20: `verify`
//! was O(n) per event; it must scale without missing anything).

use ccdsim::generate::{gas, GasConfig, Lattice};
use ccdsim::verify::Verifier;
use ccdsim::{Collision, EventKind, Scene, Simulation};

const SEEDS: [u64; 4] = [11, 23, 37, 41];

fn scene<const D: usize>(
    n: usize,
    packing: f64,
    periodic: bool,
    open: bool,
    seed: u64,
) -> Scene<D> {
    let s = gas::<D>(&GasConfig {
        n,
        packing,
        radius_min: 0.2,
        radius_max: 0.6,
        periodic,
        lattice: periodic.then_some(Lattice::Densest),
        temperature: periodic.then_some(1.0),
        seed,
        ..GasConfig::default()
    })
    .unwrap();
    if open {
        Scene {
            walls: Vec::new(),
            ..s
        }
    } else {
        s
    }
}

fn run<const D: usize>(scene: &Scene<D>, events: u64) -> (Vec<Collision<D>>, f64) {
    let mut sim = Simulation::new(scene, "cells").unwrap();
    let mut out = Vec::new();
    sim.run_events_with(events, |c| out.push(*c));
    (out, sim.time())
}

/// The verdict of a verifier on `events` ended at `end`: `Ok` with the counts, or the
/// violation's message.
fn verdict<const D: usize>(
    mut v: Verifier<D>,
    events: &[Collision<D>],
    end: f64,
) -> Result<(u64, u64), String> {
    for c in events {
        v.check(c).map_err(|e| e.what)?;
    }
    let r = v.finish(end).map_err(|e| e.what)?;
    Ok((r.body_collisions, r.wall_collisions))
}

/// The bodies a missed-collision message names.
fn named_pair(what: &str) -> Option<(usize, usize)> {
    let rest = what.strip_prefix("bodies ")?;
    let mut it = rest.split(' ');
    let i = it.next()?.parse().ok()?;
    let _and = it.next()?;
    let j = it.next()?.parse().ok()?;
    Some((i, j))
}

fn compare<const D: usize>(label: &str, scene: &Scene<D>, events: u64) {
    let (stream, end) = run(scene, events);
    assert!(stream.len() as u64 > events / 2, "{label}: too few events");
    let grid = verdict(Verifier::new(scene), &stream, end);
    let all = verdict(Verifier::all_pairs(scene), &stream, end);
    assert!(grid.is_ok(), "{label}: {grid:?}");
    assert_eq!(grid, all, "{label}");

    // Delete body–body collisions one at a time and cut the run just after: the two bodies
    // pass through each other, and both modes must name them.
    let mut deleted = 0;
    for k in (stream.len() / 3..stream.len() - 1).step_by(stream.len() / 50 + 1) {
        let c = &stream[k];
        if c.event.kind != EventKind::Body || deleted == 6 {
            continue;
        }
        let (i, j) = (c.event.a as usize, c.event.b as usize);
        let sigma = scene.bodies[i].radius + scene.bodies[j].radius;
        let closing = (c.vel[0] - c.vel[1]).norm().max(1e-300);
        // Deep enough to be seen (1e-6 of the contact distance), before the next event.
        let gap = stream[k + 1].event.time - c.event.time;
        let end = c.event.time + (1e-5 * sigma / closing).min(0.5 * gap);
        if end <= c.event.time {
            continue;
        }
        let grid = verdict(Verifier::new(scene), &stream[..k], end);
        let all = verdict(Verifier::all_pairs(scene), &stream[..k], end);
        let (Err(g), Err(a)) = (&grid, &all) else {
            panic!("{label}: deleting event {k} ({i}, {j}) must fail both: {grid:?} / {all:?}");
        };
        assert_eq!(named_pair(g), Some((i, j)), "{label}, event {k}: {g}");
        assert_eq!(named_pair(a), Some((i, j)), "{label}, event {k}: {a}");
        deleted += 1;
    }
    assert!(deleted >= 3, "{label}: only {deleted} deletions tried");
}

#[test]
fn walled_2d() {
    for seed in SEEDS {
        compare("walled 2D", &scene::<2>(300, 0.3, false, false, seed), 4000);
    }
}

#[test]
fn periodic_2d_and_3d() {
    for seed in SEEDS {
        compare(
            "periodic 2D",
            &scene::<2>(300, 0.3, true, false, seed),
            4000,
        );
        compare(
            "periodic 3D",
            &scene::<3>(250, 0.2, true, false, seed),
            4000,
        );
    }
}

#[test]
fn walled_3d_and_open() {
    for seed in SEEDS {
        compare("walled 3D", &scene::<3>(250, 0.2, false, false, seed), 3000);
        compare("open 2D", &scene::<2>(300, 0.3, false, true, seed), 1500);
    }
}
