//! The viewer's HTTP API on 127.0.0.1: the page, the run's description and its binary data.

use crate::common;

use ccdsim::generate::{rack, RackConfig};
use ccdsim_viewer::wire::STATE_HEADER;
use ccdsim_viewer::{serve, KeyframeOptions, Playback, ServeOptions};
use common::{f32s, f64s, get};

/// The server of `run`, with a keyframe every 7 events at least.
fn start(run: &std::path::Path) -> common::Running {
    common::start(
        run,
        KeyframeOptions {
            min_interval: 7,
            ..KeyframeOptions::default()
        },
    )
}

fn recorded_break(name: &str) -> (common::scratch::ScratchFile, u64) {
    let path = common::scratch::ScratchFile::new(&format!("viewer-{name}"), "break.ccd");
    let n = common::record(&rack(&RackConfig::default()), 3.0, &path);
    (path, n)
}

#[test]
fn the_page_and_its_scripts_are_embedded() {
    let (run, _) = recorded_break("server-page");
    let s = start(&run);
    let page = get(s.port, "/");
    assert_eq!(page.status, 200);
    assert!(
        page.head
            .to_ascii_lowercase()
            .contains("content-type: text/html"),
        "{}",
        page.head
    );
    let html = String::from_utf8(page.body).unwrap();
    assert!(html.contains("<canvas id=\"view\""));
    // Every script and style the page names is served, and nothing comes from elsewhere.
    for asset in ["/viewer.js", "/raster.js", "/viewer.css"] {
        assert!(html.contains(asset), "{asset} linked");
        let a = get(s.port, asset);
        assert_eq!(a.status, 200, "{asset}");
        assert!(!a.body.is_empty());
        let text = String::from_utf8(a.body).unwrap();
        assert!(
            !text.contains("https://") && !text.contains("http://"),
            "{asset} loads nothing remote"
        );
    }
    assert!(!html.contains("https://") && !html.contains("http://"));
    assert_eq!(get(s.port, "/nope").status, 404);
    assert_eq!(get(s.port, "/api/nope").status, 404);
}

#[test]
fn meta_and_bodies_describe_the_run() {
    let (run, n) = recorded_break("server-meta");
    let s = start(&run);
    let meta: serde_json::Value = serde_json::from_slice(&get(s.port, "/api/meta").body).unwrap();
    assert_eq!(meta["dim"], 2);
    assert_eq!(meta["bodies"], 16);
    assert_eq!(meta["events"], n);
    assert_eq!(meta["start_time"], 0.0);
    assert_eq!(meta["end_time"], 3.0);
    assert_eq!(meta["complete"], true);
    assert_eq!(meta["walls"].as_array().unwrap().len(), 4);
    assert!(
        meta.get("moving_walls").is_none(),
        "no moving walls, no key"
    );
    assert!(
        meta.get("rest_speed").is_none() && meta.get("slides").is_none(),
        "no resting bodies, no keys"
    );
    assert_eq!(meta["keyframe_interval"], 7);
    assert_eq!(meta["finder"], "bvh");
    // The table, up to the rounding of balls touching the cushions.
    let corner =
        |k: &str| -> Vec<f64> { serde_json::from_value(meta["bounds"][k].clone()).unwrap() };
    for (got, want) in corner("min")
        .into_iter()
        .chain(corner("max"))
        .zip([0.0, 0.0, 2.54, 1.27])
    {
        assert!((got - want).abs() < 1e-12, "bounds {got} vs {want}");
    }
    assert_eq!(meta["max_speed"], 10.0);
    let bodies = f64s(&get(s.port, "/api/bodies").body);
    assert_eq!(bodies.len(), 32);
    assert!(bodies[..16]
        .iter()
        .all(|&r| r == RackConfig::default().radius));
    assert_eq!(bodies[16..], (0..16).map(f64::from).collect::<Vec<_>>()[..]);
}

