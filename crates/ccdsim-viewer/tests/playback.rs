//! Playback answers exactly what the simulation did, from keyframes and short replays.

mod common;

use ccdsim::generate::{gas, rack, GasConfig, RackConfig};
use ccdsim::{Scene, Simulation};
use ccdsim_viewer::{KeyframeOptions, Playback, ViewerError};

const GAS_SEED: u64 = 7;
/// Keyframes every few events, so that replays cross many keyframes.
const DENSE: KeyframeOptions = KeyframeOptions {
    budget_bytes: 1 << 30,
    min_interval: 5,
};

fn small_gas() -> Scene<2> {
    gas::<2>(&GasConfig {
        n: 60,
        packing: 0.3,
        speed_min: 1.0,
        speed_max: 3.0,
        seed: GAS_SEED,
        ..GasConfig::default()
    })
    .unwrap()
}

/// The playback's state at `t` is bit for bit the simulation's stored state after
/// `run_until(t)` (the recording stopped at `end`).
fn assert_matches_simulation<const D: usize>(
    scene: &Scene<D>,
    p: &mut Playback<D>,
    end: f64,
    times: &[f64],
) {
    for &t in times {
        let mut sim = Simulation::new(scene, "all-pairs").unwrap();
        let events = sim.run_until(t.min(end));
        let snap = p.snapshot_at(t).unwrap();
        assert_eq!(snap.applied, events, "events at or before t = {t}");
        assert_eq!(snap.time, t);
        let w = sim.world();
        assert_eq!(
            snap.states.pos,
            w.positions().collect::<Vec<_>>(),
            "positions at t = {t}"
        );
        assert_eq!(
            snap.states.vel,
            w.velocities().collect::<Vec<_>>(),
            "velocities at t = {t}"
        );
        assert_eq!(
            snap.states.time,
            w.times().collect::<Vec<_>>(),
            "reference times at t = {t}"
        );
    }
}

#[test]
fn state_at_any_time_is_the_simulations() {
    let dir = common::temp_dir("playback-time");
    let scene = small_gas();
    let path = dir.join("gas.ccd");
    let n = common::record(&scene, 3.0, &path);
    assert!(n > 100, "the gas collides: {n} events");
    let mut p = Playback::<2>::open(&path, &DENSE).unwrap();
    assert_eq!(p.events(), n);
    assert_eq!(p.index().interval, 5);
    assert_eq!(p.index().keyframes.len() as u64, n / 5 + 1);
    assert!(p.complete());
    assert_eq!(p.end_time(), 3.0);
    // Out of order on purpose: seeks go back and forth.
    assert_matches_simulation(
        &scene,
        &mut p,
        3.0,
        &[2.5, 0.0, 1.0, 0.37, 2.99, 0.37, 3.0, 10.0],
    );
}

#[test]
fn state_after_k_events_is_the_simulations() {
    let dir = common::temp_dir("playback-events");
    let scene = rack(&RackConfig::default());
    let path = dir.join("break.ccd");
    let n = common::record(&scene, 4.0, &path);
    let mut p = Playback::<2>::open(&path, &DENSE).unwrap();
    for k in [0, 1, 4, 5, 6, 17, n - 1, n, n + 3] {
        let mut sim = Simulation::new(&scene, "all-pairs").unwrap();
        let mut last = None;
        sim.run_events_with(k.min(n), |c| last = Some(*c));
        let snap = p.snapshot_after(k).unwrap();
        assert_eq!(snap.applied, k.min(n));
        assert_eq!(
            snap.states.pos,
            sim.world().positions().collect::<Vec<_>>(),
            "after {k} events"
        );
        assert_eq!(
            snap.states.vel,
            sim.world().velocities().collect::<Vec<_>>()
        );
        assert_eq!(snap.last, last);
        assert_eq!(snap.time, last.map_or(0.0, |c| c.event.time));
    }
}

#[test]
fn windows_and_steps_follow_the_file() {
    let dir = common::temp_dir("playback-steps");
    let scene = rack(&RackConfig::default());
    let path = dir.join("break.ccd");
    common::record(&scene, 2.0, &path);
    let mut p = Playback::<2>::open(&path, &DENSE).unwrap();
    let all = p.events_window(0, u64::MAX).unwrap();
    assert_eq!(all.len() as u64, p.events());
    assert_eq!(p.events_window(3, 4).unwrap(), all[3..7].to_vec());
    assert!(p.events_window(p.events(), 4).unwrap().is_empty());
    let times: Vec<f64> = all.iter().map(|c| c.event.time).collect();
    assert_eq!(p.next_event_time(-1.0).unwrap(), Some(times[0]));
    assert_eq!(p.prev_event_time(times[0]).unwrap(), None);
    for k in 1..times.len() {
        // From an event, the next and previous distinct event times.
        let t = times[k];
        let next = times.iter().copied().find(|&x| x > t);
        let prev = times.iter().copied().rev().find(|&x| x < t);
        assert_eq!(p.next_event_time(t).unwrap(), next, "next after event {k}");
        assert_eq!(
            p.prev_event_time(t).unwrap(),
            prev,
            "previous before event {k}"
        );
    }
}

