//! Uniform gravity: every body accelerates by the same `g` between events, so it follows a
//! parabola, `x(t) = p + v·(t − t_i) + ½·g·(t − t_i)²`, with velocity `v + g·(t − t_i)`.
//!
//! # Pair contacts stay the same quadratic
//!
//! Two bodies under the same acceleration have relative acceleration `g − g = 0`: at any
//! time `T`, their offset is `dp(t) = dp(T) + dv(T)·(t − T)` exactly, with `dp(T)` and `dv(T)`
//! the differences of their positions and velocities at `T`. So the time of impact of a pair
//! is [`first_contact`] of `dp(T)` and `dv(T)`, evaluated from `T = max(t_a, t_b)` like the
//! fixed-velocity narrow phase ([`toi_circle_circle_falling`]); when both bodies were last
//! changed at the same time the gravity terms vanish and the bits are the fixed-velocity
//! function's.
//!
//! # Walls
//!
//! Against a plane, the distance of the centre is a quadratic in time: `gap + v_n·t + ½·g_n·t²`
//! ([`toi_circle_plane_falling`]). Against a segment (2D), the signed distance of the centre
//! from the segment's line is such a quadratic too: the ball meets the interior where it
//! enters the slab of half-width `r` around the line with its foot on the segment, and the
//! end points where `|w + v·t + ½·g·t²| = r`, a quartic whose first root is isolated by
//! [`first_contact_accelerating`]. A parabola may enter the slab beyond an end, leave it and
//! come back over the segment, so every entry into the slab is a candidate, not just the
//! first (unlike straight motion, where a first entry beyond the end can only be followed by
//! the end point's contact).
//!
//! In 3D a segment is a rod: the ball meets the capsule of radius `r` around it. Across the
//! rod (projected on the plane perpendicular to it) the centre's parabola is a parabola still,
//! so its squared distance from the rod's line is a quartic, and the ball meets the side
//! where it enters the infinite cylinder around the line with its foot on the rod
//! ([`crate::contact::rod`]). That quartic may have two entries (the parabola enters the cylinder
//! beyond an end, leaves it, and comes back over the rod), so each entry is a candidate
//! ([`crate::contact::accelerated_contact::contacts_accelerating`]); the end points are the same
//! quartic against a point as in 2D. A ball does not rest on a rod: held on top of it, it
//! would roll off around it, a pendulum's motion that no finder could bound exactly, so
//! `settings.rest_speed` holds bodies on planes (and 2D segments) only, and a ball on a rod
//! bounces with the restitution as on any wall that does not hold it. A ball off the rod's top is pushed round by its
//! bounces and falls off, unless they die away first: bounces that die away on a rod end, as
//! on such a wall, in a contact without normal speed repeated at one instant, and the run
//! stops there with [`crate::Halt::Resting`], the same event for every finder (the TC model,
//! `settings.tc`, keeps such bounces elastic instead).
//!
//! With growing radii too, see [`crate::contact::falling_growth`].
//!
//! # What "approaching" means
//!
//! As for straight motion, a pair (or body and wall) in contact collides at once only while
//! it approaches; one that rounding left overlapping while it recedes is given the next time
//! it comes back: the later root, or, if it never leaves the overlap, the time it turns to
//! approach (the vertex of the parabola).

use crate::contact::accelerated_contact::first_contact_accelerating;
use crate::contact::narrow::{first_contact, toi_circle_plane};
use crate::geom::Vector;
use crate::motion::Motion;
use crate::wall::Wall;

/// Time of impact of two balls (radii `ra`, `rb`) falling under the same acceleration `g`,
/// ball `b` displaced by `shift`: [`first_contact`] of their offset and relative velocity at
/// `T = max(a.time, b.time)` (see the module docs), as an absolute time, or `None`.
#[must_use]
#[inline]
pub fn toi_circle_circle_falling<const D: usize>(
    a: &Motion<D>,
    ra: f64,
    b: &Motion<D>,
    rb: f64,
    shift: Vector<D>,
    g: &Vector<D>,
) -> Option<f64> {
    let t0 = a.time.max(b.time);
    let dp = (b.falling_at(t0, g) - a.falling_at(t0, g)) + shift;
    let dv = b.falling_velocity(t0, g) - a.falling_velocity(t0, g);
    first_contact(dp, dv, ra + rb).map(|dt| t0 + dt)
}

