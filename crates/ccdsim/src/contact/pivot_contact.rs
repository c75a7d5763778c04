//! First contacts of a ball turning about a point ([`crate::motion::pivot`]) with what moves by
//! polynomials: a ball falling on a parabola (or flying straight, or at rest), a line.
//!
//! A pivot's position is no polynomial of time, so no formula gives these roots. They are
//! isolated instead by branch and bound on time with a second-order bound that cannot miss
//! one: on an interval of half-width `w` about its midpoint `m`, a gap `f` with
//! `|f''| ≤ M` there lies within `f(m) ± (|f'(m)| w + ½ M w²)`; an interval is dropped only
//! where that says `f > 0` throughout (apart) or `f' ≥ 0` throughout (receding), and the
//! others are halved, earlier half first, down to adjacent floats. Near a graze the bound's
//! slack, `O(w²)`, shrinks as fast as the gap's own curvature, so the search keeps a
//! handful of intervals a level. `M` comes from bounds on the speeds and accelerations
//! over the interval: a pivot's speed is largest at one end of any interval it spends held
//! (it grows with `sin²(θ/2)`, which has no interior maximum there), and its acceleration is
//! at most `r(θ̇² + k)`.
//!
//! The contact is the first time at which the gap is not positive *and* shrinking, the
//! meaning "approaching" has everywhere in the narrow phase: a pair that rounding left
//! overlapping while it recedes meets when it turns to approach, or comes back. The answer
//! is a float at which that holds, the first of the floats the search reaches; a pure function
//! of the states, so every finder asking gets the same bits.

use crate::geom::Vector;
use crate::motion::pivot::Pivot;
use crate::wall::Wall;

/// A point moving by a polynomial of degree at most two: at time `time` it is at `pos` with
/// velocity `vel`, and accelerates by `acc` (m, m/s, m/s², s).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Parabola {
    /// Position at `time`, m.
    pub pos: Vector<2>,
    /// Velocity at `time`, m/s.
    pub vel: Vector<2>,
    /// Constant acceleration, m/s².
    pub acc: Vector<2>,
    /// Reference time, s.
    pub time: f64,
}

/// A centre whose position and velocity can be evaluated, and whose speed and acceleration
/// can be bounded over an interval: what the search needs of each side of a contact.
pub trait Mover {
    /// Position (m) and velocity (m/s) at time `t`.
    fn state(&self, t: f64) -> (Vector<2>, Vector<2>);
    /// Upper bounds of the speed (m/s) and of the acceleration's magnitude (m/s²) over the
    /// times `[a, b]`.
    fn bounds(&self, a: f64, b: f64) -> (f64, f64);
}

impl Mover for Parabola {
    fn state(&self, t: f64) -> (Vector<2>, Vector<2>) {
        let dt = t - self.time;
        (
            self.pos + self.vel * dt + self.acc * (0.5 * dt * dt),
            self.vel + self.acc * dt,
        )
    }

    fn bounds(&self, a: f64, b: f64) -> (f64, f64) {
        // The speed is convex in time: largest at an end.
        let speed = |t: f64| (self.vel + self.acc * (t - self.time)).norm();
        (
            speed(a).max(speed(b)) * BOUND_SLACK,
            self.acc.norm() * BOUND_SLACK,
        )
    }
}

impl Mover for Pivot {
    fn state(&self, t: f64) -> (Vector<2>, Vector<2>) {
        (self.position(t), self.velocity(t))
    }

    fn bounds(&self, a: f64, b: f64) -> (f64, f64) {
        let (_, wa) = self.angle_and_rate(a);
        let (_, wb) = self.angle_and_rate(b);
        let w = wa.abs().max(wb.abs());
        let r = self.radius();
        let k = self.gravity_norm() / r;
        (r * w * BOUND_SLACK, r * (w * w + k) * BOUND_SLACK)
    }
}

/// A margin on bounds computed in floating point, so that rounding never makes them too
/// small.
const BOUND_SLACK: f64 = 1.0 + 1e-12;

