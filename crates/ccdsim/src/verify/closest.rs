//! Closest approach of two bodies, and of a body and a wall, over a stretch of time: the
//! verifier's own geometry, independent of the simulator's narrow phase.

use crate::geom::Vector;
use crate::motion::Motion;
use crate::wall::{wall_clearance, Wall};

/// `x · 2^e` for any `e` (in steps that neither overflow nor underflow on the way).
fn times_pow2(mut x: f64, mut e: i32) -> f64 {
    while e > 1000 {
        x *= 2f64.powi(1000);
        e -= 1000;
    }
    while e < -1000 {
        x *= 2f64.powi(-1000);
        e += 1000;
    }
    x * 2f64.powi(e)
}

/// Smallest distance between two points moving linearly over `[0, span]` from `pa`, `pb`,
/// and the time offset where it occurs.
pub(super) fn closest_approach<const D: usize>(
    pa: Vector<D>,
    va: Vector<D>,
    pb: Vector<D>,
    vb: Vector<D>,
    span: f64,
) -> (f64, f64) {
    let dp = pb - pa;
    let dv = vb - va;
    // `dv` scaled by a power of two to a largest component in [1, 2): `|dv|²` can then
    // neither underflow (relative speeds of 10⁻²⁸⁰ are real: an inelastic collapse) nor
    // overflow, and the time is scaled back exactly.
    let largest = dv.0.iter().fold(0.0f64, |m, c| m.max(c.abs()));
    let s = if largest > 0.0 {
        let e = largest.log2().floor() as i32;
        let unit = dv.0.map(|c| times_pow2(c, -e));
        let unit = Vector(unit);
        let t = times_pow2(-dp.dot(unit) / unit.norm_sq(), -e);
        if t.is_nan() {
            0.0
        } else {
            t.clamp(0.0, span.max(0.0))
        }
    } else {
        0.0
    };
    ((dp + dv * s).norm(), s)
}

/// Growing radii: the smallest value over `[0, span]` of `|dp + dv·s| − grow·s`, the distance
/// of two points less what their contact distance has grown by, and the offset `s` where it
/// occurs. The function is convex (a norm of a linear function less a linear one): its least
/// value is at an end or where its derivative vanishes, in closed form.
pub(super) fn closest_approach_growing<const D: usize>(
    dp: Vector<D>,
    dv: Vector<D>,
    span: f64,
    grow: f64,
) -> (f64, f64) {
    let span = span.max(0.0);
    let f = |s: f64| (dp + dv * s).norm() - grow * s;
    [0.0, span, least_growing(dp, dv, grow, span)]
        .into_iter()
        .map(|s| (f(s), s))
        .fold((f64::INFINITY, 0.0), smaller)
}

/// Where `|w0 + w1·s| − k·s` (`k ≥ 0`: a distance less a growth), convex in `s`, is least on
/// `[0, span]`, in closed form: where its derivative `(A s + B)/|w0 + w1 s| − k` vanishes
/// (`A = |w1|²`, `B = w0·w1`), or an end. For `k = 0` it is the closest approach, found with
/// `w1` scaled so that tiny speeds lose nothing.
fn least_growing<const D: usize>(w0: Vector<D>, w1: Vector<D>, k: f64, span: f64) -> f64 {
    if k == 0.0 {
        return closest_approach(Vector::ZERO, Vector::ZERO, w0, w1, span).1;
    }
    let (a, b, c) = (w1.norm_sq(), w0.dot(w1), w0.norm_sq());
    let q = a - k * k;
    if q.is_nan() || q <= 0.0 {
        // Growing at least as fast as it can move away: never increasing.
        return span;
    }
    // `(A s + B)² = k² |w0 + w1 s|²` with `A s + B ≥ 0`: `A s² + 2 B s = (k² C − B²)/q`.
    let disc = b * b + a * (k * k * c - b * b) / q;
    let s = (-b + disc.max(0.0).sqrt()) / a;
    if s.is_nan() {
        0.0
    } else {
        s.clamp(0.0, span)
    }
}

