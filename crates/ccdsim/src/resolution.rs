//! The resolution of `f64` time and space, and when it is too coarse to resolve contacts.
//!
//! A body's position at time `t` is `p + v (t − t_i)`, computed in `f64`. Near a time `t` the
//! clock itself is only known to `ulp(t)`, so the position is uncertain by `|v| · ulp(t)`; near
//! a coordinate `x` a position is only known to `ulp(x)`. When either becomes comparable to a
//! body's size, contact times and positions round so coarsely that bodies seem to reverse
//! apart, or collide at a distance: a start time of 10¹⁷ s (`ulp` = 16 s) or a table at 10⁶ m
//! with balls of 1 mm are such scenes.
//!
//! The rule: the resolution error `|v|∞ · ulp(t) + ulp(|p|∞)` of a body must stay within
//! [`RESOLUTION_LIMIT`] of its radius. [`Scene::validate`](crate::Scene::validate) refuses a
//! scene whose bodies break it at the start time, and the simulation stops, saying why, before
//! an event at which an involved body breaks it (see [`Halt`](crate::halt::Halt)).
//!
//! Why `5·10⁻¹⁰`: a gap between two bodies is off by the sum of their position errors, at
//! most `5·10⁻¹⁰ (r_i + r_j)` under the rule, half of the `10⁻⁹` of a contact distance that
//! the numerical rules (and `verify`) allow; and a rounding errs by half an ulp where the
//! resolution error counts a whole one. Ordinary runs are far from the limit: a gas of
//! unit-diameter discs at kT = 1 reaches it after about 10⁵ time units, a billiard ball at
//! 2 m/s after about 8 hours, and a ball of radius `r` is resolved up to about `2·10⁶ r`
//! from the origin (1 cm balls: 20 km).

use crate::geom::Vector;

/// Largest resolution error allowed, relative to a body's radius.
pub const RESOLUTION_LIMIT: f64 = 5e-10;

/// The gap between `|x|` and the next larger `f64`: the resolution of numbers near `x`
/// (`0` gives the smallest subnormal; an infinite or NaN `x` gives infinity).
#[must_use]
#[inline]
pub fn ulp(x: f64) -> f64 {
    let x = x.abs();
    if !x.is_finite() {
        return f64::INFINITY;
    }
    f64::from_bits(x.to_bits() + 1) - x
}

/// [`ulp`] of a finite `x`, without the branch for infinities: the simulation's per-event
/// check. An infinite or NaN `x` gives NaN, which no comparison accepts.
#[must_use]
#[inline(always)]
pub(crate) fn ulp_of_finite(x: f64) -> f64 {
    let x = x.abs();
    f64::from_bits(x.to_bits() + 1) - x
}

/// [`resolution_error`] with the clock's [`ulp`] already known (one per event).
#[must_use]
#[inline(always)]
pub(crate) fn resolution_error_at<const D: usize>(
    clock_ulp: f64,
    pos: Vector<D>,
    vel: Vector<D>,
) -> f64 {
    max_abs(vel) * clock_ulp + ulp_of_finite(max_abs(pos))
}

/// The largest absolute component of `v`.
#[inline(always)]
fn max_abs<const D: usize>(v: Vector<D>) -> f64 {
    v.0.iter().fold(0.0, |m, c| m.max(c.abs()))
}

/// Resolution error, metres, of a body at position `pos` moving at `vel` at time `t`:
/// `|vel|∞ · ulp(t) + ulp(|pos|∞)` (see the module docs).
#[must_use]
#[inline]
pub fn resolution_error<const D: usize>(t: f64, pos: Vector<D>, vel: Vector<D>) -> f64 {
    resolution_error_at(ulp(t), pos, vel)
}

/// True when a body of radius `radius` at `pos`, moving at `vel` at time `t`, is resolved:
/// its [`resolution_error`] is within [`RESOLUTION_LIMIT`] of its radius.
#[must_use]
#[inline]
pub fn resolves<const D: usize>(t: f64, pos: Vector<D>, vel: Vector<D>, radius: f64) -> bool {
    resolution_error(t, pos, vel) <= RESOLUTION_LIMIT * radius
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ulp_is_the_spacing_of_floats() {
        assert_eq!(ulp(1.0), f64::EPSILON);
        assert_eq!(ulp(-1.0), f64::EPSILON);
        assert_eq!(ulp(1e17), 16.0);
        assert_eq!(ulp(0.0), 5e-324);
        assert_eq!(ulp(f64::INFINITY), f64::INFINITY);
    }

    #[test]
    fn ordinary_bodies_are_resolved_and_the_issue_cases_are_not() {
        let v = Vector([1.0, -2.0]);
        // A billiard ball (radius 28 mm) at 2 m/s on a table near the origin, an hour into a
        // run; ten hours in, the clock's steps (7.3·10⁻¹² s) move it by 1.5·10⁻¹¹ m, more
        // than 5·10⁻¹⁰ of its radius.
        assert!(resolves(3_600.0, Vector([1.2, 0.6]), v, 0.028));
        assert!(!resolves(36_000.0, Vector([1.2, 0.6]), v, 0.028));
        // Start time 10¹⁷ s: the clock moves in steps of 16 s.
        assert!(!resolves(1e17, Vector([1.0, 1.0]), v, 0.5));
        // Coordinates near 10⁶ m resolve to 1.2·10⁻¹⁰ m: a 1 mm ball needs 5·10⁻¹³ m.
        assert!(!resolves(0.0, Vector([1e6, 0.0]), Vector([0.0, 0.0]), 1e-3));
        // At rest, a huge time does not matter.
        assert!(resolves(1e300, Vector([1.0, 1.0]), Vector([0.0, 0.0]), 0.5));
    }
}