/// The first time in `[lo, hi]` (s) at which centres `a` and `b` are within `reach` (m) of
/// each other and approaching (module docs), or `None`.
#[must_use]
pub fn first_contact_points(
    a: &impl Mover,
    b: &impl Mover,
    reach: f64,
    lo: f64,
    hi: f64,
) -> Option<f64> {
    let gap = |t: f64| {
        let ((pa, va), (pb, vb)) = (a.state(t), b.state(t));
        let (d, dv) = (pa - pb, va - vb);
        (d.norm_sq() - reach * reach, 2.0 * d.dot(dv), d.norm())
    };
    let curvature = |x: f64, y: f64, m: f64, w: f64| points_curvature(a, b, x, y, m, w);
    first_approach(gap, curvature, |_| true, |_, _, _| false, lo, hi)
}

/// The first time in `[lo, hi]` (s) at which centres `a` and `b` are at least `reach` (m)
/// apart and moving apart (a body leaving a sensor), or `None`.
#[must_use]
pub fn first_exit_points(
    a: &impl Mover,
    b: &impl Mover,
    reach: f64,
    lo: f64,
    hi: f64,
) -> Option<f64> {
    let gap = |t: f64| {
        let ((pa, va), (pb, vb)) = (a.state(t), b.state(t));
        let (d, dv) = (pa - pb, va - vb);
        (reach * reach - d.norm_sq(), -2.0 * d.dot(dv), d.norm())
    };
    let curvature = |x: f64, y: f64, m: f64, w: f64| points_curvature(a, b, x, y, m, w);
    first_approach(gap, curvature, |_| true, |_, _, _| false, lo, hi)
}

/// A bound of `|f''|` over `[x, y]` (half-width `w`) for `f = ±(|d|² − reach²)`, `d` the
/// offset of `b` from `a`, `m = |d|` at the midpoint: `|f''| = 2|d'|² + 2 d·d'' ≤ 2(V² + D·A)`,
/// `D` bounding `|d|` over the interval.
fn points_curvature(a: &impl Mover, b: &impl Mover, x: f64, y: f64, m: f64, w: f64) -> f64 {
    let ((sa, aa), (sb, ab)) = (a.bounds(x, y), b.bounds(x, y));
    let (speed, acc) = (sa + sb, aa + ab);
    let dist = m + speed * w;
    2.0 * (speed * speed + dist * acc) * BOUND_SLACK
}

/// The first time in `[lo, hi]` (s) at which centre `a` is within `reach` (m) of the line
/// through the moving point `line` with unit normal `normal`, on the normal's side and
/// approaching it, or `None`. With `span = Some((u, len2))` only a contact whose foot lies
/// on the segment from `line` to `line + u` counts (`0 ≤ (a − line)·u ≤ len2`, `len2 = |u|²`).
///
/// The span is bounded like the gap: where the foot is off the segment throughout an
/// interval, it is dropped, so a ball crossing the segment's line beyond its ends is never
/// searched down to adjacent floats.
#[must_use]
pub fn first_contact_line(
    a: &impl Mover,
    line: &impl Mover,
    normal: Vector<2>,
    reach: f64,
    span: Option<(Vector<2>, f64)>,
    lo: f64,
    hi: f64,
) -> Option<f64> {
    let gap = |t: f64| {
        let ((p, v), (q, u)) = (a.state(t), line.state(t));
        let dist = (p - q).dot(normal);
        (dist - reach, (v - u).dot(normal), dist.abs())
    };
    let curvature =
        |x: f64, y: f64, _m: f64, _w: f64| (a.bounds(x, y).1 + line.bounds(x, y).1) * BOUND_SLACK;
    let foot = |t: f64, u: Vector<2>| {
        let ((p, v), (q, w)) = (a.state(t), line.state(t));
        ((p - q).dot(u), (v - w).dot(u))
    };
    let counts = |t: f64| span.is_none_or(|(u, len2)| (0.0..=len2).contains(&foot(t, u).0));
    // `|foot''| ≤ (|a''| + |line''|)·|u|`: the foot stays within its second-order spread.
    let outside = |x: f64, y: f64, w: f64| {
        span.is_some_and(|(u, len2)| {
            let (f, df) = foot(0.5 * (x + y), u);
            let bend = curvature(x, y, 0.0, w) * u.norm() * BOUND_SLACK;
            let spread = (df.abs() * w + 0.5 * bend * w * w) * BOUND_SLACK;
            f + spread < 0.0 || f - spread > len2
        })
    };
    first_approach(gap, curvature, counts, outside, lo, hi)
}

