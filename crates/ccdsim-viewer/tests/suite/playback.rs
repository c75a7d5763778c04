//! Playback answers exactly what the simulation did, from keyframes and short replays.

use crate::common;

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

// ---- runs that add and remove bodies --------------------------------------------------------

/// `states` holds the simulation's slots of checkpoint `cp`: each body's stored state,
/// radius, id and kinematic flag, and vacant slots (radius 0, at rest, no id) where it has
/// none; the slots it reserved past the last one used are not known to the replay.
fn assert_slots(states: &ccdsim_viewer::BodyStates<2>, cp: &common::slots::Checkpoint) {
    let at = format!("after {} records (t = {})", cp.applied, cp.time);
    assert!(states.len() <= cp.slots.len(), "{at}");
    for (i, slot) in cp.slots.iter().enumerate() {
        if i >= states.len() {
            assert!(
                slot.is_none(),
                "{at}: slot {i}, past the replay's, holds a body"
            );
            continue;
        }
        match slot {
            Some(s) => {
                assert!(!states.is_vacant(i), "{at}: slot {i} holds a body");
                assert_eq!(states.motion(i), s.motion, "{at}: slot {i}");
                assert_eq!(states.radius(i), s.radius, "{at}: slot {i}");
                assert_eq!(states.id(i), s.id, "{at}: slot {i}");
                assert_eq!(states.is_kinematic(i), s.kinematic, "{at}: slot {i}");
            }
            None => {
                assert!(states.is_vacant(i), "{at}: slot {i} is vacant");
                assert_eq!(states.radius(i), 0.0, "{at}: slot {i}");
                assert_eq!(states.id(i), u64::MAX, "{at}: slot {i}");
                assert!(states.is_kinematic(i), "{at}: slot {i} stays at rest");
            }
        }
    }
}

#[test]
fn a_run_that_adds_and_removes_bodies_plays_the_simulations_slots() {
    use common::slots::{record_slot_run, PLAN};
    let dir = common::temp_dir("playback-slots");
    let path = dir.join("slots.ccd");
    let run = record_slot_run(&path, &PLAN);
    let n0 = run.scene.bodies.len();
    // The run does what it is meant to: slots past the scene's, removed slots filled again.
    assert!(
        run.adds.len() >= 30 && run.removals.len() >= 20,
        "{} adds, {} removals",
        run.adds.len(),
        run.removals.len()
    );
    assert!(run.adds.iter().any(|a| a.slot >= n0 + 10));
    assert!(
        run.adds.iter().any(|a| a.kinematic),
        "a kinematic body is added"
    );
    assert!(run.adds.iter().any(|a| a.id >= 1000), "an id of its own");
    assert!(run.adds.iter().any(|a| run
        .removals
        .iter()
        .any(|r| r.slot == a.slot && r.time < a.time)));
    let mut p = Playback::<2>::open(&path, &DENSE).unwrap();
    assert_eq!(p.events(), run.events);
    assert!(p.has_slot_edits());
    let slots = run.adds.iter().map(|a| a.slot + 1).max().unwrap().max(n0);
    assert_eq!(p.slots(), slots);
    assert_eq!(p.index().slots, slots);
    for cp in &run.checkpoints {
        let snap = p.snapshot_after(cp.applied).unwrap();
        assert_eq!(snap.applied, cp.applied);
        assert_slots(&snap.states, cp);
    }
    // A removed body's slot is vacant from its removal (until a body is added there), and
    // its body stays where it stopped.
    for r in &run.removals {
        let refilled = run
            .adds
            .iter()
            .any(|a| a.slot == r.slot && a.time >= r.time);
        let later = if refilled { r.time } else { run.end };
        let snap = p.snapshot_at(later).unwrap();
        assert!(
            snap.states.is_vacant(r.slot),
            "slot {} at t = {later}",
            r.slot
        );
        assert_eq!(snap.states.radius(r.slot), 0.0);
        assert_eq!(snap.states.position_at(r.slot, later), r.pos);
    }
}

