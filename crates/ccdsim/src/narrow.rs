//! Narrow phase: time of impact of a pair, a pure function of the stored states.
//!
//! Every function returns the absolute time of the first future contact of an approaching
//! pair, never earlier than the later of the two reference times, or `None`. A pair that
//! rounding left overlapping while approaching collides at once; a receding pair never does.

use crate::geom::Vector;
use crate::scene::Wall;

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
#[must_use]
#[inline]
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
    let disc = b * b - a * c;
    if disc < 0.0 {
        return None;
    }
    Some(c / (-b + disc.sqrt()))
}

/// Time of impact of two balls (radii `ra`, `rb`), evaluated from `T = max(a.time, b.time)`.
#[must_use]
#[inline]
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
#[inline]
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
}
