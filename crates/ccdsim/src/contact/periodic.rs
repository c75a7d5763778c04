//! Periodic boxes: the box `[0, L₁) × … × [0, L_D)` with opposite faces identified.
//!
//! # How periodic runs stay exact
//!
//! A body's stored position always lies in the box (up to rounding): when its centre reaches
//! a face, the body *exits* and re-enters through the opposite face. Exits are events of the
//! finder contract, ordered like wall events with wall index `walls.len() + face` where
//! `face = 2·axis + (1 for the upper face x = L, 0 for the lower face x = 0)`; the simulation
//! applies them silently (they are not collisions, never recorded nor counted) by moving the
//! body by ∓L along the axis.
//!
//! Between two exits of either body of a pair, both centres stay in the box, so their
//! displacement stays in `(−L, L)` on every axis and any contact is with one of the `3^D`
//! images `raw + k·L`, `k ∈ {−1, 0, 1}^D`, of the stored displacement `raw`. The periodic
//! narrow phase [`toi_circle_circle_periodic`] is the earliest contact over those images (each
//! evaluated by [`toi_circle_circle_shifted`]); the box must be wider than twice the largest
//! contact distance so that at most one image of a body can touch another. A pure function of
//! the stored states, like every narrow phase, it lets every finder agree bit for bit.

use crate::contact::growth::toi_circle_circle_periodic_growing;
use crate::contact::narrow::toi_circle_circle_shifted;
use crate::geom::Vector;
use crate::motion::Laws;
use crate::motion::Motion;

/// Face index of the exit through the lower (`upper = false`, x = 0) or upper (x = L) face of
/// `axis`.
#[must_use]
#[inline]
pub fn exit_face(axis: usize, upper: bool) -> usize {
    2 * axis + usize::from(upper)
}

/// Time at which the centre of a body with motion `m` leaves the box of sides `size` (moving
/// out through a face), and the face; ties go to the lower face index. A centre already on or
/// beyond the face it moves towards leaves at once (`m.time`).
#[must_use]
#[inline]
pub fn toi_box_exit<const D: usize>(m: &Motion<D>, size: &Vector<D>) -> Option<(f64, usize)> {
    // Every axis is evaluated and the choices are masks: which way a body moves along an
    // axis, and which face it reaches first, are coin flips to a branch predictor. The time
    // is the same expression either way (`−v` is `|v|` for `v < 0`).
    let (mut best_t, mut best_face, mut found) = (f64::INFINITY, 0usize, false);
    for d in 0..D {
        let v = m.vel[d];
        let up = v > 0.0;
        let valid = up | (v < 0.0);
        let gap = select(up, size[d] - m.pos[d], m.pos[d]);
        let t = select(gap <= 0.0, m.time, m.time + gap / v.abs());
        let take = valid & (!found | t.total_cmp(&best_t).is_lt());
        best_t = select(take, t, best_t);
        best_face = if take { exit_face(d, up) } else { best_face };
        found |= valid;
    }
    found.then_some((best_t, best_face))
}

/// `if c { a } else { b }` by a mask: the code generator turns an `if` on floats into a
/// branch.
#[inline(always)]
fn select(c: bool, a: f64, b: f64) -> f64 {
    let mask = u64::from(c).wrapping_neg();
    f64::from_bits((a.to_bits() & mask) | (b.to_bits() & !mask))
}

/// The displacement `dp` reduced to its minimum image: each component in `[−L/2, L/2]`.
#[must_use]
#[inline]
pub fn min_image<const D: usize>(mut dp: Vector<D>, size: &Vector<D>) -> Vector<D> {
    for d in 0..D {
        dp[d] -= size[d] * round_half_away(dp[d] / size[d]);
    }
    dp
}

/// `x.round()` (halves away from zero), inline: `f64::round` is a library call on the
/// baseline x86-64 target, and the minimum image is taken at every collision of a periodic
/// world.
#[inline]
fn round_half_away(x: f64) -> f64 {
    // Below 2^52 in magnitude the truncation fits an i64 and `x − trunc(x)` is exact; above it
    // every float is already an integer (and NaN or infinities go to the library).
    if x.abs() < 4_503_599_627_370_496.0 {
        let k = x as i64 as f64;
        let frac = x - k;
        // `k ± 1` when the fraction reaches a half, else `k`, without a branch (which way a
        // displacement rounds is a coin flip). The step is exact, and `copysign` keeps the
        // sign of a zero the way `round` does (−0.3 rounds to −0); `k ± 1` already has x's
        // sign.
        let step = f64::from(i8::from(frac >= 0.5) - i8::from(frac <= -0.5));
        (k + step).copysign(x)
    } else {
        x.round()
    }
}

