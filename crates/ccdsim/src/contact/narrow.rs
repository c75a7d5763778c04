//! Narrow phase: time of impact of a pair, a pure function of the stored states.
//!
//! Every function returns the absolute time of the first future contact of an approaching
//! pair, never earlier than the later of the two reference times, or `None`. A pair that
//! rounding left overlapping while approaching collides at once; a receding pair never does.

use crate::geom::Vector;
use crate::motion::Motion;
use crate::wall::Wall;

/// Time `t ≥ 0` after which a point at offset `dp` moving at relative velocity `dv` first
/// comes within `sigma` of the origin, if it approaches (`dp·dv < 0`).
///
/// Uses the cancellation-free form of the earlier root, `c / (−b + √(b² − ac))`.
///
/// A relative speed so small that `a = |dv|²` falls below 2⁻⁶⁰⁰ (speeds under about 10⁻⁹⁰, as
/// an inelastic collapse reaches) would lose `a`, `b²` or `ac` to underflow, and with them
/// the geometry: a pair that misses could be given a contact far in the future, and a pair
/// that meets could be given none. Such a `dv` is multiplied by 2⁶⁰⁰ first, and by 2⁶⁰⁰
/// again when that is not enough (down to the smallest subnormal speed, 2⁻¹⁰⁷⁴), and the time
/// by the same powers after: multiplying by a power of two commutes with every rounding while
/// nothing underflows or overflows, so this is the formula's time on exact inputs. A contact
/// whose time exceeds the largest float is not representable and is given as `None` here;
/// [`contact_beyond_range`] tells that case apart from a miss, so that a run can say why it
/// stopped.
#[must_use]
#[inline(always)]
pub fn first_contact<const D: usize>(dp: Vector<D>, dv: Vector<D>, sigma: f64) -> Option<f64> {
    let b = dp.dot(dv);
    if b >= 0.0 {
        return None;
    }
    let c = dp.norm_sq() - sigma * sigma;
    if c <= 0.0 {
        return Some(0.0);
    }
    let a = dv.norm_sq();
    if a >= MIN_UNSCALED_A {
        let disc = b * b - a * c;
        if disc < 0.0 {
            return None;
        }
        return Some(c / (-b + disc.sqrt()));
    }
    // Inline rather than a call: a call in the finders' scan loops costs them their
    // registers (callgrind, 2D gas: +300 instructions per collision).
    scaled_contact(dp, dv, c).filter(|t| t.is_finite())
}

/// The rare path of [`first_contact`] for a tiny `dv` (`|dv|² < 2⁻⁶⁰⁰`) and `c > 0`: the
/// time offset of the contact, `+∞` when it exists but exceeds the largest float, or `None`
/// when the pair never touches (or `dv` is zero).
#[inline(always)]
fn scaled_contact<const D: usize>(dp: Vector<D>, dv: Vector<D>, c: f64) -> Option<f64> {
    // Once scaled, |dv| ≥ 2⁻³⁰⁰; twice (|dv| < 2⁻⁶⁰⁰ after once), it stays below 2⁰ and the
    // smallest subnormal (2⁻¹⁰⁷⁴) becomes 2¹²⁶: exact, and nothing overflows.
    let (dv, steps) = scaled_velocity(dv);
    let (b, a) = (dp.dot(dv), dv.norm_sq());
    if a == 0.0 || b >= 0.0 {
        return None;
    }
    let disc = b * b - a * c;
    if disc < 0.0 {
        return None;
    }
    Some(unscaled_time(c / (-b + disc.sqrt()), steps))
}

/// True when the point at offset `dp`, moving at `dv`, approaches and would come within
/// `sigma` of the origin, but only after more seconds than the largest float holds: a
/// contact that [`first_contact`] cannot give a time. Only relative speeds far below 10⁻²⁵⁰
/// get there.
#[must_use]
pub fn contact_beyond_range<const D: usize>(dp: Vector<D>, dv: Vector<D>, sigma: f64) -> bool {
    let c = dp.norm_sq() - sigma * sigma;
    if dp.dot(dv) >= 0.0 || c <= 0.0 || dv.norm_sq() >= MIN_UNSCALED_A {
        // Unscaled times are below c / |b| ≤ |dp|² / |dp|·2⁻³⁰⁰: finite for any finite dp
        // the scene validation allows.
        return false;
    }
    scaled_contact(dp, dv, c) == Some(f64::INFINITY)
}

/// Below this `|dv|²` [`first_contact`] scales the relative velocity first.
pub(crate) const MIN_UNSCALED_A: f64 = 2.409_919_865_102_884e-181; // 2⁻⁶⁰⁰

