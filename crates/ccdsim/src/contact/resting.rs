//! Resting and sliding contacts under gravity (`settings.rest_speed`).
//!
//! Radii are fixed here: scenes refuse `rest_speed` with `settings.growth`, since a resting
//! body whose radius grows would have to move its centre off the wall at `Γ·r` while it
//! slides, which the sliding parabola does not model (growing bodies bounce instead, see
//! [`crate::contact::falling_growth`]).
//!
//! With restitution below 1 a ball's bounces on a floor die away geometrically: infinitely
//! many collisions in finite time. With `settings.rest_speed` set, a body that leaves a
//! collision with a **static plane or segment** gravity presses it on (`g·n < 0`, `n` the
//! wall's normal towards the body; on a segment, touching it between its ends) at a normal
//! speed of at most `rest_speed` comes to **rest** on it instead: its normal velocity is
//! removed ([`along_support`]), it keeps its tangential velocity and, until its state next
//! changes, it **slides** without friction with the acceleration `g − n (g·n)/(n·n)`:
//! gravity less the part the wall takes ([`slide_acceleration`]). A parabola still, so every
//! contact of a sliding body is a root of the same polynomials as a falling body's, against
//! its own acceleration:
//!
//! * a sliding body and a falling one (or two sliding on different walls) have a constant
//!   relative acceleration: their contact is the quartic of
//!   [`toi_circle_circle_accelerating`](crate::contact::gravity::toi_circle_circle_accelerating), the
//!   function kinematic bodies already use;
//! * two bodies with the same acceleration (both falling, or both sliding on one wall) keep
//!   the straight-line quadratic of their relative motion;
//! * a sliding body meets walls as a falling body does, under its own acceleration, and
//!   never its support: it touches it all along. A body sliding on a segment meets it once
//!   more, when it reaches one of its ends ([`crate::contact::ledge`]).
//!
//! A body **leaves** its wall when its velocity next changes (a collision with a body or
//! another wall, an edit, a thermostat reset): it falls again under `g`. A body knocked along
//! the wall then lands again at once, within rounding, with no normal speed, and rests
//! again: one more event, exact like every other. A body knocked up flies off.
//!
//! Two exceptions keep it on its wall. A collision that leaves its velocity as it was (the
//! pair was already parting) changes nothing. And a body **pressed into its wall** by a
//! body that hits it (a ball landing on a resting one) is held by the wall, which takes the
//! normal part of the push (`pressed_impulse` in the engine's `resolve` step): the resting
//! body moves along the wall only, and the pair's normal speed is reversed times the
//! restitution as in a free collision. Without this, the resting body would pass a share of
//! the push to its wall in an endless sequence of collisions at one instant.
//!
//! **Bodies on bodies.** A ball whose bounces on a resting one die away (or a ball sliding
//! down an incline against one resting on the floor) ends touching it without normal speed
//! while their accelerations press them together: a stack, which needs a lasting contact
//! between bodies. The run then stops with [`crate::Halt::RestingOnBody`], the same event for
//! every finder. A body wedged in a corner between two walls bounces or slides between them at
//! one instant until it stops likewise ([`crate::Halt::Resting`]): it rests on one wall at a
//! time.
//!
//! **Rods do not hold.** In 3D a segment is a rod, round in section: a body held on top of
//! it would roll off around it, a pendulum's motion, not a parabola. Bodies rest on planes
//! only there; a slow ball bounces on a rod with the restitution, and bounces that die away
//! on it end the run with [`crate::Halt::Resting`], as on any wall that does not hold them
//! (see [`crate::contact::gravity`]).
//!
//! **Segments end.** A body sliding on a segment reaches one of its ends: it slides on along
//! a segment that goes straight on from there, flies off if it is fast enough to clear the
//! edge, and otherwise rolls over the edge, turning about the end point until it comes off
//! or lands ([`crate::motion::pivot`]). See [`crate::contact::ledge`].
//!
//! Every finder reads each body's acceleration from the world ([`crate::World::acceleration`])
//! and skips its support ([`crate::World::support`]), so all of them return the oracle's
//! events bit for bit. Run files mark the wall collisions after which a body rests (format
//! version 11); `verify` checks the rule at each of them and replays sliding bodies on their
//! own parabolas.

use crate::geom::Vector;
use crate::wall::Wall;

/// The acceleration of a body sliding on `wall` under gravity `g`, metres per second
/// squared: `g − n (g·n)/(n·n)` for a plane that `g` presses bodies on (`g·n < 0`); for a
/// 2D segment not along `g`, the part of `g` along it, `u (g·u)/(u·u)` (`u = b − a`), which
/// is exact across an axis-aligned segment. `None` where no body rests: a plane gravity
/// does not press on, a segment along gravity, a segment in 3D (a rod: a body held on it
/// would roll off around it, a motion no finder bounds exactly, so it bounces there instead;
/// see [`crate::contact::gravity`]).
#[must_use]
pub fn slide_acceleration<const D: usize>(g: &Vector<D>, wall: &Wall<D>) -> Option<Vector<D>> {
    match *wall {
        Wall::Plane { normal, .. } => {
            let gn = g.dot(normal);
            (gn < 0.0).then(|| *g - normal * (gn / normal.norm_sq()))
        }
        Wall::Segment { a, b } => {
            let u = b - a;
            (D == 2 && g[0] * u[1] != g[1] * u[0]).then(|| along_segment(g, &u))
        }
    }
}

