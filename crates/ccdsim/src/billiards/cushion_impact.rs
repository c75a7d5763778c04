//! A ball bouncing off a cushion: Han's model (I. Han, "Dynamics in carom and three cushion
//! billiards", Journal of Mechanical Science and Technology 19, 2005), as pooltool 0.3.3
//! applies it (`physics/resolve/ball_cushion/han_2005`) with a constant restitution `e_c` and
//! friction `f_c`.
//!
//! The cushion's nose touches the ball above its equator, at height `h` over the cloth, so the
//! contact normal is tilted by `θ_a = asin(h/R − 1)` from the horizontal. In the cushion's
//! frame (`x` along the normal into the cushion, `y` along it, `z` up) the contact point slips
//! at `s = (v_x·sin θ_a + R·ω_y, −v_y − R·ω_z·cos θ_a + R·ω_x·sin θ_a)` and the ball drives
//! into the cushion at `c = v_x·cos θ_a`. The normal impulse that restitution asks for is
//! `(1 + e)·c·m`; if the impulse that would stop the slip, `|s|·2m/7`, is no larger, the
//! contact sticks (the slip is removed), else it slides with friction `f_c` (Han's Eqs. 14–20).
//! The ball's vertical velocity change is dropped: it stays on the cloth.

use super::ball_impact::{closing_speed, rest_if_rounding, rounding_floor};
use super::params::BallParams;
use crate::geom::Vector;
use crate::motion::{ClothBall, ClothParams};

/// The ball after bouncing off a cushion whose contact normal in the table plane is `normal`
/// (a unit vector, either sign: it is turned to point into the cushion, along the ball's
/// velocity; a ball that meets it without normal velocity, turning back towards it, takes
/// `normal` as it is), for a ball of radius `radius` (m) and mass `mass` (kg), a cushion nose at
/// `height` (m) above the cloth, restitution `e` and friction `mu`. The position is unchanged.
#[must_use]
pub fn bounce(
    b: &ClothBall,
    normal: Vector<2>,
    radius: f64,
    mass: f64,
    height: f64,
    e: f64,
    mu: f64,
) -> ClothBall {
    let n = if normal.dot(b.vel) >= 0.0 {
        normal
    } else {
        -normal
    };
    // The cushion frame: x along n, y along n turned a quarter counter-clockwise.
    let t = Vector([-n[1], n[0]]);
    let w_xy = Vector([b.spin[0], b.spin[1]]);
    let (vx, vy) = (b.vel.dot(n), b.vel.dot(t));
    let (wx, wy, wz) = (w_xy.dot(n), w_xy.dot(t), b.spin[2]);
    let phi = vy.atan2(vx).rem_euclid(std::f64::consts::TAU);
    let theta = (height / radius - 1.0).asin();
    let (sin_t, cos_t) = theta.sin_cos();

    let sx = vx * sin_t + radius * wy;
    let sy = -vy - radius * wz * cos_t + radius * wx * sin_t;
    let c = vx * cos_t;
    let inertia = 2.0 / 5.0 * mass * radius * radius;
    let a = 7.0 / 2.0 / mass;
    let bb = 1.0 / mass;
    let normal_impulse = (1.0 + e) * c / bb;
    let stick_impulse = sx.hypot(sy) / a;
    let (px, py, pz) = if stick_impulse <= normal_impulse {
        (
            -sx / a * sin_t - normal_impulse * cos_t,
            sy / a,
            sx / a * cos_t - normal_impulse * sin_t,
        )
    } else {
        let f = mu * normal_impulse;
        (
            -f * phi.cos() * sin_t - normal_impulse * cos_t,
            f * phi.sin(),
            f * phi.cos() * cos_t - normal_impulse * sin_t,
        )
    };
    let vx = vx + px / mass;
    let vy = vy + py / mass;
    let k = radius / inertia;
    let wx = wx - k * py * sin_t;
    let wy = wy + k * (px * sin_t - pz * cos_t);
    let wz = wz + k * py * cos_t;
    let vel = n * vx + t * vy;
    let w_xy = n * wx + t * wy;
    ClothBall {
        pos: b.pos,
        vel,
        spin: Vector([w_xy[0], w_xy[1], wz]),
    }
}

/// A ball that leaves a cushion (or jaw; `toward` the unit vector from its centre to the
/// contact) more slowly than its cloth acceleration towards the cushion, `a`, lets it stay
/// away for a contact's duration `τ` (`contact_time`, s) leaves at `½·a·τ` instead (through
/// any state change within `τ`, the least speed that keeps it away then, as
/// [`super::ball_impact::part_pressed`] takes it): pressed
/// against the cushion (by its spin, rolling along a rail), it bounces with a real contact's
/// period instead of ever faster (Han's restitution is below 1: the bounces would come ever
/// closer, and end at one instant for ever). The cushion's counterpart of
/// [`super::ball_impact::part_pressed`], with the same floor for rounding. Returns the kinetic
/// energy per unit mass this added (m²/s²) when the ball was pressed against the cushion,
/// `None` otherwise.
pub fn part_from_cushion(
    b: &mut ClothBall,
    toward: Vector<2>,
    cloth: &ClothParams,
    contact_time: f64,
) -> Option<f64> {
    let least = closing_speed(b, None, toward, cloth, contact_time);
    let leaving = -b.vel.dot(toward);
    let floor = rounding_floor(b.vel.norm());
    let pressed = least > leaving && least > floor;
    let target = if pressed { least } else { floor };
    if target.partial_cmp(&leaving) != Some(std::cmp::Ordering::Greater) {
        return None;
    }
    let before = b.vel.norm_sq();
    b.vel -= toward * (target - leaving);
    pressed.then(|| 0.5 * (b.vel.norm_sq() - before))
}

