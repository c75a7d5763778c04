//! Moving walls as scenes write them and as they move. Their contacts are in
//! [`crate::world::time_of_impact`].

use crate::geom::Vector;
use crate::wall::Wall;
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
