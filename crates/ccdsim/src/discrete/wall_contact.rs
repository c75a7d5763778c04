//! Discrete wall contacts: is a body touching or inside a wall at one instant, and where must it
//! go to be just out.
//!
//! A discrete stepper only sees positions, so a body that jumped through a wall in one frame
//! must still be caught, as game engines catch it with thick level colliders. Walls are
//! therefore boundaries of solid half-spaces: a plane is solid behind its normal; a 2D segment
//! is solid on the side of its line opposite to the body's *home side* (where the body
//! started) — right for the walls of a table or a room, wrong for a free-standing bar that
//! bodies may go around. A body whose centre is less than its radius from the solid is in
//! contact. Segments outside 2D have no side and stay thin (a capsule of the body's radius).

use crate::geom::Vector;
use crate::wall::Wall;

/// The side of a segment's line where `p` lies: `+1` left of `a → b`, `-1` right, `0` on the
/// line or for segments outside 2D (which have no solid side).
#[must_use]
pub fn home_side<const D: usize>(wall: &Wall<D>, p: Vector<D>) -> i8 {
    match *wall {
        Wall::Segment { a, b } if D == 2 => {
            let u = b - a;
            let w = p - a;
            let cross = u[0] * w[1] - u[1] * w[0];
            if cross > 0.0 {
                1
            } else if cross < 0.0 {
                -1
            } else {
                0
            }
        }
        _ => 0,
    }
}

/// Where a body of radius `r` centred at `p` must move to be exactly touching the wall from its
/// home side `home` (see [`home_side`]), or `None` when it is not in contact.
#[must_use]
pub fn wall_push_out<const D: usize>(
    wall: &Wall<D>,
    home: i8,
    p: Vector<D>,
    r: f64,
) -> Option<Vector<D>> {
    match *wall {
        Wall::Plane { point, normal } => push_out_of_half_space(point, normal, p, r),
        Wall::Segment { a, b } if D == 2 && home != 0 => {
            let u = b - a;
            let mut normal = Vector::<D>::ZERO;
            normal[0] = -u[1] * f64::from(home);
            normal[1] = u[0] * f64::from(home);
            push_out_of_half_space(a, normal, p, r)
        }
        Wall::Segment { a, b } => {
            let u = b - a;
            let s = ((p - a).dot(u) / u.norm_sq()).clamp(0.0, 1.0);
            let nearest = a + u * s;
            let d = p - nearest;
            let dist = d.norm();
            if dist >= r {
                None
            } else if dist > 0.0 {
                Some(nearest + d * (r / dist))
            } else {
                // On the segment itself: no direction is better than another; leave along the
                // first axis the segment does not run along.
                let mut dir = Vector::<D>::ZERO;
                let k = (0..D).find(|&k| u[k] == 0.0).unwrap_or(0);
                dir[k] = 1.0;
                Some(nearest + dir * r)
            }
        }
    }
}

/// Pushes a ball out of the solid behind the plane through `point` whose `normal` points to the
/// free side.
fn push_out_of_half_space<const D: usize>(
    point: Vector<D>,
    normal: Vector<D>,
    p: Vector<D>,
    r: f64,
) -> Option<Vector<D>> {
    let n = normal * (1.0 / normal.norm());
    let clearance = (p - point).dot(n);
    (clearance < r).then(|| p + n * (r - clearance))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn planes_catch_bodies_behind_them() {
        let wall = Wall::Plane {
            point: Vector([0.0, 0.0, 0.0]),
            normal: Vector([0.0, 0.0, 2.0]),
        };
        assert_eq!(wall_push_out(&wall, 0, Vector([1.0, 1.0, 2.0]), 1.0), None);
        assert_eq!(
            wall_push_out(&wall, 0, Vector([1.0, 1.0, 0.5]), 1.0),
            Some(Vector([1.0, 1.0, 1.0]))
        );
        assert_eq!(
            wall_push_out(&wall, 0, Vector([1.0, 1.0, -7.0]), 1.0),
            Some(Vector([1.0, 1.0, 1.0]))
        );
    }

    #[test]
    fn segments_are_solid_away_from_home() {
        let wall = Wall::Segment {
            a: Vector([0.0, 0.0]),
            b: Vector([10.0, 0.0]),
        };
        let home = home_side(&wall, Vector([5.0, 3.0]));
        assert_eq!(home, 1);
        assert_eq!(wall_push_out(&wall, home, Vector([5.0, 3.0]), 1.0), None);
        assert_eq!(
            wall_push_out(&wall, home, Vector([5.0, 0.5]), 1.0),
            Some(Vector([5.0, 1.0]))
        );
        // Tunnelled far through, even past the end point: caught and sent back home.
        assert_eq!(
            wall_push_out(&wall, home, Vector([4.0, -20.0]), 1.0),
            Some(Vector([4.0, 1.0]))
        );
        assert_eq!(
            wall_push_out(&wall, home, Vector([30.0, -20.0]), 1.0),
            Some(Vector([30.0, 1.0]))
        );
        // A body living below sees the solid above.
        assert_eq!(
            wall_push_out(&wall, -1, Vector([5.0, 0.5]), 1.0),
            Some(Vector([5.0, -1.0]))
        );
        // Without a side (3D segments), a thin capsule.
        let thin = Wall::Segment {
            a: Vector([0.0, 0.0, 0.0]),
            b: Vector([10.0, 0.0, 0.0]),
        };
        assert_eq!(home_side(&thin, Vector([1.0, 1.0, 1.0])), 0);
        assert_eq!(wall_push_out(&thin, 0, Vector([5.0, 2.0, 0.0]), 1.0), None);
        assert_eq!(
            wall_push_out(&thin, 0, Vector([5.0, 0.5, 0.0]), 1.0),
            Some(Vector([5.0, 1.0, 0.0]))
        );
    }
}
