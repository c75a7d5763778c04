//! A real recorded run that adds and removes bodies (format version 9 edit records), with the
//! simulation's own states along the way to check playback against. Also used by
//! `examples/slot_run.rs`, which writes such a run for the browser tests.

#![allow(dead_code)]

use ccdsim::generate::box_walls;
use ccdsim::record::RunWriter;
use ccdsim::Gravity;
use ccdsim::Motion;
use ccdsim::{BodySpec, CollisionFilter, Scene, Simulation, Vector};
use std::path::Path;

/// What the run does: bodies at the start, frames of `DT` seconds, an add every `add_every`
/// frames and a removal every `remove_every` frames (0: never).
#[derive(Clone, Copy, Debug)]
pub struct Plan {
    pub start_bodies: usize,
    pub frames: usize,
    pub add_every: usize,
    pub remove_every: usize,
    /// Size of the square table, metres.
    pub size: f64,
}

/// The default plan: a dozen bodies under gravity, bodies added every third frame and
/// removed every fourth (from frame 6; after the frame's add), so slots empty, stay vacant
/// for a while, fill again and grow past the scene's.
pub const PLAN: Plan = Plan {
    start_bodies: 12,
    frames: 120,
    add_every: 3,
    remove_every: 4,
    size: 8.0,
};

/// Seconds per frame.
pub const DT: f64 = 0.05;

/// The simulation's state of one slot holding a body.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Slot {
    pub motion: Motion<2>,
    pub radius: f64,
    pub id: u64,
    pub kinematic: bool,
}

/// The simulation's slots after the first `applied` records, at `time`: `None` for a vacant
/// slot (including the ones it reserved and never filled).
#[derive(Clone, Debug)]
pub struct Checkpoint {
    pub applied: u64,
    pub time: f64,
    pub slots: Vec<Option<Slot>>,
}

/// A removal: slot, time, where the body stopped, its radius.
#[derive(Clone, Copy, Debug)]
pub struct Removal {
    pub slot: usize,
    pub time: f64,
    pub pos: Vector<2>,
    pub radius: f64,
}

/// A body added.
#[derive(Clone, Copy, Debug)]
pub struct Add {
    pub slot: usize,
    pub time: f64,
    pub radius: f64,
    pub kinematic: bool,
    pub id: u64,
}

/// What was recorded.
pub struct SlotRun {
    pub scene: Scene<2>,
    pub events: u64,
    pub end: f64,
    pub checkpoints: Vec<Checkpoint>,
    pub removals: Vec<Removal>,
    pub adds: Vec<Add>,
}

/// A small deterministic generator (an LCG), so that runs are the same everywhere.
struct Lcg(u64);

impl Lcg {
    /// Uniform in [lo, hi).
    fn next(&mut self, lo: f64, hi: f64) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        lo + (hi - lo) * ((self.0 >> 11) as f64 / (1u64 << 53) as f64)
    }
}

/// The scene: `plan.start_bodies` balls of radius 0.25 m on a grid in a square box, moving,
/// under gravity (0, −3) m/s².
pub fn slot_scene(plan: &Plan) -> Scene<2> {
    let mut rng = Lcg(11);
    let per_row = ((plan.size - 1.0) / 1.0).floor() as usize;
    let bodies = (0..plan.start_bodies)
        .map(|k| {
            let (x, y) = (1.0 + (k % per_row) as f64, 1.0 + (k / per_row) as f64);
            let v = Vector([rng.next(-2.0, 2.0), rng.next(-2.0, 2.0)]);
            BodySpec::new(Vector([x, y]), v, 0.25)
        })
        .collect();
    let mut scene = Scene {
        bodies,
        walls: box_walls(Vector([plan.size, plan.size])),
        ..Scene::default()
    };
    scene.settings.gravity = Gravity::new(&[0.0, -3.0]);
    scene
}

