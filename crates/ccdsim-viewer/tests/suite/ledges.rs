//! Runs where bodies rest on 2D segments and fly off their ends (see `ccdsim::contact::ledge`) or roll
//! over them (format version 13, see `ccdsim::motion::pivot`): a ball that slides along a shelf drawn
//! in two pieces and flies off its end, the same ball slower, rolling over the end, and
//! `examples/shelves.json`. Playback at any time (forwards, backwards, scrambled, and between
//! each slide-off or roll-over and the event after it), after any number of events, the
//! rebuilt world and the served states follow the simulation bit for bit
//! (`tests/common/ledges.rs` records the runs and the simulation's states), the extent holds
//! every ball, and rendered frames draw the ball on the shelf, turning about its end on its
//! circle, and falling past it.

use crate::common;

use ccdsim::{Aabb, Vector};
use ccdsim_viewer::render::colour::{self, Rgb};
use ccdsim_viewer::render::Camera;
use ccdsim_viewer::wire::{PIVOT_A, PIVOT_SECTION, REST_A, REST_SECTION, STATE_HEADER};
use ccdsim_viewer::{render_png, KeyframeOptions, Playback, RenderOptions, Snapshot};
use common::ledges::{
    record_ledge_run, roll_scene, shelf_scene, shelves_example, Ledge, LedgeRun, FLOOR, RADIUS,
    SHELF_CORNER, SHELF_END, SHELF_LEFT, SHELF_RIGHT, SHELF_Y,
};
use common::resting::Checkpoint;
use common::{f32s, f64s, get};

/// Keyframes every 2 events, so that snapshots replay from many of them.
const DENSE: KeyframeOptions = KeyframeOptions {
    budget_bytes: 1 << 20,
    min_interval: 2,
};

const G: Vector<2> = Vector([0.0, -10.0]);

fn recorded(
    name: &str,
    scene: &ccdsim::Scene<2>,
    until: f64,
    frame: f64,
) -> (common::scratch::ScratchFile, LedgeRun) {
    let path = common::scratch::ScratchFile::new(&format!("viewer-{name}"), "ledges.ccd");
    let run = record_ledge_run(scene, until, frame, &path);
    (path, run)
}

/// The snapshot's bodies are the simulation's at the checkpoint, bit for bit: stored states,
/// supports, accelerations, and positions and velocities at its time.
fn assert_exact(snap: &Snapshot<2>, cp: &Checkpoint, what: &str) {
    let s = &snap.states;
    assert_eq!(snap.applied, cp.applied, "{what}");
    assert_eq!(s.len(), cp.bodies.len(), "{what}");
    for (i, b) in cp.bodies.iter().enumerate() {
        assert_eq!(s.motion(i), b.motion, "{what}: body {i}");
        assert_eq!(s.support(i), b.support, "{what}: body {i}");
        assert_eq!(s.acceleration(i), b.acc, "{what}: body {i}");
        assert_eq!(s.position_at(i, cp.time), b.pos, "{what}: body {i}");
        assert_eq!(s.velocity_at(i, cp.time), b.vel, "{what}: body {i}");
    }
}

/// The checkpoints that fall between a slide-off and the event after it, with the body that
/// flew off.
fn after_slide_offs(run: &LedgeRun) -> Vec<(&Checkpoint, usize)> {
    between(run, run.slide_offs())
}

/// The checkpoints that fall between a roll-over and the event after it, with the body that
/// turns.
fn after_roll_overs(run: &LedgeRun) -> Vec<(&Checkpoint, usize)> {
    between(run, run.roll_overs())
}

/// The checkpoints that fall between each of the events `ks` and the event after it, with
/// that event's body.
fn between(run: &LedgeRun, ks: Vec<usize>) -> Vec<(&Checkpoint, usize)> {
    ks.into_iter()
        .flat_map(|k| {
            let (from, to) = (run.time_of(k), run.time_of(k + 1));
            let body = run.events[k].event.a as usize;
            run.checkpoints
                .iter()
                .filter(move |cp| cp.time > from && cp.time < to)
                .map(move |cp| (cp, body))
        })
        .collect()
}

