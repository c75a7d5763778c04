//! Balls' boxes on a lattice, for the broad phases' property tests ([`super::ball_grid`],
//! [`super::box_tree`]): integer and half-integer corners make boxes that touch exactly.

use crate::geom::{Aabb, Vector};

/// The box of the ball drawn as `((x, y), r)`: centred at `spacing · (x, y)`, of radius `r / 2`;
/// no box ([`Aabb::EMPTY`]) when `r` is 0.
pub(crate) fn lattice_box(((x, y), r): ((i32, i32), u8), spacing: f64) -> Aabb<2> {
    if r == 0 {
        Aabb::EMPTY
    } else {
        let centre = Vector([f64::from(x) * spacing, f64::from(y) * spacing]);
        Aabb::of_ball(centre, f64::from(r) * 0.5)
    }
}
