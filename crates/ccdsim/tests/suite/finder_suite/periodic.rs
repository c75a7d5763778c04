//! Periodic boxes: gases, kicks and frames, boxes too short for three cells, long flights.

use super::*;

fn check_periodic_gases<const D: usize>(ns: &[usize], seeds: &[u64]) {
    for_each_gas::<D>(ns, seeds, |label, n, packing, radii, seed| {
        let scene = periodic_gas::<D>(n, packing, radii, seed);
        let events = (EVENTS_PER_BODY * n as u64).min(MAX_EVENTS);
        check_periodic(
            &format!("periodic gas {label}"),
            &scene,
            events,
            Drive::Events,
        );
    });
}

#[test]
fn periodic_gases_2d() {
    check_periodic_gases::<2>(&[2, 3, 5, 17, 64, 256], &SMALL_SEEDS[..2]);
}

#[test]
fn periodic_gases_3d() {
    check_periodic_gases::<3>(&[2, 5, 17, 64, 200], &SMALL_SEEDS[..2]);
}

/// Velocity edits after peeking (the finder has gone through internal work beyond the edit)
/// and frame-by-frame stepping, in periodic boxes.
#[test]
fn periodic_kicks_and_frames() {
    let s2 = periodic_gas::<2>(150, 0.35, (0.2, 1.0), SMALL_SEEDS[2]);
    let s3 = periodic_gas::<3>(100, 0.2, (0.3, 0.6), SMALL_SEEDS[0]);
    for (drive2, drive3) in [
        (Drive::Kicks { every: 3 }, Drive::Kicks { every: 5 }),
        (Drive::Frames { dt: 1.0 / 60.0 }, Drive::Frames { dt: 0.37 }),
    ] {
        check_periodic("periodic 2D", &s2, 1500, drive2);
        check_periodic("periodic 3D", &s3, 1000, drive3);
    }
}

/// Periodic boxes too short for three cells along some axis, and long flights across the
/// box.
#[test]
fn small_periodic_boxes_and_long_flights() {
    let pair = |size: [f64; 2], bodies: Vec<BodySpec<2>>| Scene::<2> {
        bodies,
        periodic: Some(Vector(size)),
        ..Scene::default()
    };
    let b = |p: [f64; 2], v: [f64; 2]| BodySpec::new(Vector(p), Vector(v), 0.5);
    let scenes = [
        pair(
            [2.5, 2.5],
            vec![b([0.5, 0.5], [1.0, 0.3]), b([1.8, 1.7], [-0.4, 0.9])],
        ),
        pair(
            [2.5, 9.0],
            vec![
                b([0.5, 0.5], [1.0, 0.3]),
                b([1.8, 3.0], [-0.4, 0.9]),
                b([1.0, 6.0], [0.2, -1.3]),
            ],
        ),
        pair(
            [50.0, 50.0],
            vec![b([1.0, 1.0], [3.0, 0.37]), b([25.0, 30.0], [-1.0, 0.05])],
        ),
    ];
    for (k, scene) in scenes.iter().enumerate() {
        scene.validate().unwrap();
        check_periodic(
            &format!("small periodic box {k}"),
            scene,
            600,
            Drive::Events,
        );
    }
    let s3 = Scene::<3> {
        bodies: vec![
            BodySpec::new(Vector([0.5, 0.5, 0.5]), Vector([1.0, 0.3, -0.2]), 0.5),
            BodySpec::new(Vector([1.7, 1.8, 4.0]), Vector([-0.4, 0.9, 1.1]), 0.5),
            BodySpec::new(Vector([1.2, 0.4, 7.0]), Vector([0.2, -1.1, 0.7]), 0.5),
        ],
        periodic: Some(Vector([2.5, 2.6, 9.0])),
        ..Scene::default()
    };
    check_periodic("small periodic box 3D", &s3, 600, Drive::Events);
}