/// Plays `run` back from its file with `keyframes`: every checkpoint sought forwards,
/// backwards and scrambled, and the state after every number of events, as the simulation
/// had them. Returns the playback.
fn assert_plays(
    path: &std::path::Path,
    run: &LedgeRun,
    keyframes: &KeyframeOptions,
) -> Playback<2> {
    let mut p = Playback::<2>::open(path, keyframes).unwrap();
    assert!(p.has_rests());
    assert_eq!(p.events(), run.events.len() as u64);
    assert_eq!(p.end_time(), run.end);
    let n = run.checkpoints.len();
    let order = (0..n).chain((0..n).rev()).chain((0..n).map(|k| k * 37 % n));
    for k in order {
        let cp = &run.checkpoints[k];
        let snap = p.snapshot_at(cp.time).unwrap();
        assert_exact(&snap, cp, &format!("t = {}", cp.time));
    }
    let m = run.after.len();
    for k in (0..m).chain((0..m).map(|k| k * 29 % m)) {
        let snap = p.snapshot_after(k as u64).unwrap();
        assert_eq!(snap.applied, k as u64);
        for (i, &(motion, support)) in run.after[k].iter().enumerate() {
            assert_eq!(snap.states.motion(i), motion, "after {k} events: body {i}");
            assert_eq!(
                snap.states.support(i),
                support,
                "after {k} events: body {i}"
            );
        }
    }
    // Just after a slide-off the body falls under g, in the played states and in the world
    // rebuilt for a finder's boxes alike; while a body turns it has no acceleration of its
    // own, and the rebuilt world has it where its turn does.
    let off = after_slide_offs(run).into_iter().map(|x| (x, false));
    let over = after_roll_overs(run).into_iter().map(|x| (x, true));
    for ((cp, i), turns) in off.chain(over) {
        let snap = p.snapshot_at(cp.time).unwrap();
        assert_eq!(snap.states.support(i), None, "t = {}", cp.time);
        assert_eq!(snap.states.turn(i).is_some(), turns, "t = {}", cp.time);
        let acc = if turns { None } else { run.scene.gravity() };
        assert_eq!(snap.states.acceleration(i), acc, "t = {}", cp.time);
        let world = p.world_at(&snap).unwrap();
        for (j, b) in cp.bodies.iter().enumerate() {
            let at = format!("t = {}: body {j}", cp.time);
            assert_eq!(world.support(j), b.support, "{at}");
            if snap.states.turn(j).is_some() {
                // Falling from where its turn has it (the world cannot be told of turns).
                assert_eq!(world.gravity_of(j), run.scene.gravity(), "{at}");
                assert_eq!(world.velocity_at(j, cp.time), b.vel, "{at}");
            } else {
                assert_eq!(world.gravity_of(j), b.acc, "{at}");
            }
            assert_eq!(world.position_at(j, cp.time), b.pos, "{at}");
        }
    }
    p
}

#[test]
fn a_ball_flying_off_a_shelf_plays_as_the_simulation_had_it() {
    let (path, run) = recorded("ledge-shelf", &shelf_scene(), 3.0, 0.05);
    // The run has what it is meant to: the ball lands on the left piece, goes on along the
    // right one, flies off its end with its velocity, and ends resting on the floor.
    assert_eq!(
        run.ledges[..3],
        [None, Some(Ledge::GoesOn), Some(Ledge::SlideOff)]
    );
    let [land, on, off] = [0, 1, 2].map(|k| run.events[k]);
    assert!(
        land.rests[0] && land.event.b as usize == SHELF_LEFT,
        "{land:?}"
    );
    assert!(on.rests[0] && on.event.b as usize == SHELF_RIGHT, "{on:?}");
    assert_eq!(off.event.b as usize, SHELF_RIGHT);
    assert!((off.pos[0][0] - SHELF_END).abs() < 1e-12, "{off:?}");
    assert_eq!(off.vel[0], land.vel[0]);
    assert_eq!(run.slide_offs(), [2]);
    assert_eq!(run.after.last().unwrap()[0].1, Some(FLOOR));
    // On the shelf at the checkpoints before the slide-off, and falling past its end after.
    let before: Vec<_> = run
        .checkpoints
        .iter()
        .filter(|cp| cp.time > land.event.time && cp.time < off.event.time)
        .collect();
    assert!(before.len() > 5, "{}", before.len());
    for cp in before {
        let b = cp.bodies[0];
        assert!(b.support == Some(SHELF_LEFT) || b.support == Some(SHELF_RIGHT));
        assert_eq!(b.acc, Some(Vector::ZERO));
        assert_eq!(b.pos[1], land.pos[0][1], "on the shelf to the last bit");
    }
    let falling = after_slide_offs(&run);
    // Three times placed between the slide-off and the floor, and the frames of the fall.
    assert!(falling.len() > 3 + 5, "{}", falling.len());
    for (cp, i) in falling {
        let b = cp.bodies[i];
        assert_eq!((b.support, b.acc), (None, Some(G)), "t = {}", cp.time);
        assert!(b.pos[0] > SHELF_END && b.pos[1] < SHELF_Y + RADIUS, "{b:?}");
    }
    assert_plays(&path, &run, &DENSE);
    // With one keyframe every snapshot replays the run from its start.
    let sparse = KeyframeOptions {
        budget_bytes: 1 << 20,
        min_interval: 1 << 20,
    };
    let p = assert_plays(&path, &run, &sparse);
    assert_eq!(p.index().keyframes.len(), 1);
}

