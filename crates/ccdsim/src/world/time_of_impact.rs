//! Times of impact of a world's bodies, as every finder and the simulation evaluate them
//! where a body's motion depends on the world's state: bodies resting on walls (each with its
//! own acceleration, see [`crate::contact::resting`]), sliding off or returning to a segment's end
//! ([`crate::contact::ledge`]), and moving walls (below). The pure functions of motions and shapes they
//! call are the narrow phase's ([`crate::contact::narrow`] and its siblings).
//!
//! # Moving walls
//!
//! Segments and planes that translate at a velocity a program may change at
//! any time (a paddle, a piston), with infinite mass.
//!
//! A moving wall `k` is the scene's wall `moving_walls[k]` displaced by
//! `offset + velocity · (t − time)` at time `t` ([`crate::motion::WallMotion`]). In events it is named by
//! the wall index `walls.len() + k`, after the static walls.
//!
//! **Contacts are exact, with the same functions as the static walls'.** In the frame of a
//! wall translating at `w`, a body moving at `v` (under gravity: accelerating at `g`) moves
//! at `v − w` with the same acceleration, and the wall stands still. So the first contact of
//! body `i` with wall `k` is the static wall's time of impact
//! ([`crate::contact::toi_body_wall`]) of the relative motion, taken from the later of the two
//! reference times `t₀`, against the wall where it is at `t₀`. A collision reflects the
//! normal component of the relative velocity, scaled by the restitution; the wall keeps its
//! velocity (it has infinite mass), so the body's kinetic energy changes by the work the
//! wall does.
//!
//! **Growing radii** ([`crate::contact::growth`]) change nothing in that frame, with gravity or
//! without ([`crate::contact::falling_growth`]): the ball grows as it
//! would against a static wall, so against a plane the distance of its centre, linear in
//! time, meets its radius, linear in time, and against a segment the growing-pair quadratic
//! finds the contact with the line or an end point (a point of radius zero). The collision
//! reverses the speed at which the surface approaches the wall in the wall's frame: with
//! `u = (v − w)·n` and `σ̇ = Γ·r`, `u' = (1 + e)·σ̇ − e·u`. The kinetic energy such a
//! collision changes (summed as the walls' work in the statistics and by `verify`) then
//! includes what the growth adds.
//!
//! Moving walls are not seen by the finders: the simulation keeps, per body, its next
//! contact with a moving wall in a priority queue (the moving-wall tracker), as it
//! does for sensors, and takes whichever of the finder's event and the queue's comes first
//! under the events' total order. Both are the same whatever the finder, so every finder
//! still gives the all-pairs oracle's events bit for bit.

use super::World;
use crate::contact::falling_growth::toi_circle_wall_falling_growing;
use crate::contact::gravity::{toi_circle_segment_falling_ends, toi_circle_wall_falling};
use crate::contact::ledge::{end_reached, return_time, slide_end_time};
use crate::contact::{toi_body_wall, toi_body_wall_of, toi_pair_accelerated, toi_pair_bodies};
use crate::geom::Vector;
use crate::motion::{translated, Motion};
use crate::wall::Wall;

/// Time of impact of bodies `i < j` of an open (not periodic) `world` as every finder
/// evaluates it: [`toi_pair_bodies`] of their records, or [`toi_pair_resting`] where bodies
/// rest on walls.
#[must_use]
#[inline(always)]
pub fn toi_bodies_in<const D: usize>(world: &World<D>, i: usize, j: usize) -> Option<f64> {
    match world.laws() {
        Some(l) if l.resting => toi_pair_resting(world, i, j),
        laws => toi_pair_bodies(&world.bodies()[i], &world.bodies()[j], laws),
    }
}

/// Time of impact of body `i` of `world` with static wall `w` as every finder evaluates it:
/// [`toi_body_wall_of`] of its record, or [`toi_body_wall_resting`] where bodies rest on walls.
#[must_use]
#[inline(always)]
pub fn toi_body_wall_in<const D: usize>(world: &World<D>, i: usize, w: usize) -> Option<f64> {
    match world.laws() {
        Some(l) if l.resting => toi_body_wall_resting(world, i, w),
        laws => toi_body_wall_of(&world.bodies()[i], &world.walls()[w], laws),
    }
}

/// Time of impact of bodies `i < j` of `world` as every finder evaluates it in a world where
/// bodies rest on walls (see [`crate::contact::resting`]): each body has its own acceleration
/// ([`World::acceleration`]); two with the same one meet at the root of the straight-line
/// quadratic of their relative motion ([`crate::contact::gravity::toi_circle_circle_falling`]), two with different
/// ones at the first root of the quartic of their relative parabola
/// ([`crate::contact::gravity::toi_circle_circle_accelerating`]); two kinematic bodies never meet.
#[must_use]
#[inline(never)]
pub fn toi_pair_resting<const D: usize>(world: &World<D>, i: usize, j: usize) -> Option<f64> {
    debug_assert!(i < j);
    let (a, b) = (&world.bodies()[i], &world.bodies()[j]);
    toi_pair_accelerated(a, &world.acceleration(i), b, &world.acceleration(j))
}

