//! Gravity and growing radii together: bodies fall on parabolas ([`crate::contact::gravity`]) while
//! every radius grows linearly in time ([`crate::contact::growth`]), as when grains are compressed to
//! a jammed packing under gravity (a sedimented packing).
//!
//! # Pairs
//!
//! Two falling bodies have no relative acceleration, so their offset from `T = max(t_a, t_b)`
//! on is a straight line and their contact distance a line too: growth's quadratic
//! ([`crate::contact::growth::first_contact_growing`]) of their offset and relative velocity at `T`
//! ([`toi_circle_circle_falling_growing`]). A kinematic body does not fall: against a falling
//! one the offset is a parabola and `|x(t)|² = σ(t)²` a quartic
//! ([`crate::contact::accelerated_contact::first_contact_accelerating_growing`]).
//!
//! # Walls
//!
//! Against a plane the gap between surface and plane is
//! `(gap − r) + (v_n − ṙ)·t + ½·g_n·t²`, a quadratic whose first entry
//! ([`crate::contact::gravity::first_entry`]) is the contact ([`toi_circle_plane_falling_growing`]).
//! Against a segment (2D) the ball meets the interior where it enters the slab around the
//! line, whose half-width `r + ṙ·t` now grows, with its foot on the segment, and an end point
//! at the first root of the quartic `|w + v·t + ½·g·t²|² = (r + ṙ·t)²`. As under gravity with
//! fixed radii every entry into the slab is a candidate; as under growth without gravity a
//! contact with the line beyond an end cannot hide one with the interior, which a ball within
//! reach of the line beyond an end reaches only through the end point's ball. In 3D a segment
//! is a rod ([`crate::contact::rod`]): the side is the quartic of the motion across it against the
//! growing radius, `|w⊥ + v⊥·t + ½·g⊥·t²|² = (r + ṙ·t)²`, every entry whose foot lies on the
//! rod a candidate, and the end points' quartics as in 2D
//! ([`crate::contact::rod::toi_circle_rod_falling_growing`]).
//!
//! # What "approaching" means
//!
//! The surfaces approach when the gap shrinks: for a plane when `v_n + g_n·t < ṙ`; in a
//! pair as growth has it (`dp·dv < σσ̇`). A body in contact that recedes is given the time it
//! comes back, as [`crate::contact::gravity::first_entry`] says.
//!
//! Every finder evaluates these functions with the oracle's arguments (through
//! [`crate::contact::narrow`]'s dispatchers), so their events agree bit for bit.

use crate::contact::accelerated_contact::first_contact_accelerating_growing;
use crate::contact::gravity::first_entry;
use crate::contact::growth::first_contact_growing;
use crate::geom::Vector;
use crate::motion::GrowthLaw;
use crate::motion::Motion;
use crate::wall::Wall;

/// Time of impact (absolute, seconds) of two growing balls (stored radii `ra`, `rb`) falling
/// under the same acceleration `g`, ball `b` displaced by `shift`: growth's quadratic of
/// their offset and relative velocity at `T = max(a.time, b.time)`, with the contact
/// distance at `T` (see the module docs).
#[must_use]
#[inline]
pub fn toi_circle_circle_falling_growing<const D: usize>(
    a: &Motion<D>,
    ra: f64,
    b: &Motion<D>,
    rb: f64,
    shift: Vector<D>,
    g: &Vector<D>,
    law: &GrowthLaw,
) -> Option<f64> {
    let t0 = a.time.max(b.time);
    let dp = (b.falling_at(t0, g) - a.falling_at(t0, g)) + shift;
    let dv = b.falling_velocity(t0, g) - a.falling_velocity(t0, g);
    let sum = ra + rb;
    first_contact_growing(dp, dv, law.radius_at(sum, t0), law.speed(sum)).map(|dt| t0 + dt)
}

/// Time of impact (absolute, seconds) of two growing balls under different accelerations
/// `acc_a`, `acc_b` (m/s²; a kinematic body does not fall): the first root of the quartic of
/// their relative parabola against the growing contact distance, from
/// `T = max(a.time, b.time)`.
#[must_use]
pub fn toi_circle_circle_accelerating_growing<const D: usize>(
    a: &Motion<D>,
    ra: f64,
    acc_a: &Vector<D>,
    b: &Motion<D>,
    rb: f64,
    acc_b: &Vector<D>,
    law: &GrowthLaw,
) -> Option<f64> {
    let t0 = a.time.max(b.time);
    let dp = b.falling_at(t0, acc_b) - a.falling_at(t0, acc_a);
    let dv = b.falling_velocity(t0, acc_b) - a.falling_velocity(t0, acc_a);
    let sum = ra + rb;
    first_contact_accelerating_growing(
        dp,
        dv,
        *acc_b - *acc_a,
        law.radius_at(sum, t0),
        law.speed(sum),
    )
    .map(|dt| t0 + dt)
    .filter(|t| t.is_finite())
}