/// The smaller of two (value, time) candidates; a NaN value wins (it must fail a check, not
/// hide behind a finite one).
fn smaller(best: (f64, f64), c: (f64, f64)) -> (f64, f64) {
    if c.0 < best.0 || c.0.is_nan() && !best.0.is_nan() {
        c
    } else {
        best
    }
}

/// Smallest clearance between a body moving linearly from its reference time to `t` and a
/// wall, less `grow` times the time since the reference time (a growing radius; 0 for fixed
/// ones), and the time where it occurs: at an end for a plane (linear in time), at one of
/// [`segment_candidates`] for a segment.
pub(super) fn closest_to_wall<const D: usize>(
    wall: &Wall<D>,
    m: &Motion<D>,
    t: f64,
    grow: f64,
) -> (f64, f64) {
    let f = |s: f64| wall_clearance(wall, m.at(s)) - grow * (s - m.time);
    let (lo, hi) = (m.time, t.max(m.time));
    match *wall {
        Wall::Plane { .. } => {
            let (a, b) = (f(lo), f(hi));
            if a <= b {
                (a, lo)
            } else {
                (b, hi)
            }
        }
        Wall::Segment { a, b } => segment_candidates(a, b, m, lo, hi, grow)
            .into_iter()
            .map(|s| (f(s), s))
            .fold((f64::INFINITY, lo), smaller),
    }
}

/// The times in `[lo, hi]` among which the clearance of a point moving as `m` from the
/// segment `a b`, less `grow` times the time since `lo`, is smallest. The clearance is, piece
/// by piece, the distance to `a`, to the segment's line, or to `b` (as the centre's foot lies
/// before, on or beyond the segment), each less the growth convex: its smallest value is at a
/// piece's end (the foot passing `a` or `b`, or `lo`, `hi`) or where that function is least
/// ([`least_growing`]), all in closed form. Unlike a search whose bracket shrinks relative to
/// `hi − lo`, this is as exact over 10³⁰⁸ s as over 1 s.
fn segment_candidates<const D: usize>(
    a: Vector<D>,
    b: Vector<D>,
    m: &Motion<D>,
    lo: f64,
    hi: f64,
    grow: f64,
) -> Vec<f64> {
    let span = hi - lo;
    let (p0, v, u) = (m.at(lo), m.vel, b - a);
    let uu = u.norm_sq();
    let mut out = vec![lo, hi];
    // The foot's parameter along the segment, `l0 + l1·(s − lo)`, passes 0 and 1.
    let (l0, l1) = ((p0 - a).dot(u) / uu, v.dot(u) / uu);
    if l1 != 0.0 {
        for end in [0.0, 1.0] {
            let s = lo + (end - l0) / l1;
            if !s.is_nan() {
                out.push(s.clamp(lo, hi));
            }
        }
    }
    for end in [a, b] {
        out.push(lo + least_growing(p0 - end, v, grow, span));
    }
    // The distance to the line: the part of the offset across the segment.
    let across = |w: Vector<D>| w - u * (w.dot(u) / uu);
    out.push(lo + least_growing(across(p0 - a), across(v), grow, span));
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn closest_approach_at_tiny_relative_speeds() {
        // Two balls 2 m apart closing at 2·10⁻²⁸⁰ m/s pass through each other after 10²⁸⁰ s.
        let (pa, pb) = (Vector([0.0, 0.0]), Vector([2.0, 0.0]));
        let (va, vb) = (Vector([1e-280, 0.0]), Vector([-1e-280, 0.0]));
        let (d, at) = closest_approach(pa, va, pb, vb, 3e280);
        assert!(d < 1e-12, "{d}");
        assert!((at / 1e280 - 1.0).abs() < 1e-12, "{at:e}");
        // Subnormal speeds too.
        let (d, _) = closest_approach(pa, Vector([5e-320, 0.0]), pb, Vector([0.0; 2]), 1e308);
        assert!(d < 2.0, "{d}");
        // And huge ones.
        let (d, at) = closest_approach(pa, Vector([1e300, 1e-300]), pb, Vector([0.0; 2]), 1.0);
        assert!(d < 1e-12 && at > 0.0, "{d} {at}");
    }
}
