//! A fuzz case: a scene, how the run is driven (events or frames), the edits a program makes
//! between steps, and where the run stops. Cases are plain JSON, so a failing case written
//! out by the fuzzer is a regression test that anyone can read, edit and run.

use ccdsim::{AnyScene, BodySpec, CollisionFilter, Scene, Vector};
use serde::{Deserialize, Serialize};

/// How the run advances between edits.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Schedule {
    /// `step_event` one event at a time; the edits come after every `every` events.
    Events {
        /// Events between two edits (at least 1).
        every: u32,
    },
    /// Frames of `dt` seconds, as a game loop runs: every event inside a frame is resolved,
    /// then the clock moves to the frame's end (`run_until`) and the next edit is made there.
    Frames {
        /// Frame length, seconds.
        dt: f64,
    },
}

/// One edit a program makes between steps. Body and wall indices are taken modulo the number
/// of slots (walls) at the time; an edit the simulation refuses changes nothing, alike in every
/// run.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case", tag = "op")]
pub enum EditOp {
    /// `set_velocity(body, vel)`.
    Velocity {
        /// Body slot.
        body: usize,
        /// New velocity, m/s (first `D` components).
        vel: Vec<f64>,
    },
    /// `set_position(body, pos)`.
    Position {
        /// Body slot.
        body: usize,
        /// New position, m (first `D` components).
        pos: Vec<f64>,
    },
    /// `add_body` with this position, velocity and radius.
    Add {
        /// Position, m.
        pos: Vec<f64>,
        /// Velocity, m/s.
        vel: Vec<f64>,
        /// Radius, m.
        radius: f64,
        /// Kinematic (moves at constant velocity, pushes others).
        #[serde(default)]
        kinematic: bool,
    },
    /// `remove_body(body)`.
    Remove {
        /// Body slot.
        body: usize,
    },
    /// `set_collision_filter(body, {group, mask})`.
    Filter {
        /// Body slot.
        body: usize,
        /// Groups the body belongs to.
        group: u32,
        /// Groups it collides with.
        mask: u32,
    },
    /// `set_wall_velocity(wall, vel)` on a moving wall.
    WallVelocity {
        /// Moving wall index.
        wall: usize,
        /// New velocity, m/s.
        vel: Vec<f64>,
    },
    /// `rescale_velocities(factor)`: every body's velocity times `factor` (a packing's cooling).
    Rescale {
        /// The factor, ≥ 0.
        factor: f64,
    },
}

/// A whole fuzz case.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Case {
    /// The scene, as a scene file holds it (with its `dim`).
    pub scene: serde_json::Value,
    /// Events or frames.
    pub schedule: Schedule,
    /// The edits, made in order (one at each edit point) until they run out.
    #[serde(default)]
    pub edits: Vec<EditOp>,
    /// At most this many events are resolved.
    pub max_events: u64,
    /// The run stops at this time, seconds after the scene's start.
    pub duration: f64,
    /// What the case is for (a regression case says what failed on it).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub note: Option<String>,
}

impl Case {
    /// A case of `scene` with the given drive.
    #[must_use]
    pub fn new<const D: usize>(
        scene: &Scene<D>,
        schedule: Schedule,
        edits: Vec<EditOp>,
        max_events: u64,
        duration: f64,
    ) -> Self {
        Case {
            scene: serde_json::from_str(&scene.to_json()).expect("a scene serialises"),
            schedule,
            edits,
            max_events,
            duration,
            note: None,
        }
    }

    /// Whether the case is a pool shot: its scene is a pool scene (`{"pool": …}`), played to
    /// its end with no schedule or edits (see [`crate::pool`]).
    #[must_use]
    pub fn is_pool(&self) -> bool {
        self.scene
            .as_object()
            .is_some_and(|o| o.contains_key("pool"))
    }

    /// Parses and validates the case's scene.
    pub fn any_scene(&self) -> Result<AnyScene, ccdsim::SceneError> {
        AnyScene::from_json(&self.scene.to_string())
    }

    /// Reads a case from its JSON text.
    pub fn from_json(text: &str) -> Result<Self, serde_json::Error> {
        serde_json::from_str(text)
    }

    /// The case as pretty JSON.
    #[must_use]
    pub fn to_json_pretty(&self) -> String {
        serde_json::to_string_pretty(self).expect("a case serialises")
    }
}

/// The first `D` components of `v` (missing ones are zero).
#[must_use]
pub fn vector<const D: usize>(v: &[f64]) -> Vector<D> {
    let mut out = Vector::<D>::ZERO;
    for (d, x) in v.iter().take(D).enumerate() {
        out[d] = *x;
    }
    out
}

impl EditOp {
    /// Makes the edit on `sim`; refused edits change nothing and are ignored.
    pub fn apply<const D: usize>(&self, sim: &mut ccdsim::Simulation<D>) {
        let slots = sim.world().len();
        let body = |b: usize| (slots > 0).then(|| b % slots);
        // Refusals are part of the case: every finder must refuse alike, which the run files
        // (edit records) show.
        match self {
            EditOp::Velocity { body: b, vel } => {
                if let Some(i) = body(*b) {
                    let _ = sim.set_velocity(i, vector(vel));
                }
            }
            EditOp::Position { body: b, pos } => {
                if let Some(i) = body(*b) {
                    let _ = sim.set_position(i, vector(pos));
                }
            }
            EditOp::Add {
                pos,
                vel,
                radius,
                kinematic,
            } => {
                let mut spec = BodySpec::new(vector(pos), vector(vel), *radius);
                spec.kinematic = *kinematic;
                let _ = sim.add_body(spec);
            }
            EditOp::Remove { body: b } => {
                if let Some(i) = body(*b) {
                    if !sim.world().is_vacant(i) {
                        let _ = sim.remove_body(i);
                    }
                }
            }
            EditOp::Filter {
                body: b,
                group,
                mask,
            } => {
                if let Some(i) = body(*b) {
                    let _ = sim.set_collision_filter(
                        i,
                        CollisionFilter {
                            group: *group,
                            mask: *mask,
                        },
                    );
                }
            }
            EditOp::WallVelocity { wall, vel } => {
                let n = sim.world().moving_wall_count();
                if n > 0 {
                    let _ = sim.set_wall_velocity(wall % n, vector(vel));
                }
            }
            EditOp::Rescale { factor } => {
                let _ = sim.rescale_velocities(*factor);
            }
        }
    }
}
