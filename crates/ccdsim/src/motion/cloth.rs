//! A billiard ball on the cloth: its four motion states, the law of motion in each, and when
//! one state gives way to the next.
//!
//! The model is Leckie & Greenspan's ("An event-based pool physics simulator", Advances in
//! Computer Games 2005) with the parameters and conventions of pooltool 0.3.3
//! (`pooltool/physics/evolve`, `pooltool/ptmath/utils.py`; Kiefl, "pooltool-theory", 2020).
//! The table is the plane `z = 0` seen from above: a ball's centre moves in the plane (`x`,
//! `y`), its angular velocity `ω` is a three-vector (`z` up), and the cloth touches it at
//! `−R·ẑ` from its centre. In every state a ball's planar position is a quadratic in time and
//! its velocity and angular velocity are linear, so a ball–ball contact is a root of a quartic
//! and a ball–line contact of a quadratic, as for parabolas under gravity.
//!
//! - **Sliding**: the cloth's contact point slips (`u = v + R·ẑ×ω ≠ 0`). Friction `μ_s·m·g`
//!   opposes `û`, which stays fixed while the slip shrinks: `v(t) = v₀ − μ_s·g·t·û`,
//!   `ω_xy(t) = ω₀_xy − (5·μ_s·g/(2R))·t·(û×ẑ)`; the slip falls at `(7/2)·μ_s·g` and is gone
//!   after `2|u₀|/(7·μ_s·g)`, when the ball rolls.
//! - **Rolling**: no slip (`ω_xy = ẑ×v/R`); rolling resistance `μ_r·m·g` opposes `v̂`, which
//!   stops the ball after `|v₀|/(μ_r·g)`.
//! - **Spinning**: in place, about the vertical axis only.
//! - **Stationary**: at rest.
//!
//! In every state but the last, spin about the vertical decays on its own at
//! `5·μ_sp·g/(2R)` rad/s² until it is zero (and stays zero). A rolling ball whose vertical
//! spin outlasts its roll ends spinning, otherwise stationary (pooltool's rule); a spinning
//! ball ends stationary.

use crate::geom::Vector;

/// The cloth and ball parameters the motion laws need (SI units). The default is pooltool
/// 0.3.3's generic pool ball (`BallParams()`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ClothParams {
    /// Ball radius `R`, metres (default 0.028575).
    pub radius: f64,
    /// Sliding friction coefficient `μ_s` (default 0.2).
    pub sliding_friction: f64,
    /// Rolling resistance coefficient `μ_r` (default 0.01).
    pub rolling_friction: f64,
    /// Spinning friction coefficient `μ_sp`, dimensionless (default `(10·2/5/9)·R`, pooltool's
    /// `u_sp_proportionality · R`).
    pub spinning_friction: f64,
    /// Gravitational acceleration `g`, m/s² (default 9.81).
    pub gravity: f64,
}

impl Default for ClothParams {
    fn default() -> Self {
        let radius = 0.028575;
        ClothParams {
            radius,
            sliding_friction: 0.2,
            rolling_friction: 0.01,
            spinning_friction: 10.0 * 2.0 / 5.0 / 9.0 * radius,
            gravity: 9.81,
        }
    }
}

/// A ball's motion state on the cloth (pooltool's `stationary`, `spinning`, `sliding`,
/// `rolling`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ClothState {
    /// At rest.
    Stationary,
    /// Turning in place about the vertical axis.
    Spinning,
    /// Moving with its contact point slipping on the cloth.
    Sliding,
    /// Rolling without slipping.
    Rolling,
}

impl ClothState {
    /// pooltool's name for the state: "stationary", "spinning", "sliding" or "rolling".
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            ClothState::Stationary => "stationary",
            ClothState::Spinning => "spinning",
            ClothState::Sliding => "sliding",
            ClothState::Rolling => "rolling",
        }
    }
}

/// A ball's kinematic state on the table at one instant.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ClothBall {
    /// Centre in the table plane, metres.
    pub pos: Vector<2>,
    /// Velocity of the centre, m/s.
    pub vel: Vector<2>,
    /// Angular velocity, rad/s (`z` up).
    pub spin: Vector<3>,
}