#[test]
fn a_ball_flying_off_a_shelf_is_served_as_the_simulation_had_it() {
    let (path, run) = recorded("ledge-server", &shelf_scene(), 3.0, 0.05);
    let s = common::start(&path, DENSE);
    let meta: serde_json::Value = serde_json::from_slice(&get(s.port, "/api/meta").body).unwrap();
    assert_eq!(meta["rest_speed"], 1.0);
    // Bodies rest on the shelf's pieces as on the floor, and slide along them without
    // acceleration.
    assert_eq!(
        meta["slides"],
        serde_json::json!([[0.0, 0.0], [0.0, 0.0], [0.0, 0.0]])
    );
    // Every state answer gives the simulation's positions and velocities (as f32) and its
    // supports and accelerations (rest section), between a slide-off and the next event too.
    let n = 1;
    for cp in &run.checkpoints {
        let body = get(s.port, &format!("/api/state?t={}", cp.time)).body;
        let head = f64s(&body[..8 * STATE_HEADER]);
        assert_eq!(
            (head[0], head[1], head[2]),
            (cp.time, cp.applied as f64, n as f64)
        );
        let arrays = f32s(&body[8 * STATE_HEADER..8 * STATE_HEADER + 2 * 4 * 2 * n]);
        let b = cp.bodies[0];
        let want = [b.pos[0], b.pos[1], b.vel[0], b.vel[1]].map(|x| x as f32);
        assert_eq!(arrays, want, "t = {}", cp.time);
        let rest = f64s(&body[8 * STATE_HEADER + 2 * 4 * 2 * n..]);
        let support = b.support.map_or(-1.0, |w| w as f64);
        let acc = b.acc.unwrap();
        assert_eq!(
            rest,
            [REST_SECTION, support, acc[0], acc[1]],
            "t = {}",
            cp.time
        );
    }
    // The events carry their rest flags: landing and going on flagged, the slide-off not.
    let events = f64s(
        &get(
            s.port,
            &format!("/api/events?from=0&count={}", run.events.len()),
        )
        .body,
    );
    assert_eq!(events.len(), run.events.len() * 13);
    for (e, c) in events.chunks(13).zip(&run.events) {
        assert_eq!(e[0], c.event.time);
        assert_eq!(e[12], f64::from(u8::from(c.rests[0]) * REST_A), "{c:?}");
    }
    let off = &events[2 * 13..3 * 13];
    assert_eq!((off[1], off[3], off[12]), (1.0, SHELF_RIGHT as f64, 0.0));
}

/// Pixel colour of `pm` at world point `q` under camera `cam`.
fn pixel(pm: &tiny_skia::Pixmap, cam: &Camera, q: Vector<2>) -> Rgb {
    let (x, y, _) = cam.project(q);
    let c = pm.pixel(x as u32, y as u32).unwrap().demultiply();
    [c.red(), c.green(), c.blue()]
}

