//! Arrivals: bodies a scene brings in while it runs (`arrivals[]`), a feed such as a Galton
//! board's funnel releasing one ball after another.
//!
//! Arrival `k` is added at its `time` exactly as [`crate::Simulation::add_body`] adds a body:
//! it takes the first vacant slot (else the next index), after every event at or before that
//! time, and it is recorded as that addition (a run file of a scene with arrivals is the run
//! file of a program that added them, see [`crate::record`]). Arrivals come in time order;
//! those of one time in the order the scene lists them. Should a body (or a moving wall) then
//! occupy the arrival's place, the run stops there with [`crate::Halt::ArrivalBlocked`]: an
//! arrival is never moved or dropped.

use crate::scene::BodySpec;
use serde::{Deserialize, Serialize};

/// A body that enters the scene at `time` (`arrivals[]` in a scene).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Arrival<const D: usize> {
    /// When it enters, seconds; not before the scene's `start_time`.
    pub time: f64,
    /// The body as it enters: fields as in `bodies[]`, without spin, inertia or tangential
    /// restitution (added bodies take the scene's).
    pub body: BodySpec<D>,
}

/// The order in which `arrivals` enter: by time, ties in list order.
#[must_use]
pub fn arrival_order<const D: usize>(arrivals: &[Arrival<D>]) -> Vec<usize> {
    let mut order: Vec<usize> = (0..arrivals.len()).collect();
    order.sort_by(|&a, &b| arrivals[a].time.total_cmp(&arrivals[b].time));
    order
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::Vector;

    #[test]
    fn arrivals_enter_by_time_and_ties_in_list_order() {
        let at = |time: f64| Arrival::<2> {
            time,
            body: BodySpec::new(Vector([0.0, 0.0]), Vector([0.0, 0.0]), 0.5),
        };
        let arrivals = [at(2.0), at(1.0), at(2.0), at(0.5)];
        assert_eq!(arrival_order(&arrivals), vec![3, 1, 0, 2]);
    }

    #[test]
    fn arrivals_enter_at_their_times_and_count_their_energy() {
        use crate::scene::Scene;
        use crate::Simulation;
        let ball = |x: f64, vx: f64| BodySpec::new(Vector([x, 0.0]), Vector([vx, 0.0]), 0.5);
        let scene = Scene::<2> {
            bodies: vec![ball(0.0, 0.0)],
            arrivals: vec![
                Arrival {
                    time: 1.0,
                    body: ball(5.0, -2.0),
                },
                Arrival {
                    time: 1.0,
                    body: BodySpec {
                        kinematic: true,
                        ..ball(-5.0, 0.0)
                    },
                },
            ],
            ..Scene::default()
        };
        let mut sim = Simulation::new(&scene, "cells").unwrap();
        // The moving arrival meets body 0 after closing 4 m at 2 m/s.
        let hit = sim.step_event().unwrap();
        assert_eq!(hit.event.time, 3.0);
        assert_eq!((hit.event.a, hit.event.b), (0, 1));
        assert_eq!(sim.stats().arrivals, 2);
        let m = std::f64::consts::PI * 0.25;
        assert!((sim.stats().arrival_energy - 0.5 * m * 4.0).abs() < 1e-12);
        assert!(sim.world().is_kinematic(2));
    }

    #[test]
    fn scenes_refuse_arrivals_that_cannot_enter_with_the_reason() {
        use crate::scene::Scene;
        use crate::wall::Wall;
        let scene = |time: f64, body: BodySpec<2>| Scene::<2> {
            start_time: 1.0,
            walls: vec![Wall::Segment {
                a: Vector([0.0, 0.0]),
                b: Vector([10.0, 0.0]),
            }],
            arrivals: vec![Arrival { time, body }],
            ..Scene::default()
        };
        let ball = |x: f64, y: f64| BodySpec::new(Vector([x, y]), Vector([1.0, 0.0]), 0.5);
        assert!(scene(1.0, ball(5.0, 1.0)).validate().is_ok());
        for (bad, why) in [
            (scene(0.5, ball(5.0, 1.0)), "before the scene's start_time"),
            (scene(f64::NAN, ball(5.0, 1.0)), "arrivals[0].time"),
            (scene(2.0, ball(5.0, 0.25)), "cross wall 0"),
            (
                scene(
                    2.0,
                    BodySpec {
                        radius: -1.0,
                        ..ball(5.0, 1.0)
                    },
                ),
                "arrivals[0].body",
            ),
            (
                scene(
                    2.0,
                    BodySpec {
                        spin: Some(crate::motion::Spin::Planar(1.0)),
                        ..ball(5.0, 1.0)
                    },
                ),
                "without spin",
            ),
        ] {
            let err = bad.validate().unwrap_err().to_string();
            assert!(err.contains(why), "{err}");
        }
    }
}
