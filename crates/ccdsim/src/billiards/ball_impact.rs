//! Two balls meeting: frictionless, instantaneous and perfectly elastic, between equal masses
//! (pooltool 0.3.3's default ball–ball model, `frictionless_elastic`). The velocity
//! components along the line of centres are exchanged; the rest of each velocity, and every
//! angular velocity, is kept (no friction acts between the balls).

use crate::motion::ClothBall;

/// The two balls just after they meet with centres at `a.pos` and `b.pos`: each gives the
/// other its velocity component along the line of centres.
#[must_use]
pub fn exchange(a: &ClothBall, b: &ClothBall) -> (ClothBall, ClothBall) {
    let d = b.pos - a.pos;
    let n = d * (1.0 / d.norm());
    let along = (a.vel - b.vel).dot(n);
    let push = n * along;
    (
        ClothBall {
            vel: a.vel - push,
            ..*a
        },
        ClothBall {
            vel: b.vel + push,
            ..*b
        },
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::Vector;

    #[test]
    fn a_straight_hit_stops_the_cue_ball_and_a_cut_splits_at_right_angles() {
        let r = 0.028575;
        let cue = ClothBall {
            pos: Vector([0.0, 0.0]),
            vel: Vector([2.0, 0.0]),
            spin: Vector([0.0, 70.0, 3.0]),
        };
        let object = ClothBall {
            pos: Vector([2.0 * r, 0.0]),
            vel: Vector::ZERO,
            spin: Vector::ZERO,
        };
        let (c, o) = exchange(&cue, &object);
        assert_eq!(c.vel, Vector::ZERO);
        assert_eq!(o.vel, Vector([2.0, 0.0]));
        assert_eq!(c.spin, cue.spin);
        let cut = ClothBall {
            pos: Vector([2.0 * r * 0.6, 2.0 * r * 0.8]),
            ..object
        };
        let (c, o) = exchange(&cue, &cut);
        assert!(c.vel.dot(o.vel).abs() < 1e-12);
        assert!((c.vel + o.vel - cue.vel).norm() < 1e-12);
    }
}
