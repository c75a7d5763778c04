//! When a ball on the cloth next meets another ball, a cushion, a jaw or a pocket: pure
//! functions of the balls' stored states.
//!
//! In each motion state a ball's centre moves on a parabola, `p + v·t + ½·a·t²` with a
//! constant acceleration (see [`crate::motion::cloth`]), until its state ends. Two balls meet at
//! a root of a quartic and a ball meets a jaw or drops into a pocket at a root of a quartic
//! too: the certified first root of [`first_contact_accelerating`], the routine gravity's
//! contacts use. A ball meets a straight cushion where its distance from the cushion's line
//! falls to one radius (a quadratic, solved without cancellation) with the foot of the
//! perpendicular on the segment. A root later than the end of either ball's state is no
//! contact: the state change comes first and the contact is looked for again after it.

use super::table::{Jaw, LinearCushion, Pocket};
use crate::contact::accelerated_contact::first_contact_accelerating;
use crate::contact::quadratic::crossing;
use crate::geom::{Aabb, Vector};
use crate::motion::{ClothBall, ClothParams, ClothState};

/// A ball's path in its current state: where it is at `time`, its velocity and its constant
/// acceleration, and when the state ends (seconds; infinite for a ball at rest).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Flight {
    /// Position at `time`, metres.
    pub pos: Vector<2>,
    /// Velocity at `time`, m/s.
    pub vel: Vector<2>,
    /// Acceleration while the state lasts, m/s².
    pub acc: Vector<2>,
    /// Start of the flight, seconds.
    pub time: f64,
    /// When the state ends, seconds.
    pub end: f64,
}

impl Flight {
    /// The flight of `ball` in `state` from `time` until `end`.
    #[must_use]
    pub fn new(
        cloth: &ClothParams,
        ball: &ClothBall,
        state: ClothState,
        time: f64,
        end: f64,
    ) -> Self {
        Flight {
            pos: ball.pos,
            vel: ball.vel,
            acc: cloth.acceleration(ball, state),
            time,
            end,
        }
    }

    /// Whether the ball moves at all (a spinning or stationary ball does not).
    #[must_use]
    pub fn moves(&self) -> bool {
        self.vel != Vector::ZERO || self.acc != Vector::ZERO
    }

    /// How far the ball can get from where it is `dt0` seconds into the flight before `until`
    /// (seconds, absolute), metres, an upper bound with room for rounding: speed times time
    /// plus half the acceleration times time squared. Infinite for a flight that never ends.
    #[must_use]
    fn reach(&self, dt0: f64, until: f64) -> f64 {
        let span = until - self.time - dt0;
        if !span.is_finite() {
            return f64::INFINITY;
        }
        let span = span.max(0.0);
        let speed = (self.vel + self.acc * dt0).norm();
        (speed * span + 0.5 * self.acc.norm() * span * span) * (1.0 + 1e-9)
    }

    /// The box a ball of radius `radius` (m) sweeps over the whole flight, metres, padded for
    /// rounding: no contact function of this module finds a contact between two flights, or a
    /// flight and a table part ([`super::table::LinearCushion::bounds`] and the like), whose
    /// boxes do not overlap. Infinite for a moving flight that never ends.
    ///
    /// The centre stays within [`Flight::reach`] of `pos` (with its relative room of 10⁻⁹),
    /// and the box adds another 10⁻⁹ of the lengths involved: the contact functions'
    /// rounding is of order ε times those, and a certified root lies where the computed
    /// distance equals the contact distance.
    #[must_use]
    pub fn swept_box(&self, radius: f64) -> Aabb<2> {
        let reach = if self.moves() {
            self.reach(0.0, self.end)
        } else {
            0.0
        };
        let extent = radius + reach;
        let half = extent + SWEEP_PAD * (extent + self.pos[0].abs().max(self.pos[1].abs()));
        if half < f64::INFINITY {
            Aabb::of_ball(self.pos, half)
        } else {
            Aabb {
                min: Vector::splat(f64::NEG_INFINITY),
                max: Vector::splat(f64::INFINITY),
            }
        }
    }