#[test]
fn every_snapshot_of_a_slot_run_is_a_straight_replay() {
    use common::slots::{record_slot_run, PLAN};
    let dir = common::temp_dir("playback-slots-replay");
    let path = dir.join("slots.ccd");
    let run = record_slot_run(&path, &PLAN);
    let mut p = Playback::<2>::open(&path, &DENSE).unwrap();
    let all = p.events_window(0, u64::MAX).unwrap();
    assert_eq!(all.len() as u64, run.events);
    assert!(
        all.windows(2)
            .any(|w| w[0].event.b == 1 && w[1].event.b == 2),
        "added bodies' records"
    );
    let mut s = ccdsim_viewer::BodyStates::from_scene(&run.scene);
    let interval = p.index().interval;
    let keyframes = p.index().keyframes.clone();
    assert!(keyframes.len() as u64 > run.events / interval);
    for k in 0..=all.len() {
        if k > 0 {
            s.apply(&all[k - 1]);
        }
        if k as u64 % interval == 0 {
            let kf = &keyframes[k / interval as usize];
            assert_eq!(kf.applied, k as u64);
            assert_eq!(kf.states, s, "keyframe after {k} events");
        }
        // Every count of events, those between an added body and its id record included.
        let snap = p.snapshot_after(k as u64).unwrap();
        assert_eq!(snap.states, s, "after {k} events");
        // (Compared as text: an added body's record holds a NaN, "the scene's restitution".)
        assert_eq!(
            format!("{:?}", snap.last),
            format!("{:?}", k.checked_sub(1).map(|j| all[j]))
        );
    }
}

#[test]
fn the_extent_and_the_finder_boxes_hold_every_body_present() {
    use common::slots::{record_slot_run, PLAN};
    let dir = common::temp_dir("playback-slots-extent");
    let path = dir.join("slots.ccd");
    let run = record_slot_run(&path, &PLAN);
    let mut p = Playback::<2>::open(&path, &DENSE).unwrap();
    let bounds = p.extent().bounds;
    for (j, cp) in run.checkpoints.iter().enumerate() {
        let snap = p.snapshot_after(cp.applied).unwrap();
        let present: Vec<usize> = (0..snap.states.len())
            .filter(|&i| !snap.states.is_vacant(i))
            .collect();
        let balls: Vec<ccdsim::Aabb<2>> = present
            .iter()
            .map(|&i| {
                ccdsim::Aabb::of_ball(snap.states.position_at(i, cp.time), snap.states.radius(i))
            })
            .collect();
        for b in &balls {
            assert!(bounds.contains(b), "{b:?} in {bounds:?} at t = {}", cp.time);
        }
        if j % 10 != 5 {
            continue;
        }
        // The world the boxes are built on: the bodies present, where they are.
        let world = p.world_at(&snap).unwrap();
        assert_eq!(world.len(), present.len());
        assert_eq!(world.now(), snap.time);
        let boxes = p
            .finder_boxes(&snap, "bvh", &ccdsim::FinderOptions::default())
            .unwrap();
        let leaves: Vec<_> = boxes.iter().filter(|b| b.leaf).collect();
        assert_eq!(leaves.len(), present.len(), "t = {}", cp.time);
        for (b, &i) in balls.iter().zip(&present) {
            let ball =
                ccdsim::Aabb::of_ball(snap.states.position_at(i, snap.time), snap.states.radius(i));
            assert!(
                leaves.iter().any(|l| l.aabb.contains(&ball)),
                "slot {i} ({b:?}) in a leaf at t = {}",
                snap.time
            );
        }
    }
}

#[test]
fn keyframes_thin_out_when_added_bodies_outgrow_the_budget() {
    use common::slots::{record_slot_run, Plan};
    let plan = Plan {
        start_bodies: 2,
        frames: 100,
        add_every: 1,
        remove_every: 0,
        size: 8.0,
    };
    let dir = common::temp_dir("playback-slots-budget");
    let path = dir.join("growing.ccd");
    let run = record_slot_run(&path, &plan);
    assert!(run.adds.len() >= 90, "{} adds", run.adds.len());
    let budget = 40_000;
    let options = KeyframeOptions {
        budget_bytes: budget,
        min_interval: 1,
    };
    let mut p = Playback::<2>::open(&path, &options).unwrap();
    let idx = p.index();
    // Sized for 2 bodies, the interval had to grow with the bodies.
    let first = options.interval::<2>(run.events + 1, 2);
    assert!(idx.interval >= 4 * first, "{} vs {first}", idx.interval);
    let first_bytes = idx.keyframes[0].states.heap_bytes();
    assert!(
        idx.heap_bytes() - first_bytes <= budget,
        "{} bytes",
        idx.heap_bytes()
    );
    for (j, kf) in idx.keyframes.iter().enumerate() {
        assert_eq!(kf.applied, j as u64 * idx.interval);
    }
    assert!(
        idx.keyframes.len() >= 4,
        "{} keyframes",
        idx.keyframes.len()
    );
    for cp in run.checkpoints.iter().step_by(7) {
        let snap = p.snapshot_after(cp.applied).unwrap();
        assert_slots(&snap.states, cp);
    }
}