/// Below this normal speed [`toi_circle_plane`] scales the velocity first (2⁻³⁰⁰).
const MIN_UNSCALED_SPEED: f64 = 4.909_093_465_297_727e-91;

/// The power of two by which [`first_contact`] scales a tiny relative velocity.
const SPEED_SCALE: f64 = 4.149_515_568_880_993e180; // 2⁶⁰⁰

/// Time of impact of two balls (radii `ra`, `rb`), evaluated from `T = max(a.time, b.time)`.
#[must_use]
#[inline(always)]
pub fn toi_circle_circle<const D: usize>(
    a: &Motion<D>,
    ra: f64,
    b: &Motion<D>,
    rb: f64,
) -> Option<f64> {
    let t0 = a.time.max(b.time);
    let dp = b.at(t0) - a.at(t0);
    first_contact(dp, b.vel - a.vel, ra + rb).map(|dt| t0 + dt)
}

/// Time of impact of two balls when ball `b` is displaced by `shift` (one of its periodic
/// images): [`toi_circle_circle`] with the displacement `(b.at(T) − a.at(T)) + shift`.
///
/// Every finder evaluates an image of a pair through this one function, so their times agree
/// bit for bit.
#[must_use]
#[inline(always)]
pub fn toi_circle_circle_shifted<const D: usize>(
    a: &Motion<D>,
    ra: f64,
    b: &Motion<D>,
    rb: f64,
    shift: Vector<D>,
) -> Option<f64> {
    let t0 = a.time.max(b.time);
    let dp = (b.at(t0) - a.at(t0)) + shift;
    first_contact(dp, b.vel - a.vel, ra + rb).map(|dt| t0 + dt)
}

/// Time of impact of a ball (radius `r`) with the segment `[a, b]`: its interior from either
/// side, or one of its end points.
#[must_use]
pub fn toi_circle_segment<const D: usize>(
    m: &Motion<D>,
    r: f64,
    a: Vector<D>,
    b: Vector<D>,
) -> Option<f64> {
    toi_circle_segment_ends(m, r, a, b, [true; 2])
}

/// [`toi_circle_segment`] with the end points `a` and `b` counted only where `ends` says:
/// a body resting on a segment never meets an end point it shares with another one (see
/// [`crate::contact::ledge`]).
#[must_use]
#[inline(always)]
pub fn toi_circle_segment_ends<const D: usize>(
    m: &Motion<D>,
    r: f64,
    a: Vector<D>,
    b: Vector<D>,
    ends: [bool; 2],
) -> Option<f64> {
    let u = b - a;
    let l2 = u.norm_sq();
    let w = m.pos - a;
    // A tiny velocity is scaled by powers of two first (exactly), so that projecting it on
    // the segment does not underflow; times are scaled back at the end.
    let (vel, steps) = scaled_velocity(m.vel);
    let w_perp = w - u * (w.dot(u) / l2);
    let v_perp = vel - u * (vel.dot(u) / l2);
    let interior = first_contact(w_perp, v_perp, r).filter(|&dt| {
        let s = (w + vel * dt).dot(u) / l2;
        (0.0..=1.0).contains(&s)
    });
    let end_a = ends[0].then(|| first_contact(w, vel, r)).flatten();
    let end_b = ends[1].then(|| first_contact(m.pos - b, vel, r)).flatten();
    [interior, end_a, end_b]
        .into_iter()
        .flatten()
        .reduce(f64::min)
        .map(|dt| m.time + unscaled_time(dt, steps))
}

/// `(v · 2⁶⁰⁰ᵏ, k)` with `k ∈ {0, 1, 2}` the number of times `v` was multiplied by 2⁶⁰⁰ to lift
/// it out of the range where its products underflow; `k = 0` for every speed above 2⁻³⁰⁰.
#[inline]
fn scaled_velocity<const D: usize>(v: Vector<D>) -> (Vector<D>, u32) {
    let (mut v, mut steps) = (v, 0);
    while steps < 2 && v.norm_sq() < MIN_UNSCALED_A {
        v = v * SPEED_SCALE;
        steps += 1;
    }
    (v, steps)
}

/// A time computed with a velocity scaled `steps` times by 2⁶⁰⁰, in real seconds: multiplied
/// back one power at a time (2¹²⁰⁰ itself is no float); `+∞` when it exceeds the largest one.
#[inline]
fn unscaled_time(t: f64, steps: u32) -> f64 {
    (0..steps).fold(t, |t, _| t * SPEED_SCALE)
}

