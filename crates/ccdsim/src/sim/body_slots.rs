//! Bodies added to and removed from a running simulation, in slots whose indices stay put.
//!
//! A body's index is its handle: it names the same body until the body is removed. Removing
//! a body leaves its slot *vacant* ([`World::is_vacant`]): a kinematic ball at rest that
//! collides with nothing, which every finder, like the oracle, passes by. Adding a body fills
//! the most recently vacated slot; when none is left the world appends a quarter more slots
//! (at least one), vacant, parked among the bodies, and the finder is re-initialised once,
//! so adding `k` bodies costs O(log k) re-initialisations in all. Every other add and every
//! remove is one [`Finder::update`](crate::Finder::update) of one body, plus O(n) for the
//! overlap check; a finder is also re-initialised when the world's laws change (the first
//! removal, or the first body with its own restitution) or when an added body is larger than
//! the finder was sized for.

use super::{SimError, Simulation};
use crate::edit::Edit;
use crate::geom::Vector;
use crate::scene::BodySpec;
use crate::sensor::sensor_fits_box;
use crate::world::World;

/// How many vacant slots the world appends when a body is added and none is left, to `n`
/// slots: a quarter more, at least one. (`verify` follows the thermostat's draws over them.)
pub(crate) fn reserve_count(n: usize) -> usize {
    (n / 4).max(1)
}

/// The largest radius a body may take in a vacant slot without the finder being
/// re-initialised: the second-largest radius of the slots when it was. (A grid sized for
/// contact distance `r₁ + r₂` of the two largest radii still covers every pair then.)
pub(super) fn sized_radius<const D: usize>(world: &World<D>) -> f64 {
    world.two_largest_radii().1
}

