//! The replay of edits that add and remove bodies or change their collision filters (see
//! [`crate::edit`]).
//!
//! A removed body's slot becomes what the simulation keeps there: a kinematic ball at rest
//! that meets nothing and counts for nothing in the energy sums. An added body fills a vacant
//! slot, or a slot past the last one (the slots between, which the simulation reserved, are
//! vacant). Added bodies must not overlap a body they collide with, cross a wall or lie
//! outside a closed table; the energy an edit brings in or takes out (kinetic and, under
//! gravity, potential) is counted in the report's `edit_energy`, like a motion edit's.

use super::{Verifier, Violation};
use crate::collision_filter::CollisionFilter;
use crate::edit::Edit;
use crate::event::EventKind;
use crate::geom::Vector;
use crate::motion::Motion;
use crate::sim::Collision;

impl<const D: usize> Verifier<D> {
    fn is_vacant(&self, i: usize) -> bool {
        self.vacant.get(i).copied().unwrap_or(false)
    }

    /// Kinetic plus potential energy of body `i` at `t`, joules (zero for a kinematic body).
    fn body_energy(&self, i: usize, t: f64) -> f64 {
        let m = self.mass[i];
        let potential = self.g(i).map_or(0.0, |g| -m * g.dot(self.pos_of(i, t)));
        let rotation = self
            .spins
            .as_ref()
            .map_or(0.0, |s| s.energy(i, m, self.radius_at(i, t)));
        0.5 * m * self.vel_of(i, t).norm_sq() + potential + rotation
    }

    /// An edit record other than an added body's (those go to `check_add`): a new motion,
    /// a removal or a new filter of body `i`, checked before its state is replaced.
    pub(super) fn check_slot_edit(&mut self, c: &Collision<D>, i: usize) -> Result<(), Violation> {
        let t = c.event.time;
        if self.is_vacant(i) {
            return Err(self.fail(t, format!("an edit of body {i}, whose slot is vacant")));
        }
        match Edit::decode(c, None).map_err(|why| self.fail(t, why))? {
            Edit::Motion { .. } => self.check_edit(c, i),
            Edit::Remove { .. } => {
                if c.vel[0] != Vector::ZERO {
                    return Err(self.fail(t, format!("removed body {i} keeps moving")));
                }
                self.report.edits += 1;
                self.report.edit_energy -= self.body_energy(i, t);
                self.make_vacant(i);
                Ok(())
            }
            Edit::Filter { filter, .. } => {
                if self.filters.is_empty() {
                    self.filters = vec![CollisionFilter::DEFAULT; self.motion.len()];
                }
                self.filters[i] = filter;
                self.check_edit(c, i)
            }
            Edit::Add { .. } => unreachable!("added bodies go to check_add"),
            Edit::WallMotion { .. } => unreachable!("wall edits go to check_wall_motion"),
        }
    }

    /// Slot `i` becomes vacant: a kinematic ball that meets nothing and has no energy.
    fn make_vacant(&mut self, i: usize) {
        let n = self.motion.len();
        if self.kinematic.is_empty() {
            self.kinematic = vec![false; n];
        }
        if self.filters.is_empty() {
            self.filters = vec![CollisionFilter::DEFAULT; n];
        }
        self.vacant.resize(n, false);
        self.kinematic[i] = true;
        self.filters[i] = CollisionFilter::NONE;
        self.mass[i] = 0.0;
        self.vacant[i] = true;
        if let Some(spins) = &mut self.spins {
            spins.vacate(i);
        }
    }

    /// The records of an added body: the first is kept until its id record follows, then
    /// the body is checked and put in its slot.
    pub(super) fn check_add(&mut self, c: &Collision<D>) -> Result<(), Violation> {
        let t = c.event.time;
        if !t.is_finite() || t < self.last_time {
            return Err(self.fail(
                t,
                format!("time goes backwards (previous event at {})", self.last_time),
            ));
        }
        let Some(first) = self.pending_add.take() else {
            self.pending_add = Some(*c);
            self.report.events += 1;
            return Ok(());
        };
        let edit = Edit::decode(&first, Some(c)).map_err(|why| self.fail(t, why))?;
        let Edit::Add {
            body: i,
            pos,
            vel,
            radius,
            mass,
            filter,
            restitution,
            ..
        } = edit
        else {
            unreachable!("the first record starts an added body");
        };
        // A body with its own restitution may leave walls slower: the bound resting checks
        // (see `check_rests`) takes it in.
        if let Some(e) = restitution {
            self.least_restitution = self.least_restitution.min(e);
        }
        self.restitutions.add(i, restitution);
        let valid = radius.is_finite() && radius > 0.0 && mass > 0.0 && vel.is_finite();
        if !valid {
            return Err(self.fail(
                t,
                format!("body {i} is added with radius {radius}, mass {mass}, velocity {vel:?}"),
            ));
        }
        let n = self.motion.len();
        // Past the last slot, the simulation appended `reserve_count` slots (vacant but the
        // first), and the thermostat draws over all of them from now on.
        let slots = if i < n {
            n
        } else {
            (i + 1).max(n + crate::sim::reserve_count(n))
        };
        if let Some(clock) = self.resets.as_mut().filter(|_| slots > n) {
            clock.grow(slots, t);
        }
        while self.motion.len() < slots {
            // Slots the simulation reserved: vacant until filled.
            let k = self.motion.len();
            self.motion.push(Motion {
                pos,
                vel: Vector::ZERO,
                time: t,
            });
            self.radius.push(radius);
            self.mass.push(0.0);
            if !self.kinematic.is_empty() {
                self.kinematic.push(true);
            }
            if !self.filters.is_empty() {
                self.filters.push(CollisionFilter::NONE);
            }
            if self.rest_speed.is_some() {
                self.supports.push(None);
                self.pivots.push(None);
            }
            if let Some(grid) = &mut self.grid {
                grid.resize(k + 1);
            }
            if let Some(spins) = &mut self.spins {
                spins.push();
            }
            self.make_vacant(k);
        }
        if !self.is_vacant(i) {
            return Err(self.fail(t, format!("a body is added in slot {i}, which holds one")));
        }
        self.advance_slabs(t)?;
        self.vacant[i] = false;
        let kinematic = mass == f64::INFINITY;
        self.kinematic[i] = kinematic;
        self.filters[i] = filter;
        self.radius[i] = radius;
        self.mass[i] = if kinematic { 0.0 } else { mass };
        self.motion[i] = Motion { pos, vel, time: t };
        self.check_placement(i, pos, t)?;
        self.report.edits += 1;
        self.report.edit_energy += self.body_energy(i, t);
        self.refile(i, t);
        self.last_time = t;
        self.report.events += 1;
        debug_assert_eq!(c.event.kind, EventKind::Edit);
        Ok(())
    }
}
