//! The cue's strike: the velocity and angular velocity a cue ball leaves the tip with.
//!
//! The instantaneous, point-like strike of Leckie & Greenspan ("An event-based pool physics
//! simulator", 2005) as pooltool 0.3.3 computes it (`physics/resolve/stick_ball/
//! instantaneous_point`), with pooltool's corrected impulse (the cue's mass `M` in the
//! numerator, see Alciatore, "cue tip force"), its planar simplification (the ball leaves along
//! the table even for an elevated cue) and, by default, its "throttled english" (the tip
//! offsets halved, since the model overstates spin).

use crate::geom::Vector;

/// pooltool's factor on the tip offsets `a` and `b` when english is throttled.
pub const ENGLISH_FRACTION: f64 = 0.5000001;

/// A shot: how hard, where and at what angle the cue hits the ball (pooltool's `Cue`
/// attributes, the same units).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CueStrike {
    /// Cue speed at impact, m/s (pooltool's `V0`).
    pub speed: f64,
    /// Aiming direction in the table plane, degrees counter-clockwise from `+x` (`phi`).
    pub phi: f64,
    /// Cue elevation above the table, degrees (`theta`).
    pub theta: f64,
    /// Side offset of the tip, in ball radii, −1 to 1; positive strikes left of centre as the
    /// player sees it (`a`).
    pub a: f64,
    /// Vertical offset of the tip, in ball radii, −1 to 1; positive strikes above centre (`b`).
    pub b: f64,
}

impl CueStrike {
    /// A centre-ball, level shot at `speed` m/s towards `phi` degrees.
    #[must_use]
    pub fn new(speed: f64, phi: f64) -> Self {
        CueStrike {
            speed,
            phi,
            theta: 0.0,
            a: 0.0,
            b: 0.0,
        }
    }

    /// The cue ball's velocity (m/s, in the table plane) and angular velocity (rad/s, `z` up)
    /// after the strike, for a ball of mass `m` (kg) and radius `radius` (m) hit by a cue of
    /// mass `cue_mass` (kg; pooltool's default is 0.567), with pooltool's throttled english
    /// when `throttle_english` is set (its default). `None` when the tip would miss the ball
    /// (`a² + b² > 1` after throttling).
    #[must_use]
    pub fn launch(
        &self,
        m: f64,
        radius: f64,
        cue_mass: f64,
        throttle_english: bool,
    ) -> Option<(Vector<2>, Vector<3>)> {
        let fraction = if throttle_english {
            ENGLISH_FRACTION
        } else {
            1.0
        };
        let (a, b) = (self.a * radius * fraction, self.b * radius * fraction);
        let c_sq = radius * radius - a * a - b * b;
        if c_sq < 0.0 {
            return None;
        }
        let c = c_sq.sqrt();
        let (phi, theta) = (self.phi.to_radians(), self.theta.to_radians());
        let (sin_t, cos_t) = theta.sin_cos();
        let inertia = 2.0 / 5.0 * m * radius * radius;
        let spread =
            a * a + (b * cos_t).powi(2) + (c * cos_t).powi(2) - 2.0 * b * c * cos_t * sin_t;
        let force = 2.0 * cue_mass * self.speed
            / (1.0 + m / cue_mass + 5.0 / (2.0 * radius * radius) * spread);
        // In the ball's frame the cue points along −y; the frame is then turned by φ + 90°.
        let v_ball = [0.0, -force / m * cos_t];
        let w_ball = [
            force / inertia * (-c * sin_t + b * cos_t),
            force / inertia * (a * sin_t),
            force / inertia * (-a * cos_t),
        ];
        let (s, k) = (phi + std::f64::consts::FRAC_PI_2).sin_cos();
        let turn = |x: f64, y: f64| [k * x - s * y, s * x + k * y];
        let v = turn(v_ball[0], v_ball[1]);
        let w = turn(w_ball[0], w_ball[1]);
        Some((Vector(v), Vector([w[0], w[1], w_ball[2]])))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const M: f64 = 0.170097;
    const R: f64 = 0.028575;

    #[test]
    fn a_centre_ball_shot_leaves_along_phi_without_spin() {
        let (v, w) = CueStrike::new(2.0, 30.0).launch(M, R, 0.567, true).unwrap();
        let speed = v.norm();
        // F = 2·M·V0 / (1 + m/M + 5/2): the ball takes 2·M·V0 / (m·(1 + m/M + 5/2)).
        let want = 2.0 * 0.567 * 2.0 / (M * (1.0 + M / 0.567 + 2.5));
        assert!((speed - want).abs() < 1e-12);
        assert!((v[1].atan2(v[0]).to_degrees() - 30.0).abs() < 1e-9);
        assert!(w.norm() < 1e-9 * want / R);
    }

    #[test]
    fn top_spin_rolls_the_ball_forwards_and_side_spin_turns_it_about_the_vertical() {
        // Hit above centre towards +x: ω_y > 0 (rolling forwards about +y); hit with side
        // (a > 0, left of centre): spin about the vertical is clockwise from above (ω_z < 0).
        let (v, w) = CueStrike {
            b: 0.4,
            ..CueStrike::new(1.0, 0.0)
        }
        .launch(M, R, 0.567, true)
        .unwrap();
        assert!(v[0] > 0.0 && v[1].abs() < 1e-12);
        assert!(w[1] > 0.0 && w[0].abs() < 1e-9 && w[2] == 0.0);
        let (_, w) = CueStrike {
            a: 0.5,
            ..CueStrike::new(1.0, 0.0)
        }
        .launch(M, R, 0.567, true)
        .unwrap();
        assert!(w[2] < 0.0);
    }

    #[test]
    fn a_tip_off_the_ball_is_refused() {
        let s = CueStrike {
            a: 0.9,
            b: 0.9,
            ..CueStrike::new(1.0, 0.0)
        };
        assert!(s.launch(M, R, 0.567, false).is_none());
        assert!(s.launch(M, R, 0.567, true).is_some());
    }
}
