//! The edge model: what a body sliding on a segment does at the segment's end.
//!
//! A body resting on a 2D segment (see [`crate::contact::resting`]) slides along it until its centre's
//! foot reaches an end point `e` ([`slide_end_time`], the first root of a quadratic, an event
//! of that body with that segment for every finder). There the body touches `e` with its
//! centre at `c = e + r n` (`n` the segment's unit normal on its side) and its velocity `v`
//! along the segment. Three things can happen, in this order:
//!
//! 1. **Another segment goes straight on** from `e` (it shares the end point bit for bit, is
//!    parallel to the first, points away from it, and holds bodies): the body rests on that
//!    segment from now on, its velocity projected onto it ([`continuation`]). A floor or a
//!    polygon side drawn in pieces is one floor.
//! 2. **It flies clear of the edge.** Let go at `e`, under gravity `g`, its offset from `e`
//!    is `x(t) = c − e + v t + ½ g t²`, and `|x|² − r² = t² q(t)` with
//!    `q(t) = (|v|² + (c − e)·g) + (v·g) t + ¼|g|² t²` (the constant and linear terms vanish:
//!    it touches `e`, moving along the segment). While `q(0) = |v|² − r g_n > 0` (`g_n` the
//!    part of `g` pressing it on the segment) the body moves away from `e` at once: its
//!    curve bends less than the circle of radius `r` about `e`, the free flight of a ball
//!    fast enough to leave a ledge. It falls from there under `g` ([`crate::World::departed`]),
//!    and its next contact with that segment is the first root of `q` ([`return_time`]): the
//!    time it comes back to `e` (a body thrown up over the upper end of an incline falls
//!    back onto it). `q` is used instead of `|x|² − r²` because the touch it leaves at is a
//!    double root of the latter, which rounding would turn into a spurious contact.
//! 3. **Otherwise it rolls over the edge** (2D): held against `e` by gravity, it turns about
//!    `e` on a circle of radius `r`, an inverted pendulum in closed form ([`crate::motion::pivot`]),
//!    until it comes off where `e` stops pushing, swings back onto its segment, or lands on
//!    another segment ending at `e` ([`crate::contact::pivot_end`]). That motion is not a polynomial,
//!    so the finders do not search it: they see the body parked where its turn started
//!    ([`crate::World::pivot`]) and the simulation finds its contacts itself
//!    ([`crate::contact::pivot_contact`]), the same events for every finder.
//!
//! A body reaching a segment's end is a wall event of that body and segment in run files:
//! with the rest flag and naming the next segment for case 1, without it for case 2, with
//! the pivot flag (format version 13) for case 3.

use crate::contact::gravity::first_entry;
use crate::geom::Vector;
use crate::motion::Motion;
use crate::wall::Wall;

/// Absolute time, seconds, at which a body sliding on the segment `[a, b]` with motion `m`
/// and acceleration `acc` (along the segment) first has its centre's foot leave the segment
/// through an end: `(x − a)·û` reaches `|b − a|` growing or `0` shrinking (`û` the unit
/// direction). `0` offset when the foot is already past an end and moving out; `None` when
/// the body never reaches an end or the time is not finite.
#[must_use]
pub fn slide_end_time<const D: usize>(
    m: &Motion<D>,
    acc: &Vector<D>,
    a: Vector<D>,
    b: Vector<D>,
) -> Option<f64> {
    let u = b - a;
    let len = u.norm();
    let unit = u * (1.0 / len);
    let (s, sv, sa) = ((m.pos - a).dot(unit), m.vel.dot(unit), 0.5 * acc.dot(unit));
    // The foot's distance from each end, positive while on the segment.
    let past_b = first_entry(len - s, -sv, -sa);
    let past_a = first_entry(s, sv, sa);
    [past_a, past_b]
        .into_iter()
        .flatten()
        .reduce(f64::min)
        .map(|dt| m.time + dt)
        .filter(|t| t.is_finite())
}

/// The end point of segment `[a, b]` nearest the foot of `p`: the end a body at `p` slid to.
#[must_use]
pub fn end_reached<const D: usize>(a: Vector<D>, b: Vector<D>, p: Vector<D>) -> Vector<D> {
    let u = b - a;
    if (p - a).dot(u) >= 0.5 * u.norm_sq() {
        b
    } else {
        a
    }
}