impl<const D: usize> Simulation<D> {
    /// Adds the body `spec` at the current time (its `pos` and `vel` hold now) and returns
    /// its index, which names it until it is removed. Its id is `spec.id`, or the next id
    /// above every id so far ([`World::next_id`]).
    ///
    /// Refused, leaving everything as it was, when a field is invalid (as in a scene), the id
    /// is taken, the body would overlap a body it collides with, cross a wall or lie outside
    /// the table (as for [`Simulation::set_position`]) or the periodic box, or it is too large
    /// for a sensor in the periodic box (`2·(R + r) < L` on every axis, as scenes require, see
    /// [`crate::sensor::sensor_fits_box`]). See the module docs for the cost.
    ///
    /// With growing radii, `spec.radius` is the body's radius now: it grows from now on like
    /// every other (its stored radius, that at the growth's origin, is `spec.radius` divided
    /// by the growth factor now). With a thermostat, the body takes resets from now on unless
    /// it is kinematic (see [`crate::thermostat`]).
    ///
    /// ```
    /// use ccdsim::{BodySpec, Scene, Simulation, Vector};
    /// let mut sim = Simulation::<2>::new(&Scene::default(), "cells").unwrap();
    /// let a = sim.add_body(BodySpec::new(Vector([0.0, 0.0]), Vector([1.0, 0.0]), 0.5)).unwrap();
    /// let b = sim.add_body(BodySpec::new(Vector([3.0, 0.0]), Vector([-1.0, 0.0]), 0.5)).unwrap();
    /// let hit = sim.step_event().unwrap();
    /// assert_eq!((hit.event.time, hit.event.a as usize, hit.event.b as usize), (1.0, a, b));
    /// sim.remove_body(a).unwrap();
    /// assert_eq!(sim.world().body_count(), 1);
    /// assert!(sim.step_event().is_none()); // b flies off alone
    /// ```
    pub fn add_body(&mut self, spec: BodySpec<D>) -> Result<usize, SimError> {
        let slot = self.world.free_slot().unwrap_or(self.world.len());
        spec.check_fields(slot)
            .map_err(|e| SimError::Input(format!("add_body: {e}")))?;
        if spec.is_rotational() {
            return Err(SimError::Input(
                "add_body: an added body starts without spin and with the scene's inertia \
                 factor and tangential restitution (run files do not record them): leave its \
                 `spin`, `inertia` and `tangential_restitution` out"
                    .into(),
            ));
        }
        if let (Some(size), Some(sensors)) = (self.world.periodic(), &self.sensors) {
            // A body larger than the scene's could overlap two images of a sensor.
            for (k, sensor) in sensors.sensors().iter().enumerate() {
                sensor_fits_box(sensor.radius, spec.radius, "the added body's radius", &size)
                    .map_err(|why| SimError::Input(format!("add_body: sensors[{k}]: {why}")))?;
            }
        }
        let id = spec.id.unwrap_or(self.world.next_id());
        if let Some(j) = self.world.index_of(id) {
            return Err(SimError::Input(format!(
                "add_body: id {id} is taken by body {j}"
            )));
        }
        let what = format!("the added body (slot {slot})");
        if let Some(why) =
            self.placement_error(&what, spec.pos, spec.vel, spec.radius, spec.kinematic)
        {
            return Err(SimError::Input(format!("add_body: {why}")));
        }
        let filter = spec.filter();
        if let Some(j) =
            self.overlapped_by(usize::MAX, spec.pos, spec.radius, spec.kinematic, |j| {
                filter.collides(&self.world.filter(j))
            })
        {
            return Err(SimError::Input(format!(
                "add_body: {what} at {:?} would overlap body {j}",
                spec.pos.0
            )));
        }
        self.judge_due_resets();
        let laws = self.world.laws().copied();
        let appended = self.world.free_slot().is_none();
        let now = self.world.now();
        if appended {
            let n = self.world.len();
            let count = reserve_count(n);
            let world = &self.world;
            // Parked among the bodies, one per body at most, so that no cell of a grid
            // finder fills up with them.
            let park: Vec<(Vector<D>, f64)> = (0..count)
                .map(|k| {
                    if n == 0 {
                        (spec.pos, spec.radius)
                    } else {
                        let j = k % n;
                        (world.position_at(j, now), world.radius(j))
                    }
                })
                .collect();
            self.world.reserve(count, |k| park[k]);
            self.images.resize(self.world.len());
            if let Some(clock) = &mut self.thermostat {
                clock.grow(self.world.len(), now);
            }
        }
        // Growing radii: the stored radius is the one at the growth's origin.
        let stored = BodySpec {
            radius: self
                .world
                .growth()
                .map_or(spec.radius, |law| spec.radius / law.scale(now)),
            ..spec
        };
        let i = self.world.occupy(&stored, id);
        if self.images.is_counting() {
            self.images.set(i, [0; D]);
        }
        if !spec.kinematic {
            self.free_bodies += 1;
            self.guard
                .add_energy(0.5 * self.world.mass(i) * spec.vel.norm_sq());
        }
        if let Some(s) = &mut self.sensors {
            s.resize(self.world.len());
        }
        self.journal(Edit::Add {
            body: i,
            id,
            pos: spec.pos,
            vel: spec.vel,
            radius: stored.radius,
            mass: self.world.mass(i),
            filter,
            restitution: spec.restitution,
        });
        if appended || laws != self.world.laws().copied() || stored.radius > self.sized_radius {
            self.rebuild()?;
        } else {
            self.edited(i);
        }
        Ok(i)
    }

    /// Removes body `i` at the current time: it stops where it is and its slot becomes
    /// vacant (a later [`Simulation::add_body`] may fill it); every other body keeps its
    /// index. A body inside a sensor leaves it now. Refused for an index that names no body.
    pub fn remove_body(&mut self, i: usize) -> Result<(), SimError> {
        self.check_body(i)?;
        self.judge_due_resets();
        if !self.world.is_kinematic(i) {
            self.free_bodies -= 1;
        }
        let laws = self.world.laws().copied();
        self.world.vacate(i);
        if self.images.is_counting() {
            self.images.set(i, [0; D]);
        }
        self.journal(Edit::Remove {
            body: i,
            pos: self.world.position(i),
        });
        if laws != self.world.laws().copied() {
            return self.rebuild();
        }
        self.edited(i);
        Ok(())
    }
}
