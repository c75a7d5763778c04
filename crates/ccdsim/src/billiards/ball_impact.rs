//! Two balls meeting, by one of two models between equal masses:
//!
//! * [`exchange`]: frictionless, instantaneous and perfectly elastic (pooltool 0.3.3's default
//!   ball–ball model, `frictionless_elastic`). The velocity components along the line of
//!   centres are exchanged; the rest of each velocity, and every angular velocity, is kept.
//! * [`frictional`]: instantaneous, with restitution `e_b` along the line of centres and
//!   friction between the balls' surfaces (pooltool 0.4's `frictional_inelastic`, after
//!   D. Alciatore's technical proofs TP, billiards.colostate.edu). The
//!   friction impulse opposes the contact points' relative slip and is at most `μ` times the
//!   change of the balls' normal relative speed; when that much would reverse the slip, the
//!   balls leave the contact rolling on each other instead (no slip). It throws the object
//!   ball off the line of centres and passes spin from one ball to the other.

//!
//! Then, for either model, [`part_pressed`]: balls that part more slowly than their
//! decelerations press them back together within a real contact's duration part at the speed
//! that keeps them apart for that long, the lasting contact resolved as bounces no shorter
//! than a real one.

use super::params::BallFriction;
use crate::geom::Vector;
use crate::motion::{ClothBall, ClothParams, ClothState};

/// A ball (of radius `radius`, m) leaving a collision with a speed below pooltool's `EPS`
/// (`100·ε` m/s) leaves at rest, and one whose spin moves its surface slower than that leaves
/// without that spin: such a speed is rounding of the collision's arithmetic (touching balls at rest in a
/// rack exchange residues of 10⁻¹⁷ m/s), and rounding must not set a ball rolling, with a full
/// rolling resistance in a direction it picked, into the ball it touches.
pub fn rest_if_rounding(b: &mut ClothBall, radius: f64) {
    if b.vel.norm() < NO_SLIP {
        b.vel = Vector::ZERO;
    }
    // Likewise the speeds the spin gives the ball's surface.
    if radius * b.spin[0].hypot(b.spin[1]) < NO_SLIP {
        b.spin = Vector([0.0, 0.0, b.spin[2]]);
    }
    if radius * b.spin[2].abs() < NO_SLIP {
        b.spin = Vector([b.spin[0], b.spin[1], 0.0]);
    }
}

/// How far the cloth moves a ball leaving a collision (sliding, as every ball does) in `t`
/// seconds beyond where its velocity alone would take it, metres: the part of its motion the
/// cloth's friction makes, through any state change on the way. Taken from the ball moved to
/// the origin, so that displacements of 10⁻²⁰ m keep their digits.
fn cloth_displacement(b: &ClothBall, cloth: &ClothParams, t: f64) -> Vector<2> {
    let at_origin = ClothBall {
        pos: Vector::ZERO,
        ..*b
    };
    cloth.advance(&at_origin, ClothState::Sliding, t).0.pos - b.vel * t
}

/// The times within `(0, horizon]` at which the ball's motion state changes, leaving a
/// collision sliding, and `horizon` itself: where its cloth acceleration changes.
fn breakpoints(b: &ClothBall, cloth: &ClothParams, horizon: f64, out: &mut Vec<f64>) {
    let (mut ball, mut state, mut t) = (*b, ClothState::Sliding, 0.0);
    while let Some((span, next)) = cloth.transition(&ball, state) {
        if (t + span).partial_cmp(&horizon) != Some(std::cmp::Ordering::Less) {
            break;
        }
        ball = crate::motion::cloth::settle(cloth.evolve(&ball, state, span), next);
        state = next;
        t += span;
        if t > 0.0 {
            out.push(t);
        }
    }
    out.push(horizon);
}

/// The speed (m/s) at which a body must leave a contact in direction `n` (a unit vector into
/// the contact) for the cloth's friction over the next `horizon` seconds not to bring it back
/// at any time its acceleration changes, nor at `horizon`: the largest mean closing speed
/// `c(t)/t` there, `c(t)` the displacement into the contact that the cloth makes (of `a`
/// less that of `b`, when a ball `b` is on the other side). For constant accelerations that
/// differ by `Δa` it is `½·Δa·horizon`; a ball whose slip is rounding slides for only as long as
/// that slip lasts, and counts for no more.
pub(crate) fn closing_speed(
    a: &ClothBall,
    b: Option<&ClothBall>,
    n: Vector<2>,
    cloth: &ClothParams,
    horizon: f64,
) -> f64 {
    let mut times = Vec::new();
    breakpoints(a, cloth, horizon, &mut times);
    if let Some(b) = b {
        breakpoints(b, cloth, horizon, &mut times);
    }
    times
        .iter()
        .map(|&t| {
            let mut c = cloth_displacement(a, cloth, t);
            if let Some(b) = b {
                c -= cloth_displacement(b, cloth, t);
            }
            c.dot(n) / t
        })
        .fold(f64::NEG_INFINITY, f64::max)
}

