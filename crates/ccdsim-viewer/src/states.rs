//! Every body's lazy state, as replayed from a run file.

use ccdsim::narrow::Motion;
use ccdsim::{Collision, EventKind, Scene, Vector};

/// The stored state of every body (structure of arrays): body `i` is at `pos[i]` at time
/// `time[i]` and moves with `vel[i]`, so its position at `t` is `pos + vel·(t − time)`, or,
/// in a run with gravity `g`, `pos + vel·(t − time) + ½·g·(t − time)²` (its velocity then
/// is `vel + g·(t − time)`).
///
/// Replaying a run's collisions with [`BodyStates::apply`] reproduces the simulation's stored
/// states bit for bit, since a run file records exactly the states a collision stored.
#[derive(Clone, Debug, PartialEq)]
pub struct BodyStates<const D: usize> {
    /// Reference positions, metres.
    pub pos: Vec<Vector<D>>,
    /// Velocities, metres per second.
    pub vel: Vec<Vector<D>>,
    /// Reference times, seconds.
    pub time: Vec<f64>,
    /// The acceleration of every body between events (the scene's `settings.gravity`), if
    /// the run has gravity, metres per second squared.
    pub gravity: Option<Vector<D>>,
    /// Which bodies are kinematic, by index (they move in straight lines even under gravity).
    pub kinematic: Vec<bool>,
}

impl<const D: usize> BodyStates<D> {
    /// The states at the start of a run of `scene`.
    #[must_use]
    pub fn from_scene(scene: &Scene<D>) -> Self {
        BodyStates {
            pos: scene.bodies.iter().map(|b| b.pos).collect(),
            vel: scene.bodies.iter().map(|b| b.vel).collect(),
            time: vec![scene.start_time; scene.bodies.len()],
            gravity: scene.gravity(),
            kinematic: scene.bodies.iter().map(|b| b.kinematic).collect(),
        }
    }

    /// Number of bodies.
    #[must_use]
    pub fn len(&self) -> usize {
        self.pos.len()
    }

    /// True when there are no bodies.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.pos.is_empty()
    }

    /// Stores the states a recorded collision left its bodies in.
    pub fn apply(&mut self, c: &Collision<D>) {
        let t = c.event.time;
        let a = c.event.a as usize;
        self.set(a, c.pos[0], c.vel[0], t);
        if c.event.kind == EventKind::Body {
            self.set(c.event.b as usize, c.pos[1], c.vel[1], t);
        }
    }

    fn set(&mut self, i: usize, p: Vector<D>, v: Vector<D>, t: f64) {
        self.pos[i] = p;
        self.vel[i] = v;
        self.time[i] = t;
    }

    /// Body `i`'s stored state.
    #[must_use]
    pub fn motion(&self, i: usize) -> Motion<D> {
        Motion {
            pos: self.pos[i],
            vel: self.vel[i],
            time: self.time[i],
        }
    }

    /// Position of body `i` at time `t`, metres: on its straight line, or on its parabola
    /// in a run with gravity.
    #[must_use]
    pub fn position_at(&self, i: usize, t: f64) -> Vector<D> {
        match &self.gravity {
            Some(g) if !self.kinematic[i] => self.motion(i).falling_at(t, g),
            _ => self.motion(i).at(t),
        }
    }

    /// Velocity of body `i` at time `t`, metres per second: the stored one, or in a run with
    /// gravity that plus `g·(t − time)`.
    #[must_use]
    pub fn velocity_at(&self, i: usize, t: f64) -> Vector<D> {
        match &self.gravity {
            Some(g) if !self.kinematic[i] => self.motion(i).falling_velocity(t, g),
            _ => self.vel[i],
        }
    }

    /// Heap bytes held, for the keyframe budget.
    #[must_use]
    pub fn heap_bytes(&self) -> usize {
        Self::bytes_per_body() * self.len()
    }

    /// Bytes one body's state takes.
    #[must_use]
    pub const fn bytes_per_body() -> usize {
        (2 * D + 1) * std::mem::size_of::<f64>()
    }
}
