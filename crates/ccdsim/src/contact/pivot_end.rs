//! How a pivot ends when nothing else meets the ball: it comes off the point, swings back
//! onto the segment it slid off, or lands on another segment that ends at the point.
//!
//! A ball turning about the end point `e` of the segment it slid off ([`crate::motion::pivot`])
//! touches `e` all along. Another segment `k` that ends at `e` and leaves it in direction
//! `d` is met where the centre's direction from `e`, `u(θ)`, turns perpendicular to `d`:
//! until then `u·d < 0`, so `e` is the nearest point of `k` to the centre and the ball only
//! touches `k` at `e`; past it, it would cut into `k`. So the ball lands on `k` at the first
//! angle at which `u·d` rises through zero along its motion, with its velocity along `k`
//! (tangent to the circle) and no normal speed: it rests on `k` from there, sliding. Held
//! there (the point still pushes), gravity presses it onto `k`, which is why such a `k`
//! holds bodies.
//!
//! The segment it slid off is such a `k` too, met only on the way back
//! ([`Pivot::return_time`], exactly the start's angle). Whichever comes first, landing,
//! swinging back or the release ([`Pivot::release_time`]), ends the pivot; ties go to a
//! landing (lowest index), then the swing back, then the release.

use crate::geom::Vector;
use crate::motion::pivot::Pivot;
use crate::wall::Wall;

/// What ends a pivot by itself (module docs).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum PivotEnd {
    /// At `time` (s) the point stops pushing: the ball flies off, falling.
    Release {
        /// Seconds.
        time: f64,
    },
    /// At `time` (s) the ball is back on the segment it slid off, moving the other way.
    Back {
        /// Seconds.
        time: f64,
    },
    /// At `time` (s) the ball lands on segment `wall`, which ends at the pivot's point.
    Land {
        /// Seconds.
        time: f64,
        /// The segment's index among `walls`.
        wall: usize,
    },
}

impl PivotEnd {
    /// When it happens, s.
    #[must_use]
    pub fn time(&self) -> f64 {
        match *self {
            PivotEnd::Release { time } | PivotEnd::Back { time } | PivotEnd::Land { time, .. } => {
                time
            }
        }
    }
}

/// The end of `pivot`, a ball turning about an end point of segment `w` of `walls` (static
/// walls; module docs), or `None` when it never ends by itself (it rests balanced on top, or
/// creeps towards the top for ever).
#[must_use]
pub fn pivot_end(pivot: &Pivot, walls: &[Wall<2>], w: usize) -> Option<PivotEnd> {
    let e = pivot.point();
    let landings = walls.iter().enumerate().filter_map(|(k, wall)| {
        let Wall::Segment { a, b } = *wall else {
            return None;
        };
        let d = match (a == e, b == e) {
            _ if k == w => return None,
            (true, false) => b - a,
            (false, true) => a - b,
            _ => return None,
        };
        // Either normal of `k` may be where `u·d` rises through zero, depending on the sense
        // the ball turns in; the one at which it does, first.
        let normal = Vector([-d[1], d[0]]);
        [normal, -normal]
            .into_iter()
            .filter_map(|n| {
                let t = pivot.time_at_angle(pivot.angle_of(n))?;
                // `u·d` changes at the rate `v·d / r`.
                (pivot.velocity(t).dot(d) > 0.0).then_some(PivotEnd::Land { time: t, wall: k })
            })
            .reduce(earlier)
    });
    let back = pivot.return_time().map(|time| PivotEnd::Back { time });
    let release = pivot.release_time().map(|time| PivotEnd::Release { time });
    landings.chain(back).chain(release).reduce(earlier)
}

/// The earlier of two ends, the first on a tie (the order of the module docs).
fn earlier(x: PivotEnd, y: PivotEnd) -> PivotEnd {
    if y.time() < x.time() {
        y
    } else {
        x
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const G: Vector<2> = Vector([0.0, -10.0]);
    const R: f64 = 0.5;

    fn seg(a: [f64; 2], b: [f64; 2]) -> Wall<2> {
        Wall::Segment {
            a: Vector(a),
            b: Vector(b),
        }
    }

    /// A ball of radius `R` at the end `e` of a segment along `along`, sliding off at `v`.
    fn off(e: [f64; 2], along: Vector<2>, v: f64) -> Pivot {
        let e = Vector(e);
        let n = Vector([-along[1], along[0]]);
        Pivot::new(e, R, G, e + n * R, along * v, 0.0).unwrap()
    }

    #[test]
    fn off_a_level_ledge_it_is_released() {
        let walls = [seg([-5.0, 0.0], [0.0, 0.0]), seg([0.0, 0.0], [0.0, -3.0])];
        let p = off([0.0, 0.0], Vector([1.0, 0.0]), 0.4);
        // The box's side, straight down, is never reached: it comes off first.
        let end = pivot_end(&p, &walls, 0).unwrap();
        assert_eq!(
            end,
            PivotEnd::Release {
                time: p.release_time().unwrap()
            }
        );
    }

    #[test]
    fn over_an_obtuse_corner_a_slow_ball_lands_on_the_next_slope() {
        // Level, then down at 30° from the corner at the origin.
        let a = 30f64.to_radians();
        let far = [3.0 * a.cos(), -3.0 * a.sin()];
        let walls = [seg([-5.0, 0.0], [0.0, 0.0]), seg(far, [0.0, 0.0])];
        let p = off([0.0, 0.0], Vector([1.0, 0.0]), 0.4);
        let Some(PivotEnd::Land { time, wall: 1 }) = pivot_end(&p, &walls, 0) else {
            panic!("{:?}", pivot_end(&p, &walls, 0));
        };
        assert!(time < p.release_time().unwrap());
        // It lands with its centre at R from the slope, moving along it.
        let d = Vector(far) * (1.0 / 3.0);
        let n = Vector([-d[1], d[0]]);
        assert!((p.position(time).dot(n) - R).abs() < 1e-12);
        assert!(p.velocity(time).dot(n).abs() < 1e-12);
        assert!(p.velocity(time).dot(d) > 0.0);
        // Faster, it comes off before the slope.
        let fast = off([0.0, 0.0], Vector([1.0, 0.0]), 2.0);
        assert!(matches!(
            pivot_end(&fast, &walls, 0),
            Some(PivotEnd::Release { .. })
        ));
    }

    #[test]
    fn off_the_top_of_an_incline_it_swings_back() {
        let a = 20f64.to_radians();
        let top = [2.0 * a.cos(), 2.0 * a.sin()];
        let walls = [seg([0.0, 0.0], top)];
        let p = off(top, Vector([a.cos(), a.sin()]), 0.2);
        assert_eq!(
            pivot_end(&p, &walls, 0),
            Some(PivotEnd::Back {
                time: p.return_time().unwrap()
            })
        );
    }

    #[test]
    fn turning_left_it_lands_on_the_left() {
        // Moving left off the left end of a level floor, with a slope down to the left.
        let walls = [seg([0.0, 0.0], [5.0, 0.0]), seg([0.0, 0.0], [-2.0, -1.0])];
        let p = Pivot::new(
            Vector::ZERO,
            R,
            G,
            Vector([0.0, R]),
            Vector([-0.3, 0.0]),
            0.0,
        )
        .unwrap();
        assert!(matches!(
            pivot_end(&p, &walls, 0),
            Some(PivotEnd::Land { wall: 1, .. })
        ));
    }
}
