//! 2D and 3D gases of 1 to 500 bodies, monodisperse and polydisperse, dilute and dense, several
//! seeds; non-default finder options, velocity kicks and frame-by-frame stepping.

use super::*;

/// Seeds of the large gases (n ≥ 128).
const LARGE_SEEDS: [u64; 1] = [20_240_601];

/// Body counts of the gases.
const SMALL_NS: [usize; 8] = [1, 2, 3, 4, 5, 8, 17, 64];

/// Body counts of the large gases.
const LARGE_NS: [usize; 3] = [128, 256, 500];

fn check_gases<const D: usize>(ns: &[usize], seeds: &[u64]) {
    for_each_gas::<D>(ns, seeds, |label, n, packing, radii, seed| {
        let scene = gas_scene::<D>(n, packing, radii, seed);
        let events = (EVENTS_PER_BODY * n as u64).min(MAX_EVENTS);
        check_all(&format!("gas {label}"), &scene, events);
    });
}

#[test]
fn gases_2d_small() {
    check_gases::<2>(&SMALL_NS, &SMALL_SEEDS);
}

#[test]
fn gases_3d_small() {
    check_gases::<3>(&SMALL_NS, &SMALL_SEEDS);
}

#[test]
fn gases_2d_large() {
    check_gases::<2>(&LARGE_NS, &LARGE_SEEDS);
}

#[test]
fn gases_3d_large() {
    check_gases::<3>(&LARGE_NS, &LARGE_SEEDS);
}

#[test]
fn finder_options_do_not_change_events() {
    let variants = [
        FinderOptions {
            bvh_grow: 1.1,
            bvh_shrink: 1.0,
            bvh_initial_dt: 1e-9,
            cells_skin: Some(0.0),
        },
        FinderOptions {
            bvh_grow: 8.0,
            bvh_shrink: 0.125,
            bvh_initial_dt: 100.0,
            cells_skin: Some(1.0),
        },
        FinderOptions {
            bvh_grow: 3.0,
            bvh_shrink: 0.9,
            bvh_initial_dt: 0.05,
            cells_skin: Some(0.01),
        },
    ];
    let s2 = gas_scene::<2>(150, 0.3, (0.2, 1.0), SMALL_SEEDS[0]);
    let s3 = gas_scene::<3>(100, 0.2, (0.5, 0.5), SMALL_SEEDS[1]);
    let (o2, o3) = (
        reference("options 2D", &s2, 600, Drive::Events),
        reference("options 3D", &s3, 600, Drive::Events),
    );
    for options in &variants {
        for name in finders() {
            check_run("options 2D", &s2, name, options, 600, Drive::Events, &o2);
            check_run("options 3D", &s3, name, options, 600, Drive::Events, &o3);
        }
    }
}

#[test]
fn velocity_kicks_and_frames() {
    let s2 = gas_scene::<2>(120, 0.3, (0.2, 1.0), SMALL_SEEDS[2]);
    let s3 = gas_scene::<3>(90, 0.15, (0.3, 0.6), SMALL_SEEDS[0]);
    let runs = [
        (
            "kicks",
            Drive::Kicks { every: 7 },
            Drive::Kicks { every: 5 },
        ),
        (
            "frames",
            Drive::Frames { dt: 1.0 / 60.0 },
            Drive::Frames { dt: 0.37 },
        ),
    ];
    let o = FinderOptions::default();
    for (label, drive2, drive3) in runs {
        let (o2, o3) = (
            reference(label, &s2, 800, drive2),
            reference(label, &s3, 800, drive3),
        );
        for name in finders() {
            check_run(label, &s2, name, &o, 800, drive2, &o2);
            check_run(label, &s3, name, &o, 800, drive3, &o3);
        }
    }
}