#[test]
fn records_naming_slots_without_a_body_are_refused() {
    use ccdsim::edit::Edit;
    use ccdsim::record::RunWriter;
    use ccdsim::{BodySpec, Collision, CollisionFilter, Event, EventKind, Vector};
    let dir = common::temp_dir("playback-slots-bad");
    let scene = Scene::<2> {
        bodies: vec![
            BodySpec::new(Vector([0.0, 0.0]), Vector([1.0, 0.0]), 0.5),
            BodySpec::new(Vector([3.0, 0.0]), Vector([0.0, 0.0]), 0.5),
        ],
        ..Scene::default()
    };
    let body = |t: f64, a: u32, b: u32| Collision {
        event: Event {
            time: t,
            kind: EventKind::Body,
            a,
            b,
        },
        pos: [Vector([1.0, 0.0]), Vector([2.0, 0.0])],
        vel: [Vector::ZERO, Vector([1.0, 0.0])],
        rests: [false; 2],
        pivots: [false; 2],
    };
    let add = Edit::<2>::Add {
        body: 2,
        id: 7,
        pos: Vector([0.0, 5.0]),
        vel: Vector::ZERO,
        radius: 0.5,
        mass: 1.0,
        filter: CollisionFilter::DEFAULT,
        restitution: None,
    }
    .records(0.5);
    let remove = Edit::<2>::Remove {
        body: 1,
        pos: Vector([3.0, 0.0]),
    }
    .records(0.5);
    // The run-file reader refuses what a record read in order shows (an index past the slots,
    // an added body's records apart, a slot that holds a body); the playback what needs the
    // bodies' states (a record naming a vacant slot).
    let cases: Vec<(Vec<Collision<2>>, &str)> = vec![
        (
            vec![body(1.0, 0, 5)],
            "record 0 is corrupt (index out of range: a = 0, b = 5)",
        ),
        (
            vec![remove[0], body(1.0, 0, 1)],
            "names body 1, whose slot is vacant",
        ),
        (
            vec![add[0], body(1.0, 0, 1)],
            "record 1 is corrupt (an added body's record (slot 2) is not followed by its id record)",
        ),
        (
            vec![add[1]],
            "record 0 is corrupt (an id record (slot 2) without its added body)",
        ),
        (
            vec![add[0], add[1], add[0], add[1]],
            "record 2 is corrupt (a body is added in slot 2, which holds one)",
        ),
    ];
    for (k, (records, want)) in cases.into_iter().enumerate() {
        let path = dir.join(format!("bad{k}.ccd"));
        let mut w = RunWriter::create_steered(&path, &scene).unwrap();
        for r in &records {
            w.write_event(r).unwrap();
        }
        w.finish(2.0).unwrap();
        match Playback::<2>::open(&path, &DENSE) {
            Err(e @ (ViewerError::BadRun { .. } | ViewerError::Record(_))) => {
                assert!(e.to_string().contains(want), "case {k}: {e}")
            }
            Err(e) => panic!("case {k}: expected a bad run, got {e}"),
            Ok(_) => panic!("case {k}: opened"),
        }
    }
    // The good pair of records plays.
    let path = dir.join("good.ccd");
    let mut w = RunWriter::create_steered(&path, &scene).unwrap();
    for r in add.iter().chain(&remove) {
        w.write_event(r).unwrap();
    }
    w.finish(2.0).unwrap();
    let mut p = Playback::<2>::open(&path, &DENSE).unwrap();
    let s = p.snapshot_at(1.0).unwrap().states;
    assert_eq!((s.len(), s.radius(2), s.id(2)), (3, 0.5, 7));
    assert!(s.is_vacant(1) && !s.is_vacant(2));
}

// ---- runs with moving walls -----------------------------------------------------------------

