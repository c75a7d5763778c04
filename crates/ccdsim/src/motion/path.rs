//! Where a body is between events: its stored motion under the law that moves it. The world,
//! `verify` and the viewer all ask a [`Path`] for positions and velocities; none computes one
//! of its own.

use super::pivot::{from_2d, Pivot};
use super::Motion;
use crate::geom::Vector;

/// A body's path from its last event to its next one.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Path<const D: usize> {
    /// A straight line at the stored velocity: no gravity, or a kinematic body.
    Line(Motion<D>),
    /// A parabola under a constant acceleration, m/s²: gravity's, or the slide's of a body
    /// resting on a wall.
    Parabola(Motion<D>, Vector<D>),
    /// A turn about a segment's end point (2D, see [`super::pivot`]).
    Turn(Pivot),
}

impl<const D: usize> Path<D> {
    /// The path of a body with stored motion `m` under the acceleration `acc` (m/s²; `None`
    /// for a straight line).
    #[must_use]
    #[inline(always)]
    pub fn new(m: Motion<D>, acc: Option<Vector<D>>) -> Self {
        match acc {
            Some(a) => Path::Parabola(m, a),
            None => Path::Line(m),
        }
    }

    /// Position at time `t`, metres: `pos + vel·dt`, `pos + vel·dt + a·(½·dt²)` with
    /// `dt = t − time`, or the point on the turn's circle.
    #[must_use]
    #[inline(always)]
    pub fn position(&self, t: f64) -> Vector<D> {
        match self {
            Path::Line(m) => m.at(t),
            Path::Parabola(m, a) => m.falling_at(t, a),
            Path::Turn(p) => from_2d(p.position(t)),
        }
    }

    /// Velocity at time `t`, metres per second: the stored one, that plus `a·dt`, or along
    /// the turn's circle.
    #[must_use]
    #[inline(always)]
    pub fn velocity(&self, t: f64) -> Vector<D> {
        match self {
            Path::Line(m) => m.vel,
            Path::Parabola(m, a) => m.falling_velocity(t, a),
            Path::Turn(p) => from_2d(p.velocity(t)),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_path_moves_as_its_law_says() {
        let m = Motion {
            pos: Vector([1.0, 2.0]),
            vel: Vector([3.0, -1.0]),
            time: 1.0,
        };
        let line = Path::new(m, None);
        assert_eq!(line.position(3.0), Vector([7.0, 0.0]));
        assert_eq!(line.velocity(3.0), Vector([3.0, -1.0]));
        let fall = Path::new(m, Some(Vector([0.0, -10.0])));
        assert_eq!(fall.position(3.0), Vector([7.0, -20.0]));
        assert_eq!(fall.velocity(3.0), Vector([3.0, -21.0]));
        // Bit for bit the stored motion's own formulas.
        let g = Vector([0.3, -9.81]);
        for t in [1.0, 1.1, 2.7, 1e3] {
            assert_eq!(Path::new(m, Some(g)).position(t), m.falling_at(t, &g));
            assert_eq!(Path::new(m, Some(g)).velocity(t), m.falling_velocity(t, &g));
        }
    }
}
