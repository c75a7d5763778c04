//! Runs where bodies rest on planes and slide along them (`settings.rest_speed`, format
//! version 11): playback, keyframes, bounds, the API's answers and rendered frames follow each
//! body's support as the records' flags give it, on a recorded run (`tests/common/resting.rs`).

use crate::common;

use ccdsim::contact::resting::slide_acceleration;
use ccdsim::{EventKind, Vector};
use ccdsim_viewer::render::colour::{self, Rgb};
use ccdsim_viewer::render::Camera;
use ccdsim_viewer::wire::{REST_A, REST_B, REST_SECTION, STATE_HEADER};
use ccdsim_viewer::{render_png, KeyframeOptions, Playback, RenderOptions, Snapshot};
use common::resting::{record_rest_run, Checkpoint, RestRun, FLOOR, INCLINE, KICK_AT, RADIUS};
use common::{f64s, get};

/// Keyframes every 2 events, so that snapshots replay from many of them.
const DENSE: KeyframeOptions = KeyframeOptions {
    budget_bytes: 1 << 20,
    min_interval: 2,
};

fn recorded(name: &str) -> (common::scratch::ScratchFile, RestRun) {
    let path = common::scratch::ScratchFile::new(&format!("viewer-{name}"), "resting.ccd");
    let run = record_rest_run(&path);
    (path, run)
}

/// The snapshot's bodies are the simulation's at the checkpoint: stored states and supports
/// bit for bit, and so positions and velocities at its time.
fn assert_matches(snap: &Snapshot<2>, cp: &Checkpoint, what: &str) {
    let s = &snap.states;
    assert_eq!(snap.applied, cp.applied, "{what}");
    assert_eq!(s.len(), cp.bodies.len(), "{what}");
    for (i, b) in cp.bodies.iter().enumerate() {
        assert_eq!(s.motion(i), b.motion, "{what}: body {i}");
        assert_eq!(s.support(i), b.support, "{what}: body {i}");
        let (p, v) = (s.position_at(i, cp.time), s.velocity_at(i, cp.time));
        assert!(
            (p - b.pos).norm() < 1e-9,
            "{what}: body {i} at {p:?}, not {:?}",
            b.pos
        );
        assert!(
            (v - b.vel).norm() < 1e-9,
            "{what}: body {i} at {v:?}, not {:?}",
            b.vel
        );
    }
}

