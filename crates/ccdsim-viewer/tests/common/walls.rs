//! A real recorded run with moving walls (format version 10: edit records of code 5 name a
//! moving wall, not a body), with the simulation's own states along the way to check playback
//! against. Also used by `examples/wall_run.rs`, which writes such a run for the browser tests.

#![allow(dead_code)]

use ccdsim::generate::box_walls;
use ccdsim::record::RunWriter;
use ccdsim::Motion;
use ccdsim::WallMotion;
use ccdsim::{BodySpec, MovingWall, Scene, Simulation, Vector, Wall};
use std::path::Path;

/// Seconds per frame.
pub const DT: f64 = 0.05;

/// Frames recorded.
pub const FRAMES: usize = 80;

/// The first frame the program steers the walls in: before it they move at the scene's
/// velocities, with no edit record.
pub const FIRST_STEERED: usize = 4;

/// Frame at which a body is removed, and at which one is added: a run with moving walls
/// whose snapshots also carry a slot section (the wall section then follows it, padded).
pub const REMOVE_AT: usize = 30;
/// See [`REMOVE_AT`].
pub const ADD_AT: usize = 40;

/// The simulation's state after the first `applied` records, at `time`: every slot's stored
/// state (`None` when vacant) and every moving wall's motion.
#[derive(Clone, Debug)]
pub struct Checkpoint {
    pub applied: u64,
    pub time: f64,
    pub bodies: Vec<Option<Motion<2>>>,
    pub walls: Vec<WallMotion<2>>,
}

/// What was recorded.
pub struct WallRun {
    pub scene: Scene<2>,
    pub events: u64,
    pub end: f64,
    pub checkpoints: Vec<Checkpoint>,
    /// Every motion each moving wall had, in time order: the scene's first, then one per
    /// `set_wall_velocity` (its edit record's time, offset and velocity).
    pub pieces: Vec<Vec<WallMotion<2>>>,
    /// Wall events with a moving wall (`b` ≥ the static walls).
    pub moving_wall_hits: u64,
}

impl WallRun {
    /// Moving wall `k`'s displacement from its scene geometry at `t`, from its pieces.
    #[must_use]
    pub fn offset_at(&self, k: usize, t: f64) -> Vector<2> {
        let ps = &self.pieces[k];
        let j = ps.partition_point(|m| m.time <= t).max(1) - 1;
        ps[j].offset_at(t)
    }
}

/// The scene: an 8 m box, a dozen balls of radius 0.2 m to the right of a vertical paddle
/// (moving wall 0, the segment x = 2 from y = 1 to 3, sliding right at 0.5 m/s) and below a
/// piston (moving wall 1, the line y = 7 facing down, coming down at 0.4 m/s).
#[must_use]
pub fn wall_scene() -> Scene<2> {
    let bodies = (0..12)
        .map(|k| {
            let (x, y) = (3.5 + 1.0 * (k % 4) as f64, 1.0 + 1.5 * (k / 4) as f64);
            // Varied, fixed velocities; none at rest.
            let v = Vector([
                1.5 * ((k * 7 % 5) as f64 - 2.0) + 0.3,
                1.2 * ((k * 3 % 4) as f64 - 1.5),
            ]);
            BodySpec::new(Vector([x, y]), v, 0.2)
        })
        .collect();
    Scene {
        bodies,
        walls: box_walls(Vector([8.0, 8.0])),
        moving_walls: vec![
            MovingWall {
                wall: Wall::Segment {
                    a: Vector([2.0, 1.0]),
                    b: Vector([2.0, 3.0]),
                },
                velocity: Vector([0.5, 0.0]),
            },
            MovingWall {
                wall: Wall::Plane {
                    point: Vector([0.0, 7.0]),
                    normal: Vector([0.0, -1.0]),
                },
                velocity: Vector([0.0, -0.4]),
            },
        ],
        ..Scene::default()
    }
}

fn checkpoint(sim: &Simulation<2>, applied: u64) -> Checkpoint {
    let w = sim.world();
    Checkpoint {
        applied,
        time: sim.time(),
        bodies: (0..w.len())
            .map(|i| (!w.is_vacant(i)).then(|| w.motion(i)))
            .collect(),
        walls: (0..w.moving_wall_count())
            .map(|k| w.wall_motion(k))
            .collect(),
    }
}

/// Records the run to the steered run file `path`: from frame [`FIRST_STEERED`] on, the
/// paddle swings left and right (its velocity set every frame, `1.8·cos` of the time), and the
/// piston keeps coming down until t = 2 s and then goes back up (its velocity set every
/// other frame); a body is taken out at frame [`REMOVE_AT`] and one put in at [`ADD_AT`].
pub fn record_wall_run(path: &Path) -> WallRun {
    let scene = wall_scene();
    let mut sim = Simulation::new(&scene, "cells").unwrap();
    sim.record_edits(true);
    let file = std::fs::File::create(path).unwrap();
    let mut w = RunWriter::new_steered(file, path.display().to_string(), &scene).unwrap();
    let mut pieces: Vec<Vec<WallMotion<2>>> =
        (0..2).map(|k| vec![sim.world().wall_motion(k)]).collect();
    let (mut events, mut moving_wall_hits) = (0u64, 0u64);
    let mut checkpoints = Vec::new();
    let static_walls = scene.walls.len() as u32;
    for f in 0..FRAMES {
        let t = sim.time();
        if f >= FIRST_STEERED {
            let paddle = Vector([1.8 * (2.0 * std::f64::consts::PI * t / 2.4).cos(), 0.0]);
            sim.set_wall_velocity(0, paddle).unwrap();
            if f % 2 == 0 {
                let piston = Vector([0.0, if t < 2.0 { -0.4 } else { 0.5 }]);
                sim.set_wall_velocity(1, piston).unwrap();
            }
        }
        if f == REMOVE_AT {
            sim.remove_body(3).unwrap();
        }
        if f == ADD_AT {
            // The first free place on a grid, clear of the walls and the balls.
            let added = (0..64).find_map(|c| {
                let pos = Vector([3.25 + 0.5 * (c % 8) as f64, 0.75 + 0.5 * (c / 8) as f64]);
                sim.add_body(BodySpec::new(pos, Vector([-1.0, 0.5]), 0.25))
                    .ok()
            });
            assert!(added.is_some(), "a place for the added body");
        }
        for r in sim.take_edits() {
            if let Some(k) = ccdsim::edit::Edit::moves_a_wall(&r).then_some(r.event.a as usize) {
                pieces[k].push(sim.world().wall_motion(k));
            }
            w.write_event(&r).unwrap();
            events += 1;
        }
        checkpoints.push(checkpoint(&sim, events));
        for c in sim.advance(DT) {
            if c.event.kind == ccdsim::EventKind::Wall && c.event.b >= static_walls {
                moving_wall_hits += 1;
            }
            w.write_event(&c).unwrap();
            events += 1;
        }
    }
    checkpoints.push(checkpoint(&sim, events));
    let end = sim.time();
    w.finish(end).unwrap();
    WallRun {
        scene,
        events,
        end,
        checkpoints,
        pieces,
        moving_wall_hits,
    }
}