/// Ball `b` after meeting a cushion nose at `height` (m) in the direction `toward` (a unit
/// vector from its centre to the contact), as a shot plays it with the ball parameters `p`:
/// Han's bounce ([`bounce`]), speeds of rounding set to rest
/// ([`super::ball_impact::rest_if_rounding`]), then parted from the cushion if pressed against
/// it ([`part_from_cushion`]). Returns the ball and the kinetic energy that parting added
/// (joules), if it did.
#[must_use]
pub fn bounce_as_played(
    b: &ClothBall,
    toward: Vector<2>,
    height: f64,
    p: &BallParams,
) -> (ClothBall, Option<f64>) {
    let mut after = bounce(
        b,
        toward,
        p.radius(),
        p.mass,
        height,
        p.cushion_restitution,
        p.cushion_friction,
    );
    rest_if_rounding(&mut after, p.radius());
    let added = part_from_cushion(&mut after, toward, &p.cloth, p.contact_time).map(|e| p.mass * e);
    (after, added)
}

#[cfg(test)]
mod tests {
    use super::*;

    const R: f64 = 0.028575;
    const M: f64 = 0.170097;

    #[test]
    fn a_rolling_ball_straight_into_a_rail_comes_back_slower_with_draw() {
        let v = 1.0;
        let b = ClothBall {
            pos: Vector([0.5, 1.0]),
            vel: Vector([v, 0.0]),
            spin: Vector([0.0, v / R, 0.0]),
        };
        let after = bounce(&b, Vector([1.0, 0.0]), R, M, 1.28 * R, 0.85, 0.2);
        assert!(after.vel[0] < 0.0 && after.vel[0] > -v, "{after:?}");
        assert!(after.vel[1].abs() < 1e-12);
        // Straight in, no side spin: nothing turns it sideways or about the vertical.
        assert!(after.spin[0].abs() < 1e-9 && after.spin[2].abs() < 1e-9);
        // The normal's sign does not matter.
        let same = bounce(&b, Vector([-1.0, 0.0]), R, M, 1.28 * R, 0.85, 0.2);
        assert_eq!(after, same);
    }

    #[test]
    fn a_ball_its_spin_presses_into_a_rail_leaves_at_half_its_pressing_times_the_contact_time() {
        let cloth = ClothParams::default();
        let mu_g = cloth.sliding_friction * cloth.gravity;
        // At rest against a rail on its +x side, spinning so that the cloth drives it into
        // the rail (slip along −x: friction along +x) for far longer than a contact lasts.
        let mut b = ClothBall {
            pos: Vector([0.5, 1.0]),
            vel: Vector::ZERO,
            spin: Vector([0.0, 30.0, 0.0]),
        };
        let toward = Vector([1.0, 0.0]);
        let added = part_from_cushion(&mut b, toward, &cloth, 2e-4).expect("pressed");
        let leaving = -b.vel[0];
        assert!((leaving - 0.5 * mu_g * 2e-4).abs() < 1e-12, "{b:?}");
        assert!((added - 0.5 * leaving * leaving).abs() < 1e-18);
        // Leaving fast: nothing changes.
        let mut fast = ClothBall {
            vel: Vector([-1.0, 0.0]),
            ..b
        };
        let before = fast;
        assert_eq!(part_from_cushion(&mut fast, toward, &cloth, 2e-4), None);
        assert_eq!(fast, before);
    }

    #[test]
    fn the_bounce_is_the_same_in_a_turned_frame() {
        let b = ClothBall {
            pos: Vector([0.0, 0.0]),
            vel: Vector([0.8, 0.3]),
            spin: Vector([5.0, -20.0, 12.0]),
        };
        let a = bounce(&b, Vector([1.0, 0.0]), R, M, 1.28 * R, 0.85, 0.2);
        let (s, c) = 0.7f64.sin_cos();
        let turn = |v: Vector<2>| Vector([c * v[0] - s * v[1], s * v[0] + c * v[1]]);
        let tb = ClothBall {
            pos: b.pos,
            vel: turn(b.vel),
            spin: {
                let w = turn(Vector([b.spin[0], b.spin[1]]));
                Vector([w[0], w[1], b.spin[2]])
            },
        };
        let ta = bounce(&tb, turn(Vector([1.0, 0.0])), R, M, 1.28 * R, 0.85, 0.2);
        let want = turn(a.vel);
        assert!((ta.vel - want).norm() < 1e-12, "{ta:?} vs {want:?}");
        assert!((ta.spin[2] - a.spin[2]).abs() < 1e-9);
    }
}