/// Time of impact of two balls under different accelerations `acc_a`, `acc_b` (a kinematic
/// body, which does not fall, and a falling one): the first contact of their relative motion,
/// a parabola, from `T = max(a.time, b.time)` ([`first_contact_accelerating`]).
#[must_use]
pub fn toi_circle_circle_accelerating<const D: usize>(
    a: &Motion<D>,
    ra: f64,
    acc_a: &Vector<D>,
    b: &Motion<D>,
    rb: f64,
    acc_b: &Vector<D>,
) -> Option<f64> {
    let t0 = a.time.max(b.time);
    let dp = b.falling_at(t0, acc_b) - a.falling_at(t0, acc_a);
    let dv = b.falling_velocity(t0, acc_b) - a.falling_velocity(t0, acc_a);
    first_contact_accelerating(dp, dv, *acc_b - *acc_a, ra + rb)
        .map(|dt| t0 + dt)
        .filter(|t| t.is_finite())
}

/// The first `t ≥ 0` at which the gap `c + b·t + a·t²` (positive apart, metres) enters
/// contact: reaches zero while shrinking, or `0` when it is already `≤ 0` and shrinking
/// (`b < 0`). A gap that is `≤ 0` but not shrinking is given the time it next comes back: its
/// later root if it opens first, or the vertex if it never does (see the module docs).
/// Roots are taken in the cancellation-free forms; `None` when the gap never closes or the
/// time is not finite.
#[must_use]
pub fn first_entry(c: f64, b: f64, a: f64) -> Option<f64> {
    let t = if a == 0.0 {
        if b >= 0.0 {
            return None;
        }
        if c <= 0.0 {
            0.0
        } else {
            c / -b
        }
    } else if c > 0.0 {
        let disc = b * b - 4.0 * a * c;
        if disc < 0.0 {
            return None;
        }
        if b < 0.0 {
            // The smaller root when a > 0, the only positive one when a < 0.
            2.0 * c / (disc.sqrt() - b)
        } else if a < 0.0 {
            (b + disc.sqrt()) / (-2.0 * a)
        } else {
            return None;
        }
    } else if b < 0.0 {
        0.0
    } else if a > 0.0 {
        return None;
    } else {
        let disc = b * b - 4.0 * a * c;
        if disc < 0.0 {
            b / (-2.0 * a)
        } else {
            (b + disc.sqrt()) / (-2.0 * a)
        }
    };
    Some(t).filter(|t| t.is_finite() && *t >= 0.0)
}

/// Time of impact of a ball (radius `r`) falling under `g` with the one-sided plane through
/// `point` whose `normal` points to the ball's side: the first entry of the gap
/// `gap + v_n·t + ½·g_n·t²` ([`first_entry`]), from the ball's reference time. When `g` lies
/// in the plane this is [`toi_circle_plane`] bit for bit.
#[must_use]
pub fn toi_circle_plane_falling<const D: usize>(
    m: &Motion<D>,
    r: f64,
    point: Vector<D>,
    normal: Vector<D>,
    g: &Vector<D>,
) -> Option<f64> {
    let len = normal.norm();
    let gn = g.dot(normal) / len;
    if gn == 0.0 {
        return toi_circle_plane(m, r, point, normal);
    }
    let vn = m.vel.dot(normal) / len;
    let gap = (m.pos - point).dot(normal) / len - r;
    first_entry(gap, vn, 0.5 * gn).map(|dt| m.time + dt)
}

/// Time of impact of a ball (radius `r`) falling under `g` with the segment `[a, b]`: in 2D
/// the first entry into the slab around its line whose foot lies on the segment, in 3D the
/// first entry into the cylinder around it whose foot lies on the segment (a rod,
/// [`crate::contact::rod`]), or the first contact with an end point
/// ([`first_contact_accelerating`]), from the ball's reference time. With zero gravity this is
/// [`toi_circle_segment`](crate::contact::narrow::toi_circle_segment) bit for bit.
#[must_use]
pub fn toi_circle_segment_falling<const D: usize>(
    m: &Motion<D>,
    r: f64,
    a: Vector<D>,
    b: Vector<D>,
    g: &Vector<D>,
) -> Option<f64> {
    toi_circle_segment_falling_ends(m, r, a, b, g, [true; 2])
}