/// The first time in `[lo, hi]` (s) at which the ball of radius `r` (m) turning with `pivot`
/// meets `wall`, which is where `wall` says at time `wall_time` and moves at `wall_vel`
/// (m/s; zero for a static wall), or `None`. A plane is met on its side; a segment on the
/// side the centre is on at `lo`, between its ends, or at an end point. Not met: the pivot's
/// own point, and the inside of a segment that ends there (the ball reaches those only by
/// landing on them, see [`crate::contact::pivot_end`]).
#[must_use]
pub fn toi_pivot_wall(
    pivot: &Pivot,
    r: f64,
    wall: &Wall<2>,
    wall_vel: Vector<2>,
    wall_time: f64,
    lo: f64,
    hi: f64,
) -> Option<f64> {
    let mover = |p: Vector<2>| Parabola {
        pos: p,
        vel: wall_vel,
        acc: Vector::ZERO,
        time: wall_time,
    };
    // The centre stays on the circle of radius `r` about the pivot's point (to rounding far
    // below this margin): a static wall farther than `2r` from the point is never reached.
    if wall_vel == Vector::ZERO
        && crate::wall::wall_clearance(wall, pivot.point()).abs() > 2.0 * r * (1.0 + 1e-9)
    {
        return None;
    }
    match *wall {
        Wall::Plane { point, normal } => {
            let n = normal * (1.0 / normal.norm());
            first_contact_line(pivot, &mover(point), n, r, None, lo, hi)
        }
        Wall::Segment { a, b } => {
            let e = pivot.point();
            let ends = [a, b]
                .into_iter()
                .filter(|&p| p != e || wall_vel != Vector::ZERO)
                .filter_map(|p| first_contact_points(pivot, &mover(p), r, lo, hi));
            let inside = if (a == e || b == e) && wall_vel == Vector::ZERO {
                None
            } else {
                let u = b - a;
                let len2 = u.norm_sq();
                let mut n = Vector([-u[1], u[0]]) * (1.0 / len2.sqrt());
                let start = mover(a);
                if (pivot.position(lo) - start.state(lo).0).dot(n) < 0.0 {
                    n = -n;
                }
                first_contact_line(pivot, &start, n, r, Some((u, len2)), lo, hi)
            };
            ends.chain(inside).reduce(f64::min)
        }
    }
}

/// The search of the module docs: `gap(t)` gives the gap, its derivative and a size from
/// which `curvature(a, b, size, w)` bounds `|gap''|` over `[a, b]` (`w` its half-width);
/// `counts(t)` must also hold at the answer, and `outside(a, b, w)` is true only where it
/// holds nowhere in `[a, b]` (such an interval is dropped).
fn first_approach(
    gap: impl Fn(f64) -> (f64, f64, f64),
    curvature: impl Fn(f64, f64, f64, f64) -> f64,
    counts: impl Fn(f64) -> bool,
    outside: impl Fn(f64, f64, f64) -> bool,
    lo: f64,
    hi: f64,
) -> Option<f64> {
    if lo.is_nan() || hi.is_nan() || lo > hi || !lo.is_finite() {
        return None;
    }
    let meets = |t: f64| {
        let (f, df, _) = gap(t);
        f <= 0.0 && df < 0.0 && counts(t)
    };
    if meets(lo) {
        return Some(lo);
    }
    let hi = if hi.is_finite() { hi } else { f64::MAX };
    // Depth first, earlier halves first: the first leaf that meets is the answer.
    let mut stack = vec![(lo, hi)];
    let mut visits = 0u32;
    while let Some((a, b)) = stack.pop() {
        visits += 1;
        let m = 0.5 * (a + b);
        if m <= a || m >= b || visits > MAX_VISITS {
            // Adjacent floats (or a search gone pathological): decide at the ends.
            if meets(b) {
                return Some(b);
            }
            continue;
        }
        let w = 0.5 * (b - a);
        let (f, df, size) = gap(m);
        let bend = curvature(a, b, size, w);
        let apart = f - df.abs() * w - 0.5 * bend * w * w > 0.0;
        let receding = df - bend * w >= 0.0;
        if apart || receding || outside(a, b, w) {
            continue;
        }
        stack.push((m, b));
        stack.push((a, m));
    }
    None
}