/// How two touching balls that part slowly are kept from pressing into each other, after the
/// collision model ([`exchange`] or [`frictional`]) gave `a` and `b` their velocities: if the
/// cloth decelerates `a` less than `b` along the line of centres by `Δa` (m/s², from each
/// ball's state after the collision), two rigid balls that part at a speed `w` below
/// `½·Δa·τ` meet again within `τ` (the `contact_time`, s), and at `w = 0` at once, for ever
/// (the lasting contact of two balls pushed together, which the collision models alone
/// cannot resolve: docs/model.md, "Pool"). Such balls are given equal and opposite pushes
/// along the line of centres so that they part at the least speed that keeps the cloth from
/// closing the gap again within `τ` (`½·Δa·τ` while the accelerations hold; through any
/// state change within `τ` in general, taken where an acceleration changes and at `τ`): they
/// bounce with the period of a real contact, and on average push each other with the force
/// `m·Δa/2` that a lasting contact would. Returns the kinetic energy per unit mass this added
/// (m²/s²) when it did; `None` when they part fast enough or are not pressed together. Balls
/// parting more slowly than rounding can tell ([`rounding_floor`]) are given that speed
/// either way (the next prediction would see them approach at once and meet again, for ever;
/// the energy, below 10⁻²⁷ J/kg, is not counted).
pub fn part_pressed(
    a: &mut ClothBall,
    b: &mut ClothBall,
    cloth: &ClothParams,
    contact_time: f64,
) -> Option<f64> {
    let d = b.pos - a.pos;
    let n = d * (1.0 / d.norm());
    let least = closing_speed(a, Some(b), n, cloth, contact_time);
    let parting = (b.vel - a.vel).dot(n);
    let floor = rounding_floor(a.vel.norm() + b.vel.norm());
    let pressed = least > parting && least > floor;
    let target = if pressed { least } else { floor };
    // (A NaN, from balls at one point, parts nothing.)
    if target.partial_cmp(&parting) != Some(std::cmp::Ordering::Greater) {
        return None;
    }
    let before = a.vel.norm_sq() + b.vel.norm_sq();
    let push = n * (0.5 * (target - parting));
    a.vel -= push;
    b.vel += push;
    pressed.then(|| 0.5 * (a.vel.norm_sq() + b.vel.norm_sq() - before))
}

/// The least speed (m/s) at which two touching bodies moving at `speeds` (their sum, m/s)
/// must part for the next prediction to see them part, not approach by rounding: pooltool's
/// `EPS` (`100·ε` m/s), more for fast balls.
#[must_use]
pub fn rounding_floor(speeds: f64) -> f64 {
    NO_SLIP * (1.0 + speeds)
}

/// The two balls just after they meet with centres at `a.pos` and `b.pos`: each gives the
/// other its velocity component along the line of centres.
#[must_use]
pub fn exchange(a: &ClothBall, b: &ClothBall) -> (ClothBall, ClothBall) {
    let d = b.pos - a.pos;
    let n = d * (1.0 / d.norm());
    let along = (a.vel - b.vel).dot(n);
    let push = n * along;
    (
        ClothBall {
            vel: a.vel - push,
            ..*a
        },
        ClothBall {
            vel: b.vel + push,
            ..*b
        },
    )
}

/// Below this relative speed of the contact points (m/s) the balls do not slip on each other
/// (pooltool's `EPS`).
const NO_SLIP: f64 = 100.0 * f64::EPSILON;