/// The turn a run file records (format 13, see [`crate::motion::pivot`]): a ball of radius `r` (m)
/// with centre `pos` and velocity `vel` at time `t`, under gravity `g`, rolls over the end
/// point of segment `[a, b]` it has reached ([`end_reached`]). `Err` with the centre's
/// distance from that point (m) when it is not `r` from it (to `1e-9·r`), so does not touch
/// it; `Ok(None)` where [`crate::motion::pivot::Pivot::new`] makes no turn. 2D.
pub fn recorded_turn<const D: usize>(
    (a, b): (Vector<D>, Vector<D>),
    r: f64,
    g: Vector<D>,
    (pos, vel): (Vector<D>, Vector<D>),
    t: f64,
) -> Result<Option<crate::motion::pivot::Pivot>, f64> {
    use crate::motion::pivot::{to_2d, Pivot};
    let end = end_reached(a, b, pos);
    let dist = (pos - end).norm();
    if (dist - r).abs() > 1e-9 * r {
        return Err(dist);
    }
    Ok(Pivot::new(
        to_2d(end),
        r,
        to_2d(g),
        to_2d(pos),
        to_2d(vel),
        t,
    ))
}

/// The coefficients `(q₀, q₁, q₂)` of `q(t) = q₀ + q₁ t + q₂ t²` (see the module docs) for a
/// body with motion `m` let go at end point `end` under gravity `g`: `|x − end|² − r²` is
/// `t² q(t)` for a body touching `end` and moving across the line to it.
#[must_use]
fn departure<const D: usize>(m: &Motion<D>, end: Vector<D>, g: &Vector<D>) -> (f64, f64, f64) {
    (
        m.vel.norm_sq() + (m.pos - end).dot(*g),
        m.vel.dot(*g),
        0.25 * g.norm_sq(),
    )
}

/// `q(0) = |v|² + (x − end)·g`, m²/s², for a body with motion `m` (position `x`, velocity
/// `v`) at the end point `end` of the segment it slid on, under gravity `g`: by how much it
/// is fast enough to fly clear of the edge (case 2 of the module docs) when positive.
#[must_use]
pub fn edge_margin<const D: usize>(m: &Motion<D>, end: Vector<D>, g: &Vector<D>) -> f64 {
    departure(m, end, g).0
}

/// True when a body with motion `m`, at the end point `end` of the segment it slid on, flies
/// clear of the edge under gravity `g`: [`edge_margin`] `> 0`.
#[must_use]
pub fn flies_clear<const D: usize>(m: &Motion<D>, end: Vector<D>, g: &Vector<D>) -> bool {
    edge_margin(m, end, g) > 0.0
}

/// Absolute time, seconds, at which a body that flew clear of end point `end` (its motion
/// `m` the one it left with, falling under `g`) comes back into contact with it: the first
/// root of `q` where it turns negative; `None` when it never does.
#[must_use]
pub fn return_time<const D: usize>(m: &Motion<D>, end: Vector<D>, g: &Vector<D>) -> Option<f64> {
    let (q0, q1, q2) = departure(m, end, g);
    first_entry(q0, q1, q2)
        .map(|dt| m.time + dt)
        .filter(|t| t.is_finite())
}

