//! The replay of moving walls (see [`crate::world::time_of_impact`]): where each is, the miss check
//! of a body against one, and the edits that give one a new velocity.
//!
//! A moving wall's contact with a body is checked like a static wall's, in the wall's frame:
//! the body's motion relative to it (velocity less the wall's) against the wall where it is
//! at the start of the stretch (with growing radii, less what the radius grew by since). An
//! elastic collision keeps the body's kinetic energy in that frame, and under growth the
//! collision obeys the growth rule there; in the lab frame the wall does work, which the
//! report sums in `wall_work`.

use super::{beyond, Verifier, Violation, OVERLAP_TOLERANCE};
use crate::motion::Motion;
use crate::motion::{translated, WallMotion};
use crate::sim::Collision;
use crate::wall::Wall;

impl<const D: usize> Verifier<D> {
    /// Number of walls, static and moving: wall events name indices below it.
    pub(super) fn wall_count(&self) -> usize {
        self.walls.len() + self.moving.len()
    }

    /// Wall `w` (moving from `walls.len()` on) where it is at `t`, with its velocity then.
    pub(super) fn wall_at(&self, w: usize, t: f64) -> (Wall<D>, crate::geom::Vector<D>) {
        match w.checked_sub(self.walls.len()) {
            None => (self.walls[w], crate::geom::Vector::ZERO),
            Some(k) => {
                let m = self.wall_motion[k];
                (translated(&self.moving[k], m.offset_at(t)), m.velocity)
            }
        }
    }

    /// Body `i`'s motion relative to wall `w` from the later of their reference times (its
    /// own time for a static wall), with the wall where it is then.
    pub(super) fn motion_against(&self, i: usize, w: usize) -> (Motion<D>, Wall<D>) {
        let mi = self.motion[i];
        let Some(k) = w.checked_sub(self.walls.len()) else {
            return (mi, self.walls[w]);
        };
        let wm = self.wall_motion[k];
        let t0 = mi.time.max(wm.time);
        let relative = Motion {
            pos: self.pos_of(i, t0),
            vel: self.vel_of(i, t0) - wm.velocity,
            time: t0,
        };
        (relative, translated(&self.moving[k], wm.offset_at(t0)))
    }

    /// An edit record giving moving wall `a` a new velocity: its recorded displacement must
    /// follow from its motion so far, and no body may have crossed it before.
    pub(super) fn check_wall_motion(&mut self, c: &Collision<D>) -> Result<(), Violation> {
        let (t, k) = (c.event.time, c.event.a as usize);
        if !t.is_finite() || t < self.last_time {
            return Err(self.fail(
                t,
                format!("time goes backwards (previous event at {})", self.last_time),
            ));
        }
        let Some(&wm) = self.wall_motion.get(k) else {
            return Err(self.fail(
                t,
                format!(
                    "an edit of moving wall {k} in a scene of {}",
                    self.moving.len()
                ),
            ));
        };
        let expect = wm.offset_at(t);
        let scale = 1.0 + expect.norm() + wm.velocity.norm() * (t - wm.time).abs();
        let off = (c.pos[0] - expect).norm();
        if beyond(off, 1e-9 * scale) || !expect.is_finite() {
            return Err(self.fail(
                t,
                format!(
                    "moving wall {k} recorded displaced by {:?}, its motion displaces it by {:?}",
                    c.pos[0].0, expect.0
                ),
            ));
        }
        if !c.vel[0].is_finite() {
            return Err(self.fail(t, format!("moving wall {k} gets a non-finite velocity")));
        }
        let w = self.walls.len() + k;
        for i in 0..self.motion.len() {
            if self.is_kinematic(i) {
                continue;
            }
            let (overlap, at) = self.wall_overlap(i, w, t);
            if beyond(overlap, OVERLAP_TOLERANCE) {
                return Err(self.fail(
                    t,
                    format!(
                        "body {i} crosses wall {w} by {overlap:e} of its radius at t = {at} \
                         (a missed collision)"
                    ),
                ));
            }
            self.report.max_overlap = self.report.max_overlap.max(overlap);
        }
        self.wall_motion[k] = WallMotion {
            offset: c.pos[0],
            velocity: c.vel[0],
            time: t,
        };
        self.report.edits += 1;
        self.report.events += 1;
        self.last_time = t;
        Ok(())
    }
}
