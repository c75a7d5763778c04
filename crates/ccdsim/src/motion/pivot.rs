//! A ball turning about a point: the motion of a 2D body that slid off the end of a segment
//! too slowly to fly clear ([`crate::contact::ledge`], case 3), held against the end point by gravity.
//!
//! # The motion
//!
//! The centre stays at distance `r` from the pivot point `e`: `c(t) = e + r·u(θ(t))` with
//! `u(θ) = cos θ·up + sin θ·left`, `up = −g/|g|` and `left` the quarter turn of `up`
//! counter-clockwise, so `θ = 0` is straight above `e`. The contact is frictionless, so only
//! gravity's tangential part turns the ball: `θ̈ = k·sin θ` with `k = |g|/r`, an inverted
//! pendulum, and its energy `½θ̇² + k·cos θ` stays the same. Writing `s = sin(θ/2)`,
//!
//! ```text
//! θ̇² = 4k·(c + s²),   c = θ̇₀²/(4k) − s₀²  (dimensionless)
//! ```
//!
//! and the time to turn from `θ₁` to `θ₂` is `∫ dθ/|θ̇|`, with `dθ = 2 ds/√(1 − s²)`:
//! `(1/√k)·∫ ds/√((1 − s²)(c + s²))`, an elliptic integral of the first kind in one of three
//! regimes:
//!
//! - `c > 0`: the ball goes over the top. `√k·t = G(θ)` up to a constant, with
//!   `G(θ) = s·R_F(c(1 − s²), c + s², c)` (Carlson's `R_F`), odd and increasing.
//! - `c < 0`: it cannot reach the top. It turns where `s² = −c` and comes back; with
//!   `m = 1 + c`, the time from the turn to `s` is `F(φ | m)/√k` where
//!   `sin²φ = (s² + c)/(m s²)` (the complement of the Legendre form, so that no difference
//!   of two large integrals is taken near the turn), and inversely `s² = −c/(1 − m sin²φ)`.
//! - `c = 0` (exactly): it creeps towards the top forever or away from it:
//!   `tan(|θ|/4) = tan(|θ₀|/4)·e^{±√k t}`.
//!
//! Positions at a time invert these by Newton's method safeguarded by bisection, in the
//! variable (`θ`, or `φ`) in which the integral's derivative stays finite. Every quantity is a
//! pure function of the state the pivot started from, so every caller gets the same bits.
//!
//! # How it ends
//!
//! The point pushes the ball outwards with force `N/m = |g| cos θ − r θ̇²` (the inward pull it
//! takes to stay on the circle that gravity does not give); frictionless and unglued, the
//! ball comes off where that reaches zero: `cos θ = 2h/3` with `h = 1 + 2c`, i.e.
//! `sin²(θ/2) = (1 − 4c)/6` ([`Pivot::release_time`]), the classic "particle sliding off a
//! sphere" angle (`cos θ = 2/3` from rest at the top). A ball that cannot reach the top first
//! swings back to where it started, onto the segment it came from
//! ([`Pivot::time_at_angle`]); one that meets another segment ending at `e` lands on it the
//! same way. Those are for the caller to take, as is anything else that the ball meets on
//! the way.

use crate::elliptic::{carlson_rf, elliptic_f, elliptic_k};
use crate::geom::Vector;

/// The motion of a ball held against a point `e` by gravity, turning about it (see the
/// module docs). Valid from its start time until [`Pivot::release_time`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Pivot {
    point: Vector<2>,
    radius: f64,
    /// `|g|`, m/s².
    gravity: f64,
    up: Vector<2>,
    left: Vector<2>,
    /// `√k = √(|g|/r)`, 1/s: angles advance in units of it.
    root_k: f64,
    time: f64,
    angle: f64,
    /// `θ̇₀²/(4k) − sin²(θ₀/2)`, dimensionless (module docs).
    c: f64,
    regime: Regime,
}

