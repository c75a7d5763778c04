//! Body state, kept lazily: body `i` holds a reference position, its velocity and the time at
//! which the position holds.
//!
//! Everything a collision touches about a body is one record, [`Body`]: what every time of
//! impact reads (motion and radius) first, then the mass and the change count that resolving
//! a collision and validating a prediction read (64 bytes in 2D, 80 in 3D). A finder looking
//! at a candidate partner touches one or two cache lines, and a collision finds its bodies'
//! masses and counts in lines it has already loaded: in a 2D gas of 10⁶ bodies that is about
//! 15 % more collisions per second than with masses and counts in arrays of their own. Ids,
//! read only by tools, live in a separate array.

use crate::geom::Vector;
use crate::growth::GrowthLaw;
use crate::narrow::Motion;
use crate::scene::{Scene, SceneError};
use crate::wall::Wall;

/// The hot part of one body's state: its stored motion, radius, mass and change count.
///
/// `repr(C)` keeps the fields in this order: the ones every time of impact reads come first.
#[derive(Clone, Copy, Debug, PartialEq)]
#[repr(C)]
pub struct Body<const D: usize> {
    /// Stored motion: reference position (metres), velocity (metres per second) and the
    /// reference time (seconds) at which the position holds.
    pub motion: Motion<D>,
    /// Radius, metres.
    pub radius: f64,
    /// Mass, kilograms.
    mass: f64,
    /// How many times the stored motion has been replaced (see [`World::change_count`]).
    changes: u64,
}

/// Bodies and walls of a running simulation.
///
/// Only collisions (and explicit edits) change a body's stored state, and only that body's:
/// its position at time `t` is `pos + vel · (t − time)`.
#[derive(Clone, Debug)]
pub struct World<const D: usize> {
    bodies: Vec<Body<D>>,
    id: Vec<u64>,
    walls: Vec<Wall<D>>,
    periodic: Option<Vector<D>>,
    restitution: f64,
    thermostat: Option<crate::thermostat::Thermostat>,
    growth: Option<GrowthLaw>,
    now: f64,
}

impl<const D: usize> World<D> {
    /// Builds the world of a scene after validating it.
    pub fn from_scene(scene: &Scene<D>) -> Result<Self, SceneError> {
        scene.validate()?;
        let n = scene.bodies.len();
        Ok(World {
            bodies: scene
                .bodies
                .iter()
                .map(|b| Body {
                    motion: Motion {
                        pos: b.pos,
                        vel: b.vel,
                        time: scene.start_time,
                    },
                    radius: b.radius,
                    mass: b.effective_mass(),
                    changes: 0,
                })
                .collect(),
            id: (0..n).map(|i| scene.id_of(i)).collect(),
            walls: scene.walls.clone(),
            periodic: scene.periodic,
            restitution: scene.settings.restitution,
            thermostat: scene.settings.thermostat,
            growth: scene.settings.growth.map(|g| GrowthLaw {
                rate: g.rate,
                origin: scene.start_time,
            }),
            now: scene.start_time,
        })
    }

    /// Number of bodies.
    #[must_use]
    pub fn len(&self) -> usize {
        self.bodies.len()
    }

