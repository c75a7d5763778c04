//! Proptest-generated scenes, open and periodic, 2D and 3D.

use super::*;

/// A scene on a jittered grid (never overlapping), optionally in a walled box.
fn grid_scene<const D: usize>(
    bodies: Vec<([f64; D], [f64; D], f64)>,
    walls: bool,
    restitution: f64,
) -> Scene<D> {
    grid_scene_in(
        bodies,
        if walls {
            Boundary::Walls
        } else {
            Boundary::Open
        },
        restitution,
    )
}

/// What surrounds a generated grid scene.
#[derive(Clone, Copy, Debug)]
enum Boundary {
    Open,
    Walls,
    /// A periodic box one grid step wider than the walled one, so that it is wider than
    /// four of the largest radii (below 1) even around a single body.
    Periodic,
}

/// A scene on a jittered grid (never overlapping, also across the faces of a periodic box).
fn grid_scene_in<const D: usize>(
    bodies: Vec<([f64; D], [f64; D], f64)>,
    boundary: Boundary,
    restitution: f64,
) -> Scene<D> {
    let n = bodies.len();
    let base = ((n as f64).powf(1.0 / D as f64).ceil() as usize).max(1);
    let bodies: Vec<BodySpec<D>> = bodies
        .into_iter()
        .enumerate()
        .map(|(i, (jitter, v, r))| {
            let mut p = Vector(jitter);
            let mut cell = i;
            for k in 0..D {
                p[k] += 3.0 * (cell % base) as f64 + 2.0;
                cell /= base;
            }
            BodySpec::new(p, Vector(v), r)
        })
        .collect();
    Scene {
        settings: Settings {
            restitution,
            ..Settings::default()
        },
        start_time: 0.0,
        bodies,
        walls: match boundary {
            Boundary::Walls => box_walls(Vector::splat(3.0 * base as f64 + 1.0)),
            Boundary::Open | Boundary::Periodic => Vec::new(),
        },
        periodic: match boundary {
            Boundary::Periodic => Some(Vector::splat(3.0 * base as f64 + 2.0)),
            Boundary::Open | Boundary::Walls => None,
        },
        sensors: Vec::new(),
        moving_walls: Vec::new(),
        arrivals: Vec::new(),
        histogram: None,
    }
}

/// Bodies for [`grid_scene_in`]: jitter, velocity (some at rest) and radius.
fn arb_grid_bodies<const D: usize>() -> impl Strategy<Value = Vec<([f64; D], [f64; D], f64)>> {
    let speed = prop_oneof![Just(0.0), -3.0..3.0f64];
    let body = (
        prop::array::uniform::<_, D>(-0.45..0.45f64),
        prop::array::uniform::<_, D>(speed),
        0.05..1.0f64,
    );
    prop::collection::vec(body, 1..40)
}

fn arb_scene<const D: usize>() -> impl Strategy<Value = Scene<D>> {
    (
        arb_grid_bodies::<D>(),
        any::<bool>(),
        prop_oneof![Just(1.0), 0.0..1.0f64],
    )
        .prop_map(|(bodies, walls, e)| grid_scene(bodies, walls, e))
}

fn arb_periodic_scene<const D: usize>() -> impl Strategy<Value = Scene<D>> {
    (arb_grid_bodies::<D>(), prop_oneof![Just(1.0), 0.0..1.0f64])
        .prop_map(|(bodies, e)| grid_scene_in(bodies, Boundary::Periodic, e))
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    #[test]
    fn generated_scenes_2d(scene in arb_scene::<2>()) {
        check_all("proptest 2D", &scene, 300);
    }

    #[test]
    fn generated_scenes_3d(scene in arb_scene::<3>()) {
        check_all("proptest 3D", &scene, 300);
    }

    #[test]
    fn generated_periodic_scenes_2d(scene in arb_periodic_scene::<2>()) {
        check_periodic("proptest periodic 2D", &scene, 300, Drive::Events);
    }

    #[test]
    fn generated_periodic_scenes_3d(scene in arb_periodic_scene::<3>()) {
        check_periodic("proptest periodic 3D", &scene, 300, Drive::Events);
    }
}