    /// Position and velocity `dt` seconds after the flight's start.
    #[must_use]
    fn after(&self, dt: f64) -> (Vector<2>, Vector<2>) {
        (
            self.pos + self.vel * dt + self.acc * (0.5 * dt * dt),
            self.vel + self.acc * dt,
        )
    }
}

/// Room a swept box leaves for rounding, relative to the lengths involved.
const SWEEP_PAD: f64 = 1e-9;

/// The time (seconds) two balls of radius `radius` (m) on these flights first touch while
/// approaching, if that is before either flight ends. Both are taken to the later of their
/// start times first, so the answer depends on the two flights alone.
#[must_use]
pub fn ball_ball(a: &Flight, b: &Flight, radius: f64) -> Option<f64> {
    if !a.moves() && !b.moves() {
        return None;
    }
    let t0 = a.time.max(b.time);
    let (pa, va) = a.after(t0 - a.time);
    let (pb, vb) = b.after(t0 - b.time);
    // Too far apart to meet before either flight ends: no quartic to solve.
    let until = a.end.min(b.end);
    let gap = (pb - pa).norm() - 2.0 * radius;
    if gap > 0.0 && gap * (1.0 - 1e-9) > a.reach(t0 - a.time, until) + b.reach(t0 - b.time, until) {
        return None;
    }
    let dt = first_contact_accelerating(pb - pa, vb - va, b.acc - a.acc, 2.0 * radius)?;
    let t = t0 + dt;
    (t <= a.end.min(b.end)).then_some(t)
}

/// The time (seconds) a ball of radius `radius` on this flight first meets the straight
/// cushion `c`, from either side, before its flight ends: its centre one radius from the
/// cushion's line while approaching it, with the foot of the perpendicular on the segment.
/// Both sides are looked at: a ball may cross the line beyond the segment's end and come back
/// to the segment from the other side (into a pocket's mouth, past a face's end). A ball
/// already that close and approaching meets it now; one that close and leaving, but turned
/// back by its acceleration before it gets further, meets it when it turns.
#[must_use]
pub fn cushion(f: &Flight, c: &LinearCushion, radius: f64) -> Option<f64> {
    if !f.moves() {
        return None;
    }
    let n = c.normal();
    let (d0, vn, an) = ((f.pos - c.p1).dot(n), f.vel.dot(n), f.acc.dot(n));
    let along = c.p2 - c.p1;
    let on_segment = |dt: f64| {
        let (p, _) = f.after(dt);
        let s = (p - c.p1).dot(along) / along.norm_sq();
        (0.0..=1.0).contains(&s)
    };
    // The side the ball is on first (the answer of old for a ball that does not cross the
    // line), then the other.
    let near = if d0 >= 0.0 { 1.0 } else { -1.0 };
    let mut first: Option<f64> = None;
    for side in [near, -near] {
        // Seen from this side, the distance `e` falls towards `radius`.
        let (e0, ev, ea) = (side * d0, side * vn, side * an);
        let touching = (0.0..=radius).contains(&e0);
        let dt = if touching && (ev < 0.0 || (ev == 0.0 && ea < 0.0)) {
            Some(0.0)
        } else {
            match crossing(e0, ev, 0.5 * ea, radius, true).filter(|&dt| dt >= 0.0) {
                Some(dt) => Some(dt),
                // In contact and leaving (as rounding leaves a ball after a bounce), but
                // turned back before it clears the contact distance: it meets the cushion
                // as it turns to approach it.
                None if touching && ea < 0.0 => Some(-ev / ea),
                None => None,
            }
        };
        if let Some(dt) = dt {
            if f.time + dt <= f.end && on_segment(dt) && first.is_none_or(|t| dt < t) {
                first = Some(dt);
            }
        }
    }
    first.map(|dt| f.time + dt)
}