/// Which of the module docs' regimes the motion is in, and its constants.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Regime {
    /// At rest at the top (or hanging at rest at the bottom): it stays there.
    Still,
    /// `c > 0`: turns in the sense `sense` (±1) forever; `phase0 = G(θ₀)`.
    Over { sense: f64, phase0: f64 },
    /// `c = 0`: on the side `side` (sign of `θ`), moving `away` from the top or towards it.
    Creeping { side: f64, away: bool },
    /// `c < 0`: on the side `side`, turning at absolute time `turn`; `m = 1 + c`.
    Back { side: f64, turn: f64, m: f64 },
}

impl Pivot {
    /// The pivot of a ball of radius `radius` (m) at `pos` with velocity `vel` at time `time`
    /// (s) about `point`, under gravity `gravity` (m/s²): the centre's offset from `point`
    /// gives the angle (its length is taken to be `radius`), the velocity's part across it the
    /// rate. `None` without gravity or for a radius that is not positive and finite.
    #[must_use]
    pub fn new(
        point: Vector<2>,
        radius: f64,
        gravity: Vector<2>,
        pos: Vector<2>,
        vel: Vector<2>,
        time: f64,
    ) -> Option<Self> {
        let (_, up, left) = frame(gravity).filter(|_| radius > 0.0 && radius.is_finite())?;
        let d = pos - point;
        let angle = d.dot(left).atan2(d.dot(up));
        let rate = vel.dot(tangent(up, left, angle)) / radius;
        Self::from_angle(point, radius, gravity, time, angle, rate)
    }

    /// The pivot at angle `angle` (rad, from straight above `point`, counter-clockwise) turning
    /// at `rate` (rad/s) at time `time`; see [`Pivot::new`].
    #[must_use]
    pub fn from_angle(
        point: Vector<2>,
        radius: f64,
        gravity: Vector<2>,
        time: f64,
        angle: f64,
        rate: f64,
    ) -> Option<Self> {
        let finite = radius.is_finite() && angle.is_finite() && rate.is_finite();
        let (g, up, left) = frame(gravity).filter(|_| radius > 0.0 && finite)?;
        let k = g / radius;
        let root_k = k.sqrt();
        let s0 = (0.5 * angle).sin();
        let c = rate * rate / (4.0 * k) - s0 * s0;
        let regime = if c > 0.0 {
            Regime::Over {
                sense: rate.signum(),
                phase0: over_phase(c, angle),
            }
        } else if angle == 0.0 || c <= -1.0 {
            Regime::Still
        } else if c == 0.0 {
            Regime::Creeping {
                side: angle.signum(),
                away: rate * angle > 0.0,
            }
        } else {
            let m = 1.0 + c;
            let from_turn = back_phase(c, m, s0 * s0) / root_k;
            let towards_top = rate * angle < 0.0;
            Regime::Back {
                side: angle.signum(),
                turn: if towards_top {
                    time + from_turn
                } else {
                    time - from_turn
                },
                m,
            }
        };
        Some(Self {
            point,
            radius,
            gravity: g,
            up,
            left,
            root_k,
            time,
            angle,
            c,
            regime,
        })
    }

    /// The point the ball turns about, m.
    #[must_use]
    pub fn point(&self) -> Vector<2> {
        self.point
    }

    /// The centre's distance from the point, m.
    #[must_use]
    pub fn radius(&self) -> f64 {
        self.radius
    }

    /// The magnitude of gravity, m/s².
    #[must_use]
    pub fn gravity_norm(&self) -> f64 {
        self.gravity
    }

    /// The time the motion starts from, s.
    #[must_use]
    pub fn start_time(&self) -> f64 {
        self.time
    }

    /// The angle of direction `dir` in this pivot's frame (rad, from straight up,
    /// counter-clockwise), e.g. of a segment's normal that the ball might land on.
    #[must_use]
    pub fn angle_of(&self, dir: Vector<2>) -> f64 {
        dir.dot(self.left).atan2(dir.dot(self.up))
    }