/// [`toi_circle_segment_falling`] with the end points `a` and `b` counted only where `ends`
/// says (see [`crate::contact::narrow::toi_circle_segment_ends`]).
#[must_use]
#[inline(always)]
pub fn toi_circle_segment_falling_ends<const D: usize>(
    m: &Motion<D>,
    r: f64,
    a: Vector<D>,
    b: Vector<D>,
    g: &Vector<D>,
    ends: [bool; 2],
) -> Option<f64> {
    if *g == Vector::ZERO {
        return crate::contact::narrow::toi_circle_segment_ends(m, r, a, b, ends);
    }
    if D != 2 {
        return crate::contact::rod::toi_circle_rod_falling_ends(m, r, a, b, g, ends);
    }
    crate::contact::falling_segment::toi_circle_segment_on_parabola(m, r, 0.0, a, b, g, ends)
}

/// Time of impact of a ball (radius `r`) falling under `g` with a wall of either kind.
#[must_use]
#[inline]
pub fn toi_circle_wall_falling<const D: usize>(
    m: &Motion<D>,
    r: f64,
    wall: &Wall<D>,
    g: &Vector<D>,
) -> Option<f64> {
    match *wall {
        Wall::Segment { a, b } => toi_circle_segment_falling(m, r, a, b, g),
        Wall::Plane { point, normal } => toi_circle_plane_falling(m, r, point, normal, g),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contact::narrow::toi_circle_segment;

    const G: Vector<2> = Vector([0.0, -10.0]);

    fn m2(p: [f64; 2], v: [f64; 2], t: f64) -> Motion<2> {
        Motion {
            pos: Vector(p),
            vel: Vector(v),
            time: t,
        }
    }

    #[test]
    fn a_dropped_ball_meets_the_floor_at_the_free_fall_time() {
        // Centre 6 above a floor at y = 0, radius 1: falls 5 m, t = √(2·5/10) = 1.
        let m = m2([0.0, 6.0], [0.0, 0.0], 2.0);
        let floor = (Vector([0.0, 0.0]), Vector([0.0, 1.0]));
        let t = toi_circle_plane_falling(&m, 1.0, floor.0, floor.1, &G).unwrap();
        assert!((t - 3.0).abs() < 1e-15, "{t}");
        // Thrown up at 10 m/s it rises 5 m for 1 s, then falls 10 m: 1 + √2 s.
        let m = m2([0.0, 6.0], [3.0, 10.0], 0.0);
        let t = toi_circle_plane_falling(&m, 1.0, floor.0, floor.1, &G).unwrap();
        assert!((t - (1.0 + 2f64.sqrt())).abs() < 1e-14, "{t}");
        // A ceiling at y = 10 (normal down), touched when the centre reaches 9: thrown at
        // 7 m/s the centre peaks at 6 + 49/20 = 8.45; at 8 m/s it gets there at t = 0.6.
        let ceiling = (Vector([0.0, 10.0]), Vector([0.0, -1.0]));
        let m = m2([0.0, 6.0], [0.0, 7.0], 0.0);
        assert_eq!(
            toi_circle_plane_falling(&m, 1.0, ceiling.0, ceiling.1, &G),
            None
        );
        let m = m2([0.0, 6.0], [0.0, 8.0], 0.0);
        let t = toi_circle_plane_falling(&m, 1.0, ceiling.0, ceiling.1, &G).unwrap();
        assert!((t - 0.6).abs() < 1e-15, "{t}");
    }

    #[test]
    fn first_entry_covers_every_case() {
        assert_eq!(first_entry(1.0, -1.0, 0.0), Some(1.0));
        assert_eq!(first_entry(1.0, 1.0, 0.0), None);
        assert_eq!(first_entry(-1.0, -1.0, 0.5), Some(0.0));
        // Receding from an overlap, pulled back: the later root of −1 + t − t² … none real:
        // the vertex at t = 0.5.
        assert_eq!(first_entry(-1.0, 1.0, -1.0), Some(0.5));
        // −0.25 + 2t − t²: roots 2 ± √3.75; the later one.
        let t = first_entry(-0.25, 2.0, -1.0).unwrap();
        assert!((t - (1.0 + 0.75f64.sqrt())).abs() < 1e-15, "{t}");
        // Convex and receding: never.
        assert_eq!(first_entry(-1.0, 1.0, 1.0), None);
        assert_eq!(first_entry(1.0, 1.0, 1.0), None);
    }

    #[test]
    fn falling_pairs_meet_as_their_relative_motion_says() {
        // Same reference time: exactly the straight-line function.
        let a = m2([0.0, 0.0], [1.0, 0.0], 0.0);
        let b = m2([10.0, 0.0], [-1.0, 0.0], 0.0);
        assert_eq!(
            toi_circle_circle_falling(&a, 1.0, &b, 1.0, Vector::ZERO, &G),
            Some(4.0)
        );
        // b last changed at t = 1: at t = 1 both have fallen alike; a is at (1, −5), moving
        // (1, −10); b is put at (8, −5) moving (−1, −10): gap 7 − 2 = 5 closing at 2.
        let b = m2([8.0, -5.0], [-1.0, -10.0], 1.0);
        let t = toi_circle_circle_falling(&a, 1.0, &b, 1.0, Vector::ZERO, &G).unwrap();
        assert!((t - 3.5).abs() < 1e-14, "{t}");
    }

    #[test]
    fn a_ball_arcing_over_the_end_lands_on_the_segment() {
        // A segment from (0, 0) to (4, 0); the ball starts below and beyond it, rises past
        // the end near x = 6 (clear of the end point), and falls onto the top near x = 2.4.
        let m = m2([7.0, -3.0], [-3.0, 10.0], 0.0);
        let (a, b) = (Vector([0.0, 0.0]), Vector([4.0, 0.0]));
        let t = toi_circle_segment_falling(&m, 0.5, a, b, &G).unwrap();
        let p = m.falling_at(t, &G);
        assert!((p[1] - 0.5).abs() < 1e-12, "{p:?} at {t}");
        assert!(p[0] > 0.0 && p[0] < 4.0, "{p:?}");
        assert!(m.falling_velocity(t, &G)[1] < 0.0);
        // Straight motion would only see the first entry into the slab, beyond the end.
        assert_eq!(toi_circle_segment(&m, 0.5, a, b), None);
    }

    #[test]
    fn a_ball_in_the_slab_beyond_the_end_still_lands_on_the_segment_later() {
        // Found on a peg board: the ball starts within r of the peg's line but far beyond its
        // end, moving towards the line; it leaves the slab upwards and falls onto the peg.
        let m = m2(
            [0.274_104_261_426_211_9, 10.089_703_996_966_115],
            [3.081_532_178_361_167_3, 3.759_927_848_700_852],
            0.0,
        );
        let g = Vector([0.0, -9.81]);
        let (a, b) = (Vector([1.55, 10.5]), Vector([1.95, 10.6]));
        let t = toi_circle_segment_falling(&m, 0.25, a, b, &g).unwrap();
        assert!((t - 0.452_101_698_227_093).abs() < 1e-12, "{t}");
    }

    #[test]
    fn end_points_catch_a_falling_ball() {
        let (a, b) = (Vector([0.0, 0.0]), Vector([4.0, 0.0]));
        // Dropped 0.3 beyond the end: hits the corner where |p − b| = 0.5.
        let m = m2([4.3, 3.0], [0.0, 0.0], 0.0);
        let t = toi_circle_segment_falling(&m, 0.5, a, b, &G).unwrap();
        let d = (m.falling_at(t, &G) - b).norm();
        assert!((d - 0.5).abs() < 1e-12, "{d}");
    }

    proptest::proptest! {
        /// The plane's time is a contact (gap zero, closing) with no earlier one, checked
        /// against a fine sampling of the exact parabola.
        #[test]
        fn plane_contacts_are_first_roots(
            y in 0.6..20.0f64,
            vy in -20.0..20.0f64,
            gy in -20.0..20.0f64,
        ) {
            let g = Vector([0.0, gy]);
            let m = m2([0.0, y], [0.0, vy], 0.0);
            let gap = |t: f64| y + vy * t + 0.5 * gy * t * t - 0.5;
            match toi_circle_plane_falling(&m, 0.5, Vector::ZERO, Vector([0.0, 1.0]), &g) {
                Some(t) => {
                    proptest::prop_assert!(gap(t).abs() < 1e-9 * (1.0 + y + vy.abs() * t + gy.abs() * t * t));
                    for k in 0..400 {
                        let s = t * f64::from(k) / 400.0;
                        proptest::prop_assert!(gap(s) > -1e-9);
                    }
                }
                None => {
                    for k in 0..4000 {
                        proptest::prop_assert!(gap(f64::from(k) * 0.01) > -1e-9);
                    }
                }
            }
        }
    }
}