#[test]
fn a_ball_on_a_shelf_and_falling_past_its_end_is_rendered_where_the_simulation_had_it() {
    let (path, run) = recorded("ledge-render", &shelf_scene(), 3.0, 0.05);
    let dir = path.parent().unwrap();
    let o = RenderOptions {
        width: 600,
        ..RenderOptions::default()
    };
    let p = Playback::<2>::open(&path, &o.keyframes).unwrap();
    let cam = Camera::fit(&p.extent().bounds, o.width, None, o.yaw_deg, o.pitch_deg);
    let id = colour::id_colour(colour::id_bucket(0));
    // Sliding on the shelf's right piece: drawn on it, nothing of it under the shelf.
    let on = run
        .checkpoints
        .iter()
        .find(|cp| cp.bodies[0].support == Some(SHELF_RIGHT))
        .unwrap();
    // The last checkpoint of the fall, below the shelf's line by more than a radius.
    let (falling, _) = *after_slide_offs(&run).last().unwrap();
    let below = falling.bodies[0].pos;
    assert!(below[1] < SHELF_Y - RADIUS, "{below:?}");
    for (name, cp) in [("on", on), ("falling", falling)] {
        let out = dir.join(format!("{name}.png"));
        render_png(&path, cp.time, &out, &o).unwrap();
        let pm = tiny_skia::Pixmap::load_png(&out).unwrap();
        let b = cp.bodies[0].pos;
        assert_eq!(pixel(&pm, &cam, b), id, "{name}: at its centre");
        assert_eq!(pixel(&pm, &cam, b - Vector([0.0, 0.15])), id, "{name}");
        // Where it would be, had it gone on at the shelf's height (falling) or sunk below
        // the shelf under full gravity (on it), nothing.
        let elsewhere = if name == "on" {
            b - Vector([0.0, 2.0 * RADIUS + 0.1])
        } else {
            Vector([b[0], SHELF_Y + RADIUS])
        };
        assert_eq!(pixel(&pm, &cam, elsewhere), colour::BACKGROUND, "{name}");
    }
}

#[test]
fn the_shelves_example_plays_as_the_simulation_had_it() {
    let scene = shelves_example();
    let (path, run) = recorded("ledge-shelves", &scene, 30.0, 0.1);
    // Balls fly off shelves' ends and go on across the shelf drawn in two pieces.
    let (offs, on) = (run.slide_offs(), run.goes_on());
    assert!(offs.len() >= 3, "{offs:?}");
    assert!(!on.is_empty());
    let g = scene.gravity();
    let falling = after_slide_offs(&run);
    assert!(falling.len() >= 3 * offs.len());
    for &(cp, i) in &falling {
        assert_eq!((cp.bodies[i].support, cp.bodies[i].acc), (None, g));
    }
    let p = assert_plays(&path, &run, &DENSE);
    // The run's extent holds every ball at every checkpoint, and its top speed every speed.
    let e = *p.extent();
    for cp in &run.checkpoints {
        for b in &cp.bodies {
            let ball = Aabb::of_ball(b.pos, 0.15);
            for k in 0..2 {
                assert!(
                    ball.min[k] >= e.bounds.min[k] - 1e-12
                        && ball.max[k] <= e.bounds.max[k] + 1e-12,
                    "t = {}: {b:?} out of {e:?}",
                    cp.time
                );
            }
            assert!(b.vel.norm() <= e.max_speed + 1e-12, "{b:?} {e:?}");
        }
    }
}

/// The ball rolling over the shelf's end: the events that land it, carry it on along the
/// right piece, roll it over the end and let it go, with the recorded run.
fn roll_run(name: &str) -> (common::scratch::ScratchFile, LedgeRun, [usize; 2]) {
    let (path, run) = recorded(name, &roll_scene(), 3.0, 0.05);
    assert_eq!(
        run.ledges[..3],
        [None, Some(Ledge::GoesOn), Some(Ledge::RollsOver)]
    );
    assert_eq!(run.roll_overs(), [2]);
    let (over, off) = (run.events[2], run.events[3]);
    assert!(
        over.pivots[0] && over.event.b as usize == SHELF_RIGHT,
        "{over:?}"
    );
    assert!((over.pos[0][0] - SHELF_END).abs() < 1e-12, "{over:?}");
    assert_eq!(
        over.vel[0],
        Vector([1.0, 0.0]),
        "it turns at the speed it slid at"
    );
    // It comes off: a wall event of the segment turned about, neither resting nor turning.
    assert_eq!(
        (off.event.b as usize, off.rests[0], off.pivots[0]),
        (SHELF_RIGHT, false, false),
        "{off:?}"
    );
    assert!(run.slide_offs().is_empty(), "{:?}", run.ledges);
    (path, run, [2, 3])
}

