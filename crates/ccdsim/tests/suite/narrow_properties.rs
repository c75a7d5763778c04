//! Properties of the narrow phase: the gap is ~0 at the returned time, no earlier contact
//! exists, receding pairs never collide.

use ccdsim::contact::narrow::{toi_circle_circle, toi_circle_segment};
use ccdsim::geom::Vector;
use ccdsim::scene::{wall_clearance, Wall};
use ccdsim::Motion;
use proptest::prelude::*;

fn vec2() -> impl Strategy<Value = Vector<2>> {
    (-50.0..50.0f64, -50.0..50.0f64).prop_map(|(x, y)| Vector([x, y]))
}
fn vec3() -> impl Strategy<Value = Vector<3>> {
    (-50.0..50.0f64, -50.0..50.0f64, -50.0..50.0f64).prop_map(|(x, y, z)| Vector([x, y, z]))
}

/// Checks one pair: contact at the returned time, none earlier (sampled), and `None` only
/// when the pair never comes within contact distance.
fn check_pair<const D: usize>(
    a: Motion<D>,
    ra: f64,
    b: Motion<D>,
    rb: f64,
) -> Result<(), TestCaseError> {
    let sigma = ra + rb;
    let t0 = a.time.max(b.time);
    let dist = |t: f64| (b.at(t) - a.at(t)).norm();
    let approaching = (b.at(t0) - a.at(t0)).dot(b.vel - a.vel) < 0.0;
    match toi_circle_circle(&a, ra, &b, rb) {
        Some(t) => {
            prop_assert!(approaching, "only approaching pairs collide");
            prop_assert!(t >= t0, "never before the reference time");
            if dist(t0) >= sigma {
                let scale =
                    sigma + (b.vel - a.vel).norm() * (t - t0) + (b.at(t0) - a.at(t0)).norm();
                prop_assert!(
                    (dist(t) - sigma).abs() <= 1e-9 * scale,
                    "gap {} at contact",
                    dist(t) - sigma
                );
                for k in 0..64 {
                    let s = t0 + (t - t0) * k as f64 / 64.0;
                    prop_assert!(
                        dist(s) >= sigma * (1.0 - 1e-9) - 1e-9 * scale,
                        "earlier contact at {s}"
                    );
                }
            } else {
                prop_assert_eq!(t, t0, "overlapping and approaching collide at once");
            }
        }
        None => {
            if approaching {
                // Closest approach must stay outside the contact distance.
                let dp = b.at(t0) - a.at(t0);
                let dv = b.vel - a.vel;
                let s = -dp.dot(dv) / dv.norm_sq();
                let closest = (dp + dv * s).norm();
                prop_assert!(
                    closest >= sigma * (1.0 - 1e-9),
                    "missed contact, closest {closest} < {sigma}"
                );
            }
        }
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(2000))]

    #[test]
    fn circle_circle_2d(pa in vec2(), va in vec2(), pb in vec2(), vb in vec2(),
                        ra in 0.01..10.0f64, rb in 0.01..10.0f64, ta in 0.0..5.0f64, tb in 0.0..5.0f64) {
        let a = Motion { pos: pa, vel: va, time: ta };
        let b = Motion { pos: pb, vel: vb, time: tb };
        check_pair(a, ra, b, rb)?;
        // The answer does not depend on which body is called a.
        prop_assert_eq!(toi_circle_circle(&a, ra, &b, rb).map(f64::to_bits), toi_circle_circle(&b, rb, &a, ra).map(f64::to_bits));
    }

    #[test]
    fn circle_circle_3d(pa in vec3(), va in vec3(), pb in vec3(), vb in vec3(),
                        ra in 0.01..10.0f64, rb in 0.01..10.0f64, ta in 0.0..5.0f64, tb in 0.0..5.0f64) {
        check_pair(Motion { pos: pa, vel: va, time: ta }, ra, Motion { pos: pb, vel: vb, time: tb }, rb)?;
    }

    #[test]
    fn receding_pairs_never_collide(pa in vec2(), pb in vec2(), v in vec2(), ra in 0.01..10.0f64, rb in 0.01..10.0f64) {
        // b moves straight away from a.
        let dp = pb - pa;
        prop_assume!(dp.norm() > 1e-6);
        let away = dp * (v.norm() / dp.norm());
        let a = Motion { pos: pa, vel: Vector::ZERO, time: 0.0 };
        let b = Motion { pos: pb, vel: away, time: 0.0 };
        prop_assert_eq!(toi_circle_circle(&a, ra, &b, rb), None);
    }

    #[test]
    fn circle_segment(p in vec2(), v in vec2(), a in vec2(), b in vec2(), r in 0.01..5.0f64, t0 in 0.0..5.0f64) {
        prop_assume!((b - a).norm() > 1e-3);
        let wall = Wall::Segment { a, b };
        let m = Motion { pos: p, vel: v, time: t0 };
        let clear = |t: f64| wall_clearance(&wall, m.at(t));
        prop_assume!(clear(t0) > r);
        let scale = r + p.norm() + a.norm() + b.norm() + v.norm() * 10.0;
        match toi_circle_segment(&m, r, a, b) {
            Some(t) => {
                prop_assert!(t >= t0);
                prop_assert!((clear(t) - r).abs() <= 1e-9 * scale, "clearance {} at contact", clear(t) - r);
                for k in 0..64 {
                    let s = t0 + (t - t0) * k as f64 / 64.0;
                    prop_assert!(clear(s) >= r - 1e-9 * scale, "earlier contact at {s}");
                }
            }
            None => {
                // Clearance is convex in time: sample densely far ahead.
                for k in 0..400 {
                    let s = t0 + k as f64 * 0.05;
                    prop_assert!(clear(s) >= r - 1e-9 * scale, "missed contact at {s}");
                }
            }
        }
    }
}