/// Time of impact (absolute, seconds) of a growing ball (stored radius `r`) falling under
/// `g` with the one-sided plane through `point` whose `normal` points to the ball's side:
/// the first entry of the gap `(gap − r) + (v_n − ṙ)·t + ½·g_n·t²`, from the ball's
/// reference time.
#[must_use]
pub fn toi_circle_plane_falling_growing<const D: usize>(
    m: &Motion<D>,
    r: f64,
    point: Vector<D>,
    normal: Vector<D>,
    g: &Vector<D>,
    law: &GrowthLaw,
) -> Option<f64> {
    let len = normal.norm();
    let gn = g.dot(normal) / len;
    let closing = m.vel.dot(normal) / len - law.speed(r);
    let gap = (m.pos - point).dot(normal) / len - law.radius_at(r, m.time);
    first_entry(gap, closing, 0.5 * gn).map(|dt| m.time + dt)
}

/// Time of impact (absolute, seconds) of a growing ball (stored radius `r`) falling under `g`
/// with the segment `[a, b]`: in 2D the first entry into the growing slab around its line
/// whose foot lies on the segment, or the first contact with an end point, from the ball's
/// reference time (see the module docs); in 3D, a rod's
/// ([`crate::contact::rod::toi_circle_rod_falling_growing`]).
#[must_use]
pub fn toi_circle_segment_falling_growing<const D: usize>(
    m: &Motion<D>,
    r: f64,
    a: Vector<D>,
    b: Vector<D>,
    g: &Vector<D>,
    law: &GrowthLaw,
) -> Option<f64> {
    if D != 2 {
        return crate::contact::rod::toi_circle_rod_falling_growing(m, r, a, b, g, law);
    }
    let (radius, speed) = (law.radius_at(r, m.time), law.speed(r));
    crate::contact::falling_segment::toi_circle_segment_on_parabola(
        m, radius, speed, a, b, g, [true; 2],
    )
}