#[test]
fn a_ball_rolling_over_a_shelfs_end_plays_as_the_simulation_had_it() {
    let (path, run, [over, off]) = roll_run("ledge-roll");
    let (t0, t1) = (run.time_of(over), run.time_of(off));
    // Mid-turn, the simulation has the ball on its circle about the shelf's end, with no
    // acceleration of its own, and off the parabola its turn started from.
    let turning = after_roll_overs(&run);
    assert!(turning.len() >= 3, "{}", turning.len());
    let start = run.after[over + 1][0].0;
    for &(cp, i) in &turning {
        let b = cp.bodies[i];
        assert_eq!((b.support, b.acc), (None, None), "t = {}", cp.time);
        assert!(
            ((b.pos - SHELF_CORNER).norm() - RADIUS).abs() < 1e-12,
            "{b:?}"
        );
        assert!((start.falling_at(cp.time, &G) - b.pos).norm() > 1e-6);
        assert!(cp.time > t0 && cp.time < t1);
    }
    // Played back at any time, from any keyframe: the simulation's positions and
    // velocities mid-turn to the bit (assert_exact), the turn about the shelf's end.
    let mut p = assert_plays(&path, &run, &DENSE);
    for &(cp, i) in &turning {
        let snap = p.snapshot_at(cp.time).unwrap();
        let turn = snap.states.turn(i).expect("it turns");
        assert_eq!(turn.point(), SHELF_CORNER);
        assert_eq!(turn.start_time(), t0);
        // At more times in between, still the simulation's (the turn is the same Pivot).
        for f in [0.25, 0.5, 0.75] {
            let t = cp.time + f * (t1 - cp.time);
            let mut sim = ccdsim::Simulation::new(&run.scene, "all-pairs").unwrap();
            sim.run_until(t);
            assert_eq!(snap.states.position_at(i, t), sim.position(i), "t = {t}");
            assert_eq!(
                snap.states.velocity_at(i, t),
                sim.world().velocity_at(i, t),
                "t = {t}"
            );
        }
    }
    // Before the roll-over and after it comes off, no turn.
    assert!(p
        .snapshot_after(over as u64)
        .unwrap()
        .states
        .turn(0)
        .is_none());
    assert!(p
        .snapshot_after(off as u64 + 1)
        .unwrap()
        .states
        .turn(0)
        .is_none());
    // The extent holds the ball along its turn.
    let e = *p.extent();
    for cp in &run.checkpoints {
        let ball = Aabb::of_ball(cp.bodies[0].pos, RADIUS);
        for k in 0..2 {
            assert!(ball.min[k] >= e.bounds.min[k] - 1e-12, "{e:?}");
            assert!(ball.max[k] <= e.bounds.max[k] + 1e-12, "{e:?}");
        }
    }
}

#[test]
fn a_ball_rolling_over_a_shelfs_end_is_served_with_its_turn() {
    let (path, run, [over, off]) = roll_run("ledge-roll-server");
    let s = common::start(&path, DENSE);
    let n = 1;
    let start = run.events[over];
    for cp in &run.checkpoints {
        let body = get(s.port, &format!("/api/state?t={}", cp.time)).body;
        let arrays = f32s(&body[8 * STATE_HEADER..8 * STATE_HEADER + 2 * 4 * 2 * n]);
        let b = cp.bodies[0];
        let want = [b.pos[0], b.pos[1], b.vel[0], b.vel[1]].map(|x| x as f32);
        assert_eq!(arrays, want, "t = {}", cp.time);
        let rest = f64s(&body[8 * STATE_HEADER + 2 * 4 * 2 * n..]);
        let turning = cp.time > run.time_of(over) && cp.time < run.time_of(off);
        if turning {
            // The rest section (no support, no acceleration of its own), then the turn: body
            // 0 about the shelf's end since the roll-over, from the roll-over's state.
            assert_eq!(
                rest,
                [
                    REST_SECTION,
                    -1.0,
                    0.0,
                    0.0,
                    PIVOT_SECTION,
                    1.0,
                    0.0,
                    SHELF_CORNER[0],
                    SHELF_CORNER[1],
                    start.event.time,
                    start.pos[0][0],
                    start.pos[0][1],
                    start.vel[0][0],
                    start.vel[0][1],
                ],
                "t = {}",
                cp.time
            );
        } else {
            // No turn: the answer is as before turns existed.
            assert_eq!(rest.len(), 1 + n + 2 * n, "t = {}", cp.time);
        }
    }
    // The roll-over's event carries bit 2 of its flags; no other does.
    let events = f64s(
        &get(
            s.port,
            &format!("/api/events?from=0&count={}", run.events.len()),
        )
        .body,
    );
    for (k, (e, c)) in events.chunks(13).zip(&run.events).enumerate() {
        let want = u8::from(c.rests[0]) * REST_A + if k == over { PIVOT_A } else { 0 };
        assert_eq!(e[12], f64::from(want), "event {k}: {c:?}");
    }
}