#[test]
fn a_resting_run_plays_the_simulations_bodies_and_supports_after_any_seek() {
    let (path, run) = recorded("rest-playback");
    // The run has what it is meant to: ball 0 rests on the floor after its fourth contact,
    // ball 1 at once on the incline; the kick lifts ball 0 off the floor; both end resting.
    assert_eq!(run.floor_rest, 1.375);
    assert!(run.incline_rest < 0.02, "{}", run.incline_rest);
    assert_eq!(run.checkpoints[KICK_AT - 1].bodies[0].support, Some(FLOOR));
    assert_eq!(run.checkpoints[KICK_AT].bodies[0].support, None);
    let last = run.checkpoints.last().unwrap();
    assert!(last.bodies.iter().all(|b| b.support == Some(FLOOR)));
    let mut p = Playback::<2>::open(&path, &DENSE).unwrap();
    assert!(p.has_rests());
    assert_eq!(p.events(), run.events);
    assert!(
        p.index().keyframes.len() > 5,
        "{}",
        p.index().keyframes.len()
    );
    // Forwards, backwards (each seek starting from an earlier keyframe), and scrambled.
    let n = run.checkpoints.len();
    let order: Vec<usize> = (0..n)
        .chain((0..n).rev())
        .chain((0..n).map(|k| k * 37 % n))
        .collect();
    for k in order {
        let cp = &run.checkpoints[k];
        let snap = p.snapshot_at(cp.time).unwrap();
        assert_matches(&snap, cp, &format!("t = {}", cp.time));
        let after = p.snapshot_after(cp.applied).unwrap();
        for i in 0..cp.bodies.len() {
            assert_eq!(after.states.motion(i), cp.bodies[i].motion, "k = {k}");
            assert_eq!(after.states.support(i), cp.bodies[i].support, "k = {k}");
        }
    }
    // The world rebuilt for a finder's boxes has the same bodies on the same walls.
    let cp = &run.checkpoints[90];
    let snap = p.snapshot_at(cp.time).unwrap();
    let world = p.world_at(&snap).unwrap();
    for (i, b) in cp.bodies.iter().enumerate() {
        assert_eq!(world.support(i), b.support, "body {i}");
        assert_eq!(world.position_at(i, cp.time), b.pos, "body {i}");
    }
    assert!(!p
        .finder_boxes(&snap, "bvh", &Default::default())
        .unwrap()
        .is_empty());
    // Late in the run, after a seek back from the end: ball 0 slides along the floor (it left
    // the wall x = −1 at 0.37 m/s), not below it.
    let end = p.snapshot_at(run.end).unwrap();
    assert_eq!(end.states.support(0), Some(FLOOR));
    let cp = &run.checkpoints[100];
    let snap = p.snapshot_at(cp.time).unwrap();
    assert_matches(&snap, cp, "a seek back");
    let ball = snap.states.position_at(0, cp.time);
    assert!((ball[1] - RADIUS).abs() < 1e-12, "{ball:?}");
    // Between two checkpoints, on the slide: at the floor, moving along it.
    let t = cp.time + 0.025;
    let q = snap.states.position_at(0, t);
    assert!((q[1] - RADIUS).abs() < 1e-12, "{q:?}");
    assert_eq!(snap.states.velocity_at(0, t), cp.bodies[0].vel);
}

#[test]
fn a_resting_run_is_bounded_by_its_floor_and_its_true_speeds() {
    let (path, run) = recorded("rest-extent");
    let p = Playback::<2>::open(&path, &DENSE).unwrap();
    let e = *p.extent();
    // Under full gravity a resting ball would end metres below the floor, and some 40 m/s
    // fast; on its slide it stays on it.
    assert!(e.bounds.min[1].abs() < 1e-12, "{e:?}");
    assert_eq!(e.bounds.min[0], -1.0, "the wall x = −1");
    let top = run.scene.bodies[1].pos[1] + RADIUS;
    assert!((e.bounds.max[1] - top).abs() < 1e-12, "{e:?}");
    // Every speed of the run, seen every frame, is within the extent's, which exceeds the
    // fastest seen by no more than one frame's gain (ball 1 at the foot of the incline).
    let seen = run
        .checkpoints
        .iter()
        .flat_map(|cp| cp.bodies.iter().map(|b| b.vel.norm()))
        .fold(0.0, f64::max);
    assert!(seen > 6.0, "{seen}");
    assert!(
        e.max_speed >= seen - 1e-12 && e.max_speed <= seen + 10.0 * common::resting::DT,
        "{} vs {seen}",
        e.max_speed
    );
}

