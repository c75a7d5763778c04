//! Resting and sliding contacts under gravity (`settings.rest_speed`).
//!
//! With restitution below 1 a ball's bounces on a floor die away geometrically: infinitely
//! many collisions in finite time. With `settings.rest_speed` set, a body that leaves a
//! collision with a **static plane** gravity presses it on (`g·n < 0`, `n` the plane's normal
//! towards the body) at a normal speed of at most `rest_speed` comes to **rest** on it
//! instead: its normal velocity is removed (`v − n (v·n)/(n·n)`), it keeps its tangential
//! velocity and, until its state next changes, it **slides** without friction with the
//! acceleration `g − n (g·n)/(n·n)`: gravity less the part the plane takes. A parabola still,
//! so every contact of a sliding body is a root of the same polynomials as a falling body's,
//! against its own acceleration:
//!
//! * a sliding body and a falling one (or two sliding on different planes) have a constant
//!   relative acceleration: their contact is the quartic of
//!   [`toi_circle_circle_accelerating`](crate::gravity::toi_circle_circle_accelerating), the
//!   function kinematic bodies already use;
//! * two bodies with the same acceleration (both falling, or both sliding on one plane) keep
//!   the straight-line quadratic of their relative motion;
//! * a sliding body meets walls as a falling body does, under its own acceleration, and
//!   never its support: it touches it all along.
//!
//! A body **leaves** its plane when its state next changes, whatever changes it (a collision
//! with a body or another wall, an edit, a thermostat reset): it falls again under `g`. A body
//! knocked along the plane then lands again at once, within rounding, with no normal speed,
//! and rests again: one more event, exact like every other. A body knocked up flies off; one
//! pushed into the plane meets it at once and bounces or rests.
//!
//! **Why planes only.** A body sliding on a segment reaches the segment's end, where a slow
//! body would roll over the edge: a circular motion about the end point, not a polynomial
//! one, which no finder could bound exactly. Bodies keep bouncing on segments (with the TC
//! model, or until [`crate::Halt::Resting`]).
//!
//! Every finder reads each body's acceleration from the world ([`crate::World::acceleration`])
//! and skips its support ([`crate::World::support`]), so all of them return the oracle's
//! events bit for bit. Run files mark the wall collisions after which a body rests (format
//! version 11); `verify` checks the rule at each of them and replays sliding bodies on their
//! own parabolas.

use crate::geom::Vector;
use crate::wall::Wall;

/// The acceleration of a body sliding on `wall` under gravity `g`, metres per second
/// squared: `g − n (g·n)/(n·n)` for a plane that `g` presses bodies on (`g·n < 0`), `None`
/// for a segment or a plane gravity does not press on (no body rests there).
#[must_use]
pub fn slide_acceleration<const D: usize>(g: &Vector<D>, wall: &Wall<D>) -> Option<Vector<D>> {
    match *wall {
        Wall::Plane { normal, .. } => {
            let gn = g.dot(normal);
            (gn < 0.0).then(|| *g - normal * (gn / normal.norm_sq()))
        }
        Wall::Segment { .. } => None,
    }
}

/// `v` without its component along the plane normal `normal`: `v − n (v·n)/(n·n)`, the
/// velocity a body comes to rest with.
#[must_use]
pub fn tangential<const D: usize>(v: &Vector<D>, normal: &Vector<D>) -> Vector<D> {
    *v - *normal * (v.dot(*normal) / normal.norm_sq())
}

/// True when a body that leaves a collision with a plane at normal speed `outgoing` (m/s,
/// `≥ 0`) comes to rest under `settings.rest_speed = rest_speed`.
#[must_use]
#[inline]
pub fn comes_to_rest(outgoing: f64, rest_speed: f64) -> bool {
    outgoing <= rest_speed
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_floor_takes_all_of_gravity_and_an_incline_its_normal_part() {
        let g = Vector([0.0, -10.0]);
        let floor = Wall::Plane {
            point: Vector([0.0, 0.0]),
            normal: Vector([0.0, 2.0]),
        };
        assert_eq!(slide_acceleration(&g, &floor), Some(Vector([0.0, 0.0])));
        // A 45° incline whose normal points up and right: the slide is down and right,
        // g·sin 45° along it.
        let incline = Wall::Plane {
            point: Vector([0.0, 0.0]),
            normal: Vector([1.0, 1.0]),
        };
        let a = slide_acceleration(&g, &incline).unwrap();
        assert!(
            (a[0] - 5.0).abs() < 1e-15 && (a[1] + 5.0).abs() < 1e-15,
            "{a:?}"
        );
        // A ceiling and a wall gravity runs along hold nothing.
        let ceiling = Wall::Plane {
            point: Vector([0.0, 9.0]),
            normal: Vector([0.0, -1.0]),
        };
        assert_eq!(slide_acceleration(&g, &ceiling), None);
        let side = Wall::Plane {
            point: Vector([0.0, 0.0]),
            normal: Vector([1.0, 0.0]),
        };
        assert_eq!(slide_acceleration(&g, &side), None);
        let segment = Wall::Segment {
            a: Vector([0.0, 0.0]),
            b: Vector([1.0, 0.0]),
        };
        assert_eq!(slide_acceleration(&g, &segment), None);
    }

    #[test]
    fn resting_removes_exactly_the_normal_velocity() {
        assert_eq!(
            tangential(&Vector([3.0, -2.0]), &Vector([0.0, 4.0])),
            Vector([3.0, 0.0])
        );
        let v = tangential(&Vector([1.0, -3.0, 2.0]), &Vector([1.0, 1.0, 0.0]));
        assert!((v[0] - 2.0).abs() < 1e-15 && (v[1] + 2.0).abs() < 1e-15 && v[2] == 2.0);
        assert!(comes_to_rest(0.1, 0.1) && !comes_to_rest(0.11, 0.1));
    }
}
