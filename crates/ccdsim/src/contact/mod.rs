//! The narrow phase: times of impact, pure functions of motions and shapes.
//!
//! Nothing here reads a world, a scene or a simulation: every function takes the stored
//! motions ([`crate::motion::Motion`]) and radii of a pair, or of a body and a wall, and the
//! laws in force ([`Laws`]), and returns the absolute time of their first future contact, or
//! `None`. By motion law:
//!
//! - [`narrow`]: straight lines and fixed radii (the thesis's dynamic circle test), and
//!   `narrow_lanes` its four-lane SIMD form;
//! - [`gravity`]: parabolas (a shared acceleration, or different ones: a quartic);
//! - [`growth`]: radii growing linearly in time; [`falling_growth`]: both together;
//! - [`accelerated_contact`]: the certified first root of a relative parabola's quartic,
//!   which [`rod`] (3D segments under gravity) and the end points of segments build on;
//! - [`periodic`]: the nearest image in a periodic box, and leaving the box; [`lees_edwards`]
//!   the same in a sheared box;
//! - [`resting`], [`ledge`], [`pivot_contact`] and [`pivot_end`]: a body resting on a wall,
//!   sliding off a segment's end, and turning about that end point;
//! - [`sensor_crossing`]: a body entering and leaving a sensor's ball.
//!
//! The functions below choose among them by the laws in force, as every finder evaluates a
//! pair: the straight-line functions, unchanged, when there are none. The world-dependent
//! forms (bodies resting on walls, moving walls) are [`crate::world`]'s.

pub mod accelerated_contact;
pub mod falling_growth;
mod falling_segment;
pub mod gravity;
pub mod growth;
pub mod ledge;
pub mod lees_edwards;
pub mod narrow;
pub(crate) mod narrow_lanes;
pub mod periodic;
pub mod pivot_contact;
pub mod pivot_end;
pub(crate) mod quadratic;
pub mod resting;
pub mod rod;
pub mod sensor_crossing;

use crate::contact::falling_growth::{
    toi_circle_circle_falling_growing, toi_circle_wall_falling_growing,
};
use crate::contact::gravity::{toi_circle_circle_falling, toi_circle_wall_falling};
use crate::contact::growth::{toi_circle_circle_growing, toi_circle_wall_growing};
use crate::contact::narrow::{toi_circle_circle, toi_circle_circle_shifted, toi_circle_wall};
use crate::geom::Vector;
use crate::motion::{Body, Laws, Motion};
use crate::wall::Wall;

/// Time of impact of two balls as every finder evaluates it: [`toi_circle_circle`], or under
/// the world's laws ([`crate::World::laws`]) its falling or growing form (zero shift).
#[must_use]
#[inline(always)]
pub fn toi_pair<const D: usize>(
    a: &Motion<D>,
    ra: f64,
    b: &Motion<D>,
    rb: f64,
    laws: Option<&Laws<D>>,
) -> Option<f64> {
    match laws {
        None => toi_circle_circle(a, ra, b, rb),
        Some(l) => toi_pair_under(a, ra, b, rb, Vector::ZERO, l),
    }
}

/// [`toi_circle_circle_shifted`], or under the world's laws its falling or growing form.
#[must_use]
#[inline(always)]
pub fn toi_pair_shifted<const D: usize>(
    a: &Motion<D>,
    ra: f64,
    b: &Motion<D>,
    rb: f64,
    shift: Vector<D>,
    laws: Option<&Laws<D>>,
) -> Option<f64> {
    match laws {
        None => toi_circle_circle_shifted(a, ra, b, rb, shift),
        Some(l) => toi_pair_under(a, ra, b, rb, shift, l),
    }
}

/// [`toi_pair_shifted`] of the records of bodies `a` and `b` (lower index first), the partner
/// seen through `shift` (a periodic image), or none for two kinematic bodies, which pass
/// through each other: the pair function of periodic worlds (no gravity there).
#[must_use]
#[inline(always)]
pub fn toi_bodies_shifted<const D: usize>(
    a: &Body<D>,
    b: &Body<D>,
    shift: Vector<D>,
    laws: Option<&Laws<D>>,
) -> Option<f64> {
    if laws.is_some_and(|l| l.kinematic) && a.is_kinematic() && b.is_kinematic() {
        return None;
    }
    toi_pair_shifted(&a.motion, a.radius, &b.motion, b.radius, shift, laws)
}