/// Time of impact of a ball (radius `r`) with the one-sided plane through `point` whose
/// `normal` points to the ball's side.
#[must_use]
#[inline]
pub fn toi_circle_plane<const D: usize>(
    m: &Motion<D>,
    r: f64,
    point: Vector<D>,
    normal: Vector<D>,
) -> Option<f64> {
    let len = normal.norm();
    let mut vn = m.vel.dot(normal) / len;
    let mut steps = 0;
    if vn.abs() < MIN_UNSCALED_SPEED {
        // A tiny normal speed loses bits, or all of them, to underflow in the dot product:
        // scale the velocity by powers of two (exactly) as `first_contact` does.
        let vel;
        (vel, steps) = scaled_velocity(m.vel);
        vn = vel.dot(normal) / len;
    }
    if vn >= 0.0 {
        return None;
    }
    let gap = (m.pos - point).dot(normal) / len - r;
    if gap <= 0.0 {
        return Some(m.time);
    }
    // An infinite time (beyond the largest float) stays infinite: no finder ever returns it
    // (`finite_event`), and the simulation says why the run stopped.
    Some(m.time + unscaled_time(gap / -vn, steps))
}

/// Time of impact of a ball (radius `r`) with a wall of either kind.
#[must_use]
#[inline]
pub fn toi_circle_wall<const D: usize>(m: &Motion<D>, r: f64, wall: &Wall<D>) -> Option<f64> {
    match *wall {
        Wall::Segment { a, b } => toi_circle_segment(m, r, a, b),
        Wall::Plane { point, normal } => toi_circle_plane(m, r, point, normal),
    }
}