#[test]
fn a_resting_run_is_served_with_its_supports_accelerations_and_rest_flags() {
    let (path, run) = recorded("rest-server");
    let s = common::start(&path, DENSE);
    let meta: serde_json::Value = serde_json::from_slice(&get(s.port, "/api/meta").body).unwrap();
    assert_eq!(meta["rest_speed"], 0.4);
    let g = Vector([0.0, -10.0]);
    let slides: Vec<Option<Vector<2>>> = run
        .scene
        .walls
        .iter()
        .map(|w| slide_acceleration(&g, w))
        .collect();
    assert_eq!(meta["slides"], serde_json::json!(slides));
    assert_eq!(meta["slides"][FLOOR], serde_json::json!([0.0, 0.0]));
    assert_eq!(meta["slides"][2], serde_json::Value::Null);
    let accel = |support: Option<usize>| support.map_or(g, |w| slides[w].unwrap());
    // Every state answer ends with the rest section: each body's support and acceleration.
    for cp in run.checkpoints.iter().step_by(3) {
        let body = get(s.port, &format!("/api/state?t={}", cp.time)).body;
        let n = f64s(&body[..8 * STATE_HEADER])[2] as usize;
        assert_eq!(n, 2);
        let off = 8 * STATE_HEADER + 2 * 4 * 2 * n;
        let rest = f64s(&body[off..]);
        assert_eq!(rest.len(), 1 + n + 2 * n, "t = {}", cp.time);
        assert_eq!(rest[0], REST_SECTION);
        for (i, b) in cp.bodies.iter().enumerate() {
            let support = b.support.map_or(-1.0, |w| w as f64);
            assert_eq!(rest[1 + i], support, "body {i} at t = {}", cp.time);
            let a = accel(b.support);
            assert_eq!(
                rest[1 + n + 2 * i..1 + n + 2 * i + 2],
                a.0,
                "body {i} at t = {}",
                cp.time
            );
        }
    }
    // Every event carries its rest flags after its 12 values.
    let mut p = Playback::<2>::open(&path, &DENSE).unwrap();
    let all = p.events_window(0, u64::MAX).unwrap();
    let events = f64s(&get(s.port, &format!("/api/events?from=0&count={}", all.len())).body);
    assert_eq!(events.len(), all.len() * 13);
    let mut flagged = [0; 2];
    for (e, c) in events.chunks(13).zip(&all) {
        assert_eq!(e[0], c.event.time);
        let want = u8::from(c.rests[0]) * REST_A + u8::from(c.rests[1]) * REST_B;
        assert_eq!(e[12], f64::from(want), "event at t = {}", c.event.time);
        if c.event.kind == EventKind::Wall && c.rests[0] {
            flagged[usize::from(c.event.b as usize == INCLINE)] += 1;
        }
    }
    assert!(flagged[0] >= 4 && flagged[1] == 1, "{flagged:?}");
}

/// Pixel colour of `pm` at world point `q` under camera `cam`.
fn pixel(pm: &tiny_skia::Pixmap, cam: &Camera, q: Vector<2>) -> Rgb {
    let (x, y, _) = cam.project(q);
    let c = pm.pixel(x as u32, y as u32).unwrap().demultiply();
    [c.red(), c.green(), c.blue()]
}

#[test]
fn a_resting_ball_is_rendered_on_the_floor() {
    let (path, run) = recorded("rest-render");
    let dir = path.parent().unwrap();
    let o = RenderOptions {
        width: 600,
        ..RenderOptions::default()
    };
    let p = Playback::<2>::open(&path, &o.keyframes).unwrap();
    let cam = Camera::fit(&p.extent().bounds, o.width, None, o.yaw_deg, o.pitch_deg);
    let cp = &run.checkpoints[110];
    let out = dir.join("late.png");
    render_png(&path, cp.time, &out, &o).unwrap();
    let pm = tiny_skia::Pixmap::load_png(&out).unwrap();
    assert_eq!((pm.width(), pm.height()), (cam.width, cam.height));
    for (i, b) in cp.bodies.iter().enumerate() {
        assert_eq!(b.support, Some(FLOOR));
        let id = colour::id_colour(colour::id_bucket(i as u64));
        // Its centre and a point near its bottom are drawn in its colour.
        assert_eq!(pixel(&pm, &cam, b.pos), id, "body {i}");
        assert_eq!(
            pixel(&pm, &cam, b.pos - Vector([0.0, 0.15])),
            id,
            "body {i}"
        );
        // Above it, nothing.
        let above = b.pos + Vector([0.0, 2.0 * RADIUS]);
        assert_eq!(pixel(&pm, &cam, above), colour::BACKGROUND, "body {i}");
    }
}