    /// The angle (rad) and turning rate (rad/s) at time `t` (s), `t` not before the start.
    #[must_use]
    pub fn angle_and_rate(&self, t: f64) -> (f64, f64) {
        let dt = t - self.time;
        let (c, rk) = (self.c, self.root_k);
        match self.regime {
            Regime::Still => (self.angle, 0.0),
            Regime::Over { sense, phase0 } => {
                let theta = over_angle(c, phase0 + sense * rk * dt);
                let s = (0.5 * theta).sin();
                (theta, sense * 2.0 * rk * (c + s * s).sqrt())
            }
            Regime::Creeping { side, away } => {
                let grow = if away { rk * dt } else { -rk * dt };
                let quarter = (0.25 * self.angle.abs()).tan() * grow.exp();
                let theta = side * 4.0 * quarter.atan();
                let rate = 2.0 * rk * (0.5 * theta).sin().abs();
                (theta, if away { side * rate } else { -side * rate })
            }
            Regime::Back { side, turn, m } => {
                let phi = back_angle(m, rk * (t - turn).abs());
                let sin2 = phi.sin().powi(2);
                let s2 = -c / (1.0 - m * sin2);
                let theta = side * 2.0 * s2.sqrt().min(1.0).asin();
                // c + s² without the cancellation near the turn.
                let rate = 2.0 * rk * (-c * m * sin2 / (1.0 - m * sin2)).sqrt();
                (theta, if t < turn { -side * rate } else { side * rate })
            }
        }
    }

    /// The centre's position at time `t` (s), m.
    #[must_use]
    pub fn position(&self, t: f64) -> Vector<2> {
        let (theta, _) = self.angle_and_rate(t);
        self.point + self.direction(theta) * self.radius
    }

    /// The centre's velocity at time `t` (s), m/s: along the circle.
    #[must_use]
    pub fn velocity(&self, t: f64) -> Vector<2> {
        let (theta, rate) = self.angle_and_rate(t);
        tangent(self.up, self.left, theta) * (self.radius * rate)
    }

    /// The unit direction from the point at angle `theta`.
    #[must_use]
    pub fn direction(&self, theta: f64) -> Vector<2> {
        let (s, c) = theta.sin_cos();
        self.up * c + self.left * s
    }

    /// The time (s) at which the point stops pushing the ball, which then flies off: the
    /// start time if it does not push it now (the ball was not held); `None` if the ball
    /// never comes off (it rests balanced on top, or creeps towards the top forever).
    #[must_use]
    pub fn release_time(&self) -> Option<f64> {
        let s_d2 = (1.0 - 4.0 * self.c) / 6.0;
        let s0 = (0.5 * self.angle).sin();
        let away = match self.regime {
            Regime::Over { sense, .. } => sense * self.angle > 0.0,
            Regime::Creeping { away, .. } => away,
            Regime::Back { turn, .. } => turn <= self.time,
            Regime::Still => false,
        };
        if s_d2 <= 0.0 || s0 * s0 > s_d2 || (s0 * s0 == s_d2 && away) {
            return Some(self.time);
        }
        let theta_d = 2.0 * s_d2.sqrt().asin();
        let t = match self.regime {
            Regime::Still => return None,
            Regime::Over { sense, phase0 } => {
                self.time + (over_phase(self.c, theta_d) - sense * phase0) / self.root_k
            }
            Regime::Creeping { away, .. } => {
                if !away {
                    return None;
                }
                self.time + creep_log(theta_d, self.angle) / self.root_k
            }
            Regime::Back { turn, m, .. } => turn + back_phase(self.c, m, s_d2) / self.root_k,
        };
        Some(t.max(self.time))
    }

    /// The time (s) at which a ball turning towards the top swings back to the angle it
    /// started from (onto the segment it slid off), turning the other way as fast; `None` if
    /// it goes over the top, creeps, or is moving away from the top already. Symmetric about
    /// the turn, so that it is exactly the start's angle that is reached, not one an ulp off.
    #[must_use]
    pub fn return_time(&self) -> Option<f64> {
        match self.regime {
            Regime::Back { turn, .. } if turn > self.time => Some(turn + (turn - self.time)),
            _ => None,
        }
    }

