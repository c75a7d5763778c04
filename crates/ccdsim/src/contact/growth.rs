//! Growing radii (Lubachevsky–Stillinger compression): every radius grows linearly in time,
//! `r_i(t) = r_i · (1 + Γ·(t − t₀))`, with `r_i` the scene's radius and `t₀` its start time,
//! so a polydisperse packing keeps its size ratios.
//!
//! # Contacts stay quadratic
//!
//! Two balls at offset `dp(t) = dp + dv·t` touch when `|dp(t)| = σ(t) = σ + σ̇·t`, with `σ` the
//! sum of their radii at the evaluation time and `σ̇ = Γ·(r_a + r_b)` its growth speed. Squared,
//! `C + 2B·t + A·t² = 0` with `A = |dv|² − σ̇²`, `B = dp·dv − σ·σ̇`, `C = |dp|² − σ²`: the same
//! quadratic as for fixed radii, two more products. `C(t)/2`'s slope is `B + A·t`, so "the pair
//! approaches" is `B < 0`, as for fixed radii. Unlike fixed radii, `A` may be negative (the
//! surfaces grow towards each other faster than the centres part): then a pair that recedes
//! now still meets later, and [`first_contact_growing`] finds that root too.
//!
//! A ball and a plane touch when the distance of its centre, linear in time, equals its radius,
//! linear in time: one division. A ball and a segment: the segment's line (the same quadratic
//! on the components across the line) or one of its end points (a pair with a point of radius
//! zero); the first contact with the line outside the segment cannot hide an earlier contact
//! with the segment, since a ball within reach of the line beyond an end reaches the interior
//! only through the end point's ball, which grows with it.
//!
//! # Collisions push the surfaces apart
//!
//! A collision reverses the speed at which the *surfaces* approach, not the centres: with
//! `u = (v_b − v_a)·n` the normal relative velocity, the surfaces approach at `σ̇ − u` and after
//! the collision `u' − σ̇ = −e·(u − σ̇)`, so `u' = (1 + e)·σ̇ − e·u` (elastic: `2σ̇ − u`). A pair
//! therefore parts faster than it grows and the packing heats up: compression rescales the
//! velocities now and then ([`crate::Simulation::rescale_velocities`]). Against a wall the
//! same rule holds with `σ̇ = Γ·r`, against a moving wall in the wall's frame (`u` relative to
//! its velocity, see [`crate::world::time_of_impact`]). `e` is the collision's restitution as for fixed
//! radii: the mean of the pair's own (the body's own at a wall), or 1 under the TC model
//! ([`crate::World::pair_restitution`]). A kinematic body (infinite mass) grows like every
//! body and keeps its velocity: the other body takes the whole change. Momentum is conserved
//! by pair collisions of dynamic bodies, kinetic energy is not (it grows by the work of the
//! growth).
//!
//! Under gravity too, see [`crate::contact::falling_growth`]: pairs keep this quadratic (falling bodies
//! have no relative acceleration), walls and kinematic bodies take parabolas.
//!
//! # Exactness
//!
//! Every finder evaluates pairs through the functions of this module when the world grows,
//! lower index first as for fixed radii, so their events agree bit for bit with the oracle's.
//! Finders that size a structure for the largest contact distance size it for the distance at
//! a horizon and rebuild it before passing that horizon (see each finder's docs).

use crate::geom::Vector;
use crate::motion::GrowthLaw;
use crate::motion::Motion;
use crate::wall::Wall;