/// Time of impact of body `i` of `world` with static wall `w` as every finder evaluates it
/// in a world where bodies rest on walls (see [`crate::contact::resting`]): under the body's own
/// acceleration ([`World::acceleration`]); never with the plane it rests on, nor for a
/// kinematic body. A body sliding on a segment meets it at its end, and one that just flew
/// off a segment's end meets it when it comes back to that end point ([`crate::contact::ledge`]).
#[must_use]
#[inline(never)]
pub fn toi_body_wall_resting<const D: usize>(world: &World<D>, i: usize, w: usize) -> Option<f64> {
    let b = &world.bodies()[i];
    if b.is_kinematic() {
        return None;
    }
    match world.walls()[w] {
        Wall::Segment { a, b } => crate::world::toi_body_segment(world, i, w, a, b),
        Wall::Plane { .. } if world.support(i) == Some(w) => None,
        ref plane => toi_circle_wall_falling(&b.motion, b.radius, plane, &world.acceleration(i)),
    }
}

/// Time of impact of body `i` of `world` with segment `w` (from `a` to `b`) where bodies rest
/// on walls ([`crate::world::toi_body_wall_resting`]): for a body sliding on `w`, its
/// arrival at an end ([`slide_end_time`]); for one sliding on another segment, the usual
/// contact under its slide's acceleration, but never at an end point the two share (it is
/// a point of its support, which it touches all along); for one that has just flown off
/// an end point, its return to that point ([`return_time`]) wherever a segment ends
/// there, and the usual contact with the rest of the segment.
#[must_use]
pub fn toi_body_segment<const D: usize>(
    world: &World<D>,
    i: usize,
    w: usize,
    a: Vector<D>,
    b: Vector<D>,
) -> Option<f64> {
    let body = &world.bodies()[i];
    let (m, r, acc) = (&body.motion, body.radius, world.acceleration(i));
    if let Some(support) = world.support(i) {
        if support == w {
            return slide_end_time(m, &acc, a, b);
        }
        let ends = match world.walls()[support] {
            Wall::Segment { a: sa, b: sb } => [a != sa && a != sb, b != sa && b != sb],
            Wall::Plane { .. } => [true; 2],
        };
        return toi_circle_segment_falling_ends(m, r, a, b, &acc, ends);
    }
    if let Some(left) = world.released(i) {
        // Come off an end point after turning about it: never that point again.
        let Wall::Segment { a: la, b: lb } = world.walls()[left] else {
            unreachable!("bodies turn about segment ends only");
        };
        let end = end_reached(la, lb, m.pos);
        return toi_circle_segment_falling_ends(m, r, a, b, &acc, [a != end, b != end]);
    }
    if let (Some(left), Some(g)) = (world.departed(i), world.gravity()) {
        let Wall::Segment { a: la, b: lb } = world.walls()[left] else {
            unreachable!("bodies fly off segments only");
        };
        let end = end_reached(la, lb, m.pos);
        if left == w {
            return return_time(m, end, &g);
        }
        let ends = [a != end, b != end];
        if ends != [true; 2] {
            let rest = toi_circle_segment_falling_ends(m, r, a, b, &acc, ends);
            return [rest, return_time(m, end, &g)]
                .into_iter()
                .flatten()
                .reduce(f64::min);
        }
    }
    toi_circle_segment_falling_ends(m, r, a, b, &acc, [true; 2])
}

/// The time of the first contact of body `i` with moving wall `k` (absolute, seconds) on
/// their current motions, if they meet: the static wall's time of impact of the body's
/// motion relative to the wall, from the later of their reference times (see the module's
/// documentation). Kinematic bodies (and vacant slots) meet no wall.
#[must_use]
pub fn toi_body_moving_wall<const D: usize>(world: &World<D>, i: usize, k: usize) -> Option<f64> {
    if world.is_kinematic(i) {
        return None;
    }
    let body = world.motion(i);
    let wall = world.wall_motion(k);
    let t0 = body.time.max(wall.time);
    let relative = Motion {
        pos: world.position_at(i, t0),
        vel: world.velocity_at(i, t0) - wall.velocity,
        time: t0,
    };
    let there = translated(&world.moving_wall_base(k), wall.offset_at(t0));
    match (world.gravity_of(i), world.growth()) {
        // Growing and falling: the parabola against the growing radius.
        (Some(a), Some(law)) => {
            toi_circle_wall_falling_growing(&relative, world.radius(i), &there, &a, law)
        }
        // The body's own acceleration: gravity's, or its slide's on the wall it rests on.
        (Some(a), None) => toi_circle_wall_falling(&relative, world.radius(i), &there, &a),
        (None, _) => toi_body_wall(&relative, world.radius(i), &there, world.laws()),
    }
}