#[test]
fn a_ball_rolling_over_a_shelfs_end_is_rendered_on_its_circle() {
    let (path, run, _) = roll_run("ledge-roll-render");
    let dir = path.parent().unwrap();
    let o = RenderOptions {
        width: 1200,
        ..RenderOptions::default()
    };
    let p = Playback::<2>::open(&path, &o.keyframes).unwrap();
    let cam = Camera::fit(&p.extent().bounds, o.width, None, o.yaw_deg, o.pitch_deg);
    let px = 1.0 / f64::from(cam.project(Vector([1.0, 0.0])).0 - cam.project(Vector([0.0, 0.0])).0);
    let id = colour::id_colour(colour::id_bucket(0));
    // The checkpoint mid-turn where the parabola from the turn's start is furthest from the
    // circle.
    let start = run.after[run.roll_overs()[0] + 1][0].0;
    let parabola = |t: f64| start.falling_at(t, &G);
    let (cp, _) = after_roll_overs(&run)
        .into_iter()
        .max_by(|x, y| {
            let gap = |cp: &Checkpoint| (parabola(cp.time) - cp.bodies[0].pos).norm();
            gap(x.0).total_cmp(&gap(y.0))
        })
        .unwrap();
    let b = cp.bodies[0].pos;
    let gap = (parabola(cp.time) - b).norm();
    assert!(gap > 5.0 * px, "the parabola {gap} m away, {px} m a pixel");
    let out = dir.join("turning.png");
    render_png(&path, cp.time, &out, &o).unwrap();
    let pm = tiny_skia::Pixmap::load_png(&out).unwrap();
    assert_eq!(pixel(&pm, &cam, b), id, "at its centre on the circle");
    // Its disc is centred on the circle, not on the parabola (nor on the straight line from
    // the turn's start): painted 2 pixels inside its edge and not 2 pixels outside it (where
    // the shelf's corner may be drawn) all around, and towards the parabola.
    let line = start.at(cp.time);
    assert!((line - b).norm() > 5.0 * px, "{line:?} {b:?}");
    let towards = |q: Vector<2>| (q - b) * (1.0 / (q - b).norm());
    let dirs = [[1.0, 0.0], [-1.0, 0.0], [0.0, 1.0], [0.0, -1.0]].map(Vector);
    for d in dirs
        .into_iter()
        .chain([towards(parabola(cp.time)), towards(line)])
    {
        assert_eq!(pixel(&pm, &cam, b + d * (RADIUS - 2.0 * px)), id, "{d:?}");
        assert_ne!(pixel(&pm, &cam, b + d * (RADIUS + 2.0 * px)), id, "{d:?}");
    }
}

#[test]
fn a_ball_turning_over_the_top_of_an_incline_is_inside_the_extent_at_its_highest() {
    // Up a 20° incline and off its top end at 0.8 m/s: too slow to fly clear (v² < r g cos
    // 20°), fast enough to turn over the top of the end point and come off on the far side.
    // Its highest point, straight above the end, lies between its records: the extent must
    // still reach it.
    let a = 20f64.to_radians();
    let (c, s) = (a.cos(), a.sin());
    let top = Vector([2.0 * c, SHELF_Y + 2.0 * s]);
    let start = Vector([
        1.5 * c - s * (RADIUS + 1e-7),
        SHELF_Y + 1.5 * s + c * (RADIUS + 1e-7),
    ]);
    let v0 = (0.8f64 * 0.8 + 2.0 * 10.0 * s * 0.5).sqrt();
    let mut scene = roll_scene();
    scene.bodies[0] = ccdsim::BodySpec::new(start, Vector([v0 * c, v0 * s]), RADIUS);
    scene.walls = vec![
        scene.walls[FLOOR],
        ccdsim::Wall::Segment {
            a: Vector([0.0, SHELF_Y]),
            b: top,
        },
    ];
    let (path, run) = recorded("ledge-over-the-top", &scene, 2.0, 0.05);
    let over = run.roll_overs();
    assert_eq!(over.len(), 1, "{:?}", run.events);
    let roll = run.events[over[0]];
    assert!(
        roll.pos[0][1] + RADIUS < top[1] + 2.0 * RADIUS - 1e-3,
        "{roll:?}"
    );
    // Over the top: on the far side of the end point when it comes off.
    let off = run.events[over[0] + 1];
    assert!(off.pos[0][0] > top[0] && !off.rests[0], "{off:?}");
    let p = assert_plays(&path, &run, &DENSE);
    let e = p.extent();
    assert!(
        (e.bounds.max[1] - (top[1] + 2.0 * RADIUS)).abs() < 1e-12,
        "{e:?}, the top of the turn at {}",
        top[1] + 2.0 * RADIUS
    );
}