#[test]
fn a_run_with_moving_walls_plays_the_simulations_walls_and_bodies() {
    use ccdsim::motion::translated;
    use common::walls::{record_wall_run, DT, FRAMES};
    let dir = common::temp_dir("playback-walls");
    let path = dir.join("walls.ccd");
    let run = record_wall_run(&path);
    // The run does what it is meant to: both walls steered many times, balls meet them.
    assert!(
        run.pieces.iter().all(|p| p.len() > 30),
        "{:?}",
        run.pieces.iter().map(Vec::len).collect::<Vec<_>>()
    );
    assert!(
        run.moving_wall_hits >= 5,
        "{} moving-wall events",
        run.moving_wall_hits
    );
    let mut p = Playback::<2>::open(&path, &DENSE).unwrap();
    assert_eq!(p.events(), run.events);
    assert!(p.has_slot_edits(), "a body is removed and one added");
    assert!(p.index().keyframes.len() > 20);
    // After every frame's edits: every body's stored state and every wall's motion, bit for
    // bit. (Edit records of code 5 name walls 0 and 1, which are bodies' slots too: those
    // bodies must not take the walls' offsets.)
    for cp in &run.checkpoints {
        let snap = p.snapshot_after(cp.applied).unwrap();
        let s = &snap.states;
        assert!(s.len() <= cp.bodies.len());
        for (i, body) in cp.bodies.iter().enumerate().take(s.len()) {
            match body {
                Some(m) => assert_eq!(s.motion(i), *m, "body {i} at t = {}", cp.time),
                None => assert!(s.is_vacant(i), "slot {i} at t = {}", cp.time),
            }
        }
        assert_eq!(s.wall_count(), 2);
        for (k, m) in cp.walls.iter().enumerate() {
            assert_eq!(s.wall_motion(k), *m, "wall {k} at t = {}", cp.time);
        }
    }
    // At any instant, sought by time: each wall where its motion of that frame puts it.
    for cp in run.checkpoints.iter().take(FRAMES).step_by(3) {
        for frac in [0.0, 0.37, 0.999] {
            let t = cp.time + frac * DT;
            let snap = p.snapshot_at(t).unwrap();
            for (k, m) in cp.walls.iter().enumerate() {
                let want = translated(&run.scene.moving_walls[k].wall, m.offset_at(t));
                assert_eq!(
                    snap.states.moving_wall_at(k, t),
                    want,
                    "wall {k} at t = {t}"
                );
                // The pieces the browser tests check the page against say the same.
                assert_eq!(run.offset_at(k, t), m.offset_at(t), "wall {k} at t = {t}");
            }
        }
    }
}

#[test]
fn an_unsteered_run_moves_its_walls_at_the_scenes_velocities() {
    let scene = common::walls::wall_scene();
    let dir = common::temp_dir("playback-walls-unsteered");
    let path = dir.join("walls.ccd");
    let end = 3.0;
    let events = common::record(&scene, end, &path);
    let mut p = Playback::<2>::open(&path, &DENSE).unwrap();
    assert_eq!(p.events(), events);
    let times = [0.0, 0.3, 1.1, 2.9, 3.0];
    assert_matches_simulation(&scene, &mut p, end, &times);
    for t in times {
        let mut sim = Simulation::new(&scene, "all-pairs").unwrap();
        sim.run_until(t);
        let snap = p.snapshot_at(t).unwrap();
        for k in 0..2 {
            let w = scene.walls.len() + k;
            assert_eq!(
                snap.states.moving_wall_at(k, t),
                sim.world().wall_at(w, t),
                "wall {k} at t = {t}"
            );
        }
    }
}

#[test]
fn the_extent_holds_the_moving_walls_wherever_they_went() {
    use ccdsim::record::RunWriter;
    use ccdsim::{BodySpec, MovingWall, Vector, Wall};
    // One ball at rest, no static walls; a segment sliding right at 5 m/s and turned back at
    // t = 2 (its farthest, x = 11, is neither where it starts nor where it ends), and a floor
    // sinking at 1 m/s from y = −1.
    let scene = Scene::<2> {
        bodies: vec![BodySpec::new(Vector([0.0, 0.0]), Vector::ZERO, 0.5)],
        moving_walls: vec![
            MovingWall {
                wall: Wall::Segment {
                    a: Vector([1.0, -1.0]),
                    b: Vector([1.0, 1.0]),
                },
                velocity: Vector([5.0, 0.0]),
            },
            MovingWall {
                wall: Wall::Plane {
                    point: Vector([0.0, -1.0]),
                    normal: Vector([0.0, 1.0]),
                },
                velocity: Vector([0.0, -1.0]),
            },
        ],
        ..Scene::default()
    };
    let dir = common::temp_dir("playback-walls-extent");
    let path = dir.join("walls.ccd");
    let mut sim = Simulation::new(&scene, "all-pairs").unwrap();
    let mut w = RunWriter::record_steered(&mut sim, &path, &scene).unwrap();
    assert!(sim.advance(2.0).is_empty());
    sim.set_wall_velocity(0, Vector([-2.0, 0.0])).unwrap();
    for r in sim.take_edits() {
        w.write_event(&r).unwrap();
    }
    assert!(sim.advance(2.0).is_empty());
    w.finish(sim.time()).unwrap();
    let p = Playback::<2>::open(&path, &DENSE).unwrap();
    let b = p.extent().bounds;
    assert_eq!((b.min.0, b.max.0), ([-0.5, -5.0], [11.0, 1.0]), "{b:?}");
}