#[test]
fn state_events_and_steps_agree_with_the_playback() {
    let (run, n) = recorded_break("server-state");
    let s = start(&run);
    let mut p = Playback::<2>::open(&run, &KeyframeOptions::default()).unwrap();
    let all = p.events_window(0, u64::MAX).unwrap();
    for t in [0.0, 0.2, all[20].event.time, 2.5] {
        let body = get(s.port, &format!("/api/state?t={t}")).body;
        let head = f64s(&body[..8 * STATE_HEADER]);
        let snap = p.snapshot_at(t).unwrap();
        assert_eq!(head[0], t);
        assert_eq!(head[1], snap.applied as f64);
        assert_eq!((head[2], head[3]), (16.0, 2.0));
        match snap.last {
            Some(c) => {
                let kind = if c.body_count() == 2 { 0.0 } else { 1.0 };
                assert_eq!(
                    head[4..],
                    [
                        kind,
                        c.event.time,
                        f64::from(c.event.a),
                        f64::from(c.event.b)
                    ][..]
                );
            }
            None => assert_eq!(head[4], -1.0, "no event before t = {t}"),
        }
        let arrays = f32s(&body[8 * STATE_HEADER..]);
        assert_eq!(arrays.len(), 2 * 16 * 2);
        for i in 0..16 {
            let pos = snap.states.position_at(i, t);
            let vel = snap.states.vel[i];
            assert_eq!(arrays[2 * i], pos[0] as f32);
            assert_eq!(arrays[2 * i + 1], pos[1] as f32);
            assert_eq!(arrays[32 + 2 * i], vel[0] as f32);
        }
    }
    // The start, asked by event count.
    let head = f64s(&get(s.port, "/api/state?k=0").body[..8 * STATE_HEADER]);
    assert_eq!(head[..2], [0.0, 0.0]);
    assert_eq!(head[4], -1.0, "no event yet");
    let events = f64s(&get(s.port, "/api/events?from=5&count=3").body);
    assert_eq!(events.len(), 3 * 12);
    for (k, e) in events.chunks(12).enumerate() {
        let c = all[5 + k];
        assert_eq!(e[0], c.event.time);
        assert_eq!((e[2], e[3]), (f64::from(c.event.a), f64::from(c.event.b)));
        assert_eq!(e[4..6], c.pos[0].0);
        assert_eq!(e[6..8], c.vel[0].0);
    }
    assert!(get(s.port, &format!("/api/events?from={n}"))
        .body
        .is_empty());
    let step: serde_json::Value =
        serde_json::from_slice(&get(s.port, "/api/step?dir=next&t=0").body).unwrap();
    assert_eq!(step["time"], all[0].event.time);
    let t = all[10].event.time;
    let step: serde_json::Value =
        serde_json::from_slice(&get(s.port, &format!("/api/step?dir=prev&t={t}")).body).unwrap();
    assert_eq!(step["time"], all[9].event.time);
    let step: serde_json::Value =
        serde_json::from_slice(&get(s.port, "/api/step?dir=next&t=1e9").body).unwrap();
    assert_eq!(step["time"], serde_json::Value::Null);
}

#[test]
fn bad_requests_get_a_clear_error() {
    let (run, _) = recorded_break("server-errors");
    let s = start(&run);
    let bad = |path: &str, needle: &str| {
        let a = get(s.port, path);
        assert_eq!(a.status, 400, "{path}");
        let v: serde_json::Value = serde_json::from_slice(&a.body).unwrap();
        let msg = v["error"].as_str().unwrap();
        assert!(msg.contains(needle), "{path}: {msg}");
    };
    bad("/api/state", "exactly one of t");
    bad("/api/state?t=abc", "`abc` is not a finite number");
    bad("/api/state?t=NaN", "not a finite number");
    bad("/api/events?from=-1", "not a whole number");
    bad("/api/step?t=0&dir=up", "next or prev");
    bad(
        "/api/boxes?t=0.5&finder=no-such-finder",
        "unknown finder `no-such-finder`",
    );
    // The server keeps answering after errors.
    assert_eq!(get(s.port, "/api/meta").status, 200);
}

#[test]
fn boxes_of_a_finder_without_structure_are_empty() {
    let (run, _) = recorded_break("server-boxes-empty");
    let s = start(&run);
    let a = get(s.port, "/api/boxes?t=0.5&finder=all-pairs");
    assert_eq!(a.status, 200);
    assert!(a.body.is_empty());
}

#[test]
fn a_taken_port_is_reported_as_such() {
    let (run, _) = recorded_break("server-bind");
    let s = start(&run);
    match serve(&run, s.port, &ServeOptions::default()) {
        Err(e @ ccdsim_viewer::ViewerError::Bind { .. }) => {
            assert!(
                e.to_string()
                    .starts_with(&format!("cannot listen on 127.0.0.1:{}", s.port)),
                "{e}"
            )
        }
        Err(e) => panic!("expected a bind error, got {e}"),
        Ok(_) => panic!("bound a taken port"),
    }
}

