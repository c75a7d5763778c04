//! A ball falling under gravity against a rod: a segment wall in 3D.
//!
//! In 3D a segment is a rod of radius zero, and a ball of radius `r` meets it where its
//! centre reaches the capsule of radius `r` around it: the side of the infinite cylinder
//! around the rod's line, where the centre's foot lies on the rod, or one of the balls about
//! its end points.
//!
//! # The side: a quartic with two entries
//!
//! Seen along the rod (projected on the plane perpendicular to `u = b − a`), the centre still
//! moves on a parabola, `w⊥ + v⊥·t + ½·g⊥·t²`, so its squared distance from the line is a
//! quartic in time: the same problem as a point on a parabola against a ball
//! ([`crate::contact::accelerated_contact`]), on the projected offset, velocity and gravity. Unlike a
//! straight path, a parabola can enter the cylinder beyond an end, leave it, and come back
//! over the rod (a ball thrown up past the end falls back onto it): the quartic has up to
//! two entries, and every one whose foot lies on the rod is a candidate
//! ([`contacts_accelerating`]), not only the first. An entry beyond an end whose path then
//! stays in the cylinder and carries its foot onto the rod passes through the ball about that
//! end point first, which the end point's quartic finds; so the earliest of the side's
//! candidates and the end points' first contacts is the capsule's first contact.
//!
//! # Growing radii
//!
//! With `settings.growth` the capsule's radius grows with the ball's, `ρ(t) = ρ + ρ̇·t`: the
//! side is the quartic `|x⊥(t)|² = ρ(t)²` and each end point `|x(t)|² = ρ(t)²`, solved by the
//! same isolation ([`crate::contact::accelerated_contact`]), every entry into the growing cylinder with
//! its foot on the rod a candidate. The end balls still catch what enters beyond an end: when
//! the foot crosses an end the centre is within `ρ(t)` of the line there, so of the end point
//! ([`toi_circle_rod_falling_growing`]).
//!
//! # Resting
//!
//! A ball held on top of a rod would roll off around it, a pendulum's motion, not a parabola:
//! bodies never rest on rods (see [`crate::contact::resting`]); they bounce with the restitution.

use crate::contact::accelerated_contact::{
    contacts_accelerating, contacts_accelerating_growing, first_contact_accelerating,
    first_contact_accelerating_growing,
};
use crate::geom::Vector;
use crate::motion::GrowthLaw;
use crate::motion::Motion;

/// Time of impact of a ball (radius `r`, metres; motion `m`) falling under `g` (m/s², not
/// zero) with the rod from `a` to `b` (metres): the first entry into the cylinder of radius
/// `r` around the rod's line with its foot on the rod, or the first contact with an end point
/// ([`first_contact_accelerating`]), counted only where `ends` says; an absolute time,
/// seconds, from the ball's reference time, or `None`. See the module docs.
#[must_use]
#[inline(never)]
pub fn toi_circle_rod_falling_ends<const D: usize>(
    m: &Motion<D>,
    r: f64,
    a: Vector<D>,
    b: Vector<D>,
    g: &Vector<D>,
    ends: [bool; 2],
) -> Option<f64> {
    capsule_contact(
        m,
        a,
        b,
        g,
        ends,
        |p, v, acc| contacts_accelerating(p, v, acc, r),
        |p, v, acc| first_contact_accelerating(p, v, acc, r),
    )
}

/// Time of impact of a growing ball (stored radius `r`, metres; motion `m`) falling under
/// `g` (m/s², not zero) with the rod from `a` to `b` (metres): as
/// [`toi_circle_rod_falling_ends`] with both end points, against the capsule whose radius
/// grows as the ball's does, `ρ(t) = ρ + ρ̇·(t − t_m)` (`ρ` the radius at the ball's
/// reference time `t_m`). The side is then the quartic `|x⊥(t)|² = ρ(t)²`, every entry a
/// candidate, and each end point the quartic `|x(t)|² = ρ(t)²` (see
/// [`crate::contact::accelerated_contact`]); the end balls still catch whatever enters the cylinder
/// beyond an end and carries its foot onto the rod, since the ball is within `ρ(t)` of the
/// end point when its foot crosses it. An absolute time, seconds, or `None`.
#[must_use]
#[inline(never)]
pub fn toi_circle_rod_falling_growing<const D: usize>(
    m: &Motion<D>,
    r: f64,
    a: Vector<D>,
    b: Vector<D>,
    g: &Vector<D>,
    law: &GrowthLaw,
) -> Option<f64> {
    let (radius, speed) = (law.radius_at(r, m.time), law.speed(r));
    capsule_contact(
        m,
        a,
        b,
        g,
        [true; 2],
        |p, v, acc| contacts_accelerating_growing(p, v, acc, radius, speed),
        |p, v, acc| first_contact_accelerating_growing(p, v, acc, radius, speed),
    )
}

