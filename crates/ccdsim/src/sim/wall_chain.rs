//! Under gravity: the run of wall events of one body that the clock cannot tell apart as
//! motion, which ends the run with [`Halt::Resting`](crate::Halt::Resting) once it is long.
//!
//! Bounces on a floor that die away come ever closer in time. Exactly they would end after
//! infinitely many; in `f64` they end in one of two ways. Either the speed reaches zero and
//! the same contact repeats at one instant (the `idle` check of the simulation), or the clock
//! quantises the flights: a hop of a few ulps of time is rounded to whole ulps, and that
//! rounding can feed back as much speed as the restitution takes, so the hops settle at a
//! fixed point and go on for ever, each a few ulps later (a ball of restitution 0.9 on a
//! floor: a normal speed of 1.65·10⁻¹⁴ m/s, 4 ulps of time a hop, at t ≈ 7.2 s, for ever).
//! Neither is motion the simulation resolves: a hop lasting `Δt` rises at most `|g|·Δt²/8`,
//! and below [`RESOLUTION_LIMIT`] of the body's radius the run halts with
//! [`Halt::Resolution`](crate::Halt::Resolution) elsewhere too. So a chain counts the wall
//! events of one body in a row that come at the very instant of the one before (a body
//! wedged between two walls alternates between them), or off the same wall after such an
//! unresolved hop; past [`WEDGED_AFTER`] of them the body rests. The chain depends on the
//! events alone, so every finder halts at the same one.

use crate::event::{Event, EventKind};
use crate::resolution::RESOLUTION_LIMIT;

/// How many wall events of one body in a row at one instant, or after hops too low to
/// resolve (under gravity), end the run ([`Halt::Resting`](crate::Halt::Resting)): bounces
/// in a wedge whose walls do not hold it die away geometrically, each halving its speed or
/// so, so a thousand take any speed below the smallest float.
pub const WEDGED_AFTER: u32 = 1000;

/// The current chain of unresolved wall events (see the module docs).
#[derive(Clone, Copy, Debug)]
pub(crate) struct WallChain {
    /// Time of the chain's last event, seconds (NaN: no chain).
    time: f64,
    body: u32,
    wall: u32,
    count: u32,
}

impl WallChain {
    /// No chain.
    pub(crate) const NONE: Self = WallChain {
        time: f64::NAN,
        body: 0,
        wall: 0,
        count: 0,
    };

    /// True when wall event `e` continues the chain: the same body as its last event, at the
    /// same instant, or off the same wall after a hop no higher than `gravity·Δt²/8` below
    /// [`RESOLUTION_LIMIT`] of `radius` (metres; `gravity` is `|g|`, m/s²).
    pub(crate) fn continues(&self, e: &Event, gravity: f64, radius: f64) -> bool {
        if e.kind != EventKind::Wall || e.a != self.body {
            return false;
        }
        let gap = e.time - self.time;
        gap == 0.0 || (e.b == self.wall && gravity * gap * gap < 8.0 * RESOLUTION_LIMIT * radius)
    }

    /// Takes in wall event `e` (of a body of radius `radius`, under gravity `|g|`, see
    /// [`WallChain::continues`]): it continues the chain or starts a new one.
    pub(crate) fn note(&mut self, e: &Event, gravity: f64, radius: f64) {
        let count = if self.continues(e, gravity, radius) {
            self.count + 1
        } else {
            1
        };
        *self = WallChain {
            time: e.time,
            body: e.a,
            wall: e.b,
            count,
        };
    }

    /// True when the chain is long enough to end the run if `e` continues it.
    #[inline]
    pub(crate) fn is_long(&self) -> bool {
        self.count >= WEDGED_AFTER
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn wall(time: f64, a: u32, b: u32) -> Event {
        Event {
            time,
            kind: EventKind::Wall,
            a,
            b,
        }
    }

    #[test]
    fn hops_too_low_to_resolve_make_a_chain_and_real_ones_do_not() {
        let (g, r) = (9.81, 0.5);
        let mut c = WallChain::NONE;
        let mut t = 7.231_067_016_504_777_f64;
        for k in 0..WEDGED_AFTER {
            c.note(&wall(t, 3, 0), g, r);
            assert_eq!(c.is_long(), k + 1 == WEDGED_AFTER);
            // 4 ulps later: a hop of 3.6e-15 s, 1.6e-29 m high.
            t = f64::from_bits(t.to_bits() + 4);
        }
        assert!(c.continues(&wall(t, 3, 0), g, r));
        // Another body, another wall after a gap, or a hop of a millisecond (1.2 µm high): no.
        assert!(!c.continues(&wall(t, 4, 0), g, r));
        assert!(!c.continues(&wall(t, 3, 1), g, r));
        assert!(!c.continues(&wall(t + 1e-3, 3, 0), g, r));
        // At the very instant, any wall (a wedge): yes.
        let last = f64::from_bits(t.to_bits() - 4);
        assert!(c.continues(&wall(last, 3, 7), g, r));
        c.note(&wall(t + 1e-3, 3, 0), g, r);
        assert!(!c.is_long());
    }

    #[test]
    fn the_resolution_limit_sets_the_longest_unresolved_hop() {
        // |g|·Δt²/8 < 5e-10·r: Δt < 2e-5 s for g = 10, r = 1.
        let mut c = WallChain::NONE;
        c.note(&wall(1.0, 0, 0), 10.0, 1.0);
        assert!(c.continues(&wall(1.0 + 1.9e-5, 0, 0), 10.0, 1.0));
        assert!(!c.continues(&wall(1.0 + 2.1e-5, 0, 0), 10.0, 1.0));
        assert!(!WallChain::NONE.continues(&wall(1.0, 0, 0), 10.0, 1.0));
    }
}