/// The pair function under laws in force: gravity's ([`toi_circle_circle_falling`]),
/// growth's ([`toi_circle_circle_growing`]), or both together's
/// ([`toi_circle_circle_falling_growing`]).
#[inline]
fn toi_pair_under<const D: usize>(
    a: &Motion<D>,
    ra: f64,
    b: &Motion<D>,
    rb: f64,
    shift: Vector<D>,
    laws: &Laws<D>,
) -> Option<f64> {
    match (&laws.gravity, &laws.growth) {
        (Some(g), Some(law)) => toi_circle_circle_falling_growing(a, ra, b, rb, shift, g, law),
        (Some(g), None) => toi_circle_circle_falling(a, ra, b, rb, shift, g),
        (None, Some(law)) => toi_circle_circle_growing(a, ra, b, rb, shift, law),
        (None, None) => toi_circle_circle_shifted(a, ra, b, rb, shift),
    }
}

/// Time of impact of two bodies (records `a` and `b`, lower index first) as every finder of
/// an open world evaluates it: [`toi_pair`], except in a world with kinematic bodies, where
/// two kinematic bodies never meet and a kinematic body, which gravity does not move, meets
/// a falling one at the first root of the quartic of their relative motion
/// ([`crate::contact::gravity::toi_circle_circle_accelerating`], with growing radii
/// [`crate::contact::falling_growth::toi_circle_circle_accelerating_growing`]).
#[must_use]
#[inline(always)]
pub fn toi_pair_bodies<const D: usize>(
    a: &Body<D>,
    b: &Body<D>,
    laws: Option<&Laws<D>>,
) -> Option<f64> {
    match laws {
        Some(l) if l.kinematic => toi_kinematic_pair(a, b, l),
        _ => toi_pair(&a.motion, a.radius, &b.motion, b.radius, laws),
    }
}

/// [`toi_pair_bodies`] in a world with kinematic bodies (out of line: such worlds are rare).
#[inline(never)]
fn toi_kinematic_pair<const D: usize>(a: &Body<D>, b: &Body<D>, laws: &Laws<D>) -> Option<f64> {
    let (ka, kb) = (a.is_kinematic(), b.is_kinematic());
    if ka && kb {
        return None;
    }
    match &laws.gravity {
        Some(g) if ka || kb => {
            // The kinematic body does not fall.
            let acc = |k: bool| if k { Vector::ZERO } else { *g };
            let (ga, gb) = (acc(ka), acc(kb));
            let (ma, mb) = (&a.motion, &b.motion);
            match &laws.growth {
                Some(law) => {
                    crate::contact::falling_growth::toi_circle_circle_accelerating_growing(
                        ma, a.radius, &ga, mb, b.radius, &gb, law,
                    )
                }
                None => crate::contact::gravity::toi_circle_circle_accelerating(
                    ma, a.radius, &ga, mb, b.radius, &gb,
                ),
            }
        }
        _ => toi_pair(&a.motion, a.radius, &b.motion, b.radius, Some(laws)),
    }
}

/// [`crate::world::toi_pair_resting`] of the records `a` and `b` (lower index first) with the accelerations
/// `ga` and `gb`, metres per second squared.
#[must_use]
#[inline(never)]
pub fn toi_pair_accelerated<const D: usize>(
    a: &Body<D>,
    ga: &Vector<D>,
    b: &Body<D>,
    gb: &Vector<D>,
) -> Option<f64> {
    if a.is_kinematic() && b.is_kinematic() {
        return None;
    }
    if ga == gb {
        toi_circle_circle_falling(&a.motion, a.radius, &b.motion, b.radius, Vector::ZERO, ga)
    } else {
        crate::contact::gravity::toi_circle_circle_accelerating(
            &a.motion, a.radius, ga, &b.motion, b.radius, gb,
        )
    }
}

/// Time of impact of a body (record `b`) with a wall as every finder evaluates it:
/// [`toi_body_wall`], except that kinematic bodies meet no wall.
#[must_use]
#[inline]
pub fn toi_body_wall_of<const D: usize>(
    b: &Body<D>,
    wall: &Wall<D>,
    laws: Option<&Laws<D>>,
) -> Option<f64> {
    match laws {
        Some(l) if l.kinematic && b.is_kinematic() => None,
        _ => toi_body_wall(&b.motion, b.radius, wall, laws),
    }
}

/// [`toi_circle_wall`], or under the world's laws its falling, growing, or falling and
/// growing form.
#[must_use]
#[inline]
pub fn toi_body_wall<const D: usize>(
    m: &Motion<D>,
    r: f64,
    wall: &Wall<D>,
    laws: Option<&Laws<D>>,
) -> Option<f64> {
    match laws {
        None => toi_circle_wall(m, r, wall),
        Some(Laws {
            gravity: Some(g),
            growth: Some(law),
            ..
        }) => toi_circle_wall_falling_growing(m, r, wall, g, law),
        Some(Laws {
            gravity: Some(g), ..
        }) => toi_circle_wall_falling(m, r, wall, g),
        Some(Laws {
            growth: Some(law), ..
        }) => toi_circle_wall_growing(m, r, wall, law),
        Some(_) => toi_circle_wall(m, r, wall),
    }
}