/// The rod's contact from its side's entries (`side`: every entry of the projected parabola
/// into the cylinder, in order) and its end points' first contacts (`end`), each given the
/// offset, velocity and acceleration of the ball's centre; see the module docs.
#[inline(always)]
fn capsule_contact<const D: usize>(
    m: &Motion<D>,
    a: Vector<D>,
    b: Vector<D>,
    g: &Vector<D>,
    ends: [bool; 2],
    side: impl Fn(Vector<D>, Vector<D>, Vector<D>) -> [Option<f64>; 3],
    end: impl Fn(Vector<D>, Vector<D>, Vector<D>) -> Option<f64>,
) -> Option<f64> {
    let u = b - a;
    let l2 = u.norm_sq();
    let w = m.pos - a;
    let across = |x: Vector<D>| x - u * (x.dot(u) / l2);
    let foot = |dt: f64| {
        let s = (w + m.vel * dt + *g * (0.5 * dt * dt)).dot(u) / l2;
        (0.0..=1.0).contains(&s)
    };
    // In increasing order: the first whose foot lies on the rod.
    let side = side(across(w), across(m.vel), across(*g))
        .into_iter()
        .flatten()
        .find(|&dt| foot(dt));
    let end_a = ends[0].then(|| end(w, m.vel, *g)).flatten();
    let end_b = ends[1].then(|| end(m.pos - b, m.vel, *g)).flatten();
    earliest_at(m.time, [side, end_a, end_b])
}