#[test]
fn bvh_boxes_are_served_by_default() {
    let (run, _) = recorded_break("server-boxes-bvh");
    let s = start(&run);
    // The default finder is bvh: 31 boxes of 2 + 2·2 f32s, the root (depth 0) first.
    let boxes = f32s(&get(s.port, "/api/boxes?t=0.5").body);
    assert_eq!(boxes.len(), 31 * 6);
    assert_eq!(boxes[0], 0.0);
    assert_eq!(
        boxes.chunks(6).filter(|b| b[1] == 1.0).count(),
        16,
        "16 leaves"
    );
    assert_eq!(
        get(s.port, "/api/boxes?t=0.5&finder=bvh").body,
        get(s.port, "/api/boxes?t=0.5").body
    );
}

#[test]
fn a_run_that_adds_and_removes_bodies_is_served_with_its_slots() {
    use ccdsim_viewer::wire::{SLOT_KINEMATIC, SLOT_SECTION, SLOT_VACANT};
    let dir = common::temp_dir("server-slots");
    let path = dir.join("slots.ccd");
    let run = common::slots::record_slot_run(&path, &common::slots::PLAN);
    let n0 = run.scene.bodies.len();
    let s = start(&path);
    let mut p = Playback::<2>::open(&path, &KeyframeOptions::default()).unwrap();
    let slots = p.slots();
    assert!(slots > n0 + 5, "{slots} slots");
    let meta: serde_json::Value = serde_json::from_slice(&get(s.port, "/api/meta").body).unwrap();
    assert_eq!(meta["bodies"], slots);
    assert_eq!(meta["scene_bodies"], n0);
    assert_eq!(meta["slot_edits"], true);
    // The scene's radii and ids, padded to the slots.
    let bodies = f64s(&get(s.port, "/api/bodies").body);
    assert_eq!(bodies.len(), 2 * slots);
    for i in 0..slots {
        let (r, id) = if i < n0 {
            (run.scene.bodies[i].radius, i as f64)
        } else {
            (0.0, 0.0)
        };
        assert_eq!((bodies[i], bodies[slots + i]), (r, id), "slot {i}");
    }
    // Before the first record, the scene's bodies and no slot section.
    let body = get(s.port, "/api/state?k=0").body;
    let head = f64s(&body[..8 * STATE_HEADER]);
    assert_eq!(head[2], n0 as f64);
    assert_eq!(body.len(), 8 * STATE_HEADER + 2 * 4 * 2 * n0);
    // Then every slot's radius, id and flags, as the playback has them.
    let mut vacant_seen = 0;
    for cp in run.checkpoints.iter().skip(1).step_by(5) {
        let body = get(s.port, &format!("/api/state?t={}", cp.time)).body;
        let snap = p.snapshot_at(cp.time).unwrap();
        let st = &snap.states;
        let n = st.len();
        let head = f64s(&body[..8 * STATE_HEADER]);
        assert_eq!(head[2], n as f64, "t = {}", cp.time);
        let off = 8 * STATE_HEADER + 2 * 4 * 2 * n;
        assert_eq!(body.len(), off + 8 + 17 * n, "t = {}", cp.time);
        let section = f64s(&body[off..off + 8 + 16 * n]);
        assert_eq!(section[0], SLOT_SECTION);
        let flags = &body[off + 8 + 16 * n..];
        for i in 0..n {
            let (r, id, f) = (section[1 + i], section[1 + n + i], flags[i]);
            assert_eq!(r, st.radius(i), "slot {i} at t = {}", cp.time);
            assert_eq!(id, st.id(i) as f64, "slot {i} at t = {}", cp.time);
            assert_eq!(f & SLOT_KINEMATIC != 0, st.is_kinematic(i));
            assert_eq!(f & SLOT_VACANT != 0, st.is_vacant(i));
            // The simulation's own slots at that instant.
            match cp.slots[i] {
                Some(b) => assert_eq!((r, f & SLOT_VACANT), (b.radius, 0), "slot {i}"),
                None => {
                    assert_eq!((r, f & SLOT_VACANT), (0.0, SLOT_VACANT), "slot {i}");
                    vacant_seen += 1;
                }
            }
        }
    }
    assert!(vacant_seen > 5, "{vacant_seen} vacant slots seen");
    // An added body's pair of records in the events stream, in its usual layout.
    let all = p.events_window(0, u64::MAX).unwrap();
    let k = all
        .iter()
        .position(|c| c.event.b == 1 && c.event.kind == ccdsim::EventKind::Edit)
        .unwrap();
    let e = f64s(&get(s.port, &format!("/api/events?from={k}&count=2")).body);
    assert_eq!(e.len(), 2 * 12);
    assert_eq!((e[1], e[3], e[13], e[15]), (3.0, 1.0, 3.0, 2.0));
    assert_eq!(e[8], all[k].pos[1][0], "the radius");
    assert_eq!(
        e[12 + 8].to_bits(),
        all[k + 1].pos[1][0].to_bits(),
        "the id's bits"
    );
    assert_eq!(e[12 + 4..12 + 8], [0.0; 4], "no state in the id record");
}

