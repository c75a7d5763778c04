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
//! A body **leaves** its plane when its velocity next changes (a collision with a body or
//! another wall, an edit, a thermostat reset): it falls again under `g`. A body knocked along
//! the plane then lands again at once, within rounding, with no normal speed, and rests
//! again: one more event, exact like every other. A body knocked up flies off.
//!
//! Two exceptions keep it on its plane. A collision that leaves its velocity as it was (the
//! pair was already parting) changes nothing. And a body **pressed into its plane** by a
//! body that hits it (a ball landing on a resting one) is held by the plane, which takes the
//! normal part of the push ([`pressed_impulse`]): the resting body moves along the plane
//! only, and the pair's normal speed is reversed times the restitution as in a free
//! collision. Without this, the resting body would pass a share of the push to its plane in
//! an endless sequence of collisions at one instant.
//!
//! **Bodies on bodies.** A ball whose bounces on a resting one die away (or a ball sliding
//! down an incline against one resting on the floor) ends touching it without normal speed
//! while their accelerations press them together: a stack, which needs a lasting contact
//! between bodies. The run then stops with [`crate::Halt::RestingOnBody`], the same event for
//! every finder. A body wedged in a corner between two planes bounces between them until it
//! stops likewise ([`crate::Halt::Resting`]): it rests on one plane at a time.
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

/// The acceleration of a body sliding on each static wall of `scene`, by wall index
/// ([`slide_acceleration`]; `None` where no body rests), when bodies rest on walls there
/// (`settings.rest_speed` and gravity); empty otherwise.
#[must_use]
pub fn slides<const D: usize>(scene: &crate::Scene<D>) -> Vec<Option<Vector<D>>> {
    match (scene.settings.rest_speed, scene.gravity()) {
        (Some(_), Some(g)) => scene
            .walls
            .iter()
            .map(|w| slide_acceleration(&g, w))
            .collect(),
        _ => Vec::new(),
    }
}

/// `v` without its component along the plane normal `normal`: `v − n (v·n)/(n·n)`, the
/// velocity a body comes to rest with.
#[must_use]
pub fn tangential<const D: usize>(v: &Vector<D>, normal: &Vector<D>) -> Vector<D> {
    *v - *normal * (v.dot(*normal) / normal.norm_sq())
}

/// The velocities after a collision of bodies `i` and `j` (velocities `vi`, `vj` at the
/// contact, `n` the unit vector from `i` to `j`, `vn = (vj − vi)·n < 0`, restitution `e`)
/// when it presses one of them, or both, into the plane it rests on: such a body is held by
/// its plane, which takes the normal part of its push, so it moves along the plane only
/// (its velocity changes along `P n`, `P` the projection onto the plane). The pair's
/// impulse `J = −(1 + e) vn / (w_i (P_i n)·n + w_j (P_j n)·n)` (`w` the inverse masses, 0
/// for a kinematic body; `P = 1` for a body not held) reverses their normal speed times
/// `e` as a free collision does. Returns the two velocities and which body its plane
/// held; `None` when no body is pressed into its plane (or the pair parts), for the free
/// collision.
#[must_use]
#[inline(never)]
#[allow(clippy::type_complexity)]
pub fn pressed_impulse<const D: usize>(
    world: &crate::World<D>,
    (i, vi): (usize, Vector<D>),
    (j, vj): (usize, Vector<D>),
    n: Vector<D>,
    vn: f64,
    e: f64,
) -> Option<((Vector<D>, Vector<D>), (bool, bool))> {
    if vn >= 0.0 {
        return None;
    }
    // The direction the pair's impulse moves body `k` (pushed along `push`) and its plane's
    // normal if the plane holds it.
    let held = |k: usize, push: Vector<D>| match world.support(k).map(|w| world.walls()[w]) {
        Some(Wall::Plane { normal, .. }) if push.dot(normal) < 0.0 => {
            (tangential(&push, &normal), Some(normal))
        }
        _ => (push, None),
    };
    let (ui, hi) = held(i, Vector::ZERO - n);
    let (uj, hj) = held(j, n);
    if hi.is_none() && hj.is_none() {
        return None;
    }
    let inverse = |k: usize| 1.0 / world.mass(k);
    let (wi, wj) = (inverse(i), inverse(j));
    let denominator = wi * ui.dot(Vector::ZERO - n) + wj * uj.dot(n);
    if denominator <= 0.0 {
        // Pressed straight into its plane by a kinematic body: no motion takes the push.
        return None;
    }
    let impulse = -(1.0 + e) * vn / denominator;
    let along = |v: Vector<D>, u: Vector<D>, w: f64, plane: Option<Vector<D>>| {
        let v2 = v + u * (impulse * w);
        // On its plane to the last bit where the normal is an axis.
        plane.map_or(v2, |normal| tangential(&v2, &normal))
    };
    Some((
        (along(vi, ui, wi, hi), along(vj, uj, wj, hj)),
        (hi.is_some(), hj.is_some()),
    ))
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