    /// The first time (s) after the start at which the angle is `target` (rad, see
    /// [`Pivot::angle_of`]), or `None` if the motion never passes it. It is meant for angles
    /// before the release (landing on a segment, or swinging back onto the one it came
    /// from): past [`Pivot::release_time`] the ball has flown off.
    #[must_use]
    pub fn time_at_angle(&self, target: f64) -> Option<f64> {
        let (c, rk, t0, a0) = (self.c, self.root_k, self.time, self.angle);
        let t = match self.regime {
            Regime::Still => return None,
            Regime::Over { sense, phase0 } => {
                if sense * (target - a0) <= 0.0 {
                    return None;
                }
                t0 + sense * (over_phase(c, target) - phase0) / rk
            }
            Regime::Creeping { side, away } => {
                if side * target <= 0.0 || (target.abs() > a0.abs()) != away {
                    return None;
                }
                t0 + creep_log(target, a0).abs() / rk
            }
            Regime::Back { side, turn, m } => {
                let s = (0.5 * target).sin();
                if side * target <= 0.0 || s * s < -c {
                    return None;
                }
                let from_turn = back_phase(c, m, s * s) / rk;
                if turn > t0 && target.abs() < a0.abs() {
                    turn - from_turn
                } else if turn > t0 || target.abs() > a0.abs() {
                    turn + from_turn
                } else {
                    return None;
                }
            }
        };
        (t.is_finite() && t > t0).then_some(t)
    }
}

/// `|g|`, `up = −g/|g|` and `left`, its quarter turn counter-clockwise: the frame angles are
/// measured in; `None` for a gravity that is zero or not finite.
fn frame(gravity: Vector<2>) -> Option<(f64, Vector<2>, Vector<2>)> {
    let g = gravity.norm();
    if !(g > 0.0 && g.is_finite()) {
        return None;
    }
    let up = gravity * (-1.0 / g);
    Some((g, up, Vector([-up[1], up[0]])))
}

/// The unit tangent of the circle at angle `theta` (the direction of increasing angle).
fn tangent(up: Vector<2>, left: Vector<2>, theta: f64) -> Vector<2> {
    let (s, c) = theta.sin_cos();
    left * c - up * s
}

/// `G(θ) = s·R_F(c(1 − s²), c + s², c)` with `s = sin(θ/2)`, for `c > 0`: `√k` times the time
/// to turn from the top to `θ` (negative before it).
fn over_phase(c: f64, theta: f64) -> f64 {
    let s = (0.5 * theta).sin();
    s * carlson_rf(c * (1.0 - s * s), c + s * s, c)
}

/// The angle `θ ∈ [−π, π]` with [`over_phase`] `= u`.
fn over_angle(c: f64, u: f64) -> f64 {
    let pi = std::f64::consts::PI;
    let top = over_phase(c, pi);
    let u = u.clamp(-top, top);
    solve_increasing(
        |theta| {
            let s = (0.5 * theta).sin();
            (over_phase(c, theta), 0.5 / (c + s * s).sqrt())
        },
        u,
        (-pi, pi),
        u * (pi / top),
    )
}

/// For `c < 0`, `m = 1 + c`: `√k` times the time from the turn (`s² = −c`) to `s² = s2`,
/// `F(φ | m)` with `sin²φ = (s2 + c)/(m·s2)`, written out as `sin φ·R_F(cos²φ, 1 − m sin²φ, 1)`.
fn back_phase(c: f64, m: f64, s2: f64) -> f64 {
    let sin2 = ((s2 + c) / (m * s2)).clamp(0.0, 1.0);
    sin2.sqrt() * carlson_rf(-c * (1.0 - s2) / (m * s2), -c / s2, 1.0)
}