#[test]
fn a_run_with_moving_walls_is_served_with_them() {
    use ccdsim_viewer::wire::{SLOT_SECTION, WALL_SECTION};
    let dir = common::temp_dir("server-walls");
    let path = dir.join("walls.ccd");
    let run = common::walls::record_wall_run(&path);
    let s = start(&path);
    let meta: serde_json::Value = serde_json::from_slice(&get(s.port, "/api/meta").body).unwrap();
    assert_eq!(meta["walls"], serde_json::json!(run.scene.walls));
    assert_eq!(
        meta["moving_walls"],
        serde_json::json!(run.scene.moving_walls)
    );
    // Each as a static wall is written, with its velocity.
    assert_eq!(
        meta["moving_walls"][0],
        serde_json::json!({"a": [2.0, 1.0], "b": [2.0, 3.0], "velocity": [0.5, 0.0]})
    );
    assert_eq!(
        meta["moving_walls"][1],
        serde_json::json!({"point": [0.0, 7.0], "normal": [0.0, -1.0], "velocity": [0.0, -0.4]})
    );
    // Every state answer ends with the wall section: each wall's motion, bit for bit the
    // simulation's; after the slot section (zero-padded to 8 bytes) once a body was removed.
    let (mut plain, mut slotted) = (0, 0);
    for cp in run.checkpoints.iter().step_by(4) {
        let body = get(s.port, &format!("/api/state?t={}", cp.time)).body;
        let head = f64s(&body[..8 * STATE_HEADER]);
        let n = head[2] as usize;
        let mut off = 8 * STATE_HEADER + 2 * 4 * 2 * n;
        if f64s(&body[off..off + 8])[0] == SLOT_SECTION {
            off += 8 + 17 * n;
            let padded = off.next_multiple_of(8);
            assert!(body[off..padded].iter().all(|&b| b == 0), "zero padding");
            off = padded;
            slotted += 1;
        } else {
            plain += 1;
        }
        let walls = f64s(&body[off..]);
        assert_eq!(walls.len(), 1 + 2 * 5, "t = {}", cp.time);
        assert_eq!(walls[0], WALL_SECTION);
        for (k, m) in cp.walls.iter().enumerate() {
            let w = &walls[1 + 5 * k..1 + 5 * (k + 1)];
            assert_eq!(w[0], m.time, "wall {k} at t = {}", cp.time);
            assert_eq!(w[1..3], m.offset.0, "wall {k} at t = {}", cp.time);
            assert_eq!(w[3..5], m.velocity.0, "wall {k} at t = {}", cp.time);
        }
    }
    assert!(
        plain > 3 && slotted > 3,
        "{plain} without slots, {slotted} with"
    );
    // A wall's edit in the events stream: kind 3, the wall in a, code 5 in b, its offset and
    // velocity in slot 0.
    let mut p = Playback::<2>::open(&path, &KeyframeOptions::default()).unwrap();
    let all = p.events_window(0, u64::MAX).unwrap();
    let k = all
        .iter()
        .position(|c| c.event.kind == ccdsim::EventKind::Edit && c.event.b == 5 && c.event.a == 1)
        .unwrap();
    let e = f64s(&get(s.port, &format!("/api/events?from={k}&count=1")).body);
    assert_eq!(e[..4], [all[k].event.time, 3.0, 1.0, 5.0]);
    let piece = run.pieces[1][1];
    assert_eq!(
        (e[0], &e[4..6], &e[6..8]),
        (piece.time, &piece.offset.0[..], &piece.velocity.0[..])
    );
}