/// Unit normal of the wall at its point nearest to `p`, pointing from the wall towards `p`;
/// `None` when `p` lies on a segment.
#[must_use]
pub fn wall_normal<const D: usize>(wall: &Wall<D>, p: Vector<D>) -> Option<Vector<D>> {
    match *wall {
        Wall::Segment { a, b } => {
            let u = b - a;
            let s = ((p - a).dot(u) / u.norm_sq()).clamp(0.0, 1.0);
            let d = p - (a + u * s);
            let len = d.norm();
            (len > 0.0).then(|| d * (1.0 / len))
        }
        Wall::Plane { normal, .. } => Some(normal * (1.0 / normal.norm())),
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

    #[test]
    fn head_on_contact_time() {
        let a = m2([0.0, 0.0], [1.0, 0.0], 0.0);
        let b = m2([10.0, 0.0], [-1.0, 0.0], 0.0);
        assert_eq!(toi_circle_circle(&a, 1.0, &b, 1.0), Some(4.0));
    }

    #[test]
    fn evaluates_from_later_reference_time() {
        let a = m2([0.0, 0.0], [1.0, 0.0], 0.0);
        let b = m2([8.0, 0.0], [-1.0, 0.0], 2.0); // at t=2, a is at 2: gap 6 - 2 = 4, closing at 2
        assert_eq!(toi_circle_circle(&a, 1.0, &b, 1.0), Some(4.0));
    }

    #[test]
    fn receding_and_missing_pairs() {
        let a = m2([0.0, 0.0], [-1.0, 0.0], 0.0);
        let b = m2([10.0, 0.0], [1.0, 0.0], 0.0);
        assert_eq!(toi_circle_circle(&a, 1.0, &b, 1.0), None);
        let c = m2([10.0, 5.0], [-1.0, 0.0], 0.0);
        assert_eq!(toi_circle_circle(&a, 1.0, &c, 1.0), None);
        // Overlapping but receding: never.
        let d = m2([1.5, 0.0], [1.0, 0.0], 0.0);
        assert_eq!(
            toi_circle_circle(&m2([0.0, 0.0], [0.0, 0.0], 0.0), 1.0, &d, 1.0),
            None
        );
        // Overlapping and approaching: at once.
        let e = m2([1.5, 0.0], [-1.0, 0.0], 3.0);
        assert_eq!(
            toi_circle_circle(&m2([0.0, 0.0], [0.0, 0.0], 0.0), 1.0, &e, 1.0),
            Some(3.0)
        );
    }

    #[test]
    fn segment_interior_and_end_points() {
        let (a, b) = (Vector([0.0, 0.0]), Vector([10.0, 0.0]));
        // Falling onto the interior from above.
        assert_eq!(
            toi_circle_segment(&m2([5.0, 3.0], [0.0, -1.0], 0.0), 1.0, a, b),
            Some(2.0)
        );
        // From below too (segments are two-sided).
        assert_eq!(
            toi_circle_segment(&m2([5.0, -3.0], [0.0, 1.0], 1.0), 1.0, a, b),
            Some(3.0)
        );
        // Heading at the end point along the segment's line.
        assert_eq!(
            toi_circle_segment(&m2([14.0, 0.0], [-1.0, 0.0], 0.0), 1.0, a, b),
            Some(3.0)
        );
        // Passing beyond the end: the corner is hit where distance to (10,0) is 1.
        let t = toi_circle_segment(&m2([10.5, 3.0], [0.0, -1.0], 0.0), 1.0, a, b).unwrap();
        assert!((t - (3.0 - (0.75f64).sqrt())).abs() < 1e-12);
        // Missing it entirely.
        assert_eq!(
            toi_circle_segment(&m2([12.0, 3.0], [0.0, -1.0], 0.0), 1.0, a, b),
            None
        );
    }

    #[test]
    fn plane_one_sided() {
        let m = Motion {
            pos: Vector([0.0, 0.0, 5.0]),
            vel: Vector([1.0, 0.0, -2.0]),
            time: 1.0,
        };
        let (p, n) = (Vector([0.0, 0.0, 0.0]), Vector([0.0, 0.0, 3.0]));
        assert_eq!(toi_circle_plane(&m, 1.0, p, n), Some(3.0));
        let away = Motion {
            vel: Vector([0.0, 0.0, 2.0]),
            ..m
        };
        assert_eq!(toi_circle_plane(&away, 1.0, p, n), None);
    }

    #[test]
    fn tiny_relative_speeds_keep_the_geometry() {
        // From an inelastic collapse (restitution 0.11, 170 bounces): `|dv|²` underflows to
        // zero, and the unscaled formula would give this missing pair a contact near 10¹⁶⁴.
        let dp = Vector([3.0, -1.837_571_798_121_552]);
        let dv = Vector([0.0, 1.396_037_021_646_344e-164]);
        assert_eq!(first_contact(dp, dv, 0.830_064_830_652_208_6), None);
        // Head-on at 10⁻²⁰⁰: contact after 2·10²⁰⁰, to the last bits of the exact value.
        let t = first_contact(Vector([0.0, 3.0]), Vector([0.0, -1e-200]), 1.0).unwrap();
        assert!((t / 2e200 - 1.0).abs() < 1e-15, "{t:e}");
        // Speeds whose squares underflow even after one scaling: scaled twice, the contact
        // is found (issue 20: at 10⁻²⁸⁰ pairs used to pass through each other).
        let t = first_contact(Vector([0.0, 3.0]), Vector([0.0, -1e-280]), 1.0).unwrap();
        assert!((t / 2e280 - 1.0).abs() < 1e-15, "{t:e}");
        let t = first_contact(Vector([0.0, 3.0]), Vector([0.0, -1e-305]), 1.0).unwrap();
        assert!((t / 2e305 - 1.0).abs() < 1e-15, "{t:e}");
        // The smallest subnormal speed, on a gap that keeps the time representable.
        let t = first_contact(Vector([0.0, 1.0 + 1e-300]), Vector([0.0, -5e-324]), 1.0);
        assert!(t.is_some_and(f64::is_finite), "{t:?}");
        // Beyond the largest float: no time, but known to be a contact, not a miss.
        let (dp, dv) = (Vector([0.0, 3.0]), Vector([0.0, -1e-320]));
        assert_eq!(first_contact(dp, dv, 1.0), None);
        assert!(contact_beyond_range(dp, dv, 1.0));
        assert!(!contact_beyond_range(Vector([2.0, 3.0]), dv, 1.0), "a miss");
        assert!(!contact_beyond_range(dp, -dv, 1.0), "receding");
        assert!(
            !contact_beyond_range(dp, Vector([0.0, -1.0]), 1.0),
            "finite"
        );
    }

    proptest::proptest! {
        /// Scaling the relative velocity by a power of two scales the time back exactly: the
        /// scaled path agrees bit for bit with the unscaled formula on scaled inputs.
        #[test]
        fn time_scales_exactly_with_a_tiny_relative_velocity(
            dp in proptest::array::uniform2(-100.0..100.0f64),
            dv in proptest::array::uniform2(-1e3..1e3f64),
            sigma in 0.01..10.0f64,
        ) {
            let tiny = 2f64.powi(-500);
            let plain = first_contact(Vector(dp), Vector(dv), sigma);
            let scaled = first_contact(Vector(dp), Vector(dv) * tiny, sigma);
            let expect = plain.and_then(|t| Some(t / tiny).filter(|t| t.is_finite()));
            proptest::prop_assert_eq!(scaled.map(f64::to_bits), expect.map(f64::to_bits));
        }
    }
}
