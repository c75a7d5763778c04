//! Angular velocity of rough bodies: how a scene writes it, and the cross products that link
//! it to the velocity of a body's surface.
//!
//! A ball's spin never changes between events (no torque acts on a free ball, and a round
//! ball's contacts happen at the same times whatever it spins), so it needs no motion law of
//! its own: only collisions of rough bodies change it (a tangential restitution above −1, see
//! [`crate::scene::Settings::tangential_restitution`]). Spins are three-vectors in both
//! dimensions: a disc spins about the axis out of the plane, the third component.

use crate::geom::Vector;
use serde::{Deserialize, Serialize};

/// A body's angular velocity as a scene file writes it, radians per second: one number in
/// 2D (about the axis out of the plane, counter-clockwise positive), three components in 3D.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(untagged)]
pub enum Spin {
    /// A disc's angular velocity about the axis out of the plane (2D scenes).
    Planar(f64),
    /// A sphere's angular velocity vector (3D scenes).
    Spatial([f64; 3]),
}

impl Spin {
    /// The angular velocity as a three-vector (a disc's lies along the third axis).
    #[must_use]
    pub fn vector(&self) -> Vector<3> {
        match *self {
            Spin::Planar(w) => Vector([0.0, 0.0, w]),
            Spin::Spatial(w) => Vector(w),
        }
    }

    /// The form a scene of dimension `D` writes `w` in (`w`'s third component in 2D).
    #[must_use]
    pub fn of<const D: usize>(w: Vector<3>) -> Spin {
        if D == 2 {
            Spin::Planar(w[2])
        } else {
            Spin::Spatial(w.0)
        }
    }

    /// True when it is written in the form a scene of dimension `D` takes.
    #[must_use]
    pub fn fits<const D: usize>(&self) -> bool {
        matches!((D, self), (2, Spin::Planar(_)) | (3, Spin::Spatial(_)))
    }
}

/// The default moment-of-inertia factor `q` (`I = q·m·r²`) of a uniform body of dimension
/// `D`: 1/2 for a disc, 2/5 for a sphere.
#[must_use]
pub fn default_inertia<const D: usize>() -> f64 {
    if D == 2 {
        0.5
    } else {
        0.4
    }
}

/// Degrees of freedom of rotation in dimension `D`: 1 for a disc, 3 for a sphere.
#[must_use]
pub fn rotational_freedom<const D: usize>() -> usize {
    if D == 2 {
        1
    } else {
        3
    }
}

fn widen<const D: usize>(v: Vector<D>) -> Vector<3> {
    let mut w = Vector::<3>::ZERO;
    w.0[..D].copy_from_slice(&v.0);
    w
}

/// `ω × n`, the velocity of the point at unit offset `n` from the centre of a body spinning
/// at `ω`, in the body's `D` dimensions (in 2D `ω` lies along the third axis and the result
/// in the plane).
#[must_use]
pub fn surface_velocity<const D: usize>(omega: Vector<3>, n: Vector<D>) -> Vector<D> {
    let w = omega.cross(widen(n));
    let mut out = Vector::<D>::ZERO;
    out.0.copy_from_slice(&w.0[..D]);
    out
}

/// `n × J`, the angular impulse of the impulse `J` applied at unit offset `n` from a body's
/// centre, per metre of lever (multiply by the radius for newton-metre-seconds).
#[must_use]
pub fn moment<const D: usize>(n: Vector<D>, impulse: Vector<D>) -> Vector<3> {
    widen(n).cross(widen(impulse))
}

/// Rotational kinetic energy `½·q·m·r²·|ω|²` of a body of mass `m`, radius `r`, inertia
/// factor `q` and angular velocity `ω`, joules.
#[must_use]
pub fn rotational_energy(q: f64, m: f64, r: f64, omega: Vector<3>) -> f64 {
    0.5 * q * m * r * r * omega.norm_sq()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_disc_spinning_counter_clockwise_moves_its_right_edge_up() {
        let v = surface_velocity(Vector([0.0, 0.0, 2.0]), Vector([1.0, 0.0]));
        assert_eq!(v.0, [0.0, 2.0]);
        // The moment of an upward push at the right edge spins it counter-clockwise.
        assert_eq!(
            moment(Vector([1.0, 0.0]), Vector([0.0, 3.0])).0,
            [0.0, 0.0, 3.0]
        );
    }

    #[test]
    fn spins_are_written_as_the_dimension_asks() {
        let planar: Spin = serde_json::from_str("1.5").unwrap();
        assert!(planar.fits::<2>() && !planar.fits::<3>());
        assert_eq!(planar.vector().0, [0.0, 0.0, 1.5]);
        let spatial: Spin = serde_json::from_str("[1, 2, 3]").unwrap();
        assert!(spatial.fits::<3>() && !spatial.fits::<2>());
        assert_eq!(Spin::of::<2>(planar.vector()), planar);
        assert_eq!(Spin::of::<3>(spatial.vector()), spatial);
    }

    #[test]
    fn a_sphere_surface_velocity_is_perpendicular_to_spin_and_offset() {
        let w = Vector([0.3, -1.0, 2.0]);
        let n = Vector([0.6, 0.0, 0.8]);
        let v = surface_velocity(w, n);
        assert!(v.dot(n).abs() < 1e-15);
        assert!(v.dot(w).abs() < 1e-15);
    }
}
