//! Closest approach of a body falling under uniform gravity (a parabola) to a wall over a
//! stretch of time: the verifier's own geometry for gravity runs, sharing nothing with the
//! simulator's narrow phase.
//!
//! **Planes.** The signed clearance from a plane is a quadratic in time, so its minimum over a
//! window lies at an end or at the vertex: three evaluations, exact.
//!
//! **Segments.** The clearance of a centre from a segment is the distance from the segment's
//! line while the centre's foot lies on the segment, and the distance to the nearer end point
//! otherwise (the distance to the segment is never more than either). Under gravity each of
//! these is the norm of a quadratic in time, `|q0 + q1·s + q2·s²|`, whose square has its
//! stationary points at the roots of a cubic. So the clearance over a window is smallest at one
//! of finitely many times: the window's ends, the times the foot crosses an end of the segment
//! (roots of two quadratics), and the stationary points of the squared distance from the line
//! and from each end point. The exact clearance is evaluated at every one of them; a candidate
//! that is not a minimum costs an evaluation and nothing else. Unlike a golden-section search
//! (which is only right for the convex clearance of straight motion), this cannot be fooled by
//! a parabola that dips towards the segment twice.
//!
//! **Growing radii.** With a radius growing at `ṙ` the quantity to minimise is the clearance
//! less `ṙ·s`. Against a plane that is still a quadratic (its vertex moves). Against a line or
//! a point it is `√P(s) − ṙ·s` with `P = |q0 + q1·s + q2·s²|²` a quartic; it is stationary
//! where `P'(s) = 2ṙ·√P(s)`, so at roots of the sextic `P'² − 4ṙ²·P`, which are found like the
//! cubic's (the interval cut at the roots of the derivatives, every monotone piece bisected)
//! and evaluated with the rest, together with the times the centre crosses a segment's line
//! (where the distance has a kink, a double root of the sextic). With `ṙ = 0` the candidates
//! are exactly those above.

use crate::geom::Vector;
use crate::motion::Motion;
use crate::wall::{wall_clearance, Wall};

/// Smallest clearance (see [`wall_clearance`]) between a body falling under `g` from its
/// reference time to `t` and a wall, less `grow` (m/s) times the time since the reference
/// time (a growing radius; 0 for fixed ones), and the time where it occurs.
pub(super) fn closest_to_wall_falling<const D: usize>(
    wall: &Wall<D>,
    m: &Motion<D>,
    t: f64,
    g: &Vector<D>,
    grow: f64,
) -> (f64, f64) {
    let span = (t - m.time).max(0.0);
    let mut candidates = vec![0.0, span];
    match *wall {
        Wall::Plane { normal, .. } => {
            let (vn, gn) = (m.vel.dot(normal), g.dot(normal));
            if gn != 0.0 {
                // The vertex of clearance − grow·s (the clearance is along the unit normal).
                candidates.push(if grow == 0.0 {
                    -vn / gn
                } else {
                    (grow * normal.norm() - vn) / gn
                });
            }
        }
        Wall::Segment { a, b } => {
            let u = b - a;
            let l2 = u.norm_sq();
            let w = m.pos - a;
            let half_g = *g * 0.5;
            // The foot's parameter along the segment, `w·u/l2` moved on: it crosses 0 and 1.
            let (f0, f1, f2) = (w.dot(u) / l2, m.vel.dot(u) / l2, half_g.dot(u) / l2);
            for k in [0.0, 1.0] {
                candidates.extend(quadratic_roots(f2, f1, f0 - k).into_iter().flatten());
            }
            // Distance from the line: the components across `u`.
            let across = |x: Vector<D>| x - u * (x.dot(u) / l2);
            let line = [across(w), across(m.vel), across(half_g)];
            candidates.extend(stationary_points(line, span, grow));
            if grow > 0.0 && D == 2 {
                // Where the centre crosses the line the distance has a kink, a double root of
                // the sextic that shows no sign change: the crossings are candidates of
                // their own (the signed distance along the normal is a quadratic).
                let mut n = Vector::<D>::ZERO;
                n[0] = -u[1];
                n[1] = u[0];
                let h = line.map(|q| q.dot(n));
                candidates.extend(quadratic_roots(h[2], h[1], h[0]).into_iter().flatten());
            }
            for end in [a, b] {
                candidates.extend(stationary_points([m.pos - end, m.vel, half_g], span, grow));
            }
        }
    }
    candidates
        .into_iter()
        .filter(|s| s.is_finite())
        .map(|s| s.clamp(0.0, span))
        .map(|s| {
            let at = m.time + s;
            (wall_clearance(wall, m.falling_at(at, g)) - grow * s, at)
        })
        .fold(
            (f64::INFINITY, m.time),
            |best, c| {
                if c.0 < best.0 {
                    c
                } else {
                    best
                }
            },
        )
}