/// Time `t ≥ 0` after which a point at offset `dp` moving at relative velocity `dv` first
/// comes within `sigma + sigma_dot·t` of the origin, when it then approaches (see the module
/// docs); `None` when it never does.
///
/// The earlier root uses the cancellation-free form `C / (−B + √(B² − AC))`; an overlapping
/// pair that approaches collides at once, and an overlapping pair that recedes while the
/// surfaces outgrow the centres (`A < 0`) meets again at the later root, `(B + √(B² − AC)) /
/// −A`, or, if it never leaves the overlap, when it turns to approach (`B / −A`).
#[must_use]
#[inline]
pub fn first_contact_growing<const D: usize>(
    dp: Vector<D>,
    dv: Vector<D>,
    sigma: f64,
    sigma_dot: f64,
) -> Option<f64> {
    let b = dp.dot(dv) - sigma * sigma_dot;
    let c = dp.norm_sq() - sigma * sigma;
    let a = dv.norm_sq() - sigma_dot * sigma_dot;
    if c <= 0.0 {
        if b < 0.0 {
            return Some(0.0);
        }
        if a >= 0.0 {
            return None;
        }
        let disc = b * b - a * c;
        let t = if disc < 0.0 {
            b / -a
        } else {
            (b + disc.sqrt()) / -a
        };
        return Some(t).filter(|t| t.is_finite());
    }
    let disc = b * b - a * c;
    if disc < 0.0 {
        return None;
    }
    let q = -b + disc.sqrt();
    if q <= 0.0 {
        return None;
    }
    Some(c / q).filter(|t| t.is_finite())
}

/// Time `t ≥ 0` after which a point at offset `dp` moving at relative velocity `dv` is first
/// at least `sigma + sigma_dot·t` from the origin while moving away from that sphere: the time
/// it leaves a growing ball (a body leaving a sensor while it grows, see [`crate::sensor`]).
/// `None` when it never does.
///
/// [`crate::contact::accelerated_contact::first_exit`]'s contract for the quadratic of
/// [`first_contact_growing`], `f(t) = C + 2B·t + A·t²`: `0` when the point is out (`C ≥ 0`)
/// and moving away (`B > 0`); otherwise the first root where `f` turns positive. For `A > 0`
/// that is the later root, `(−B + √(B² − AC)) / A`, computed without cancellation; for
/// `A = 0`, `−C / 2B` when `B > 0`; for `A < 0` (the sphere outgrows the point) never.
#[must_use]
#[inline]
pub fn first_exit_growing<const D: usize>(
    dp: Vector<D>,
    dv: Vector<D>,
    sigma: f64,
    sigma_dot: f64,
) -> Option<f64> {
    let b = dp.dot(dv) - sigma * sigma_dot;
    let c = dp.norm_sq() - sigma * sigma;
    if c >= 0.0 && b > 0.0 {
        return Some(0.0);
    }
    let a = dv.norm_sq() - sigma_dot * sigma_dot;
    let t = if a > 0.0 {
        let disc = b * b - a * c;
        // A path that misses the sphere (possible only when the point is out): it is out and
        // passes by, as `first_exit` has it.
        if disc.is_nan() || disc < 0.0 {
            return Some(0.0);
        }
        let root = disc.sqrt();
        if b <= 0.0 {
            (root - b) / a
        } else {
            -c / (b + root)
        }
    } else if a == 0.0 {
        // `f` is linear: it turns positive only while rising.
        if b <= 0.0 {
            return (c >= 0.0 && b == 0.0).then_some(0.0);
        }
        -c / (2.0 * b)
    } else {
        // The sphere grows faster than the point moves (`|dv| < σ̇`): a point on or inside it
        // stays inside, `|x(t)| ≤ |x| + |dv|·t < σ + σ̇·t`.
        return None;
    };
    Some(t.max(0.0)).filter(|t| t.is_finite())
}

/// Time of impact of two growing balls (stored radii `ra`, `rb`), ball `b` displaced by
/// `shift` (a periodic image; zero otherwise), evaluated from `T = max(a.time, b.time)` as
/// [`crate::contact::narrow::toi_circle_circle_shifted`] is for fixed radii.
#[must_use]
#[inline]
pub fn toi_circle_circle_growing<const D: usize>(
    a: &Motion<D>,
    ra: f64,
    b: &Motion<D>,
    rb: f64,
    shift: Vector<D>,
    law: &GrowthLaw,
) -> Option<f64> {
    let t0 = a.time.max(b.time);
    let dp = (b.at(t0) - a.at(t0)) + shift;
    let sum = ra + rb;
    first_contact_growing(dp, b.vel - a.vel, law.radius_at(sum, t0), law.speed(sum))
        .map(|dt| t0 + dt)
}