impl ClothParams {
    /// Spin about the vertical decays at this rate while the ball moves or spins, rad/s².
    #[must_use]
    pub fn spin_decay(&self) -> f64 {
        5.0 * self.spinning_friction * self.gravity / (2.0 * self.radius)
    }

    /// Velocity of the ball's point on the cloth, m/s: `v + R·ẑ×ω` (zero when it rolls).
    #[must_use]
    pub fn slip(&self, b: &ClothBall) -> Vector<2> {
        Vector([
            b.vel[0] - self.radius * b.spin[1],
            b.vel[1] + self.radius * b.spin[0],
        ])
    }

    /// The state a ball with this velocity and angular velocity is in: sliding while its
    /// contact point slips, rolling while it moves, spinning while it turns about the
    /// vertical, stationary otherwise (exact comparisons with zero).
    #[must_use]
    pub fn state_of(&self, b: &ClothBall) -> ClothState {
        let slip = self.slip(b);
        if slip[0] != 0.0 || slip[1] != 0.0 {
            ClothState::Sliding
        } else if b.vel[0] != 0.0 || b.vel[1] != 0.0 {
            ClothState::Rolling
        } else if b.spin[2] != 0.0 {
            ClothState::Spinning
        } else {
            ClothState::Stationary
        }
    }

    /// The constant planar acceleration of a ball in `state`, m/s²: `−μ_s·g·û` sliding,
    /// `−μ_r·g·v̂` rolling, zero otherwise.
    #[must_use]
    pub fn acceleration(&self, b: &ClothBall, state: ClothState) -> Vector<2> {
        match state {
            ClothState::Sliding => unit(self.slip(b)) * (-self.sliding_friction * self.gravity),
            ClothState::Rolling => unit(b.vel) * (-self.rolling_friction * self.gravity),
            ClothState::Spinning | ClothState::Stationary => Vector::ZERO,
        }
    }

    /// How long a ball stays in `state`, seconds, and the state that follows (pooltool's
    /// `get_slide_time`, `get_roll_time`, `get_spin_time` and its choice between them);
    /// `None` for a stationary ball, or when the friction that would end the state is zero.
    #[must_use]
    pub fn transition(&self, b: &ClothBall, state: ClothState) -> Option<(f64, ClothState)> {
        let g = self.gravity;
        let spin_time = || {
            (self.spinning_friction != 0.0)
                .then(|| b.spin[2].abs() * 2.0 / 5.0 * self.radius / self.spinning_friction / g)
        };
        match state {
            ClothState::Stationary => None,
            ClothState::Spinning => spin_time().map(|t| (t, ClothState::Stationary)),
            ClothState::Sliding => (self.sliding_friction != 0.0).then(|| {
                (
                    2.0 * self.slip(b).norm() / (7.0 * self.sliding_friction * g),
                    ClothState::Rolling,
                )
            }),
            ClothState::Rolling => (self.rolling_friction != 0.0).then(|| {
                let roll = b.vel.norm() / (self.rolling_friction * g);
                let next = match spin_time() {
                    Some(spin) if spin > roll => ClothState::Spinning,
                    _ => ClothState::Stationary,
                };
                (roll, next)
            }),
        }
    }

    /// The ball `dt` seconds later, `dt` no longer than its state lasts (see
    /// [`ClothParams::transition`]): the closed forms of the module docs.
    #[must_use]
    pub fn evolve(&self, b: &ClothBall, state: ClothState, dt: f64) -> ClothBall {
        let wz = self.decayed_spin(b.spin[2], dt);
        match state {
            ClothState::Stationary => *b,
            ClothState::Spinning => ClothBall {
                spin: Vector([b.spin[0], b.spin[1], wz]),
                ..*b
            },
            ClothState::Sliding => {
                let u = unit(self.slip(b));
                let a = u * (-self.sliding_friction * self.gravity);
                let k = 5.0 * self.sliding_friction * self.gravity / (2.0 * self.radius) * dt;
                ClothBall {
                    pos: b.pos + b.vel * dt + a * (0.5 * dt * dt),
                    vel: b.vel + a * dt,
                    // ω_xy − k·(û×ẑ), with û×ẑ = (u_y, −u_x).
                    spin: Vector([b.spin[0] - k * u[1], b.spin[1] + k * u[0], wz]),
                }
            }
            ClothState::Rolling => {
                let a = unit(b.vel) * (-self.rolling_friction * self.gravity);
                let vel = b.vel + a * dt;
                ClothBall {
                    pos: b.pos + b.vel * dt + a * (0.5 * dt * dt),
                    vel,
                    spin: Vector([-vel[1] / self.radius, vel[0] / self.radius, wz]),
                }
            }
        }
    }

