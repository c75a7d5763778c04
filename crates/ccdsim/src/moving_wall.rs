//! Moving walls: segments and planes that translate at a velocity a program may change at
//! any time (a paddle, a piston), with infinite mass.
//!
//! A moving wall `k` is the scene's wall `moving_walls[k]` displaced by
//! `offset + velocity · (t − time)` at time `t` ([`WallMotion`]). In events it is named by
//! the wall index `walls.len() + k`, after the static walls.
//!
//! **Contacts are exact, with the same functions as the static walls'.** In the frame of a
//! wall translating at `w`, a body moving at `v` (under gravity: accelerating at `g`) moves
//! at `v − w` with the same acceleration, and the wall stands still. So the first contact of
//! body `i` with wall `k` is the static wall's time of impact
//! ([`crate::narrow::toi_body_wall`]) of the relative motion, taken from the later of the two
//! reference times `t₀`, against the wall where it is at `t₀`. A collision reflects the
//! normal component of the relative velocity, scaled by the restitution; the wall keeps its
//! velocity (it has infinite mass), so the body's kinetic energy changes by the work the
//! wall does.
//!
//! **Growing radii** ([`crate::growth`]) change nothing in that frame, with gravity or
//! without ([`crate::falling_growth`]): the ball grows as it
//! would against a static wall, so against a plane the distance of its centre, linear in
//! time, meets its radius, linear in time, and against a segment the growing-pair quadratic
//! finds the contact with the line or an end point (a point of radius zero). The collision
//! reverses the speed at which the surface approaches the wall in the wall's frame: with
//! `u = (v − w)·n` and `σ̇ = Γ·r`, `u' = (1 + e)·σ̇ − e·u`. The kinetic energy such a
//! collision changes (summed as the walls' work in the statistics and by `verify`) then
//! includes what the growth adds.
//!
//! Moving walls are not seen by the finders: the simulation keeps, per body, its next
//! contact with a moving wall in a priority queue ([`crate::moving_wall_tracker`]), as it
//! does for sensors, and takes whichever of the finder's event and the queue's comes first
//! under the events' total order. Both are the same whatever the finder, so every finder
//! still gives the all-pairs oracle's events bit for bit.

use crate::falling_growth::toi_circle_wall_falling_growing;
use crate::geom::Vector;
use crate::gravity::toi_circle_wall_falling;
use crate::narrow::{toi_body_wall, Motion};
use crate::wall::Wall;
use crate::world::World;
use serde::{Deserialize, Serialize};

/// A moving wall as written in a scene (`moving_walls[]`): a wall (the fields of a segment
/// or of a plane) where it is at the scene's start time, and the velocity it translates at
/// from then on.
///
/// ```
/// use ccdsim::{MovingWall, Vector, Wall};
/// let piston: MovingWall<2> =
///     serde_json::from_str(r#"{"point": [0, 9], "normal": [0, -1], "velocity": [0, -0.5]}"#)
///         .unwrap();
/// assert_eq!(piston.velocity, Vector([0.0, -0.5]));
/// assert!(matches!(piston.wall, Wall::Plane { .. }));
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct MovingWall<const D: usize> {
    /// The wall's geometry at the scene's start time.
    #[serde(flatten)]
    pub wall: Wall<D>,
    /// Its velocity, m/s (zero when left out).
    #[serde(default)]
    pub velocity: Vector<D>,
}

/// How each of `walls` (a scene's `moving_walls`) moves at the scene's start time `t0`: at
/// its scene geometry, translating at its scene velocity. Where a simulation, `verify` and
/// the viewer all start replaying the walls from.
#[must_use]
pub fn start_motions<const D: usize>(walls: &[MovingWall<D>], t0: f64) -> Vec<WallMotion<D>> {
    walls
        .iter()
        .map(|m| WallMotion {
            offset: Vector::ZERO,
            velocity: m.velocity,
            time: t0,
        })
        .collect()
}

/// Where a moving wall is: displaced from its scene geometry by `offset` (metres) at `time`
/// (seconds), translating at `velocity` (m/s) from then on.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WallMotion<const D: usize> {
    /// Displacement from the scene's geometry at `time`, metres.
    pub offset: Vector<D>,
    /// Velocity, m/s.
    pub velocity: Vector<D>,
    /// Reference time, seconds.
    pub time: f64,
}

impl<const D: usize> WallMotion<D> {
    /// The displacement at time `t`, metres.
    #[must_use]
    #[inline]
    pub fn offset_at(&self, t: f64) -> Vector<D> {
        self.offset + self.velocity * (t - self.time)
    }
}

/// `wall` translated by `d`.
#[must_use]
pub fn translated<const D: usize>(wall: &Wall<D>, d: Vector<D>) -> Wall<D> {
    match *wall {
        Wall::Segment { a, b } => Wall::Segment { a: a + d, b: b + d },
        Wall::Plane { point, normal } => Wall::Plane {
            point: point + d,
            normal,
        },
    }
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_wall_is_displaced_along_its_velocity() {
        let m = WallMotion {
            offset: Vector([1.0, 0.0]),
            velocity: Vector([0.0, -2.0]),
            time: 1.0,
        };
        assert_eq!(m.offset_at(1.5).0, [1.0, -1.0]);
        let seg = Wall::Segment {
            a: Vector([0.0, 0.0]),
            b: Vector([1.0, 0.0]),
        };
        assert_eq!(
            translated(&seg, m.offset_at(1.5)),
            Wall::Segment {
                a: Vector([1.0, -1.0]),
                b: Vector([2.0, -1.0]),
            }
        );
    }

    #[test]
    fn a_scene_moving_wall_reads_either_kind_and_defaults_to_rest() {
        let seg: MovingWall<2> = serde_json::from_str(r#"{"a": [0, 0], "b": [1, 0]}"#).unwrap();
        assert_eq!(seg.velocity, Vector::ZERO);
        let back: MovingWall<2> =
            serde_json::from_str(&serde_json::to_string(&seg).unwrap()).unwrap();
        assert_eq!(back, seg);
        assert!(serde_json::from_str::<MovingWall<2>>(r#"{"velocity": [1, 0]}"#).is_err());
    }
}