/// Time of impact of two growing balls in a periodic box of sides `size`: the earliest
/// contact of `b`'s `3^D` images `k·L`, `k ∈ {−1, 0, 1}^D`, each by
/// [`toi_circle_circle_growing`], in the oracle's order of images. (No image is skipped: the
/// reach grows with time.)
#[must_use]
pub fn toi_circle_circle_periodic_growing<const D: usize>(
    a: &Motion<D>,
    ra: f64,
    b: &Motion<D>,
    rb: f64,
    size: &Vector<D>,
    law: &GrowthLaw,
) -> Option<f64> {
    let mut best: Option<f64> = None;
    let images = 3usize.pow(D as u32);
    for code in 0..images {
        let mut shift = Vector::<D>::ZERO;
        let mut rest = code;
        for d in 0..D {
            let k = (rest % 3) as f64 - 1.0;
            rest /= 3;
            shift[d] = k * size[d];
        }
        if let Some(t) = toi_circle_circle_growing(a, ra, b, rb, shift, law) {
            if best.is_none_or(|bt| t.total_cmp(&bt).is_lt()) {
                best = Some(t);
            }
        }
    }
    best
}

/// Time of impact of a growing ball (stored radius `r`) with a wall of either kind, from the
/// ball's reference time.
#[must_use]
pub fn toi_circle_wall_growing<const D: usize>(
    m: &Motion<D>,
    r: f64,
    wall: &Wall<D>,
    law: &GrowthLaw,
) -> Option<f64> {
    let radius = law.radius_at(r, m.time);
    let speed = law.speed(r);
    match *wall {
        Wall::Segment { a, b } => {
            let u = b - a;
            let l2 = u.norm_sq();
            let w = m.pos - a;
            let w_perp = w - u * (w.dot(u) / l2);
            let v_perp = m.vel - u * (m.vel.dot(u) / l2);
            let interior = first_contact_growing(w_perp, v_perp, radius, speed).filter(|&dt| {
                let s = (w + m.vel * dt).dot(u) / l2;
                (0.0..=1.0).contains(&s)
            });
            let end_a = first_contact_growing(w, m.vel, radius, speed);
            let end_b = first_contact_growing(m.pos - b, m.vel, radius, speed);
            [interior, end_a, end_b]
                .into_iter()
                .flatten()
                .reduce(f64::min)
                .map(|dt| m.time + dt)
        }
        Wall::Plane { point, normal } => {
            let len = normal.norm();
            let vn = m.vel.dot(normal) / len;
            let closing = vn - speed;
            let gap = (m.pos - point).dot(normal) / len - radius;
            if closing >= 0.0 {
                return None;
            }
            if gap <= 0.0 {
                return Some(m.time);
            }
            Some(m.time + gap / -closing).filter(|t| t.is_finite())
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn m2(p: [f64; 2], v: [f64; 2], t: f64) -> Motion<2> {
        Motion {
            pos: Vector(p),
            vel: Vector(v),
            time: t,
        }
    }

    const LAW: GrowthLaw = GrowthLaw {
        rate: 0.5,
        origin: 0.0,
    };

    #[test]
    fn scale_and_time_to_reach() {
        assert_eq!(LAW.scale(0.0), 1.0);
        assert_eq!(LAW.scale(2.0), 2.0);
        assert_eq!(LAW.radius_at(0.5, 2.0), 1.0);
        assert_eq!(LAW.time_to_reach(0.5, 1.0, 0.0), 2.0);
        assert_eq!(LAW.time_to_reach(0.5, 1.0, 3.0), 3.0);
        let still = GrowthLaw {
            rate: 0.0,
            origin: 0.0,
        };
        assert_eq!(still.time_to_reach(0.5, 1.0, 0.0), f64::INFINITY);
    }

    #[test]
    fn resting_balls_meet_when_they_have_grown_into_each_other() {
        // Radii 0.5 each, centres 4 apart: σ(t) = 1 + 0.5·t reaches 4 at t = 6.
        let a = m2([0.0, 0.0], [0.0, 0.0], 0.0);
        let b = m2([4.0, 0.0], [0.0, 0.0], 0.0);
        let t = toi_circle_circle_growing(&a, 0.5, &b, 0.5, Vector::ZERO, &LAW).unwrap();
        assert!((t - 6.0).abs() < 1e-12, "{t}");
        // Receding slower than they grow: they still meet (A < 0).
        let b = m2([4.0, 0.0], [0.25, 0.0], 0.0);
        let t = toi_circle_circle_growing(&a, 0.5, &b, 0.5, Vector::ZERO, &LAW).unwrap();
        assert!((t - 12.0).abs() < 1e-12, "{t}");
        // Receding faster than they grow: never.
        let b = m2([4.0, 0.0], [0.75, 0.0], 0.0);
        assert_eq!(
            toi_circle_circle_growing(&a, 0.5, &b, 0.5, Vector::ZERO, &LAW),
            None
        );
    }

    #[test]
    fn overlapping_pairs_collide_when_they_approach() {
        let a = m2([0.0, 0.0], [0.0, 0.0], 1.0);
        // σ(1) = 1.5; 1.4 apart, approaching: at once.
        let b = m2([1.4, 0.0], [-0.1, 0.0], 1.0);
        assert_eq!(
            toi_circle_circle_growing(&a, 0.5, &b, 0.5, Vector::ZERO, &LAW),
            Some(1.0)
        );
        // Parting at 0.1 while the contact distance grows at 0.5: the gap keeps closing.
        let b = m2([1.4, 0.0], [0.1, 0.0], 1.0);
        assert_eq!(
            toi_circle_circle_growing(&a, 0.5, &b, 0.5, Vector::ZERO, &LAW),
            Some(1.0)
        );
        // Parting at 1 while growing at 0.5: never.
        let b = m2([1.4, 0.0], [1.0, 0.0], 1.0);
        assert_eq!(
            toi_circle_circle_growing(&a, 0.5, &b, 0.5, Vector::ZERO, &LAW),
            None
        );
    }

    #[test]
    fn walls_meet_growing_balls() {
        let m = m2([0.0, 3.0], [0.0, 0.0], 0.0);
        // A plane at y = 0 facing up; radius 1 grows at 0.5: reaches 3 at t = 4.
        let plane = Wall::Plane {
            point: Vector([0.0, 0.0]),
            normal: Vector([0.0, 2.0]),
        };
        assert_eq!(toi_circle_wall_growing(&m, 1.0, &plane, &LAW), Some(4.0));
        // The segment from (-1, 0) to (1, 0): the same contact on its interior.
        let seg = Wall::Segment {
            a: Vector([-1.0, 0.0]),
            b: Vector([1.0, 0.0]),
        };
        let t = toi_circle_wall_growing(&m, 1.0, &seg, &LAW).unwrap();
        assert!((t - 4.0).abs() < 1e-12, "{t}");
        // Beyond the end, at (5, 3): distance 5 from the end point (1, 0): t = 8 (the line
        // is reached at t = 4, beyond the end, and does not count).
        let m = m2([5.0, 3.0], [0.0, 0.0], 0.0);
        let t = toi_circle_wall_growing(&m, 1.0, &seg, &LAW).unwrap();
        assert!((t - 8.0).abs() < 1e-12, "{t}");
    }

    #[test]
    fn exits_from_a_growing_ball() {
        let dp = Vector([1.0, 0.0]);
        // Sphere 2 growing at 0.5, point moving out at 1: |x| − σ = −1 + 0.5·t, out at 2.
        let t = first_exit_growing(dp, Vector([1.0, 0.0]), 2.0, 0.5).unwrap();
        assert!((t - 2.0).abs() < 1e-15, "{t}");
        // Moving out at the growth speed or slower: never.
        assert_eq!(first_exit_growing(dp, Vector([0.5, 0.0]), 2.0, 0.5), None);
        assert_eq!(first_exit_growing(dp, Vector([0.25, 0.0]), 2.0, 0.5), None);
        // Passing sideways through a slowly growing sphere: out at the later root of
        // 1 + t² = (2 + 0.1·t)², i.e. 0.99·t² − 0.4·t − 3 = 0.
        let t = first_exit_growing(dp, Vector([0.0, 1.0]), 2.0, 0.1).unwrap();
        let want = (0.4 + (0.16f64 + 4.0 * 0.99 * 3.0).sqrt()) / (2.0 * 0.99);
        assert!((t - want).abs() < 1e-14, "{t} {want}");
        // Out and moving away: at once; out and approaching a sphere that outgrows it: never.
        assert_eq!(
            first_exit_growing(Vector([3.0, 0.0]), Vector([1.0, 0.0]), 2.0, 0.5),
            Some(0.0)
        );
        assert_eq!(
            first_exit_growing(Vector([3.0, 0.0]), Vector([-1.0, 0.0]), 2.0, 2.0),
            None
        );
        // Inside, moving out faster than the sphere grows, in 1D: |x| = 1 + 2·t reaches
        // σ = 1.5 + t at 0.5.
        let t = first_exit_growing(Vector([1.0]), Vector([2.0]), 1.5, 1.0).unwrap();
        assert!((t - 0.5).abs() < 1e-15, "{t}");
    }

    proptest::proptest! {
        /// The exit time is a root where the point goes out: inside (gap < 0) until then, the
        /// gap zero there within rounding; `None` only when it stays inside.
        #[test]
        fn the_exit_is_the_first_root_going_out(
            angle in 0.0..std::f64::consts::TAU,
            depth in 0.0..0.999f64,
            dv in proptest::array::uniform2(-3.0..3.0f64),
            sigma in 0.5..5.0f64,
            sigma_dot in 0.0..3.0f64,
        ) {
            // A point inside the sphere: `depth` of the way out from the centre.
            let dp = Vector([angle.cos(), angle.sin()]) * (depth * sigma);
            let dv = Vector(dv);
            let gap = |t: f64| (dp + dv * t).norm() - (sigma + sigma_dot * t);
            let tol = |t: f64| 1e-9 * (1.0 + t) * (sigma + sigma_dot * t + (dp + dv * t).norm());
            match first_exit_growing(dp, dv, sigma, sigma_dot) {
                Some(t) => {
                    proptest::prop_assert!(gap(t).abs() <= tol(t), "gap {} at {t}", gap(t));
                    for k in 0..200 {
                        let s = t * k as f64 / 200.0;
                        proptest::prop_assert!(gap(s) < tol(s), "out at {s} before {t}");
                    }
                    // And it goes out: a little later the gap is positive.
                    let later = t * (1.0 + 1e-6) + 1e-6;
                    proptest::prop_assert!(gap(later) > -tol(later), "{}", gap(later));
                }
                None => {
                    for k in 0..2000 {
                        let s = k as f64 * 0.05;
                        proptest::prop_assert!(gap(s) < tol(s), "missed an exit near {s}");
                    }
                }
            }
        }
    }

    proptest::proptest! {
        /// The contact time is a root: the gap is zero there, within rounding, and the gap
        /// was positive just before (no earlier root was skipped).
        #[test]
        fn the_first_root_is_a_contact(
            dp in proptest::array::uniform2(-10.0..10.0f64),
            dv in proptest::array::uniform2(-3.0..3.0f64),
            sigma in 0.1..2.0f64,
            sigma_dot in 0.0..2.0f64,
        ) {
            let (dp, dv) = (Vector(dp), Vector(dv));
            proptest::prop_assume!(dp.norm() > sigma * 1.001);
            let gap = |t: f64| (dp + dv * t).norm() - (sigma + sigma_dot * t);
            match first_contact_growing(dp, dv, sigma, sigma_dot) {
                Some(t) => {
                    proptest::prop_assert!(gap(t).abs() <= 1e-9 * (1.0 + t) * (sigma + sigma_dot * t), "gap {} at {t}", gap(t));
                    for k in 0..200 {
                        let s = t * k as f64 / 200.0;
                        proptest::prop_assert!(gap(s) > -1e-9 * (sigma + sigma_dot * s));
                    }
                }
                None => {
                    for k in 0..2000 {
                        let s = k as f64 * 0.05;
                        proptest::prop_assert!(gap(s) > -1e-9 * (sigma + sigma_dot * s), "missed a contact near {s}");
                    }
                }
            }
        }
    }
}