/// Smallest distance over `[0, span]` from the origin of a point at `dp + dv·s + ½·acc·s²`
/// (a falling body seen from a kinematic one), less `grow` (m/s) times `s` (growing radii; 0
/// for fixed ones), and the offset `s` where it occurs: the squared distance is a quartic,
/// smallest at an end of the window or at a root of its derivative, a cubic (with growth, at
/// a root of the sextic of the module docs), all of which are evaluated.
pub(super) fn closest_to_point_falling<const D: usize>(
    dp: Vector<D>,
    dv: Vector<D>,
    acc: Vector<D>,
    span: f64,
    grow: f64,
) -> (f64, f64) {
    let half = acc * 0.5;
    let mut candidates = vec![0.0, span];
    candidates.extend(stationary_points([dp, dv, half], span, grow));
    candidates
        .into_iter()
        .filter(|s| s.is_finite())
        .map(|s| s.clamp(0.0, span))
        .map(|s| ((dp + dv * s + half * (s * s)).norm() - grow * s, s))
        .fold(
            (f64::INFINITY, 0.0),
            |best, c| if c.0 < best.0 { c } else { best },
        )
}

/// The real roots of `a·x² + b·x + c` (a linear or constant one when `a` or `b` is zero), in
/// the cancellation-free forms.
fn quadratic_roots(a: f64, b: f64, c: f64) -> [Option<f64>; 2] {
    if a == 0.0 {
        return [(b != 0.0).then(|| -c / b), None];
    }
    let disc = b * b - 4.0 * a * c;
    if disc < 0.0 {
        return [None, None];
    }
    let q = -0.5 * (b + disc.sqrt().copysign(b));
    if q == 0.0 {
        // b = 0 and c = 0: a double root at 0.
        return [Some(0.0), None];
    }
    [Some(q / a), Some(c / q)]
}

/// The times in `[0, span]` where `|q0 + q1·s + q2·s²| − grow·s` is stationary: for
/// `grow = 0` the roots of the cubic `(q0 + q1·s + q2·s²)·(q1 + 2·q2·s)`, otherwise the roots
/// of the sextic `P'² − 4·grow²·P` with `P = |q0 + q1·s + q2·s²|²` (see the module docs; it
/// also holds the points where the distance shrinks at `grow`, which cost an evaluation).
fn stationary_points<const D: usize>(q: [Vector<D>; 3], span: f64, grow: f64) -> Vec<f64> {
    let [q0, q1, q2] = q;
    let cubic = [
        q0.dot(q1),
        q1.norm_sq() + 2.0 * q0.dot(q2),
        3.0 * q1.dot(q2),
        2.0 * q2.norm_sq(),
    ];
    if grow == 0.0 {
        return cubic_roots_in(cubic, 0.0, span);
    }
    // P = p0 + p1·s + … + p4·s⁴; P' = 2·cubic.
    let p = [
        q0.norm_sq(),
        2.0 * q0.dot(q1),
        q1.norm_sq() + 2.0 * q0.dot(q2),
        2.0 * q1.dot(q2),
        q2.norm_sq(),
    ];
    let d = cubic.map(|c| 2.0 * c);
    let mut sextic = [0.0; 7];
    for (i, a) in d.iter().enumerate() {
        for (j, b) in d.iter().enumerate() {
            sextic[i + j] += a * b;
        }
    }
    for (i, c) in p.iter().enumerate() {
        sextic[i] -= 4.0 * grow * grow * c;
    }
    poly_roots_in(&sextic, 0.0, span)
}

/// `Σ c[i]·x^i`, by Horner.
fn poly_of(c: &[f64], x: f64) -> f64 {
    c.iter().rev().fold(0.0, |acc, &ci| acc * x + ci)
}

/// Real roots of the polynomial `c` (lowest degree first, any degree) in `[lo, hi]`, as
/// [`cubic_roots_in`] finds them: the interval cut at the roots of the derivative (found the
/// same way) into monotone pieces, each whose ends differ in sign bisected to the last bit.
fn poly_roots_in(c: &[f64], lo: f64, hi: f64) -> Vec<f64> {
    let degree = c.iter().rposition(|&x| x != 0.0).unwrap_or(0);
    if degree == 0 {
        return Vec::new();
    }
    let c = &c[..=degree];
    let derivative: Vec<f64> = c
        .iter()
        .enumerate()
        .skip(1)
        .map(|(i, ci)| i as f64 * ci)
        .collect();
    let mut cuts = vec![lo];
    let mut turns: Vec<f64> = poly_roots_in(&derivative, lo, hi)
        .into_iter()
        .filter(|x| *x > lo && *x < hi)
        .collect();
    turns.sort_by(f64::total_cmp);
    cuts.extend(turns);
    cuts.push(hi);
    bisect_pieces(|x| poly_of(c, x), &cuts)
}