/// The two balls of radius `radius` (metres) just after they meet with centres at `a.pos` and
/// `b.pos`, with restitution `restitution` along the line of centres and friction `friction`
/// between their surfaces (see the module docs). Velocities stay in the table's plane: the
/// vertical part of the friction impulse turns spins but lifts no ball.
#[must_use]
pub fn frictional(
    a: &ClothBall,
    b: &ClothBall,
    radius: f64,
    restitution: f64,
    friction: &BallFriction,
) -> (ClothBall, ClothBall) {
    let lift = |v: Vector<2>| Vector([v[0], v[1], 0.0]);
    let d = b.pos - a.pos;
    let n2 = d * (1.0 / d.norm());
    let n = lift(n2);
    let (va, vb) = (lift(a.vel), lift(b.vel));
    let (an, bn) = (va.dot(n), vb.dot(n));
    let e = restitution;
    let an_after = 0.5 * ((1.0 - e) * an + (1.0 + e) * bn);
    let bn_after = 0.5 * ((1.0 + e) * an + (1.0 - e) * bn);
    // The tangential parts, and the contact points' velocities from them and the spins.
    let (at, bt) = (va - n * an, vb - n * bn);
    let contact_slip = |at: Vector<3>, wa: Vector<3>, bt: Vector<3>, wb: Vector<3>| {
        (at + wa.cross(n * radius)) - (bt + wb.cross(n * -radius))
    };
    let slip = contact_slip(at, a.spin, bt, b.spin);
    let slip_speed = slip.norm();
    // The friction impulse per unit mass on `a` (on `b` it is the opposite), and the spin it
    // gives each ball (the same for both: opposite impulses at opposite points).
    let mut kick = None;
    if slip_speed > NO_SLIP {
        let mu = friction.coefficient(slip_speed);
        let dv = slip * (-mu * (bn_after - an_after).abs() / slip_speed);
        let dw = n.cross(dv) * (2.5 / radius);
        let after = contact_slip(at + dv, a.spin + dw, bt - dv, b.spin + dw);
        if slip.dot(after) > 0.0 {
            kick = Some((dv, dw));
        }
    }
    // Sliding would reverse the slip (or there is none): the impulse that stops it.
    let (dv, dw) = kick.unwrap_or_else(|| {
        let w = a.spin + b.spin;
        (
            (at - bt + w.cross(n) * radius) * (-1.0 / 7.0),
            (n.cross(at - bt) * (1.0 / radius) + w) * (-5.0 / 14.0),
        )
    });
    let flat = |v: Vector<3>, along: f64| Vector([v[0], v[1]]) + n2 * along;
    (
        ClothBall {
            pos: a.pos,
            vel: flat(at + dv, an_after),
            spin: a.spin + dw,
        },
        ClothBall {
            pos: b.pos,
            vel: flat(bt - dv, bn_after),
            spin: b.spin + dw,
        },
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::Vector;

    #[test]
    fn a_straight_hit_stops_the_cue_ball_and_a_cut_splits_at_right_angles() {
        let r = 0.028575;
        let cue = ClothBall {
            pos: Vector([0.0, 0.0]),
            vel: Vector([2.0, 0.0]),
            spin: Vector([0.0, 70.0, 3.0]),
        };
        let object = ClothBall {
            pos: Vector([2.0 * r, 0.0]),
            vel: Vector::ZERO,
            spin: Vector::ZERO,
        };
        let (c, o) = exchange(&cue, &object);
        assert_eq!(c.vel, Vector::ZERO);
        assert_eq!(o.vel, Vector([2.0, 0.0]));
        assert_eq!(c.spin, cue.spin);
        let cut = ClothBall {
            pos: Vector([2.0 * r * 0.6, 2.0 * r * 0.8]),
            ..object
        };
        let (c, o) = exchange(&cue, &cut);
        assert!(c.vel.dot(o.vel).abs() < 1e-12);
        assert!((c.vel + o.vel - cue.vel).norm() < 1e-12);
    }

    #[test]
    fn balls_pressed_together_part_at_half_their_pressing_times_the_contact_time() {
        let cloth = ClothParams::default();
        let r = cloth.radius;
        // Behind, a ball with topspin and no speed (it slides forward, accelerating); in
        // front, touching it, a ball sliding away slowly without spin (decelerating).
        let mut a = ClothBall {
            pos: Vector([0.0, 0.0]),
            vel: Vector::ZERO,
            spin: Vector([0.0, 20.0, 0.0]),
        };
        let mut b = ClothBall {
            pos: Vector([2.0 * r, 0.0]),
            vel: Vector([1e-5, 0.0]),
            spin: Vector::ZERO,
        };
        let mu_g = cloth.sliding_friction * cloth.gravity;
        // The rear ball slides for 80 ms: the cloth drives it on at μ_s g over a contact's
        // time, ½ μ_s g τ on average. The front one's slide is over in microseconds: it rolls
        // on and stops within the contact time, which adds a little.
        let added = part_pressed(&mut a, &mut b, &cloth, 2e-4).expect("pressed");
        let parting = (b.vel - a.vel)[0];
        let half = 0.5 * mu_g * 2e-4;
        assert!(parting > half && parting < half + 1e-5, "{a:?} {b:?}");
        assert!((a.vel + b.vel - Vector([1e-5, 0.0])).norm() < 1e-18);
        let e = 0.5 * (a.vel.norm_sq() + b.vel.norm_sq() - 1e-10);
        assert!((added - e).abs() < 1e-18 && added > 0.0);
        // Pulled apart (the front ball's spin drives it on): not pressed; only parted at the
        // speed rounding can tell, since they touch without parting.
        let (mut c, mut d) = (b, a);
        c.pos = Vector([0.0, 0.0]);
        d.pos = Vector([2.0 * r, 0.0]);
        c.vel = Vector::ZERO;
        d.vel = Vector::ZERO;
        c.spin = Vector::ZERO;
        d.spin = Vector([0.0, 20.0, 0.0]);
        assert_eq!(part_pressed(&mut c, &mut d, &cloth, 2e-4), None);
        assert!(
            ((d.vel - c.vel)[0] - rounding_floor(0.0)).abs() < 1e-30,
            "{c:?} {d:?}"
        );
        // Parting fast: nothing changes.
        let (mut c, mut d) = (c, d);
        d.vel = Vector([1.0, 0.0]);
        let before = (c, d);
        assert_eq!(part_pressed(&mut c, &mut d, &cloth, 2e-4), None);
        assert_eq!((c, d), before);
    }

    #[test]
    fn friction_throws_a_cut_object_ball_and_keeps_momentum() {
        let r = 0.028575;
        let friction = BallFriction::Constant(0.05);
        // Head on, no spin, e = 1: the frictionless exchange.
        let cue = ClothBall {
            pos: Vector([0.0, 0.0]),
            vel: Vector([2.0, 0.0]),
            spin: Vector::ZERO,
        };
        let object = ClothBall {
            pos: Vector([2.0 * r, 0.0]),
            vel: Vector::ZERO,
            spin: Vector::ZERO,
        };
        let (c, o) = frictional(&cue, &object, r, 1.0, &friction);
        assert_eq!((c.vel, o.vel), (Vector::ZERO, Vector([2.0, 0.0])));
        assert_eq!((c.spin, o.spin), (Vector::ZERO, Vector::ZERO));
        // Restitution 0.9: the object ball takes 95 % and the cue ball keeps 5 %.
        let (c, o) = frictional(&cue, &object, r, 0.9, &friction);
        assert!((c.vel - Vector([0.1, 0.0])).norm() < 1e-15);
        assert!((o.vel - Vector([1.9, 0.0])).norm() < 1e-15);
        // A half-ball cut (30°): the object ball leaves off the line of centres, towards the
        // cue ball's motion (throw), with spin; the momentum in the plane is kept.
        let d = Vector([(30f64).to_radians().cos(), -(30f64).to_radians().sin()]) * (2.0 * r);
        let cut = ClothBall { pos: d, ..object };
        let (c, o) = frictional(&cue, &cut, r, 1.0, &friction);
        let n = d * (1.0 / d.norm());
        let off_line = o.vel[0] * n[1] - o.vel[1] * n[0];
        assert!(off_line < 0.0, "{o:?}");
        let throw = off_line.abs().atan2(o.vel.dot(n)).to_degrees();
        assert!(throw > 1.0 && throw < 5.0, "{throw}°");
        assert!((c.vel + o.vel - cue.vel).norm() < 1e-12);
        assert!(o.spin[2] != 0.0 && c.spin[2] == o.spin[2]);
        // Large friction: the balls leave rolling on each other at the contact.
        let (c, o) = frictional(&cue, &cut, r, 1.0, &BallFriction::Constant(1.0));
        let lift = |v: Vector<2>| Vector([v[0], v[1], 0.0]);
        let n3 = lift(n);
        let ct = lift(c.vel) - n3 * c.vel.dot(n) + c.spin.cross(n3 * r);
        let ot = lift(o.vel) - n3 * o.vel.dot(n) + o.spin.cross(n3 * -r);
        let slip = ct - ot;
        assert!(Vector([slip[0], slip[1]]).norm() < 1e-12, "{slip:?}");
    }
}