    /// True when there are no bodies.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.bodies.is_empty()
    }

    /// Current simulated time, seconds: every event before it has been resolved.
    #[must_use]
    pub fn now(&self) -> f64 {
        self.now
    }

    pub(crate) fn set_now(&mut self, t: f64) {
        debug_assert!(t >= self.now);
        self.now = t;
    }

    /// The stored state of body `i`: its reference position, velocity and reference time.
    #[must_use]
    #[inline]
    pub fn motion(&self, i: usize) -> Motion<D> {
        self.bodies[i].motion
    }

    /// Position of body `i` at time `t`, metres.
    #[must_use]
    #[inline]
    pub fn position_at(&self, i: usize, t: f64) -> Vector<D> {
        self.motion(i).at(t)
    }

    /// Reference position of body `i`, metres (valid at its reference time [`World::time`]).
    #[must_use]
    #[inline]
    pub fn position(&self, i: usize) -> Vector<D> {
        self.bodies[i].motion.pos
    }

    /// Velocity of body `i`, metres per second.
    #[must_use]
    #[inline]
    pub fn velocity(&self, i: usize) -> Vector<D> {
        self.bodies[i].motion.vel
    }

    /// Reference time of body `i`, seconds: when its stored position holds.
    #[must_use]
    #[inline]
    pub fn time(&self, i: usize) -> f64 {
        self.bodies[i].motion.time
    }

    /// Stored radius of body `i`, metres: its radius at all times, or, in a growing world
    /// (see [`World::growth`]), at the growth's origin.
    #[must_use]
    #[inline]
    pub fn radius(&self, i: usize) -> f64 {
        self.bodies[i].radius
    }

    /// Radius of body `i` at time `t`, metres: the stored radius, grown by the growth law if
    /// the world grows.
    #[must_use]
    #[inline]
    pub fn radius_at(&self, i: usize, t: f64) -> f64 {
        match &self.growth {
            None => self.bodies[i].radius,
            Some(law) => law.radius_at(self.bodies[i].radius, t),
        }
    }

    /// The growth law of a growing world (radii grow linearly in time, see
    /// [`crate::growth`]), or `None` when radii are fixed.
    #[must_use]
    #[inline]
    pub fn growth(&self) -> Option<&GrowthLaw> {
        self.growth.as_ref()
    }

    /// Stops the growth at time `t`: the stored radii become the radii at `t`, and stay.
    /// A finder serving this world must be re-initialised.
    pub fn stop_growth(&mut self, t: f64) {
        if let Some(law) = self.growth.take() {
            for b in &mut self.bodies {
                b.radius = law.radius_at(b.radius, t);
            }
        }
    }

    /// Every body's hot record (stored motion and radius), by body index.
    #[must_use]
    #[inline]
    pub fn bodies(&self) -> &[Body<D>] {
        &self.bodies
    }

    /// Reference positions, metres, by body index (each valid at its body's reference time).
    pub fn positions(&self) -> impl ExactSizeIterator<Item = Vector<D>> + '_ {
        self.bodies.iter().map(|b| b.motion.pos)
    }

    /// Velocities, metres per second, by body index.
    pub fn velocities(&self) -> impl ExactSizeIterator<Item = Vector<D>> + '_ {
        self.bodies.iter().map(|b| b.motion.vel)
    }

    /// Reference times, seconds, by body index.
    pub fn times(&self) -> impl ExactSizeIterator<Item = f64> + '_ {
        self.bodies.iter().map(|b| b.motion.time)
    }

    /// Radii, metres, by body index.
    pub fn radii(&self) -> impl ExactSizeIterator<Item = f64> + '_ {
        self.bodies.iter().map(|b| b.radius)
    }

    /// Mass of body `i`, kilograms.
    #[must_use]
    #[inline]
    pub fn mass(&self, i: usize) -> f64 {
        self.bodies[i].mass
    }

    /// Masses, kilograms, by body index.
    pub fn masses(&self) -> impl ExactSizeIterator<Item = f64> + '_ {
        self.bodies.iter().map(|b| b.mass)
    }

    /// User ids, by body index.
    #[must_use]
    pub fn ids(&self) -> &[u64] {
        &self.id
    }

    /// The static walls.
    #[must_use]
    pub fn walls(&self) -> &[Wall<D>] {
        &self.walls
    }

    /// The sides of the periodic box, for periodic worlds (see [`crate::periodic`]).
    #[must_use]
    pub fn periodic(&self) -> Option<Vector<D>> {
        self.periodic
    }

    /// Coefficient of restitution used for every collision.
    #[must_use]
    pub fn restitution(&self) -> f64 {
        self.restitution
    }

    /// The scene's Andersen thermostat, if any.
    #[must_use]
    pub fn thermostat(&self) -> Option<&crate::thermostat::Thermostat> {
        self.thermostat.as_ref()
    }

    /// How many times body `i`'s stored state has been replaced; a cached prediction about
    /// body `i` is still valid while this count is unchanged.
    #[must_use]
    #[inline]
    pub fn change_count(&self, i: usize) -> u64 {
        self.bodies[i].changes
    }

    /// Replaces body `i`'s state: position `pos` holding at time `t`, velocity `vel`.
    pub(crate) fn set_state(&mut self, i: usize, pos: Vector<D>, vel: Vector<D>, t: f64) {
        let b = &mut self.bodies[i];
        b.motion = Motion { pos, vel, time: t };
        b.changes += 1;
    }

    /// Replaces body `i`'s stored state with `motion`, for tools that rebuild a world from a
    /// record (a viewer restoring the state at some instant from a run file). A running
    /// [`Simulation`](crate::Simulation) only lends its world immutably, so this cannot
    /// desynchronise a simulation from its finder; a finder serving this world must be told
    /// through [`Finder::update`](crate::Finder::update) or re-initialised.
    pub fn set_motion(&mut self, i: usize, motion: Motion<D>) {
        self.set_state(i, motion.pos, motion.vel, motion.time);
    }

    /// Sets the current simulated time, seconds, for tools that rebuild a world at a given
    /// instant (see [`World::set_motion`]); the caller promises that no event lies between the
    /// stored states' times and `t`.
    pub fn set_time(&mut self, t: f64) {
        self.now = t;
    }

    /// Multiplies every velocity by `factor` at the current time: each body's stored position
    /// moves to now. A finder serving this world must be re-initialised.
    pub fn scale_velocities(&mut self, factor: f64) {
        let now = self.now;
        for i in 0..self.bodies.len() {
            let m = self.bodies[i].motion;
            self.set_state(i, m.at(now), m.vel * factor, now);
        }
    }

    /// Total kinetic energy, joules.
    #[must_use]
    pub fn kinetic_energy(&self) -> f64 {
        self.bodies
            .iter()
            .map(|b| 0.5 * b.mass * b.motion.vel.norm_sq())
            .sum()
    }

    /// Total momentum, kg·m/s.
    #[must_use]
    pub fn momentum(&self) -> Vector<D> {
        self.bodies
            .iter()
            .fold(Vector::ZERO, |acc, b| acc + b.motion.vel * b.mass)
    }
}