/// The segment that goes straight on from end point `end` of segment `w` (case 1 of the
/// module docs): another segment with an end point equal to `end`, parallel to `w` (their
/// 2D cross product exactly zero) and pointing away from it, on which bodies rest
/// (`slides[k]` is `Some`, see [`crate::scene::slides`]). The lowest such index; `None`
/// in 3D or when there is none.
#[must_use]
pub fn continuation<const D: usize>(
    walls: &[Wall<D>],
    slides: &[Option<Vector<D>>],
    w: usize,
    end: Vector<D>,
) -> Option<usize> {
    let Wall::Segment { a, b } = walls[w] else {
        return None;
    };
    if D != 2 {
        return None;
    }
    let out = if end == b { b - a } else { a - b };
    (0..walls.len()).find(|&k| {
        let Wall::Segment { a: a2, b: b2 } = walls[k] else {
            return false;
        };
        let away = if a2 == end {
            b2 - a2
        } else if b2 == end {
            a2 - b2
        } else {
            return false;
        };
        k != w
            && slides.get(k).copied().flatten().is_some()
            && out[0] * away[1] == out[1] * away[0]
            && out.dot(away) > 0.0
    })
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

    const G: Vector<2> = Vector([0.0, -10.0]);

    fn seg(a: [f64; 2], b: [f64; 2]) -> Wall<2> {
        Wall::Segment {
            a: Vector(a),
            b: Vector(b),
        }
    }

    #[test]
    fn a_body_sliding_on_a_floor_reaches_the_end_it_moves_to() {
        let (a, b) = (Vector([0.0, 0.0]), Vector([4.0, 0.0]));
        // At x = 1 moving right at 2 m/s: the foot reaches x = 4 after 1.5 s.
        let m = m2([1.0, 0.5], [2.0, 0.0], 10.0);
        assert_eq!(slide_end_time(&m, &Vector::ZERO, a, b), Some(11.5));
        // Moving left: the foot reaches x = 0 after 0.5 s.
        let m = m2([1.0, 0.5], [-2.0, 0.0], 10.0);
        assert_eq!(slide_end_time(&m, &Vector::ZERO, a, b), Some(10.5));
        // At rest on a floor: never.
        let m = m2([1.0, 0.5], [0.0, 0.0], 10.0);
        assert_eq!(slide_end_time(&m, &Vector::ZERO, a, b), None);
        // Thrown up an incline (along +x here) and turned back by its slide: it reaches
        // the lower end, x = 0, when 1 + 2t − t² = 0.
        let m = m2([1.0, 0.5], [2.0, 0.0], 0.0);
        let t = slide_end_time(&m, &Vector([-2.0, 0.0]), a, b).unwrap();
        assert!((t - (1.0 + 2f64.sqrt())).abs() < 1e-15, "{t}");
        // Past the end and moving out: now.
        let m = m2([4.5, 0.5], [1.0, 0.0], 3.0);
        assert_eq!(slide_end_time(&m, &Vector::ZERO, a, b), Some(3.0));
        assert_eq!(end_reached(a, b, Vector([3.9, 0.5])), b);
        assert_eq!(end_reached(a, b, Vector([0.1, 0.5])), a);
    }

    #[test]
    fn a_fast_body_flies_clear_and_a_slow_one_would_roll_over() {
        // A ball of radius 0.1 at the end of a floor: it clears the edge when v² > r g = 1.
        let end = Vector([0.0, 0.0]);
        assert!(flies_clear(&m2([0.0, 0.1], [1.01, 0.0], 0.0), end, &G));
        assert!(!flies_clear(&m2([0.0, 0.1], [0.99, 0.0], 0.0), end, &G));
        // Leaving at the lower end of a floor it never comes back.
        assert_eq!(return_time(&m2([0.0, 0.1], [2.0, 0.0], 0.0), end, &G), None);
    }

    #[test]
    fn a_body_thrown_over_the_top_of_an_incline_falls_back_onto_its_end() {
        // The upper end of an incline rising to the right, g with a part along it (−x).
        let g = Vector([-8.0, -1.0]);
        let end = Vector([0.0, 0.0]);
        // Touching the end from straight above, moving right (over the top) at 2 m/s.
        let m = m2([0.0, 0.1], [2.0, 0.0], 1.0);
        assert!(flies_clear(&m, end, &g));
        let t = return_time(&m, end, &g).unwrap() - 1.0;
        // The offset at that time is again 0.1 from the end, and moving back in.
        let x = m.pos - end + m.vel * t + g * (0.5 * t * t);
        assert!((x.norm() - 0.1).abs() < 1e-12, "{t} {x:?}");
        assert!(x.dot(m.vel + g * t) < 0.0);
    }

    #[test]
    fn a_floor_in_pieces_goes_straight_on() {
        let walls = [
            seg([0.0, 0.0], [1.0, 0.0]),
            seg([3.0, 0.0], [1.0, 0.0]),
            seg([1.0, 0.0], [2.0, 1.0]),
            seg([-1.0, 0.0], [0.0, 0.0]),
        ];
        let slides: Vec<_> = walls
            .iter()
            .map(|w| crate::contact::resting::slide_acceleration(&G, w))
            .collect();
        // From (1, 0) segment 1 goes on (it is drawn the other way); 2 turns up.
        assert_eq!(
            continuation(&walls, &slides, 0, Vector([1.0, 0.0])),
            Some(1)
        );
        assert_eq!(
            continuation(&walls, &slides, 0, Vector([0.0, 0.0])),
            Some(3)
        );
        assert_eq!(continuation(&walls, &slides, 1, Vector([3.0, 0.0])), None);
        assert_eq!(continuation(&walls, &slides, 3, Vector([-1.0, 0.0])), None);
        // A segment going back over the first is no continuation.
        let back = [seg([0.0, 0.0], [1.0, 0.0]), seg([1.0, 0.0], [0.5, 0.0])];
        let slides: Vec<_> = back
            .iter()
            .map(|w| crate::contact::resting::slide_acceleration(&G, w))
            .collect();
        assert_eq!(continuation(&back, &slides, 0, Vector([1.0, 0.0])), None);
    }
}