/// `v`'s part along the direction `u`: `u (v·u)/(u·u)`.
fn along_segment<const D: usize>(v: &Vector<D>, u: &Vector<D>) -> Vector<D> {
    *u * (v.dot(*u) / u.norm_sq())
}

/// `v` with its part normal to `wall` removed: [`tangential`] to a plane's normal, the part
/// along a segment. The velocity a body comes to rest on `wall` with, and keeps sliding.
#[must_use]
pub fn along_support<const D: usize>(v: &Vector<D>, wall: &Wall<D>) -> Vector<D> {
    match *wall {
        Wall::Plane { normal, .. } => tangential(v, &normal),
        Wall::Segment { a, b } => along_segment(v, &(b - a)),
    }
}

/// The normal of `wall` on the side a body resting on it lies, not of unit length: a
/// plane's own normal; for a 2D segment the perpendicular `(−u_y, u_x)` or its negation,
/// whichever gravity `g` presses against (`g·n < 0`). Meaningful where
/// [`slide_acceleration`] is `Some`.
#[must_use]
pub fn support_normal<const D: usize>(wall: &Wall<D>, g: &Vector<D>) -> Vector<D> {
    match *wall {
        Wall::Plane { normal, .. } => normal,
        Wall::Segment { a, b } => {
            let u = b - a;
            let mut n = Vector::<D>::ZERO;
            if D >= 2 {
                n[0] = -u[1];
                n[1] = u[0];
            }
            if g.dot(n) > 0.0 {
                Vector::ZERO - n
            } else {
                n
            }
        }
    }
}

/// True when a body whose centre is at `p`, touching `wall`, lies where the wall can hold it
/// under gravity `g`: on a plane, anywhere (if gravity presses on it at all); on a segment,
/// on the side gravity presses against and with its centre's foot between the ends (a body
/// touching an end point from beyond it is not held).
#[must_use]
pub fn held_at<const D: usize>(wall: &Wall<D>, g: &Vector<D>, p: Vector<D>) -> bool {
    if slide_acceleration(g, wall).is_none() {
        return false;
    }
    match *wall {
        Wall::Plane { .. } => true,
        Wall::Segment { a, b } => {
            let u = b - a;
            let s = (p - a).dot(u) / u.norm_sq();
            (0.0..=1.0).contains(&s) && (p - a).dot(support_normal(wall, g)) > 0.0
        }
    }
}

/// `v` without its component along the plane normal `normal`: `v − n (v·n)/(n·n)`, the
/// velocity a body comes to rest with.
#[must_use]
pub fn tangential<const D: usize>(v: &Vector<D>, normal: &Vector<D>) -> Vector<D> {
    *v - *normal * (v.dot(*normal) / normal.norm_sq())
}

/// True when a body that leaves a collision with a wall at normal speed `outgoing` (m/s,
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
        // A level shelf takes all of gravity too; a tilted one its normal part; a post none.
        let shelf = Wall::Segment {
            a: Vector([0.0, 0.0]),
            b: Vector([3.0, 0.0]),
        };
        assert_eq!(slide_acceleration(&g, &shelf), Some(Vector([0.0, 0.0])));
        let ramp = Wall::Segment {
            a: Vector([0.0, 0.0]),
            b: Vector([-2.0, 2.0]),
        };
        let a = slide_acceleration(&g, &ramp).unwrap();
        assert_eq!(a, Vector([5.0, -5.0]), "down the ramp, g·sin 45° along it");
        let post = Wall::Segment {
            a: Vector([0.0, 0.0]),
            b: Vector([0.0, 1.0]),
        };
        assert_eq!(slide_acceleration(&g, &post), None);
    }

    #[test]
    fn a_shelf_holds_bodies_on_its_top_between_its_ends() {
        let g = Vector([0.0, -10.0]);
        // Drawn right to left: its perpendicular (−u_y, u_x) points down, so the support
        // normal is its negation.
        let shelf = Wall::Segment {
            a: Vector([3.0, 1.0]),
            b: Vector([0.0, 1.0]),
        };
        assert_eq!(support_normal(&shelf, &g), Vector([0.0, 3.0]));
        assert!(held_at(&shelf, &g, Vector([1.0, 1.5])));
        assert!(!held_at(&shelf, &g, Vector([1.0, 0.5])), "under it");
        assert!(!held_at(&shelf, &g, Vector([3.2, 1.4])), "beyond its end");
        assert_eq!(
            along_support(&Vector([0.3, -0.7]), &shelf),
            Vector([0.3, 0.0])
        );
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