/// Time of impact (absolute, seconds) of a growing ball (stored radius `r`) falling under `g`
/// with a wall of either kind.
#[must_use]
#[inline]
pub fn toi_circle_wall_falling_growing<const D: usize>(
    m: &Motion<D>,
    r: f64,
    wall: &Wall<D>,
    g: &Vector<D>,
    law: &GrowthLaw,
) -> Option<f64> {
    match *wall {
        Wall::Segment { a, b } => toi_circle_segment_falling_growing(m, r, a, b, g, law),
        Wall::Plane { point, normal } => {
            toi_circle_plane_falling_growing(m, r, point, normal, g, law)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contact::accelerated_contact::first_contact_accelerating;
    use crate::wall::wall_clearance;
    use proptest::array::{uniform2, uniform3};
    use proptest::prelude::*;

    const G: Vector<2> = Vector([0.0, -10.0]);
    const LAW: GrowthLaw = GrowthLaw {
        rate: 0.5,
        origin: 0.0,
    };

    fn m2(p: [f64; 2], v: [f64; 2], t: f64) -> Motion<2> {
        Motion {
            pos: Vector(p),
            vel: Vector(v),
            time: t,
        }
    }

    /// The root of `6 − 5·t² = 1 + 0.5·t`: a ball of radius 1 growing at 0.5 m/s, its centre
    /// dropped from 6 above a floor under g = 10.
    fn dropped_onto_floor() -> f64 {
        (-0.5 + (0.25f64 + 100.0).sqrt()) / 10.0
    }

    #[test]
    fn a_growing_ball_falling_onto_a_floor_meets_it_when_the_gap_closes() {
        let want = dropped_onto_floor();
        let m = m2([0.0, 6.0], [0.0, 0.0], 0.0);
        let floor = (Vector([0.0, 0.0]), Vector([0.0, 2.0]));
        let t = toi_circle_plane_falling_growing(&m, 1.0, floor.0, floor.1, &G, &LAW).unwrap();
        assert!((t - want).abs() < 1e-15, "{t} {want}");
        // The same from a later reference time: the radius is already 1.5 at t = 1 and grows
        // at 0.5, so 6 − 5·s² = 1.5 + 0.5·s.
        let m = m2([0.0, 6.0], [0.0, 0.0], 1.0);
        let t = toi_circle_plane_falling_growing(&m, 1.0, floor.0, floor.1, &G, &LAW).unwrap();
        let s = (-0.5 + (0.25f64 + 4.0 * 5.0 * 4.5).sqrt()) / 10.0;
        assert!((t - (1.0 + s)).abs() < 1e-15, "{t}");
        // A segment under the ball: its interior, at the same time.
        let seg = Wall::Segment {
            a: Vector([-2.0, 0.0]),
            b: Vector([2.0, 0.0]),
        };
        let m = m2([0.0, 6.0], [0.0, 0.0], 0.0);
        let t = toi_circle_wall_falling_growing(&m, 1.0, &seg, &G, &LAW).unwrap();
        assert!((t - want).abs() < 1e-14, "{t} {want}");
        // A point (an end point, or a kinematic ball's centre) straight below: the quartic.
        let t = first_contact_accelerating_growing(Vector([0.0, 6.0]), Vector::ZERO, G, 1.0, 0.5)
            .unwrap();
        assert!((t - want).abs() < 1e-14, "{t} {want}");
        // Growth makes the ball meet a floor it would have missed: thrown up, held above 1.
        let m = m2([0.0, 6.0], [0.0, 0.0], 0.0);
        let up = Vector([0.0, 0.0]);
        assert_eq!(
            crate::contact::gravity::toi_circle_plane_falling(&m, 1.0, floor.0, floor.1, &up),
            None
        );
        let t = toi_circle_plane_falling_growing(&m, 1.0, floor.0, floor.1, &up, &LAW).unwrap();
        assert!((t - 10.0).abs() < 1e-14, "{t}");
    }

    #[test]
    fn a_kinematic_ball_meets_a_falling_growing_one() {
        // Kinematic ball at rest at the origin and a dynamic one 6 above, radii 0.5 each:
        // the contact distance 1 grows at 0.5, as for the floor.
        let k = m2([0.0, 0.0], [0.0, 0.0], 0.0);
        let b = m2([0.0, 6.0], [0.0, 0.0], 0.0);
        let t = toi_circle_circle_accelerating_growing(&k, 0.5, &Vector::ZERO, &b, 0.5, &G, &LAW)
            .unwrap();
        assert!((t - dropped_onto_floor()).abs() < 1e-14, "{t}");
        // Two falling balls: no relative acceleration, growth's straight-line quadratic; 4
        // apart at rest, σ(t) = 1 + 0.5·t reaches 4 at t = 6.
        let a = m2([0.0, 0.0], [0.0, 0.0], 0.0);
        let b = m2([4.0, 0.0], [0.0, 0.0], 0.0);
        let t = toi_circle_circle_falling_growing(&a, 0.5, &b, 0.5, Vector::ZERO, &G, &LAW);
        assert_eq!(t, Some(6.0));
    }

    #[test]
    fn a_growing_ball_arcing_over_the_end_lands_on_the_segment() {
        // As for fixed radii (see `crate::contact::gravity`): up past the end, down onto the top.
        let m = m2([7.0, -3.0], [-3.0, 10.0], 0.0);
        let (a, b) = (Vector([0.0, 0.0]), Vector([4.0, 0.0]));
        let law = GrowthLaw {
            rate: 0.05,
            origin: 0.0,
        };
        let t = toi_circle_segment_falling_growing(&m, 0.5, a, b, &G, &law).unwrap();
        let p = m.falling_at(t, &G);
        assert!((p[1] - law.radius_at(0.5, t)).abs() < 1e-12, "{p:?} at {t}");
        assert!(p[0] > 0.0 && p[0] < 4.0, "{p:?}");
    }

    #[test]
    fn zero_growth_is_the_fixed_radius_quartic_bit_for_bit() {
        let cases = [
            ([0.3, 6.0], [0.0, 0.0], [0.0, -10.0], 1.0),
            ([5.0, 1.0], [-3.0, 2.0], [0.0, -9.81], 0.7),
            ([0.5, 0.2], [1.0, 1.0], [0.0, -1.0], 1.0),
            ([2.0, 0.0], [0.0, 0.0], [0.0, 0.0], 0.5),
            ([2.0, 0.0], [-1.0, 0.1], [0.0, 0.0], 0.5),
        ];
        for (dp, dv, acc, sigma) in cases {
            let (dp, dv, acc) = (Vector(dp), Vector(dv), Vector(acc));
            assert_eq!(
                first_contact_accelerating_growing(dp, dv, acc, sigma, 0.0).map(f64::to_bits),
                first_contact_accelerating(dp, dv, acc, sigma).map(f64::to_bits),
            );
        }
    }

    /// Checks `got`, the first contact of `|x(t)| = σ + σ̇·t` with `x(t) = dp + dv·t + ½·acc·t²`
    /// for a pair apart at 0, against a dense sampling of the exact gap `|x(t)| − σ(t)`: zero
    /// at `got` within rounding, never below zero before it; `None` only when it stays apart
    /// over the sampled horizon.
    fn check_against_sampling<const D: usize>(
        got: Option<f64>,
        gap: impl Fn(f64) -> f64,
        scale: impl Fn(f64) -> f64,
    ) -> Result<(), TestCaseError> {
        let tol = |t: f64| 1e-9 * (1.0 + t) * scale(t);
        match got {
            Some(t) => {
                prop_assert!(gap(t).abs() <= tol(t), "gap {} at {t}", gap(t));
                for k in 0..2000 {
                    let s = t * f64::from(k) / 2000.0;
                    prop_assert!(gap(s) > -tol(s), "in contact at {s} before {t}");
                }
            }
            None => {
                for k in 0..4000 {
                    let s = f64::from(k) * 0.0025;
                    prop_assert!(gap(s) > -tol(s), "missed a contact near {s}");
                }
            }
        }
        Ok(())
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(512))]

        /// The growing quartic's first contact against a brute-force sampling, 3D.
        #[test]
        fn growing_quartic_matches_sampling(
            dp in uniform3(-5.0..5.0f64),
            dv in uniform3(-4.0..4.0f64),
            acc in uniform3(-10.0..10.0f64),
            sigma in 0.2..2.0f64,
            sigma_dot in 0.0..2.0f64,
        ) {
            let (dp, dv, acc) = (Vector(dp), Vector(dv), Vector(acc));
            prop_assume!(dp.norm() > sigma * 1.001);
            let x = |t: f64| dp + dv * t + acc * (0.5 * t * t);
            let got = first_contact_accelerating_growing(dp, dv, acc, sigma, sigma_dot);
            prop_assert!(got.is_none_or(|t| t >= 0.0 && t.is_finite()));
            check_against_sampling::<3>(
                got,
                |t| x(t).norm() - (sigma + sigma_dot * t),
                |t| x(t).norm() + sigma + sigma_dot * t + dv.norm() * t + acc.norm() * t * t,
            )?;
        }

        /// At `σ̇ = 0` the growing quartic is the fixed-radius one bit for bit.
        #[test]
        fn zero_growth_keeps_the_bits(
            dp in uniform2(-5.0..5.0f64),
            dv in uniform2(-4.0..4.0f64),
            acc in uniform2(-10.0..10.0f64),
            sigma in 0.2..2.0f64,
        ) {
            let (dp, dv, acc) = (Vector(dp), Vector(dv), Vector(acc));
            prop_assert_eq!(
                first_contact_accelerating_growing(dp, dv, acc, sigma, 0.0).map(f64::to_bits),
                first_contact_accelerating(dp, dv, acc, sigma).map(f64::to_bits)
            );
        }

        /// A growing ball falling at a segment: the contact against a sampling of its exact
        /// clearance less its radius.
        #[test]
        fn growing_segment_contacts_match_sampling(
            p in uniform2(-3.0..3.0f64),
            v in uniform2(-4.0..4.0f64),
            gy in -10.0..-0.5f64,
            gx in -2.0..2.0f64,
            rate in 0.0..1.0f64,
        ) {
            let seg = Wall::Segment { a: Vector([-1.0, 0.0]), b: Vector([1.0, 0.4]) };
            let (m, g) = (m2(p, v, 0.0), Vector([gx, gy]));
            let law = GrowthLaw { rate, origin: 0.0 };
            let r = 0.3;
            prop_assume!(wall_clearance(&seg, m.pos) > r * 1.001);
            let got = toi_circle_wall_falling_growing(&m, r, &seg, &g, &law);
            let gap = |t: f64| wall_clearance(&seg, m.falling_at(t, &g)) - law.radius_at(r, t);
            check_against_sampling::<2>(got, gap, |t| {
                5.0 + m.falling_at(t, &g).norm() + law.radius_at(r, t)
            })?;
        }

        /// The same for a plane, in 3D.
        #[test]
        fn growing_plane_contacts_match_sampling(
            p in uniform3(-3.0..3.0f64),
            v in uniform3(-4.0..4.0f64),
            g in uniform3(-10.0..10.0f64),
            rate in 0.0..1.0f64,
        ) {
            let plane = Wall::Plane { point: Vector([0.0, 0.0, -4.0]), normal: Vector([0.3, 0.2, 1.0]) };
            let m = Motion { pos: Vector(p), vel: Vector(v), time: 0.0 };
            let g = Vector(g);
            let law = GrowthLaw { rate, origin: 0.0 };
            let r = 0.3;
            prop_assume!(wall_clearance(&plane, m.pos) > r * 1.001);
            let got = toi_circle_wall_falling_growing(&m, r, &plane, &g, &law);
            let gap = |t: f64| wall_clearance(&plane, m.falling_at(t, &g)) - law.radius_at(r, t);
            check_against_sampling::<3>(got, gap, |t| {
                5.0 + m.falling_at(t, &g).norm() + law.radius_at(r, t)
            })?;
        }
    }
}