/// The sign changes of `f` on the pieces between consecutive `cuts`, on each of which `f` is
/// monotone: a piece whose ends differ in sign is bisected to the last bit.
fn bisect_pieces(f: impl Fn(f64) -> f64, cuts: &[f64]) -> Vec<f64> {
    let mut roots = Vec::new();
    for piece in cuts.windows(2) {
        let (mut a, mut b) = (piece[0], piece[1]);
        let (mut fa, fb) = (f(a), f(b));
        if fa == 0.0 {
            roots.push(a);
            continue;
        }
        if fb == 0.0 {
            roots.push(b);
            continue;
        }
        if (fa < 0.0) == (fb < 0.0) {
            continue;
        }
        for _ in 0..2200 {
            let mid = 0.5 * (a + b);
            if mid <= a || mid >= b {
                break;
            }
            let fm = f(mid);
            if (fm < 0.0) == (fa < 0.0) {
                a = mid;
                fa = fm;
            } else {
                b = mid;
            }
        }
        roots.push(a);
    }
    roots
}

/// `c[0] + c[1]·x + c[2]·x² + c[3]·x³`.
fn poly(c: [f64; 4], x: f64) -> f64 {
    ((c[3] * x + c[2]) * x + c[1]) * x + c[0]
}

/// Real roots of the polynomial `c` (degree 3 at most) in `[lo, hi]`: the interval is cut at
/// the roots of the derivative into pieces on which the polynomial is monotone, and each
/// piece whose ends differ in sign is bisected to the last bit.
fn cubic_roots_in(c: [f64; 4], lo: f64, hi: f64) -> Vec<f64> {
    let mut cuts = vec![lo];
    let mut turns: Vec<f64> = quadratic_roots(3.0 * c[3], 2.0 * c[2], c[1])
        .into_iter()
        .flatten()
        .filter(|x| *x > lo && *x < hi)
        .collect();
    turns.sort_by(f64::total_cmp);
    cuts.extend(turns);
    cuts.push(hi);
    bisect_pieces(|x| poly(c, x), &cuts)
}

#[cfg(test)]
mod tests {
    use super::*;

    const G: Vector<2> = Vector([0.0, -10.0]);

    fn m2(p: [f64; 2], v: [f64; 2], t: f64) -> Motion<2> {
        Motion {
            pos: Vector(p),
            vel: Vector(v),
            time: t,
        }
    }

    /// The clearance sampled densely: an upper bound on the minimum, close to it.
    fn sampled<const D: usize>(wall: &Wall<D>, m: &Motion<D>, t: f64, g: &Vector<D>) -> f64 {
        (0..=200_000)
            .map(|k| m.time + (t - m.time) * f64::from(k) / 200_000.0)
            .map(|s| wall_clearance(wall, m.falling_at(s, g)))
            .fold(f64::INFINITY, f64::min)
    }

    #[test]
    fn a_thrown_ball_peaks_under_a_ceiling() {
        // From y = 0 at 10 m/s up: peaks at y = 5 at t = 1; a ceiling at y = 6 facing down.
        let ceiling = Wall::Plane {
            point: Vector([0.0, 6.0]),
            normal: Vector([0.0, -1.0]),
        };
        let m = m2([0.0, 0.0], [3.0, 10.0], 0.0);
        let (d, at) = closest_to_wall_falling(&ceiling, &m, 2.0, &G, 0.0);
        assert!(
            (d - 1.0).abs() < 1e-14 && (at - 1.0).abs() < 1e-14,
            "{d} at {at}"
        );
        // Cut before the peak: the end of the window.
        let (d, at) = closest_to_wall_falling(&ceiling, &m, 0.5, &G, 0.0);
        assert!((d - (6.0 - 3.75)).abs() < 1e-14 && at == 0.5, "{d} at {at}");
    }