/// The earliest of a segment contact's candidate time offsets (seconds, from `time`: its
/// side and its two end points), as an absolute time, if any is finite then.
#[inline]
pub(crate) fn earliest_at(time: f64, offsets: [Option<f64>; 3]) -> Option<f64> {
    offsets
        .into_iter()
        .flatten()
        .reduce(f64::min)
        .map(|dt| time + dt)
        .filter(|t| t.is_finite())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contact::gravity::toi_circle_segment_falling;
    use crate::wall::{wall_clearance, Wall};
    use proptest::prelude::*;

    const G: Vector<3> = Vector([0.0, 0.0, -10.0]);

    fn m3(p: [f64; 3], v: [f64; 3], t: f64) -> Motion<3> {
        Motion {
            pos: Vector(p),
            vel: Vector(v),
            time: t,
        }
    }

    fn rod(m: &Motion<3>, r: f64, a: [f64; 3], b: [f64; 3], g: &Vector<3>) -> Option<f64> {
        toi_circle_rod_falling_ends(m, r, Vector(a), Vector(b), g, [true; 2])
    }

    #[test]
    fn a_ball_dropped_onto_a_level_rod_meets_it_at_the_free_fall_time() {
        // Rod along x at height 0, ball of radius 0.5 dropped from rest at z = 3 right above
        // it: it falls 2.5 m, t = √(2·2.5/10) = √0.5.
        let (a, b) = ([-2.0, 0.0, 0.0], [2.0, 0.0, 0.0]);
        let m = m3([0.3, 0.0, 3.0], [0.0, 0.0, 0.0], 1.0);
        let t = rod(&m, 0.5, a, b, &G).unwrap() - 1.0;
        assert!((t - 0.5f64.sqrt()).abs() < 1e-15, "{t}");
        // 0.3 off the rod's vertical plane: the centre meets the cylinder at z = 0.4, after
        // a fall of 2.6 m.
        let m = m3([0.3, 0.3, 3.0], [0.0, 0.0, 0.0], 0.0);
        let t = rod(&m, 0.5, a, b, &G).unwrap();
        assert!((t - 0.52f64.sqrt()).abs() < 1e-15, "{t}");
        // Dropped 0.6 off it: it passes by.
        let m = m3([0.3, 0.6, 3.0], [0.0, 0.0, 0.0], 0.0);
        assert_eq!(rod(&m, 0.5, a, b, &G), None);
        // The same through the public dispatcher.
        let m = m3([0.3, 0.0, 3.0], [0.0, 0.0, 0.0], 0.0);
        let t = toi_circle_segment_falling(&m, 0.5, Vector(a), Vector(b), &G).unwrap();
        assert!((t - 0.5f64.sqrt()).abs() < 1e-15, "{t}");
    }

    #[test]
    fn a_ball_thrown_past_the_end_falls_back_onto_the_rod() {
        // Rod from (0, 0, 0) to (4, 0, 0); the ball starts below and beyond it, 0.2 to the
        // side, rises through the cylinder near x = 6 (clear of the end point: its first
        // entry, beyond the end), leaves it above, and falls onto the rod near x = 2.4.
        let (a, b) = ([0.0, 0.0, 0.0], [4.0, 0.0, 0.0]);
        let m = m3([7.0, 0.2, -3.0], [-3.0, 0.0, 10.0], 0.0);
        let t = rod(&m, 0.5, a, b, &G).unwrap();
        let p = m.falling_at(t, &G);
        let lateral = (p[1] * p[1] + p[2] * p[2]).sqrt();
        assert!((lateral - 0.5).abs() < 1e-12, "{p:?} at {t}");
        assert!(p[0] > 0.0 && p[0] < 4.0 && p[2] > 0.0, "{p:?}");
        assert!(m.falling_velocity(t, &G)[2] < 0.0, "falling");
        // The cylinder's first entry lies beyond the end: only the second is the rod's.
        let across = |x: Vector<3>| Vector([0.0, x[1], x[2]]);
        let entries =
            contacts_accelerating(across(m.pos - Vector(a)), across(m.vel), across(G), 0.5);
        let first = entries[0].unwrap();
        assert!(m.falling_at(first, &G)[0] > 4.5, "{entries:?}");
        assert_eq!(entries[1].map(f64::to_bits), Some(t.to_bits()));
        // The 2D slab of the same motion in the rod's vertical plane agrees.
        let m2 = Motion {
            pos: Vector([7.0, -3.0]),
            vel: Vector([-3.0, 10.0]),
            time: 0.0,
        };
        let g2 = Vector([0.0, -10.0]);
        let r2 = (0.25f64 - 0.04).sqrt();
        let t2 = toi_circle_segment_falling(&m2, r2, Vector([0.0, 0.0]), Vector([4.0, 0.0]), &g2);
        assert!((t2.unwrap() - t).abs() < 1e-12, "{t2:?} vs {t}");
    }

    #[test]
    fn a_ball_falling_beyond_the_end_hits_the_end_cap() {
        let (a, b) = ([0.0, 0.0, 0.0], [4.0, 0.0, 0.0]);
        // Dropped 0.3 beyond the end and 0.1 to the side: it meets the ball about b, where
        // |p − b| = 0.5, at z = √(0.25 − 0.09 − 0.01) after a fall from 3.
        let m = m3([4.3, 0.1, 3.0], [0.0, 0.0, 0.0], 0.0);
        let t = rod(&m, 0.5, a, b, &G).unwrap();
        let z = 0.15f64.sqrt();
        assert!((t - (0.2 * (3.0 - z)).sqrt()).abs() < 1e-15, "{t}");
        let p = m.falling_at(t, &G);
        assert!(((p - Vector(b)).norm() - 0.5).abs() < 1e-12, "{p:?}");
        // Without its end points counted (shared with a support), it falls past.
        let m = m3([4.3, 0.1, 3.0], [0.0, 0.0, 0.0], 0.0);
        let none = toi_circle_rod_falling_ends(&m, 0.5, Vector(a), Vector(b), &G, [true, false]);
        assert_eq!(none, None);
    }

    #[test]
    fn a_vertical_rod_under_vertical_gravity_is_met_side_on() {
        // Gravity along the rod: across it the path is straight, the straight-line contact.
        let (a, b) = ([0.0, 0.0, 0.0], [0.0, 0.0, 4.0]);
        let m = m3([3.0, 0.0, 2.0], [-2.0, 0.0, 5.0], 0.0);
        let t = rod(&m, 0.5, a, b, &G).unwrap();
        assert_eq!(t, 1.25);
        // Falling past the bottom end before it gets there: the end cap, or nothing.
        let m = m3([3.0, 0.0, 1.0], [-1.0, 0.0, 0.0], 0.0);
        assert_eq!(rod(&m, 0.5, a, b, &G), None);
    }

    /// The clearance of the falling ball from the rod at `t`.
    fn clearance(m: &Motion<3>, g: &Vector<3>, wall: &Wall<3>, t: f64) -> f64 {
        wall_clearance(wall, m.falling_at(t, g))
    }

    /// Checks the rod's time of impact against brute force: the exact clearance sampled every
    /// `1e-4` s over `[0, 8]` s (by then the ball has fallen far below the rod). At the time
    /// given the clearance is `r`; before it, never below `r`; and the first sample deeper
    /// than `2%` of `r` inside the capsule (a contact no rounding decides) is not before it.
    fn check(m: &Motion<3>, r: f64, a: Vector<3>, b: Vector<3>, g: &Vector<3>) {
        let got = toi_circle_rod_falling_ends(m, r, a, b, g, [true; 2]);
        check_contact(m, |_| r, a, b, g, got);
    }

    /// [`check`] for a ball whose radius grows by `law` (stored radius `r`): its clearance
    /// against the radius at each time.
    fn check_growing(
        m: &Motion<3>,
        r: f64,
        a: Vector<3>,
        b: Vector<3>,
        g: &Vector<3>,
        law: &GrowthLaw,
    ) {
        let got = toi_circle_rod_falling_growing(m, r, a, b, g, law);
        check_contact(m, |t| law.radius_at(r, t), a, b, g, got);
    }

    /// The brute-force check of [`check`] of the contact `got` of a ball whose radius at
    /// time `t` is `radius(t)`.
    fn check_contact(
        m: &Motion<3>,
        radius: impl Fn(f64) -> f64,
        a: Vector<3>,
        b: Vector<3>,
        g: &Vector<3>,
        got: Option<f64>,
    ) {
        let wall = Wall::Segment { a, b };
        if clearance(m, g, &wall, 0.0) <= radius(0.0) * 1.02 {
            return;
        }
        let scale = 1.0 + m.pos.norm() + a.norm() + b.norm() + 8.0 * m.vel.norm() + 32.0 * g.norm();
        let steps = 80_000;
        let deep = (0..=steps)
            .map(|k| 8.0 * f64::from(k) / f64::from(steps))
            .find(|&t| clearance(m, g, &wall, t) < 0.98 * radius(t));
        match got {
            Some(t) => {
                assert!(t >= 0.0 && t.is_finite(), "{t}");
                let (c, r) = (clearance(m, g, &wall, t), radius(t));
                assert!((c - r).abs() <= 1e-9 * scale, "clearance {c} at {t}, r {r}");
                for k in 0..=4000 {
                    let s = t * f64::from(k) / 4000.0;
                    let c = clearance(m, g, &wall, s);
                    assert!(c >= radius(s) - 1e-9 * scale, "contact at {s} before {t}");
                }
                if let Some(d) = deep {
                    assert!(t <= d, "deep inside at {d}, contact given at {t}");
                }
            }
            None => assert_eq!(deep, None, "missed a contact"),
        }
    }

    fn v3(range: f64) -> impl Strategy<Value = Vector<3>> {
        proptest::array::uniform3(-range..range).prop_map(Vector)
    }

    /// Gravity of 2 to 10 m/s² in any direction.
    fn gravity() -> impl Strategy<Value = Vector<3>> {
        (v3(1.0), 2.0..10.0f64).prop_filter_map("a direction", |(d, k)| {
            let n = d.norm();
            (n > 0.1).then(|| d * (k / n))
        })
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(256))]

        /// Random rods and throws.
        #[test]
        fn rod_contacts_match_brute_force(
            p in v3(5.0), v in v3(5.0), a in v3(3.0), b in v3(3.0), g in gravity(),
            r in 0.1..1.0f64,
        ) {
            prop_assume!((b - a).norm() > 0.5);
            check(&Motion { pos: p, vel: v, time: 0.0 }, r, a, b, &g);
        }

        /// Throws aimed to pass within `1.5·r` of a point of the rod (or a little beyond its
        /// ends) after `tau` seconds: mostly contacts, many after a first pass beyond an end.
        #[test]
        fn aimed_rod_contacts_match_brute_force(
            p in v3(5.0), a in v3(3.0), b in v3(3.0), g in gravity(), r in 0.1..1.0f64,
            s in -0.3..1.3f64, q in v3(1.0), tau in 0.2..2.0f64,
        ) {
            prop_assume!((b - a).norm() > 0.5);
            let target = a + (b - a) * s + q * (1.5 * r);
            let v = (target - p - g * (0.5 * tau * tau)) * (1.0 / tau);
            prop_assume!(v.norm() < 20.0);
            check(&Motion { pos: p, vel: v, time: 0.0 }, r, a, b, &g);
        }

        /// Growing balls against random rods, and throws aimed at them: the contact against
        /// the grown radius, none missed.
        #[test]
        fn growing_rod_contacts_match_brute_force(
            p in v3(5.0), a in v3(3.0), b in v3(3.0), g in gravity(), r in 0.1..1.0f64,
            s in -0.3..1.3f64, q in v3(1.0), tau in 0.2..2.0f64, rate in 0.01..0.5f64,
            origin in -1.0..0.5f64, aimed in proptest::bool::ANY,
        ) {
            prop_assume!((b - a).norm() > 0.5);
            let law = GrowthLaw { rate, origin };
            let target = a + (b - a) * s + q * (1.5 * r);
            let v = if aimed {
                (target - p - g * (0.5 * tau * tau)) * (1.0 / tau)
            } else {
                q * 5.0
            };
            prop_assume!(v.norm() < 20.0);
            check_growing(&Motion { pos: p, vel: v, time: 0.0 }, r, a, b, &g, &law);
        }

        /// Without growth (`Γ = 0`) the growing rod contact is the fixed-radius one, bit for
        /// bit.
        #[test]
        fn zero_growth_keeps_the_rods_bits(
            p in v3(5.0), v in v3(5.0), a in v3(3.0), b in v3(3.0), g in gravity(),
            r in 0.1..1.0f64, t0 in -2.0..2.0f64, along in proptest::bool::ANY,
        ) {
            prop_assume!((b - a).norm() > 0.5);
            // Gravity along the rod too: the straight-line answer across it.
            let g = if along { (b - a) * (g.norm() / (b - a).norm()) } else { g };
            let m = Motion { pos: p, vel: v, time: t0 };
            let law = GrowthLaw { rate: 0.0, origin: 0.0 };
            let fixed = toi_circle_rod_falling_ends(&m, r, a, b, &g, [true; 2]);
            let growing = toi_circle_rod_falling_growing(&m, r, a, b, &g, &law);
            prop_assert_eq!(fixed.map(f64::to_bits), growing.map(f64::to_bits));
        }

        /// A rod and a motion in the plane z = 0 meet as the 2D segment and motion do (the
        /// slab's and the cylinder's contacts are then the same), within rounding.
        #[test]
        fn a_planar_problem_agrees_with_the_2d_segment(
            p in proptest::array::uniform2(-5.0..5.0f64), v in proptest::array::uniform2(-5.0..5.0f64),
            a in proptest::array::uniform2(-3.0..3.0f64), b in proptest::array::uniform2(-3.0..3.0f64),
            g in proptest::array::uniform2(-10.0..10.0f64), r in 0.1..1.0f64,
        ) {
            let lift = |x: [f64; 2]| Vector([x[0], x[1], 0.0]);
            prop_assume!((lift(b) - lift(a)).norm() > 0.5 && Vector(g).norm() > 1.0);
            let m2 = Motion { pos: Vector(p), vel: Vector(v), time: 0.0 };
            prop_assume!(wall_clearance(&Wall::Segment { a: Vector(a), b: Vector(b) }, m2.pos) > r);
            let m3 = Motion { pos: lift(p), vel: lift(v), time: 0.0 };
            let t2 = toi_circle_segment_falling(&m2, r, Vector(a), Vector(b), &Vector(g));
            let t3 = toi_circle_rod_falling_ends(&m3, r, lift(a), lift(b), &lift(g), [true; 2]);
            match (t2, t3) {
                (Some(x), Some(y)) => prop_assert!((x - y).abs() <= 1e-9 * (1.0 + x), "{x} vs {y}"),
                (x, y) => prop_assert_eq!(x, y),
            }
        }
    }
}