/// The `φ ∈ [0, π/2]` with `F(φ | m) = x` (`π/2` for `x ≥ K(m)`).
fn back_angle(m: f64, x: f64) -> f64 {
    let half_pi = std::f64::consts::FRAC_PI_2;
    if x >= elliptic_k(m) {
        return half_pi;
    }
    let hi = x.min(half_pi);
    solve_increasing(
        |phi| {
            (
                elliptic_f(phi, m),
                1.0 / (1.0 - m * phi.sin().powi(2)).sqrt(),
            )
        },
        x,
        (0.0, hi),
        hi,
    )
}

/// `ln tan(|θ|/4) − ln tan(|θ₀|/4)`: `√k` times the signed time to creep from `θ₀` to `θ` on
/// the separatrix (`c = 0`).
fn creep_log(theta: f64, theta0: f64) -> f64 {
    ((0.25 * theta.abs()).tan() / (0.25 * theta0.abs()).tan()).ln()
}

/// The root in `bracket` of the increasing `f` (returning value and derivative) at `target`:
/// Newton's steps from `guess`, bisecting whenever a step leaves the shrinking bracket.
fn solve_increasing(
    f: impl Fn(f64) -> (f64, f64),
    target: f64,
    bracket: (f64, f64),
    guess: f64,
) -> f64 {
    let (mut lo, mut hi) = bracket;
    let mut x = guess.clamp(lo, hi);
    for _ in 0..200 {
        let (value, slope) = f(x);
        let miss = value - target;
        if miss == 0.0 {
            return x;
        }
        if miss < 0.0 {
            lo = x;
        } else {
            hi = x;
        }
        let mut next = x - miss / slope;
        if !(next > lo && next < hi) {
            next = 0.5 * (lo + hi);
        }
        if (next - x).abs() <= 2.0 * f64::EPSILON * x.abs().max(f64::MIN_POSITIVE) || hi <= lo {
            return next;
        }
        x = next;
    }
    x
}

/// The first two components of `v`, metres or m/s: a `Vector<D>` of a run where bodies turn
/// about points, which is 2D.
#[must_use]
pub fn to_2d<const D: usize>(v: Vector<D>) -> Vector<2> {
    Vector([v[0], v[1]])
}

/// A wall of a run where bodies turn about points as a 2D one (see [`to_2d`]).
#[must_use]
pub fn wall_2d<const D: usize>(w: &crate::wall::Wall<D>) -> crate::wall::Wall<2> {
    use crate::wall::Wall;
    match *w {
        Wall::Segment { a, b } => Wall::Segment {
            a: to_2d(a),
            b: to_2d(b),
        },
        Wall::Plane { point, normal } => Wall::Plane {
            point: to_2d(point),
            normal: to_2d(normal),
        },
    }
}