    #[test]
    fn a_parabola_dipping_through_a_segment_is_seen() {
        // A segment from (0, 0) to (4, 0); the ball starts above its left end, arcs up and
        // comes down through the segment's middle: a golden-section search started on the
        // rising arc would settle at the start.
        let seg = Wall::Segment {
            a: Vector([0.0, 0.0]),
            b: Vector([4.0, 0.0]),
        };
        let m = m2([0.0, 1.0], [1.0, 8.0], 0.0);
        let (d, at) = closest_to_wall_falling(&seg, &m, 2.0, &G, 0.0);
        assert!(d < 1e-12, "{d} at {at}");
        let p = m.falling_at(at, &G);
        assert!(p[0] > 1.0 && p[0] < 2.0, "{p:?}");
    }

    #[test]
    fn end_points_and_arcs_match_dense_sampling() {
        let seg = Wall::Segment {
            a: Vector([0.0, 0.0]),
            b: Vector([4.0, 1.0]),
        };
        let mut state = 7u64;
        let mut next = || {
            state = state
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        for _ in 0..200 {
            let m = m2(
                [12.0 * next() - 4.0, 6.0 * next() - 1.0],
                [10.0 * next() - 5.0, 10.0 * next() - 5.0],
                0.0,
            );
            let g = Vector([2.0 * next() - 1.0, -10.0 * next()]);
            let t = 2.0 * next();
            let (d, at) = closest_to_wall_falling(&seg, &m, t, &g, 0.0);
            let dense = sampled(&seg, &m, t, &g);
            assert!(
                (wall_clearance(&seg, m.falling_at(at, &g)) - d).abs() < 1e-12,
                "the minimum is where it says"
            );
            // Never above the sampled minimum (up to rounding), and not far below it: the
            // sampling misses at most the distance travelled in one step.
            assert!(
                d <= dense + 1e-12,
                "{d} > sampled {dense} ({m:?}, {g:?}, {t})"
            );
            assert!(d >= dense - 1e-3, "{d} ≪ sampled {dense}");
        }
    }

    #[test]
    fn rods_in_3d_match_dense_sampling() {
        // A segment in 3D (a rod) takes the same candidates: its line's distance is the norm
        // of the components across it, still a quadratic in time, and its end points' too.
        let rod = Wall::Segment {
            a: Vector([0.0, 0.0, 0.0]),
            b: Vector([4.0, 1.0, -1.0]),
        };
        let mut state = 11u64;
        let mut next = || {
            state = state
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        for _ in 0..200 {
            let m = Motion {
                pos: Vector([12.0 * next() - 4.0, 6.0 * next() - 3.0, 6.0 * next() - 1.0]),
                vel: Vector([
                    10.0 * next() - 5.0,
                    10.0 * next() - 5.0,
                    10.0 * next() - 5.0,
                ]),
                time: 0.0,
            };
            let g = Vector([2.0 * next() - 1.0, 2.0 * next() - 1.0, -10.0 * next()]);
            let t = 2.0 * next();
            let (d, at) = closest_to_wall_falling(&rod, &m, t, &g, 0.0);
            let dense = sampled(&rod, &m, t, &g);
            assert!((wall_clearance(&rod, m.falling_at(at, &g)) - d).abs() < 1e-12);
            assert!(
                d <= dense + 1e-12,
                "{d} > sampled {dense} ({m:?}, {g:?}, {t})"
            );
            assert!(d >= dense - 1e-3, "{d} ≪ sampled {dense}");
        }
    }

    #[test]
    fn plane_in_3d_and_degenerate_windows() {
        let floor = Wall::Plane {
            point: Vector([0.0, 0.0, 1.0]),
            normal: Vector([0.0, 0.0, 2.0]),
        };
        let g = Vector([0.0, 0.0, -2.0]);
        let m = Motion {
            pos: Vector([0.0, 0.0, 3.0]),
            vel: Vector([1.0, 0.0, 2.0]),
            time: 5.0,
        };
        // Rises 1 in 1 s, then falls through the floor 1 below by t = 5 + 1 + √3.
        let (d, at) = closest_to_wall_falling(&floor, &m, 8.0, &g, 0.0);
        assert!((d - (3.0 + 2.0 * 3.0 - 9.0 - 1.0)).abs() < 1e-12, "{d}");
        assert_eq!(at, 8.0);
        // A window ending before the reference time is the reference time alone.
        assert_eq!(
            closest_to_wall_falling(&floor, &m, 4.0, &g, 0.0),
            (2.0, 5.0)
        );
    }

    #[test]
    fn cubic_roots_are_found_on_every_monotone_piece() {
        // (x − 1)(x − 2)(x − 3) = −6 + 11x − 6x² + x³.
        let r = cubic_roots_in([-6.0, 11.0, -6.0, 1.0], 0.0, 10.0);
        assert_eq!(r.len(), 3, "{r:?}");
        for (x, want) in r.iter().zip([1.0, 2.0, 3.0]) {
            assert!((x - want).abs() < 1e-14, "{r:?}");
        }
        // Lower degrees.
        let r = cubic_roots_in([-1.0, 1.0, 0.0, 0.0], 0.0, 5.0);
        assert!(r.len() == 1 && (r[0] - 1.0).abs() < 1e-15, "{r:?}");
        assert!(cubic_roots_in([1.0, 0.0, 0.0, 0.0], 0.0, 5.0).is_empty());
    }

    #[test]
    fn growing_radii_lower_the_clearance_by_the_growth() {
        // A ball dropped from rest 5 above a floor, its radius growing at 1 m/s: the
        // clearance less the growth, 5 − 5·s² − s, falls all the way: smallest at the end.
        let floor = Wall::Plane {
            point: Vector([0.0, 0.0]),
            normal: Vector([0.0, 2.0]),
        };
        let m = m2([0.0, 5.0], [0.0, 0.0], 0.0);
        let (d, at) = closest_to_wall_falling(&floor, &m, 0.5, &G, 1.0);
        assert!(
            (d - (5.0 - 1.25 - 0.5)).abs() < 1e-14 && at == 0.5,
            "{d} at {at}"
        );
        // Thrown up at 10 m/s under a ceiling 6 up, the radius growing at 2 m/s:
        // 6 − (10·s − 5·s²) − 2·s = 6 − 12·s + 5·s² is smallest at s = 1.2 (after the peak,
        // s = 1), where it is −1.2.
        let ceiling = Wall::Plane {
            point: Vector([0.0, 6.0]),
            normal: Vector([0.0, -1.0]),
        };
        let m = m2([0.0, 0.0], [0.0, 10.0], 0.0);
        let (d, at) = closest_to_wall_falling(&ceiling, &m, 2.0, &G, 2.0);
        assert!(
            (at - 1.2).abs() < 1e-14 && (d + 1.2).abs() < 1e-13,
            "{d} at {at}"
        );
    }

    proptest::proptest! {
        /// With growth the minimum of clearance − ṙ·s over a segment's line and end points is
        /// found among the sextic's roots: never above a dense sampling of it, not far below.
        #[test]
        fn growing_segment_minimum_matches_dense_sampling(
            p in proptest::array::uniform2(-3.0..3.0f64),
            v in proptest::array::uniform2(-4.0..4.0f64),
            g in proptest::array::uniform2(-10.0..10.0f64),
            grow in 0.0..3.0f64,
            t in 0.1..2.0f64,
        ) {
            let seg = Wall::Segment {
                a: Vector([-1.0, 0.0]),
                b: Vector([1.0, 0.5]),
            };
            let (m, g) = (m2(p, v, 0.0), Vector(g));
            let (d, at) = closest_to_wall_falling(&seg, &m, t, &g, grow);
            let f = |s: f64| wall_clearance(&seg, m.falling_at(s, &g)) - grow * s;
            proptest::prop_assert!((f(at) - d).abs() < 1e-12);
            let dense = (0..=4000)
                .map(|k| f(t * f64::from(k) / 4000.0))
                .fold(f64::INFINITY, f64::min);
            proptest::prop_assert!(d <= dense + 1e-9, "{} > sampled {}", d, dense);
            proptest::prop_assert!(d >= dense - 1e-2, "{} << sampled {}", d, dense);
        }

        /// The same for a point seen from a kinematic body.
        #[test]
        fn growing_point_minimum_matches_dense_sampling(
            dp in proptest::array::uniform2(-3.0..3.0f64),
            dv in proptest::array::uniform2(-4.0..4.0f64),
            acc in proptest::array::uniform2(-10.0..10.0f64),
            grow in 0.0..3.0f64,
            span in 0.1..2.0f64,
        ) {
            let (dp, dv, acc) = (Vector(dp), Vector(dv), Vector(acc));
            let (d, s) = closest_to_point_falling(dp, dv, acc, span, grow);
            let f = |s: f64| (dp + dv * s + acc * (0.5 * s * s)).norm() - grow * s;
            proptest::prop_assert!((f(s) - d).abs() < 1e-12);
            let dense = (0..=4000)
                .map(|k| f(span * f64::from(k) / 4000.0))
                .fold(f64::INFINITY, f64::min);
            proptest::prop_assert!(d <= dense + 1e-9, "{} > sampled {}", d, dense);
            proptest::prop_assert!(d >= dense - 1e-2, "{} << sampled {}", d, dense);
        }
    }
}