#[test]
fn the_keyframe_budget_sets_the_interval() {
    let dir = common::temp_dir("playback-budget");
    let scene = small_gas();
    let path = dir.join("gas.ccd");
    let n = common::record(&scene, 3.0, &path);
    // Room for about 10 keyframes of 60 bodies (40 bytes each).
    let budget = 10 * 60 * 40;
    let p = Playback::<2>::open(
        &path,
        &KeyframeOptions {
            budget_bytes: budget,
            min_interval: 1,
        },
    )
    .unwrap();
    assert_eq!(p.index().interval, (n + 1).div_ceil(10));
    assert!(
        p.index().heap_bytes() <= budget + 60 * 40,
        "{} bytes",
        p.index().heap_bytes()
    );
}

#[test]
fn a_run_cut_short_plays_to_its_last_whole_event() {
    let dir = common::temp_dir("playback-cut");
    let scene = rack(&RackConfig::default());
    let path = dir.join("break.ccd");
    let n = common::record(&scene, 2.0, &path);
    let len = std::fs::metadata(&path).unwrap().len();
    let rec = ccdsim::record::record_len(2) as u64;
    // Drop the end record and half of the last event.
    let bytes = std::fs::read(&path).unwrap();
    std::fs::write(&path, &bytes[..(len - rec - rec / 2) as usize]).unwrap();
    let mut p = Playback::<2>::open(&path, &DENSE).unwrap();
    assert_eq!(p.events(), n - 1);
    assert!(!p.complete());
    let last = p.events_window(n - 2, 1).unwrap()[0];
    assert_eq!(p.end_time(), last.event.time);
    assert_eq!(p.snapshot_at(100.0).unwrap().applied, n - 1);
}

#[test]
fn the_wrong_dimension_is_refused() {
    let dir = common::temp_dir("playback-dim");
    let path = dir.join("break.ccd");
    common::record(&rack(&RackConfig::default()), 0.5, &path);
    let err = Playback::<3>::open(&path, &DENSE).err().unwrap();
    assert!(err.to_string().contains("2D"), "{err}");
}

#[test]
fn finder_boxes_come_from_the_named_finder() {
    let dir = common::temp_dir("playback-boxes");
    let scene = rack(&RackConfig::default());
    let path = dir.join("break.ccd");
    common::record(&scene, 1.0, &path);
    let mut p = Playback::<2>::open(&path, &DENSE).unwrap();
    let snap = p.snapshot_at(0.5).unwrap();
    let world = p.world_at(&snap).unwrap();
    assert_eq!(world.now(), 0.5);
    assert_eq!(world.positions().collect::<Vec<_>>(), snap.states.pos);
    // The all-pairs finder has no spatial structure to show.
    let opts = ccdsim::FinderOptions::default();
    assert!(p
        .finder_boxes(&snap, "all-pairs", &opts)
        .unwrap()
        .is_empty());
    match p.finder_boxes(&snap, "no-such-finder", &opts) {
        Err(ViewerError::Finder(e)) => assert!(
            e.to_string().contains("unknown finder `no-such-finder`"),
            "{e}"
        ),
        other => panic!("expected an unknown-finder error, got {other:?}"),
    }
}

#[test]
fn bvh_boxes_are_the_thesis_tree_around_the_bodies() {
    let dir = common::temp_dir("playback-bvh");
    let scene = rack(&RackConfig::default());
    let path = dir.join("break.ccd");
    common::record(&scene, 2.0, &path);
    let mut p = Playback::<2>::open(&path, &DENSE).unwrap();
    for t in [0.0, 0.3, 1.7] {
        let snap = p.snapshot_at(t).unwrap();
        let boxes = p
            .finder_boxes(&snap, "bvh", &ccdsim::FinderOptions::default())
            .unwrap();
        // A binary tree over 16 bodies: 16 leaves, 15 inner nodes, one root at depth 0.
        let leaves: Vec<_> = boxes.iter().filter(|b| b.leaf).collect();
        assert_eq!(leaves.len(), 16, "t = {t}");
        assert_eq!(boxes.len(), 31, "t = {t}");
        assert_eq!(boxes.iter().filter(|b| b.depth == 0).count(), 1);
        let root = boxes.iter().find(|b| b.depth == 0).unwrap();
        // Every body at t lies in exactly its own swept leaf box (and so in the root).
        for i in 0..16 {
            let ball = ccdsim::Aabb::of_ball(snap.states.position_at(i, t), scene.bodies[i].radius);
            assert!(
                leaves.iter().any(|b| b.aabb.contains(&ball)),
                "body {i} at t = {t} in a leaf"
            );
            assert!(root.aabb.contains(&ball));
        }
    }
}