/// The point `p` moved into the box `[0, L)` by whole periods.
#[must_use]
pub fn wrap_point<const D: usize>(mut p: Vector<D>, size: &Vector<D>) -> Vector<D> {
    for d in 0..D {
        // `%` is exact for floats; only the final shift of a negative remainder rounds.
        let mut x = p[d] % size[d];
        if x < 0.0 {
            x += size[d];
        }
        if x >= size[d] {
            x = 0.0;
        }
        p[d] = x;
    }
    p
}

/// Time of impact of two balls in a periodic box of sides `size`: the earliest contact of `b`'s
/// images `raw + k·L`, `k ∈ {−1, 0, 1}^D`, with `a`, each by [`toi_circle_circle_shifted`].
///
/// Images that cannot come within the contact distance on some axis at a time allowed by the
/// other axes are skipped; the test carries a slack of 10⁻³ of the contact distance, far above
/// rounding, so it never skips an image the narrow phase would report.
#[must_use]
pub fn toi_circle_circle_periodic<const D: usize>(
    a: &Motion<D>,
    ra: f64,
    b: &Motion<D>,
    rb: f64,
    size: &Vector<D>,
) -> Option<f64> {
    let t0 = a.time.max(b.time);
    let raw = b.at(t0) - a.at(t0);
    let dv = b.vel - a.vel;
    let reach = (ra + rb) * (1.0 + 1e-3);
    // Per axis, the images that can come within `reach`, with the interval of times offsets
    // during which they are.
    let mut choices = [[(0.0f64, 0.0f64, 0.0f64); 3]; D];
    let mut counts = [0usize; D];
    for d in 0..D {
        let inv = 1.0 / dv[d];
        for k in [-1.0, 0.0, 1.0] {
            let x = raw[d] + k * size[d];
            let (lo, hi) = if dv[d] == 0.0 {
                if x.abs() > reach {
                    continue;
                }
                (0.0, f64::INFINITY)
            } else {
                let s1 = (-reach - x) * inv;
                let s2 = (reach - x) * inv;
                (s1.min(s2).max(0.0), s1.max(s2))
            };
            if lo <= hi {
                choices[d][counts[d]] = (k * size[d], lo, hi);
                counts[d] += 1;
            }
        }
        if counts[d] == 0 {
            return None;
        }
    }
    let mut best: Option<f64> = None;
    let mut idx = [0usize; D];
    loop {
        let mut shift = Vector::<D>::ZERO;
        let (mut lo, mut hi) = (0.0f64, f64::INFINITY);
        for d in 0..D {
            let (s, l, h) = choices[d][idx[d]];
            shift[d] = s;
            lo = lo.max(l);
            hi = hi.min(h);
        }
        if lo <= hi * (1.0 + 1e-9) {
            if let Some(t) = toi_circle_circle_shifted(a, ra, b, rb, shift) {
                if best.is_none_or(|bt| t.total_cmp(&bt).is_lt()) {
                    best = Some(t);
                }
            }
        }
        let mut d = 0;
        loop {
            idx[d] += 1;
            if idx[d] < counts[d] {
                break;
            }
            idx[d] = 0;
            d += 1;
            if d == D {
                return best;
            }
        }
    }
}

/// Time of impact of bodies `a` and `b` (lower index first) in a periodic box as every finder
/// evaluates it: [`toi_pair_periodic`] of their records, or none for two kinematic bodies,
/// which pass through each other.
#[must_use]
#[inline]
pub fn toi_bodies_periodic<const D: usize>(
    a: &crate::motion::Body<D>,
    b: &crate::motion::Body<D>,
    size: &Vector<D>,
    laws: Option<&Laws<D>>,
) -> Option<f64> {
    if laws.is_some_and(|l| l.kinematic) && a.is_kinematic() && b.is_kinematic() {
        return None;
    }
    toi_pair_periodic(&a.motion, a.radius, &b.motion, b.radius, size, laws)
}