/// How many intervals one search may look at before it decides at the ends of the rest:
/// far more than any search near a graze takes (a few per level over about 60 levels).
const MAX_VISITS: u32 = 1 << 20;

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    const G: Vector<2> = Vector([0.0, -10.0]);

    fn at_rest(pos: Vector<2>) -> Parabola {
        Parabola {
            pos,
            vel: Vector::ZERO,
            acc: Vector::ZERO,
            time: 0.0,
        }
    }

    fn level_ledge_pivot(v: f64) -> Pivot {
        Pivot::new(
            Vector([0.0, 0.0]),
            0.5,
            G,
            Vector([0.0, 0.5]),
            Vector([v, 0.0]),
            0.0,
        )
        .unwrap()
    }

    #[test]
    fn a_ball_at_rest_beside_the_edge_is_hit_on_the_way_down() {
        // A ball turning right off a ledge at the origin meets a ball of radius 0.5 resting at
        // (1.2, 0.3): their centres come within 1.0 of each other.
        let p = level_ledge_pivot(0.5);
        let rest = Parabola {
            pos: Vector([1.2, 0.3]),
            vel: Vector([0.0, 0.0]),
            acc: Vector([0.0, 0.0]),
            time: 0.0,
        };
        let end = p.release_time().unwrap();
        let t = first_contact_points(&p, &rest, 1.0, 0.0, end).expect("they meet");
        assert!(t > 0.0 && t < end);
        let d = (p.position(t) - rest.pos).norm();
        assert!(d <= 1.0 && d > 1.0 - 1e-12, "{d}");
        assert!((p.position(t - 1e-9) - rest.pos).norm() > 1.0);
        // Too far to the right, it never meets it before release.
        let far = Parabola {
            pos: Vector([3.0, 0.3]),
            ..rest
        };
        assert_eq!(first_contact_points(&p, &far, 1.0, 0.0, end), None);
    }

    #[test]
    fn a_wall_beside_the_ledge_is_met_and_a_receding_touch_is_not() {
        let p = level_ledge_pivot(0.5);
        let end = p.release_time().unwrap();
        // A vertical wall at x = 0.8 facing left: the centre comes within 0.5 of it.
        let t = first_contact_line(
            &p,
            &at_rest(Vector([0.8, 0.0])),
            Vector([-1.0, 0.0]),
            0.5,
            None,
            0.0,
            end,
        )
        .expect("it reaches the wall");
        let x = p.position(t)[0];
        assert!((0.3..0.3 + 1e-12).contains(&x), "{x}");
        // The floor it slid off (x ≤ 0) is touched at the start, but its centre goes below
        // the floor's line only with its foot beyond the floor's end: no contact.
        let floor = |span| {
            first_contact_line(
                &p,
                &at_rest(Vector([-5.0, 0.0])),
                Vector([0.0, 1.0]),
                0.5,
                span,
                0.0,
                end,
            )
        };
        assert_eq!(floor(Some((Vector([5.0, 0.0]), 25.0))), None);
        // The whole line would be met at once.
        assert!(floor(None).is_some_and(|t| t < 1e-3));
    }

    fn ledge_ball() -> (Pivot, f64) {
        let p = level_ledge_pivot(0.5);
        let end = p.release_time().unwrap();
        (p, end)
    }

    #[test]
    fn walls_met_while_turning() {
        let (p, end) = ledge_ball();
        let seg = |a: [f64; 2], b: [f64; 2]| Wall::Segment {
            a: Vector(a),
            b: Vector(b),
        };
        let toi = |w: &Wall<2>, vel: Vector<2>| toi_pivot_wall(&p, 0.5, w, vel, 0.0, 0.0, end);
        // A wall standing beside the ledge: its inside.
        let t = toi(&seg([0.8, -2.0], [0.8, 2.0]), Vector::ZERO).unwrap();
        assert!((p.position(t)[0] - 0.3).abs() < 1e-12);
        // The floor it slid off: never (its end is the pivot, its inside is landed on).
        assert_eq!(toi(&seg([-5.0, 0.0], [0.0, 0.0]), Vector::ZERO), None);
        // A shelf whose end point sticks into the ball's way: the end point.
        let t = toi(&seg([0.7, 0.2], [3.0, 0.2]), Vector::ZERO).unwrap();
        assert!(((p.position(t) - Vector([0.7, 0.2])).norm() - 0.5).abs() < 1e-12);
        // A plane closing in from the right at 1 m/s.
        let plane = Wall::Plane {
            point: Vector([1.2, 0.0]),
            normal: Vector([-2.0, 0.0]),
        };
        let t = toi(&plane, Vector([-1.0, 0.0])).unwrap();
        assert!((1.2 - t - p.position(t)[0] - 0.5).abs() < 1e-12);
        // Far away, nothing.
        assert_eq!(toi(&seg([5.0, -2.0], [5.0, 2.0]), Vector::ZERO), None);
    }

    /// The reference: the gap sampled densely; the first sample at which it is not positive
    /// and shrinking.
    fn sampled(p: &Pivot, o: &Parabola, reach: f64, lo: f64, hi: f64) -> Option<f64> {
        let n = 20_000;
        (0..=n)
            .map(|i| lo + (hi - lo) * f64::from(i) / f64::from(n))
            .find(|&t| {
                let ((pa, va), (pb, vb)) = (p.state(t), o.state(t));
                let d = pa - pb;
                d.norm() <= reach && d.dot(va - vb) < 0.0
            })
    }

    proptest! {
        /// No contact is missed, none is invented, and the one found is where the gap
        /// closes: against dense sampling, for balls held on a ledge and balls falling by.
        #[test]
        fn never_misses_a_sampled_contact(
            theta0 in -0.6f64..0.6,
            frac in -1.0f64..1.0,
            r in 0.2f64..1.0,
            ox in -2.0f64..2.0,
            oy in -1.0f64..2.5,
            vx in -3.0f64..3.0,
            vy in -3.0f64..3.0,
            falls in any::<bool>(),
            other_r in 0.1f64..0.8,
        ) {
            let k = 10.0 / r;
            let rate = frac * (k * theta0.cos()).sqrt();
            let p = Pivot::from_angle(Vector([0.0, 0.0]), r, G, 0.0, theta0, rate).unwrap();
            let end = p.release_time().unwrap_or(2.0).min(2.0);
            prop_assume!(end > 0.0);
            let o = Parabola {
                pos: Vector([ox, oy]),
                vel: Vector([vx, vy]),
                acc: if falls { G } else { Vector([0.0, 0.0]) },
                time: 0.0,
            };
            let reach = r + other_r;
            let got = first_contact_points(&p, &o, reach, 0.0, end);
            let want = sampled(&p, &o, reach, 0.0, end);
            if let Some(ts) = want {
                let t = got.expect("a sampled contact was missed");
                prop_assert!(t <= ts + 1e-12, "found {t}, sampled {ts}");
            }
            if let Some(t) = got {
                let ((pa, va), (pb, vb)) = (p.state(t), o.state(t));
                let d = pa - pb;
                prop_assert!(d.norm() <= reach && d.dot(va - vb) < 0.0);
                // Just before, they were apart or receding: it is the first such time.
                if t > 0.0 {
                    let before = t - 1e-7;
                    let ((qa, ua), (qb, ub)) = (p.state(before), o.state(before));
                    let e = qa - qb;
                    prop_assert!(e.norm() > reach - 1e-6 || e.dot(ua - ub) >= -1e-6);
                }
            }
        }
    }
}