fn checkpoint(sim: &Simulation<2>, applied: u64) -> Checkpoint {
    let w = sim.world();
    let slots = (0..w.len())
        .map(|i| {
            (!w.is_vacant(i)).then(|| Slot {
                motion: w.motion(i),
                radius: w.radius(i),
                id: w.ids()[i],
                kinematic: w.is_kinematic(i),
            })
        })
        .collect();
    Checkpoint {
        applied,
        time: sim.time(),
        slots,
    }
}

/// Records `plan` to the steered run file `path`. Added bodies have radii of 0.15 to 0.3 m,
/// every fourth is kinematic (a slow obstacle that does not fall), every fifth names its own
/// id; a body is given a new velocity at frame 10 and a new collision filter at frame 20.
pub fn record_slot_run(path: &Path, plan: &Plan) -> SlotRun {
    let scene = slot_scene(plan);
    let mut sim = Simulation::new(&scene, "cells").unwrap();
    let mut w = RunWriter::record_steered(&mut sim, path, &scene).unwrap();
    let mut rng = Lcg(5);
    let (mut events, mut added) = (0u64, 0usize);
    let (mut checkpoints, mut removals, mut adds) = (Vec::new(), Vec::new(), Vec::new());
    for f in 0..plan.frames {
        let t = sim.time();
        if f % plan.add_every == 0 {
            let radius = 0.15 + 0.05 * (added % 4) as f64;
            let kinematic = added % 4 == 3;
            let vel = if kinematic {
                Vector([rng.next(-0.2, 0.2), 0.0])
            } else {
                Vector([rng.next(-2.0, 2.0), rng.next(-1.0, 1.0)])
            };
            // The first free place, from a random one on.
            let start = rng.next(0.0, 1000.0) as usize;
            let cols = (plan.size - 1.0).floor() as usize * 2;
            let rows = cols;
            for c in 0..cols * rows {
                let k = (start + c) % (cols * rows);
                let pos = Vector([
                    0.75 + 0.5 * (k % cols) as f64,
                    0.75 + 0.5 * (k / cols) as f64,
                ]);
                let spec = BodySpec {
                    id: (added % 5 == 4).then_some(1000 + added as u64),
                    kinematic,
                    ..BodySpec::new(pos, vel, radius)
                };
                if let Ok(i) = sim.add_body(spec) {
                    adds.push(Add {
                        slot: i,
                        time: t,
                        radius,
                        kinematic,
                        id: sim.world().ids()[i],
                    });
                    break;
                }
            }
            added += 1;
        }
        if plan.remove_every > 0 && f >= 6 && f % plan.remove_every == 0 {
            let n = sim.world().len();
            let slot = (0..n)
                .map(|k| (f * 7 + k) % n)
                .find(|&i| !sim.world().is_vacant(i));
            if let Some(i) = slot {
                let (pos, radius) = (sim.position(i), sim.world().radius(i));
                sim.remove_body(i).unwrap();
                removals.push(Removal {
                    slot: i,
                    time: t,
                    pos,
                    radius,
                });
            }
        }
        if f == 10 || f == 20 {
            let i = (0..sim.world().len())
                .find(|&i| !sim.world().is_vacant(i) && !sim.world().is_kinematic(i))
                .unwrap();
            if f == 10 {
                sim.set_velocity(i, Vector([1.5, 2.5])).unwrap();
            } else {
                let filter = CollisionFilter {
                    group: 2,
                    mask: u32::MAX,
                };
                sim.set_collision_filter(i, filter).unwrap();
            }
        }
        for r in sim.take_edits() {
            w.write_event(&r).unwrap();
            events += 1;
        }
        checkpoints.push(checkpoint(&sim, events));
        for c in sim.advance(DT) {
            w.write_event(&c).unwrap();
            events += 1;
        }
    }
    checkpoints.push(checkpoint(&sim, events));
    let end = sim.time();
    w.finish(end).unwrap();
    SlotRun {
        scene,
        events,
        end,
        checkpoints,
        removals,
        adds,
    }
}
