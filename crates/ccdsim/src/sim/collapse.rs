//! Inelastic collapse: bodies that lose relative speed at every collision (restitution below 1)
//! and, without the TC model (`settings.tc`), collide ever faster until infinitely many
//! collisions would come in a finite time (McNamara & Young). Exactly, the run would never get
//! past that time; in `f64` it goes on at one instant or a few ulps apart, writing events
//! without end (a restitution-0 gas wrote 3.1 GB in 90 s).
//!
//! The watch counts each body's body–body collisions in windows of
//! [`COLLAPSE_COLLISIONS`]; when a window closes within [`COLLAPSE_SPAN`] of the mean free
//! time (the run's so far, `(t − t₀) · N / (2 · collisions)`), the run halts
//! ([`Halt::InelasticCollapse`]) after that collision. A gas at any density collides at rates
//! within a few times the mean; a million times the mean over a thousand collisions is a
//! collapse. The watch is on only where a collapse can happen (some restitution below 1, no
//! `settings.tc`), and it depends on the events alone, so every finder halts at the same one.

use crate::halt::Halt;
use crate::world::World;

/// Body–body collisions of one body per window of the watch.
pub const COLLAPSE_COLLISIONS: u32 = 1000;

/// A window of [`COLLAPSE_COLLISIONS`] collisions lasting at most this fraction of the mean
/// free time is a collapse.
pub const COLLAPSE_SPAN: f64 = 1e-6;

/// Each body's current window: its start time and the collisions in it.
#[derive(Clone, Debug, Default)]
pub(crate) struct CollapseWatch {
    start: Vec<f64>,
    count: Vec<u32>,
}

impl CollapseWatch {
    /// A watch for `world`, or `None` where no collapse can happen: every restitution is 1,
    /// or the TC model makes collisions closer than `tc` apart elastic.
    pub(crate) fn new<const D: usize>(world: &World<D>) -> Option<Self> {
        let inelastic =
            world.restitution() < 1.0 || (0..world.len()).any(|i| world.body_restitution(i) < 1.0);
        (inelastic && world.tc().is_none()).then(Self::default)
    }

    /// Body `i` collided with a body at `t`; `mean_free_time` gives the run's mean free time
    /// so far. Returns the collapse halt when its window closes too soon.
    pub(crate) fn note(
        &mut self,
        i: usize,
        t: f64,
        mean_free_time: impl FnOnce() -> f64,
    ) -> Option<Halt> {
        if i >= self.count.len() {
            self.count.resize(i + 1, 0);
            self.start.resize(i + 1, 0.0);
        }
        if self.count[i] == 0 {
            self.start[i] = t;
        }
        self.count[i] += 1;
        if self.count[i] < COLLAPSE_COLLISIONS {
            return None;
        }
        self.count[i] = 0;
        let span = t - self.start[i];
        let tau = mean_free_time();
        (span <= COLLAPSE_SPAN * tau).then_some(Halt::InelasticCollapse {
            time: t,
            body: i,
            collisions: COLLAPSE_COLLISIONS,
            span,
            mean_free_time: tau,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_thousand_collisions_in_a_vanishing_span_halt() {
        let mut w = CollapseWatch::default();
        let mut halt = None;
        for k in 0..COLLAPSE_COLLISIONS {
            assert!(halt.is_none(), "halted early, at {k}");
            halt = w.note(3, 5.0 + f64::from(k) * 1e-12, || 1.0);
        }
        let Some(Halt::InelasticCollapse { body, time, .. }) = halt else {
            panic!("{halt:?}")
        };
        assert_eq!(body, 3);
        assert!(time > 5.0);
    }

    #[test]
    fn collisions_at_the_mean_rate_never_halt() {
        let mut w = CollapseWatch::default();
        for k in 0..10 * COLLAPSE_COLLISIONS {
            // A thousand times the mean rate, for ten windows.
            assert!(w.note(0, f64::from(k) * 1e-3, || 1.0).is_none());
        }
    }
}
