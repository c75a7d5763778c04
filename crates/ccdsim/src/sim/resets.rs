//! The thermostat's velocity resets in a running simulation (see [`crate::thermostat`]): a
//! reset of a body that moves freely is an event; a draw naming a kinematic body or a vacant
//! slot is passed over when the clock reaches it, like a box exit, and leaves no trace.

use super::{Collision, Simulation};
use crate::event::{Event, EventKind};
use crate::geom::Vector;

impl<const D: usize> Simulation<D> {
    /// True for a thermostat draw that resets nothing: its slot holds a kinematic body or
    /// none.
    #[inline(always)]
    pub(super) fn is_void_reset(&self, e: &Event) -> bool {
        e.kind == EventKind::Reset && self.world.is_kinematic(e.a as usize)
    }

    /// Passes over the void draw due at `time`: the clock, and the current time, reach it.
    /// Out of line: drawing is long, and the event loop stays as tight as it was without it.
    #[cold]
    #[inline(never)]
    pub(super) fn skip_reset(&mut self, time: f64) {
        self.world.set_now(time.max(self.world.now()));
        if let Some(clock) = &mut self.thermostat {
            clock.skip();
        }
    }

    /// Before an edit: passes over the void draws due by now, so that a slot filled now takes
    /// no reset drawn for it while it was empty (`verify` judges them in the same order).
    pub(super) fn judge_due_resets(&mut self) {
        let now = self.world.now();
        while let Some(clock) = &mut self.thermostat {
            if clock.next_time() > now || !self.world.is_kinematic(clock.next_body()) {
                break;
            }
            clock.skip();
        }
    }

    /// Applies the thermostat's next reset (at `time`, the current time now).
    pub(super) fn apply_reset(&mut self, time: f64) -> Collision<D> {
        let clock = self
            .thermostat
            .as_mut()
            .expect("resets come from a thermostat");
        let i = clock.next_body();
        let mut reset = clock.take::<D>(self.world.mass(i));
        debug_assert_eq!((reset.time, reset.body), (time, i));
        let p = self.world.position_at(i, time);
        if let Some(bx) = self.world.shear() {
            // In a sheared box the draw is the peculiar velocity: the flow is added.
            reset.velocity[0] += bx.flow(p[1]);
        }
        let added = 0.5
            * self.world.mass(i)
            * (reset.velocity.norm_sq() - self.world.velocity_at(i, time).norm_sq());
        self.guard.add_energy(added);
        self.world.set_state(i, p, reset.velocity, time);
        self.bodies_changed(&[i]);
        self.sensors_changed(i);
        // The world changed: an earlier halt may no longer hold.
        self.halt = None;
        self.stats.resets += 1;
        Collision {
            event: Event::reset(time, i),
            pos: [p, Vector::ZERO],
            vel: [reset.velocity, Vector::ZERO],
            rests: [false; 2],
            pivots: [false; 2],
        }
    }
}