/// The time (seconds) a ball of radius `radius` on this flight first meets the jaw `j`
/// while approaching it, before its flight ends.
#[must_use]
pub fn jaw(f: &Flight, j: &Jaw, radius: f64) -> Option<f64> {
    round(f, j.center, j.radius + radius)
}

/// The time (seconds) this ball's centre first enters the pocket `k`'s circle, before its
/// flight ends.
#[must_use]
pub fn pocket(f: &Flight, k: &Pocket) -> Option<f64> {
    round(f, k.center, k.radius)
}

fn round(f: &Flight, center: Vector<2>, sigma: f64) -> Option<f64> {
    if !f.moves() {
        return None;
    }
    let gap = (f.pos - center).norm() - sigma;
    if gap > 0.0 && gap * (1.0 - 1e-9) > f.reach(0.0, f.end) {
        return None;
    }
    let dt = first_contact_accelerating(f.pos - center, f.vel, f.acc, sigma)?;
    let t = f.time + dt;
    (t <= f.end).then_some(t)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn flight(pos: [f64; 2], vel: [f64; 2], acc: [f64; 2]) -> Flight {
        Flight {
            pos: Vector(pos),
            vel: Vector(vel),
            acc: Vector(acc),
            time: 1.0,
            end: f64::INFINITY,
        }
    }

    #[test]
    fn a_ball_meets_a_rail_one_radius_before_its_line_from_either_side() {
        let c = LinearCushion {
            id: "t".into(),
            p1: Vector([0.0, 0.0]),
            p2: Vector([0.0, 2.0]),
            height: 0.0,
        };
        let r = 0.25;
        let t = cushion(&flight([1.0, 1.0], [-1.0, 0.0], [0.0, 0.0]), &c, r).unwrap();
        assert_eq!(t, 1.75);
        let t = cushion(&flight([-1.0, 1.0], [1.0, 0.0], [0.0, 0.0]), &c, r).unwrap();
        assert_eq!(t, 1.75);
        // Beyond the segment's end: no contact with it.
        assert_eq!(
            cushion(&flight([1.0, 3.0], [-1.0, 0.0], [0.0, 0.0]), &c, r),
            None
        );
        // Moving away, and decelerating before it arrives: none.
        assert_eq!(
            cushion(&flight([1.0, 1.0], [1.0, 0.0], [0.0, 0.0]), &c, r),
            None
        );
        assert_eq!(
            cushion(&flight([1.0, 1.0], [-1.0, 0.0], [1.0, 0.0]), &c, r),
            None
        );
        // Already touching and approaching: now.
        assert_eq!(
            cushion(&flight([0.2, 1.0], [-1.0, 0.0], [0.0, 0.0]), &c, r),
            Some(1.0)
        );
        // Touching, moving away, but pulled back: when it returns to one radius.
        let t = cushion(&flight([0.25, 1.0], [1.0, 0.0], [-2.0, 0.0]), &c, r).unwrap();
        assert!((t - 2.0).abs() < 1e-15, "{t}");
    }

    #[test]
    fn nothing_is_found_after_the_flight_ends() {
        let k = Pocket {
            id: "k".into(),
            center: Vector([3.0, 0.0]),
            radius: 0.5,
        };
        let mut f = flight([0.0, 0.0], [1.0, 0.0], [0.0, 0.0]);
        assert_eq!(pocket(&f, &k), Some(3.5));
        f.end = 3.4;
        assert_eq!(pocket(&f, &k), None);
    }

    #[test]
    fn two_balls_are_compared_at_the_later_start() {
        let a = flight([0.0, 0.0], [1.0, 0.0], [0.0, 0.0]);
        let mut b = flight([3.0, 0.0], [0.0, 0.0], [0.0, 0.0]);
        b.time = 2.0;
        // a is at x = 1 at t = 2; it touches b (radius 0.5 each) at x = 2, t = 3.
        assert_eq!(ball_ball(&a, &b, 0.5), Some(3.0));
        assert_eq!(ball_ball(&b, &a, 0.5), Some(3.0));
    }
}