/// [`toi_circle_circle_periodic`], or in a growing world its growing form (every image
/// tried). Periodic worlds have no gravity (scenes refuse it).
#[must_use]
#[inline]
pub fn toi_pair_periodic<const D: usize>(
    a: &Motion<D>,
    ra: f64,
    b: &Motion<D>,
    rb: f64,
    size: &Vector<D>,
    laws: Option<&Laws<D>>,
) -> Option<f64> {
    debug_assert!(laws.is_none_or(|l| l.gravity.is_none()));
    match laws.and_then(|l| l.growth.as_ref()) {
        None => toi_circle_circle_periodic(a, ra, b, rb, size),
        Some(law) => toi_circle_circle_periodic_growing(a, ra, b, rb, size, law),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `toi_box_exit` as first written, with a branch per axis: the model the branch-free
    /// version must match bit for bit.
    fn toi_box_exit_model<const D: usize>(m: &Motion<D>, size: &Vector<D>) -> Option<(f64, usize)> {
        let mut best: Option<(f64, usize)> = None;
        for d in 0..D {
            let v = m.vel[d];
            let (gap, speed, face) = if v > 0.0 {
                (size[d] - m.pos[d], v, exit_face(d, true))
            } else if v < 0.0 {
                (m.pos[d], -v, exit_face(d, false))
            } else {
                continue;
            };
            let t = if gap <= 0.0 {
                m.time
            } else {
                m.time + gap / speed
            };
            if best.is_none_or(|(bt, _)| t.total_cmp(&bt).is_lt()) {
                best = Some((t, face));
            }
        }
        best
    }

    /// A coordinate or velocity component: often zero (either sign), on a face, outside the
    /// box, tiny or huge.
    fn component() -> impl proptest::strategy::Strategy<Value = f64> {
        use proptest::prelude::*;
        prop_oneof![
            Just(0.0),
            Just(-0.0),
            Just(10.0),
            Just(1e-300),
            Just(-1e-300),
            Just(1e300),
            -12.0..12.0f64,
        ]
    }

    proptest::proptest! {
        #[test]
        fn box_exit_matches_the_branching_model(
            pos in proptest::collection::vec(component(), 3),
            vel in proptest::collection::vec(component(), 3),
            time in proptest::prop_oneof![proptest::strategy::Just(0.0), 0.0..100.0f64],
        ) {
            let m3 = Motion { pos: Vector([pos[0], pos[1], pos[2]]), vel: Vector([vel[0], vel[1], vel[2]]), time };
            let m2 = Motion { pos: Vector([pos[0], pos[1]]), vel: Vector([vel[0], vel[1]]), time };
            let bits = |r: Option<(f64, usize)>| r.map(|(t, f)| (t.to_bits(), f));
            proptest::prop_assert_eq!(bits(toi_box_exit(&m3, &Vector([10.0; 3]))), bits(toi_box_exit_model(&m3, &Vector([10.0; 3]))));
            proptest::prop_assert_eq!(bits(toi_box_exit(&m2, &Vector([10.0, 7.5]))), bits(toi_box_exit_model(&m2, &Vector([10.0, 7.5]))));
        }
    }

    proptest::proptest! {
        #[test]
        fn inline_round_is_round(x in proptest::num::f64::ANY) {
            let (ours, std) = (round_half_away(x), x.round());
            proptest::prop_assert!(ours.to_bits() == std.to_bits() || (ours.is_nan() && std.is_nan()));
        }

        #[test]
        fn inline_round_is_round_near_halves(k in -1_000_000i64..1_000_000, f in -1.0f64..1.0) {
            let x = k as f64 + f;
            proptest::prop_assert_eq!(round_half_away(x).to_bits(), x.round().to_bits());
        }
    }

    fn m2(p: [f64; 2], v: [f64; 2]) -> Motion<2> {
        Motion {
            pos: Vector(p),
            vel: Vector(v),
            time: 0.0,
        }
    }

    #[test]
    fn contact_across_the_box() {
        let size = Vector([10.0, 10.0]);
        // The direct gap is 6 and closing at 2 (contact at 2.5); the minimum image (−4) is
        // receding.
        let a = m2([0.5, 5.0], [1.0, 0.0]);
        let b = m2([6.5, 5.0], [-1.0, 0.0]);
        assert_eq!(
            toi_circle_circle_periodic(&a, 0.5, &b, 0.5, &size),
            Some(2.5)
        );
        // Across the face: b at 9.5 moving right meets a at 0.5 moving left through x = 0.
        let a = m2([0.5, 5.0], [-1.0, 0.0]);
        let b = m2([9.0, 5.0], [1.0, 0.0]);
        assert_eq!(
            toi_circle_circle_periodic(&a, 0.5, &b, 0.5, &size),
            Some(0.25)
        );
        // Missing on the other axis.
        let b = m2([9.0, 7.0], [1.0, 0.0]);
        assert_eq!(toi_circle_circle_periodic(&a, 0.5, &b, 0.5, &size), None);
    }

    #[test]
    fn every_image_agrees_with_brute_force() {
        // Brute force over all 27 images in 3D on a grid of cases.
        let size = Vector([5.0, 6.0, 7.0]);
        let mut cases = 0;
        for i in 0..400 {
            let f = |k: u64| ((i as u64 * 2_654_435_761 + k * 40_503) % 1000) as f64 / 1000.0;
            let a = Motion {
                pos: Vector([f(1) * 5.0, f(2) * 6.0, f(3) * 7.0]),
                vel: Vector([f(4) - 0.5, f(5) - 0.5, f(6) - 0.5]),
                time: f(7),
            };
            let b = Motion {
                pos: Vector([f(8) * 5.0, f(9) * 6.0, f(10) * 7.0]),
                vel: Vector([f(11) * 4.0 - 2.0, f(12) - 0.5, f(13) * 3.0 - 1.5]),
                time: f(14),
            };
            let mut brute: Option<f64> = None;
            for code in 0..27 {
                let mut shift = Vector::<3>::ZERO;
                let mut c = code;
                for d in 0..3 {
                    shift[d] = ((c % 3) as f64 - 1.0) * size[d];
                    c /= 3;
                }
                if let Some(t) = toi_circle_circle_shifted(&a, 0.9, &b, 1.1, shift) {
                    brute = Some(brute.map_or(t, |bt: f64| bt.min(t)));
                }
            }
            let fast = toi_circle_circle_periodic(&a, 0.9, &b, 1.1, &size);
            assert_eq!(fast.map(f64::to_bits), brute.map(f64::to_bits), "case {i}");
            cases += usize::from(fast.is_some());
        }
        assert!(cases > 100, "{cases}");
    }

    #[test]
    fn exits_and_wrapping() {
        let size = Vector([4.0, 2.0]);
        let m = m2([3.0, 1.5], [2.0, 1.0]);
        assert_eq!(toi_box_exit(&m, &size), Some((0.5, exit_face(0, true))));
        let m = m2([3.5, 0.5], [1.0, -1.0]);
        // Both faces at t = 0.5 (x = 4 and y = 0): the lower index wins.
        assert_eq!(toi_box_exit(&m, &size), Some((0.5, exit_face(0, true))));
        let m = m2([3.0, 0.25], [1.0, -1.0]);
        assert_eq!(toi_box_exit(&m, &size), Some((0.25, exit_face(1, false))));
        assert_eq!(toi_box_exit(&m2([1.0, 1.0], [0.0, 0.0]), &size), None);
        assert_eq!(wrap_point(Vector([-0.5, 4.5]), &size).0, [3.5, 0.5]);
        assert_eq!(min_image(Vector([3.5, -1.5]), &size).0, [-0.5, 0.5]);
        for x in [
            0.0,
            -0.0,
            0.3,
            -0.3,
            0.5,
            -0.5,
            0.49999999999999994,
            1.5,
            -2.5,
            2.5000001,
            -7.49999,
            1e15 + 0.5,
            -1e15 - 0.5,
            4.5e15,
            -9e300,
            f64::INFINITY,
        ] {
            assert_eq!(round_half_away(x).to_bits(), x.round().to_bits(), "{x}");
        }
        assert!(round_half_away(f64::NAN).is_nan());
    }
}
