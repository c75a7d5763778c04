//! Narrow phase: time of impact of a pair, a pure function of the stored states.
//!
//! Every function returns the absolute time of the first future contact of an approaching
//! pair, never earlier than the later of the two reference times, or `None`. A pair that
//! rounding left overlapping while approaching collides at once; a receding pair never does.

use crate::geom::Vector;
use crate::wall::Wall;

/// A body's stored linear motion: at time `time` it is at `pos`, moving with `vel`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Motion<const D: usize> {
    /// Reference position, metres.
    pub pos: Vector<D>,
    /// Velocity, metres per second.
    pub vel: Vector<D>,
    /// Time at which `pos` holds, seconds.
    pub time: f64,
}

impl<const D: usize> Motion<D> {
    /// Position at time `t`.
    #[must_use]
    #[inline]
    pub fn at(&self, t: f64) -> Vector<D> {
        self.pos + self.vel * (t - self.time)
    }
}

/// Time `t ≥ 0` after which a point at offset `dp` moving at relative velocity `dv` first
/// comes within `sigma` of the origin, if it approaches (`dp·dv < 0`).
///
/// Uses the cancellation-free form of the earlier root, `c / (−b + √(b² − ac))`.
///
/// A relative speed so small that `a = |dv|²` falls below 2⁻⁶⁰⁰ (speeds under about 10⁻⁹⁰, as
/// an inelastic collapse reaches) would lose `a`, `b²` or `ac` to underflow, and with them
/// the geometry: a pair that misses could be given a contact far in the future. Such a `dv`
/// is multiplied by 2⁶⁰⁰ first and the time by 2⁶⁰⁰ after: multiplying by a power of two
/// commutes with every rounding while nothing underflows or overflows, so this is the
/// formula's time on exact inputs. Below 2⁻⁹⁰⁰ even that underflows and the pair is given no
/// contact (a lost contact is consistent for every finder; an invented one is not), as is a
/// time beyond the largest float. (A `b` that underflowed to zero likewise loses a contact.)
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
    let dv = dv * SPEED_SCALE;
    let (b, a) = (dp.dot(dv), dv.norm_sq());
    if a < MIN_UNSCALED_A || b >= 0.0 {
        return None;
    }
    let disc = b * b - a * c;
    if disc < 0.0 {
        return None;
    }
    Some(c / (-b + disc.sqrt()) * SPEED_SCALE).filter(|t| t.is_finite())
}

/// Below this `|dv|²` [`first_contact`] scales the relative velocity first.
pub(crate) const MIN_UNSCALED_A: f64 = 2.409_919_865_102_884e-181; // 2⁻⁶⁰⁰

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
    let u = b - a;
    let l2 = u.norm_sq();
    let w = m.pos - a;
    let w_perp = w - u * (w.dot(u) / l2);
    let v_perp = m.vel - u * (m.vel.dot(u) / l2);
    let interior = first_contact(w_perp, v_perp, r).filter(|&dt| {
        let s = (w + m.vel * dt).dot(u) / l2;
        (0.0..=1.0).contains(&s)
    });
    let end_a = first_contact(w, m.vel, r);
    let end_b = first_contact(m.pos - b, m.vel, r);
    [interior, end_a, end_b]
        .into_iter()
        .flatten()
        .reduce(f64::min)
        .map(|dt| m.time + dt)
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
    let vn = m.vel.dot(normal) / len;
    if vn >= 0.0 {
        return None;
    }
    let gap = (m.pos - point).dot(normal) / len - r;
    if gap <= 0.0 {
        return Some(m.time);
    }
    Some(m.time + gap / -vn)
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
        // Speeds whose squares underflow even after scaling: no contact (never an invented
        // one).
        assert_eq!(
            first_contact(Vector([0.0, 3.0]), Vector([0.0, -1e-305]), 1.0),
            None
        );
        assert_eq!(
            first_contact(Vector([0.0, 3.0]), Vector([0.0, -1e-320]), 1.0),
            None
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