/// A 2D vector as a `Vector<D>` (`D = 2` wherever bodies turn about points).
#[must_use]
pub fn from_2d<const D: usize>(v: Vector<2>) -> Vector<D> {
    let mut out = Vector::ZERO;
    out[0] = v[0];
    out[1] = v[1];
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    const G: Vector<2> = Vector([0.0, -10.0]);

    /// The reference: the pendulum `θ̈ = k sin θ` integrated by classical Runge–Kutta with
    /// steps far below its time scale; returns `(θ, θ̇)` at `t` after the start.
    fn integrate(k: f64, theta: f64, rate: f64, t: f64) -> (f64, f64) {
        let n = ((t * k.sqrt()) / 2e-4).ceil().max(1.0);
        let h = t / n;
        let f = |y: (f64, f64)| (y.1, k * y.0.sin());
        let mut y = (theta, rate);
        for _ in 0..n as usize {
            let k1 = f(y);
            let k2 = f((y.0 + 0.5 * h * k1.0, y.1 + 0.5 * h * k1.1));
            let k3 = f((y.0 + 0.5 * h * k2.0, y.1 + 0.5 * h * k2.1));
            let k4 = f((y.0 + h * k3.0, y.1 + h * k3.1));
            y.0 += h / 6.0 * (k1.0 + 2.0 * k2.0 + 2.0 * k3.0 + k4.0);
            y.1 += h / 6.0 * (k1.1 + 2.0 * k2.1 + 2.0 * k3.1 + k4.1);
        }
        y
    }

    /// The point's push per unit mass at `t`, m/s².
    fn push(p: &Pivot, g: f64, t: f64) -> f64 {
        let (theta, rate) = p.angle_and_rate(t);
        g * theta.cos() - p.radius * rate * rate
    }

    #[test]
    fn ball_sliding_off_a_level_ledge_leaves_at_the_classic_angle() {
        // A ball of radius 0.5 at the end of a level floor, moving right at 1 m/s.
        let (r, v) = (0.5, 1.0);
        let p = Pivot::new(
            Vector([0.0, 0.0]),
            r,
            G,
            Vector([0.0, r]),
            Vector([v, 0.0]),
            2.0,
        )
        .unwrap();
        assert_eq!(p.angle_and_rate(2.0).0, 0.0);
        let t = p.release_time().unwrap();
        assert!(t > 2.0);
        let (theta, rate) = p.angle_and_rate(t);
        // Turning right is clockwise: the angle goes negative.
        assert!(theta < 0.0 && rate < 0.0);
        let want = (2.0 / 3.0 + v * v / (3.0 * 10.0 * r)).acos();
        assert!((theta.abs() - want).abs() < 1e-12, "{theta} vs {want}");
        assert!(push(&p, 10.0, t).abs() < 1e-10);
        assert!(push(&p, 10.0, 0.5 * (2.0 + t)) > 0.0);
        // Energy: the speed at release is what the drop gave it.
        let drop = r * (1.0 - theta.cos());
        let speed = p.velocity(t).norm();
        assert!((speed * speed - (v * v + 2.0 * 10.0 * drop)).abs() < 1e-10);
        assert!((p.position(t) - p.point()).norm() - r < 1e-15);
    }

    #[test]
    fn a_slow_ball_off_the_top_of_an_incline_swings_back_onto_it() {
        // The incline rises to the right at 30°; the ball slides up off its top end slowly.
        let (r, a) = (0.5, 30f64.to_radians());
        let n = Vector([-a.sin(), a.cos()]);
        let along = Vector([a.cos(), a.sin()]);
        let e = Vector([1.0, 2.0]);
        let p = Pivot::new(e, r, G, e + n * r, along * 0.3, 0.0).unwrap();
        let theta0 = p.angle_of(n);
        assert!((theta0 - a).abs() < 1e-15);
        let back = p.return_time().expect("it swings back");
        // An angle a hair short of the start is passed at once, on the way up.
        assert!(p.time_at_angle(theta0 - 1e-9).unwrap() < 1e-6);
        assert!(p.release_time().is_none_or(|t| t > back));
        let (theta, rate) = p.angle_and_rate(back);
        assert!((theta - theta0).abs() < 1e-12);
        // It comes back as fast as it left, the other way.
        assert!((p.velocity(back) + along * 0.3).norm() < 1e-12);
        assert!(rate > 0.0);
        assert!((p.position(back) - (e + n * r)).norm() < 1e-12);
    }

    #[test]
    fn on_the_separatrix_it_creeps_to_the_top_forever() {
        // k = 1 and θ̇₀ = 2 sin(θ₀/2) make c exactly zero.
        let theta0: f64 = 0.8;
        let rate = -2.0 * (0.5 * theta0).sin();
        let p = Pivot::from_angle(Vector([0.0, 0.0]), 10.0, G, 0.0, theta0, rate).unwrap();
        assert!(matches!(p.regime, Regime::Creeping { away: false, .. }));
        assert_eq!(p.release_time(), None);
        assert_eq!(p.time_at_angle(-0.1), None);
        for t in [0.5, 2.0, 5.0] {
            let (theta, r) = p.angle_and_rate(t);
            let (want, want_rate) = integrate(1.0, theta0, rate, t);
            assert!((theta - want).abs() < 1e-9 && (r - want_rate).abs() < 1e-9);
            assert!((p.time_at_angle(theta).unwrap() - t).abs() < 1e-9);
        }
        // The other way it falls off.
        let away = Pivot::from_angle(Vector([0.0, 0.0]), 10.0, G, 0.0, theta0, -rate).unwrap();
        let t = away.release_time().unwrap();
        assert!(push(&away, 10.0, t).abs() < 1e-10);
    }

    #[test]
    fn balanced_on_top_it_stays() {
        let p = Pivot::from_angle(Vector([0.0, 0.0]), 1.0, G, 0.0, 0.0, 0.0).unwrap();
        assert_eq!(p.angle_and_rate(100.0), (0.0, 0.0));
        assert_eq!(p.release_time(), None);
        assert_eq!(p.time_at_angle(0.1), None);
    }

    #[test]
    fn a_ball_not_held_leaves_at_once_and_bad_input_has_no_pivot() {
        // Fast over a level ledge: v² > g r.
        let p = Pivot::new(
            Vector([0.0, 0.0]),
            0.5,
            G,
            Vector([0.0, 0.5]),
            Vector([3.0, 0.0]),
            1.0,
        )
        .unwrap();
        assert_eq!(p.release_time(), Some(1.0));
        let zero = Vector([0.0, 0.0]);
        assert!(Pivot::new(zero, 1.0, zero, zero, zero, 0.0).is_none());
        assert!(Pivot::new(zero, 0.0, G, zero, zero, 0.0).is_none());
        assert!(Pivot::from_angle(zero, 1.0, G, 0.0, f64::NAN, 0.0).is_none());
    }

    proptest! {
        /// Against the integrated reference, in every regime a held ball can be in: angle and
        /// rate agree to 1e-8 up to the release, the push is zero there and positive before,
        /// and the time at an angle inverts the angle at a time.
        #[test]
        fn matches_the_integrated_pendulum(
            g in 1.0f64..20.0,
            r in 0.05f64..2.0,
            theta0 in -1.2f64..1.2,
            frac in -1.0f64..1.0,
            t0 in -10.0f64..10.0,
        ) {
            let k = g / r;
            // Any rate at which the point still pushes: θ̇² ≤ k cos θ.
            let rate = frac * (k * theta0.cos()).sqrt();
            let gravity = Vector([0.6, -0.8]) * g;
            let p = Pivot::from_angle(Vector([1.0, -2.0]), r, gravity, t0, theta0, rate).unwrap();
            let horizon = 3.0 / k.sqrt();
            let end = p.release_time().map_or(t0 + horizon, |t| t.min(t0 + horizon));
            prop_assert!(end >= t0);
            for i in 1..=4 {
                let t = t0 + (end - t0) * f64::from(i) / 4.0;
                let (theta, w) = p.angle_and_rate(t);
                let (want, want_w) = integrate(k, theta0, rate, t - t0);
                prop_assert!((theta - want).abs() < 1e-8, "θ({t}) = {theta}, want {want}");
                prop_assert!((w - want_w).abs() < 1e-8 * k.sqrt().max(1.0), "θ̇ {w} vs {want_w}");
                prop_assert!(push(&p, g, t) >= -1e-9 * g);
                // Where the angle is passed once, the time at it is the time.
                if let Some(back) = p.time_at_angle(theta).filter(|_| end > t0) {
                    prop_assert!(back <= t + 1e-9 * (1.0 + t.abs()), "{back} > {t}");
                    let (again, _) = p.angle_and_rate(back);
                    prop_assert!((again - theta).abs() < 1e-9);
                }
            }
            if let Some(t) = p.release_time().filter(|&t| t > t0) {
                prop_assert!(push(&p, g, t).abs() < 1e-8 * g, "push at release {}", push(&p, g, t));
            }
        }
    }
}