    /// The ball and its state `dt` seconds later, through every state change on the way
    /// (pooltool's `evolve_ball_motion`): at each change the ball takes the next state, with
    /// the residual velocity (a spinning or stationary ball's) and in-plane spin (a spinning
    /// ball's) set to zero, as pooltool's canonical transition does.
    #[must_use]
    pub fn advance(
        &self,
        b: &ClothBall,
        state: ClothState,
        mut dt: f64,
    ) -> (ClothBall, ClothState) {
        let (mut b, mut state) = (*b, state);
        loop {
            match self.transition(&b, state) {
                Some((span, next)) if span <= dt => {
                    b = settle(self.evolve(&b, state, span), next);
                    state = next;
                    dt -= span;
                }
                _ => return (self.evolve(&b, state, dt), state),
            }
        }
    }

    /// `wz` after `dt` seconds of decay towards zero, never past it.
    fn decayed_spin(&self, wz: f64, dt: f64) -> f64 {
        if dt == 0.0 || wz == 0.0 {
            return wz;
        }
        let alpha = self.spin_decay();
        let t = dt.min(wz.abs() / alpha);
        wz - wz.signum() * alpha * t
    }
}

/// A ball entering `state` at a state change: a spinning ball keeps only its vertical spin, a
/// stationary one nothing (the residues of rounding set to zero).
#[must_use]
pub fn settle(mut b: ClothBall, state: ClothState) -> ClothBall {
    match state {
        ClothState::Spinning => {
            b.vel = Vector::ZERO;
            b.spin = Vector([0.0, 0.0, b.spin[2]]);
        }
        ClothState::Stationary => {
            b.vel = Vector::ZERO;
            b.spin = Vector::ZERO;
        }
        ClothState::Sliding | ClothState::Rolling => {}
    }
    b
}

