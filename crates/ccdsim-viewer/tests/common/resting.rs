//! A real recorded run where bodies come to rest on planes and slide along them
//! (`settings.rest_speed`, format version 11), with the simulation's own states along the way
//! to check playback against. Also used by `examples/rest_run.rs`, which writes such a run for
//! the browser tests.

#![allow(dead_code)]

use ccdsim::record::RunWriter;
use ccdsim::Gravity;
use ccdsim::Motion;
use ccdsim::{BodySpec, Scene, Settings, Simulation, Vector, Wall};
use std::path::Path;

/// Seconds per frame.
pub const DT: f64 = 0.05;

/// Frames recorded.
pub const FRAMES: usize = 120;

/// The frame at which the program kicks the floor ball (body 0) up and to the right: an edit,
/// which lifts it off the floor it rests on by then.
pub const KICK_AT: usize = 60;

/// The kick's velocity, m/s.
pub const KICK: Vector<2> = Vector([0.3, 2.0]);

/// Radius of every ball, metres.
pub const RADIUS: f64 = 0.25;

/// The floor (static wall 0).
pub const FLOOR: usize = 0;
/// The 30° incline (static wall 1).
pub const INCLINE: usize = 1;

/// One body at a checkpoint, as the simulation has it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BodyAt {
    /// Its stored state.
    pub motion: Motion<2>,
    /// The wall it rests on.
    pub support: Option<usize>,
    /// Its position and velocity at the checkpoint's time.
    pub pos: Vector<2>,
    pub vel: Vector<2>,
    /// Its acceleration until its next event (`World::gravity_of`).
    pub acc: Option<Vector<2>>,
}

/// Body `i`'s stored state as the run file records it: [`ccdsim::World::motion`], except for a
/// body turning about a segment's end point (format 13), which the world keeps parked at rest
/// where its turn started: its velocity is then the one its turn started with
/// ([`ccdsim::World::recorded_state`]), as a playback's states hold it.
pub fn recorded_motion(w: &ccdsim::World<2>, i: usize) -> Motion<2> {
    let (pos, vel) = w.recorded_state(i);
    Motion {
        pos,
        vel,
        time: w.motion(i).time,
    }
}

/// The simulation's state after the first `applied` records, at `time` (between events).
#[derive(Clone, Debug)]
pub struct Checkpoint {
    pub applied: u64,
    pub time: f64,
    pub bodies: Vec<BodyAt>,
}

/// What was recorded.
pub struct RestRun {
    pub scene: Scene<2>,
    pub events: u64,
    pub end: f64,
    pub checkpoints: Vec<Checkpoint>,
    /// Time of the first wall event after which body 0 rests on the floor.
    pub floor_rest: f64,
    /// Time of the first wall event after which body 1 rests on the incline.
    pub incline_rest: f64,
}

/// The normal of the incline: 30° from the vertical, facing up and to the left, so that the
/// incline rises to the right of its foot at (10, 0).
#[must_use]
pub fn incline_normal() -> Vector<2> {
    Vector([-0.5, 0.75f64.sqrt()])
}

/// The scene, under `g = (0, −10)` with restitution 0.5 and `rest_speed` 0.4 m/s: a floor
/// plane `y = 0`, a 30° incline plane rising to the right from (10, 0), and a wall plane
/// `x = −1`, which holds no resting body (gravity runs along it). Ball 0 is dropped from
/// 1.25 m above the floor at 0.5 m/s to the right: its bounces die away and it rests at the
/// fourth contact, at t = 1.375 s, then slides on at 0.5 m/s. Ball 1 is let go a millimetre
/// above the incline at x = 14: it rests at once and slides down at `g sin 30°`, down to the
/// floor, where it bounces on towards ball 0.
#[must_use]
pub fn rest_scene() -> Scene<2> {
    let n = incline_normal();
    let foot = Vector([10.0, 0.0]);
    // The point of the incline at x = 14, and a ball a millimetre off it.
    let on = foot + Vector([4.0, 4.0 / 3f64.sqrt()]);
    let ball1 = on + n * (RADIUS + 1e-3);
    Scene {
        settings: Settings {
            restitution: 0.5,
            gravity: Gravity::new(&[0.0, -10.0]),
            rest_speed: Some(0.4),
            ..Settings::default()
        },
        bodies: vec![
            BodySpec::new(Vector([0.0, 1.5]), Vector([0.5, 0.0]), RADIUS),
            BodySpec::new(ball1, Vector([0.0, 0.0]), RADIUS),
        ],
        walls: vec![
            Wall::Plane {
                point: Vector([0.0, 0.0]),
                normal: Vector([0.0, 1.0]),
            },
            Wall::Plane {
                point: foot,
                normal: n,
            },
            Wall::Plane {
                point: Vector([-1.0, 0.0]),
                normal: Vector([1.0, 0.0]),
            },
        ],
        ..Scene::default()
    }
}

/// The simulation's bodies now, after its first `applied` records.
pub fn checkpoint(sim: &Simulation<2>, applied: u64) -> Checkpoint {
    let (w, t) = (sim.world(), sim.time());
    Checkpoint {
        applied,
        time: t,
        bodies: (0..w.len())
            .map(|i| BodyAt {
                motion: recorded_motion(w, i),
                support: w.support(i),
                pos: w.position_at(i, t),
                vel: w.velocity_at(i, t),
                acc: w.gravity_of(i),
            })
            .collect(),
    }
}

/// Records the run to the steered run file `path` (format version 11): frames of [`DT`], with
/// ball 0 kicked to [`KICK`] at frame [`KICK_AT`].
pub fn record_rest_run(path: &Path) -> RestRun {
    let scene = rest_scene();
    let mut sim = Simulation::new(&scene, "all-pairs").unwrap();
    sim.record_edits(true);
    let file = std::fs::File::create(path).unwrap();
    let mut w = RunWriter::new_steered(file, path.display().to_string(), &scene).unwrap();
    let mut events = 0u64;
    let mut checkpoints = Vec::new();
    let (mut floor_rest, mut incline_rest) = (f64::NAN, f64::NAN);
    for f in 0..FRAMES {
        if f == KICK_AT {
            sim.set_velocity(0, KICK).unwrap();
        }
        for r in sim.take_edits() {
            w.write_event(&r).unwrap();
            events += 1;
        }
        checkpoints.push(checkpoint(&sim, events));
        for c in sim.advance(DT) {
            if c.event.kind == ccdsim::EventKind::Wall && c.rests[0] {
                match (c.event.a, c.event.b as usize) {
                    (0, FLOOR) if floor_rest.is_nan() => floor_rest = c.event.time,
                    (1, INCLINE) if incline_rest.is_nan() => incline_rest = c.event.time,
                    _ => {}
                }
            }
            w.write_event(&c).unwrap();
            events += 1;
        }
        assert!(sim.halt().is_none(), "{:?}", sim.halt());
    }
    checkpoints.push(checkpoint(&sim, events));
    let end = sim.time();
    w.finish(end).unwrap();
    RestRun {
        scene,
        events,
        end,
        checkpoints,
        floor_rest,
        incline_rest,
    }
}