/// `v / |v|`, or zero for the zero vector.
fn unit(v: Vector<2>) -> Vector<2> {
    let n = v.norm();
    if n == 0.0 {
        Vector::ZERO
    } else {
        v * (1.0 / n)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ball(vel: [f64; 2], spin: [f64; 3]) -> ClothBall {
        ClothBall {
            pos: Vector([0.5, 1.0]),
            vel: Vector(vel),
            spin: Vector(spin),
        }
    }

    fn close(a: f64, b: f64, tol: f64) -> bool {
        (a - b).abs() <= tol * (1.0 + a.abs().max(b.abs()))
    }

    #[test]
    fn a_struck_ball_slides_then_rolls_at_five_sevenths_of_its_speed() {
        // A stun shot (no spin): the slip is the velocity, the roll starts after
        // 2v/(7·μ_s·g) at 5/7 of the speed (a classic result).
        let p = ClothParams::default();
        let b = ball([2.0, 0.0], [0.0, 0.0, 0.0]);
        assert_eq!(p.state_of(&b), ClothState::Sliding);
        let (t, next) = p.transition(&b, ClothState::Sliding).unwrap();
        assert_eq!(next, ClothState::Rolling);
        assert!(close(t, 4.0 / (7.0 * 0.2 * 9.81), 1e-15));
        let at = settle(p.evolve(&b, ClothState::Sliding, t), next);
        assert!(close(at.vel[0], 2.0 * 5.0 / 7.0, 1e-14));
        assert!(p.slip(&at).norm() < 1e-14);
        assert!(close(at.spin[1], at.vel[0] / p.radius, 1e-14));
    }

    #[test]
    fn a_rolling_ball_stops_where_its_kinetic_energy_runs_out() {
        // Rolling at v: stops after v/(μ_r·g), having travelled v²/(2·μ_r·g).
        let p = ClothParams::default();
        let v = 1.5;
        let b = ball([0.0, v], [-v / p.radius, 0.0, 0.0]);
        assert_eq!(p.state_of(&b), ClothState::Rolling);
        let (t, next) = p.transition(&b, ClothState::Rolling).unwrap();
        assert_eq!(next, ClothState::Stationary);
        let end = p.evolve(&b, ClothState::Rolling, t);
        assert!(end.vel.norm() < 1e-14);
        assert!(close(
            end.pos[1] - b.pos[1],
            v * v / (2.0 * 0.01 * 9.81),
            1e-14
        ));
        let (rest, state) = p.advance(&b, ClothState::Rolling, t + 5.0);
        assert_eq!(state, ClothState::Stationary);
        assert_eq!(rest.vel, Vector::ZERO);
        assert_eq!(rest.spin, Vector::ZERO);
    }

    #[test]
    fn vertical_spin_outlasting_the_roll_leaves_the_ball_spinning_then_stationary() {
        let p = ClothParams::default();
        let b = ball([0.1, 0.0], [0.0, 0.1 / p.radius, 30.0]);
        let (roll, next) = p.transition(&b, ClothState::Rolling).unwrap();
        assert_eq!(next, ClothState::Spinning);
        let spin_time = 30.0 / p.spin_decay();
        assert!(spin_time > roll);
        let (mid, state) = p.advance(&b, ClothState::Rolling, roll + 0.01);
        assert_eq!(state, ClothState::Spinning);
        assert_eq!(mid.vel, Vector::ZERO);
        assert!(close(
            mid.spin[2],
            30.0 - p.spin_decay() * (roll + 0.01),
            1e-12
        ));
        let (end, state) = p.advance(&b, ClothState::Rolling, spin_time + 1.0);
        assert_eq!(state, ClothState::Stationary);
        assert_eq!(end.spin, Vector::ZERO);
    }

    #[test]
    fn the_slip_shrinks_along_a_fixed_direction_at_seven_halves_mu_g() {
        // Draw with side spin: the slip's direction stays fixed while sliding and its length
        // falls linearly, so the transition time is exact.
        let p = ClothParams::default();
        let b = ball([1.0, 0.5], [12.0, -40.0, 5.0]);
        let u0 = p.slip(&b);
        let (t, _) = p.transition(&b, ClothState::Sliding).unwrap();
        for f in [0.25, 0.5, 0.75] {
            let s = p.slip(&p.evolve(&b, ClothState::Sliding, f * t));
            assert!(close(s.norm(), (1.0 - f) * u0.norm(), 1e-13));
            assert!((s[0] * u0[1] - s[1] * u0[0]).abs() < 1e-12);
        }
        assert!(p.slip(&p.evolve(&b, ClothState::Sliding, t)).norm() < 1e-13);
    }

    #[test]
    fn position_velocity_and_acceleration_agree() {
        let p = ClothParams::default();
        let b = ball([1.0, -0.3], [3.0, 20.0, -2.0]);
        for state in [ClothState::Sliding, ClothState::Rolling] {
            let b = if state == ClothState::Rolling {
                ClothBall {
                    spin: Vector([0.3 / p.radius, 1.0 / p.radius, -2.0]),
                    ..b
                }
            } else {
                b
            };
            let a = p.acceleration(&b, state);
            let dt = 0.05;
            let e = p.evolve(&b, state, dt);
            let want = b.pos + b.vel * dt + a * (0.5 * dt * dt);
            assert!((e.pos - want).norm() < 1e-15);
            assert!((e.vel - (b.vel + a * dt)).norm() < 1e-15);
        }
    }

    #[test]
    fn no_friction_no_transition() {
        let p = ClothParams {
            sliding_friction: 0.0,
            rolling_friction: 0.0,
            spinning_friction: 0.0,
            ..ClothParams::default()
        };
        let b = ball([1.0, 0.0], [0.0, 0.0, 3.0]);
        for s in [
            ClothState::Sliding,
            ClothState::Rolling,
            ClothState::Spinning,
            ClothState::Stationary,
        ] {
            assert_eq!(p.transition(&b, s), None);
        }
    }
}
