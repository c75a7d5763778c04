//! A program steering the world: kinematic bodies, teleports, collision filters, bodies added and
//! removed, moving walls.

use super::*;

/// `scene` with the collision filters of [`FILTERS`] dealt out at random (seed `seed`) to
/// about half of its bodies.
fn with_filters<const D: usize>(mut scene: Scene<D>, seed: u64) -> Scene<D> {
    let mut x = seed ^ KICK_SEED;
    for b in &mut scene.bodies {
        x = x
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        if x >> 63 == 1 {
            let f = FILTERS[(x >> 20) as usize % FILTERS.len()];
            b.group = Some(f.group);
            b.mask = Some(f.mask);
        }
    }
    scene
}

/// A filtered 2D gas (for the edit runs).
fn s2_of(seed: u64) -> Scene<2> {
    with_filters(gas_scene::<2>(100, 0.3, (0.2, 0.6), seed), seed)
}

#[test]
fn kinematic_bodies() {
    // Kinematic bodies move in straight lines whatever happens, push dynamic bodies, and meet
    // no wall and no other kinematic body; under gravity a dynamic body meets one at the
    // first root of their relative parabola's quartic. Kicks reset velocities, kinematic
    // bodies' included, as a game steering its paddles does.
    for &seed in &SMALL_SEEDS {
        let s2 = with_kinematic(gas_scene::<2>(80, 0.3, (0.2, 0.6), seed), 4);
        let s3 = with_kinematic(gas_scene::<3>(60, 0.15, (0.3, 0.5), seed), 3);
        let f2 = falling(s2.clone(), [0.0, -9.81]);
        let f3 = falling(s3.clone(), [0.0, 0.0, -9.81]);
        let board = with_kinematic(peg_board(4, 24, seed), 2);
        check_all(&format!("kinematic 2D seed {seed}"), &s2, 1500);
        check_all(&format!("kinematic 3D seed {seed}"), &s3, 1200);
        check_all(&format!("kinematic gravity 2D seed {seed}"), &f2, 1500);
        check_all(&format!("kinematic gravity 3D seed {seed}"), &f3, 1200);
        check_all(&format!("kinematic peg board seed {seed}"), &board, 1500);
        // In a periodic box kinematic bodies leave through a face and come back through the
        // opposite one, like the others.
        let p2 = with_kinematic(periodic_gas::<2>(100, 0.35, (0.3, 0.5), seed), 5);
        let p3 = with_kinematic(periodic_gas::<3>(60, 0.2, (0.5, 0.5), seed), 4);
        check_periodic(
            &format!("kinematic periodic 2D seed {seed}"),
            &p2,
            1500,
            Drive::Events,
        );
        check_periodic(
            &format!("kinematic periodic 3D seed {seed}"),
            &p3,
            1200,
            Drive::Events,
        );
    }
    let o = FinderOptions::default();
    let s2 = falling(
        with_kinematic(gas_scene::<2>(80, 0.3, (0.2, 0.6), SMALL_SEEDS[1]), 5),
        [0.0, -3.0],
    );
    let p2 = with_kinematic(periodic_gas::<2>(100, 0.35, (0.3, 0.5), SMALL_SEEDS[2]), 5);
    for drive in [Drive::Kicks { every: 3 }, Drive::Frames { dt: 1.0 / 60.0 }] {
        let oracle = reference("kinematic edits", &s2, 1500, drive);
        for name in finders() {
            check_run("kinematic edits", &s2, name, &o, 1500, drive, &oracle);
        }
        check_periodic("kinematic edits periodic 2D", &p2, 1500, drive);
    }
}

#[test]
fn teleports() {
    // set_position moves one body at a time: every finder updates just that body and still
    // gives the oracle's events, in walled and periodic worlds, under gravity and with
    // kinematic bodies, every cells mode.
    let s2 = gas_scene::<2>(100, 0.3, (0.2, 0.6), SMALL_SEEDS[0]);
    let s3 = gas_scene::<3>(60, 0.15, (0.3, 0.5), SMALL_SEEDS[1]);
    let f2 = with_kinematic(falling(s2.clone(), [0.0, -9.81]), 3);
    let p2 = periodic_gas::<2>(120, 0.35, (0.3, 0.5), SMALL_SEEDS[2]);
    let p3 = periodic_gas::<3>(80, 0.2, (0.5, 0.5), SMALL_SEEDS[0]);
    let drive = Drive::Teleports { every: 4 };
    let board = peg_board(5, 32, SMALL_SEEDS[1]);
    for (label, scene) in [
        ("teleports 2D", &s2),
        ("teleports gravity 2D", &f2),
        ("teleports peg board", &board),
    ] {
        let oracle = reference(label, scene, 1500, drive);
        for (name, options) in variants() {
            check_run(label, scene, name, &options, 1500, drive, &oracle);
        }
    }
    let oracle = reference("teleports 3D", &s3, 1200, drive);
    for (name, options) in variants() {
        check_run("teleports 3D", &s3, name, &options, 1200, drive, &oracle);
    }
    check_periodic("teleports periodic 2D", &p2, 1500, drive);
    check_periodic("teleports periodic 3D", &p3, 1200, drive);
    // Teleports at the ends of frames, after the finders looked past them: under gravity
    // `cells` must schedule the crossings it takes back from the edit's time (a crossing
    // from a later clock would be skipped, and the body's events with it).
    let drive = Drive::FrameTeleports { dt: 1.0 / 30.0 };
    for (label, scene) in [
        ("frame teleports peg board", &board),
        ("frame teleports gravity 2D", &f2),
        ("frame teleports 2D", &s2),
    ] {
        let oracle = reference(label, scene, 2000, drive);
        for (name, options) in variants() {
            check_run(label, scene, name, &options, 2000, drive, &oracle);
        }
    }
}

#[test]
fn collision_filters() {
    // Bodies in groups that ignore each other pass through each other: every finder, in
    // every mode (the cells lanes drop their lanes, the lists skip their entries), skips
    // exactly the pairs the oracle skips, in walled and periodic worlds, under gravity and
    // with kinematic bodies, and as filters change during the run.
    for &seed in &SMALL_SEEDS {
        let s2 = with_filters(gas_scene::<2>(100, 0.3, (0.2, 0.6), seed), seed);
        let s3 = with_filters(gas_scene::<3>(60, 0.15, (0.3, 0.5), seed), seed);
        check_all(&format!("filters 2D seed {seed}"), &s2, 1500);
        check_all(&format!("filters 3D seed {seed}"), &s3, 1200);
    }
    let seed = SMALL_SEEDS[1];
    let f2 = with_kinematic(
        with_filters(
            falling(gas_scene::<2>(80, 0.3, (0.2, 0.6), seed), [0.0, -9.81]),
            seed,
        ),
        3,
    );
    check_all("filters gravity kinematic 2D", &f2, 1500);
    let board = with_filters(peg_board(4, 24, seed), seed);
    check_all("filters peg board", &board, 1500);
    let p2 = with_filters(periodic_gas::<2>(120, 0.35, (0.3, 0.5), seed), seed);
    let p3 = with_filters(periodic_gas::<3>(80, 0.2, (0.5, 0.5), seed), seed);
    check_periodic("filters periodic 2D", &p2, 1500, Drive::Events);
    check_periodic("filters periodic 3D", &p3, 1200, Drive::Events);
    // Live filter edits, starting from a world without filters (the first edit rebuilds the
    // finder) and from one with them.
    let drive = Drive::Filters { every: 5 };
    let plain = gas_scene::<2>(100, 0.3, (0.2, 0.6), SMALL_SEEDS[2]);
    for (label, scene) in [
        ("filter edits 2D", &plain),
        ("filter edits filtered 2D", &s2_of(seed)),
    ] {
        let oracle = reference(label, scene, 1500, drive);
        for (name, options) in variants() {
            check_run(label, scene, name, &options, 1500, drive, &oracle);
        }
    }
    check_periodic("filter edits periodic 2D", &p2, 1500, drive);
}

#[test]
fn bodies_added_and_removed() {
    // add_body and remove_body: bodies come and go in stable slots, vacant slots are passed
    // by, new slots are appended (a finder rebuild) and larger bodies re-size the finders;
    // every finder still gives the oracle's events, in walled and periodic worlds (every
    // cells mode), under gravity, with kinematic bodies and filters, with a thermostat (whose
    // draws for kinematic bodies and vacant slots are void) and with growing radii, after
    // events and at the ends of frames.
    let s2 = gas_scene::<2>(100, 0.3, (0.2, 0.6), SMALL_SEEDS[0]);
    let mut heated = with_kinematic(s2.clone(), 4);
    heated.settings.thermostat = Some(ccdsim::thermostat::Thermostat {
        temperature: 1.0,
        rate: 0.5,
        seed: 3,
    });
    let grown = growing(s2.clone(), 0.02);
    let s3 = gas_scene::<3>(60, 0.15, (0.3, 0.5), SMALL_SEEDS[1]);
    let f2 = with_kinematic(falling(s2.clone(), [0.0, -9.81]), 3);
    let board = peg_board(5, 32, SMALL_SEEDS[2]);
    let filtered = s2_of(SMALL_SEEDS[1]);
    let p2 = periodic_gas::<2>(120, 0.35, (0.3, 0.5), SMALL_SEEDS[2]);
    let p3 = periodic_gas::<3>(80, 0.2, (0.5, 0.5), SMALL_SEEDS[0]);
    for drive in [
        Drive::Slots { every: 3 },
        Drive::FrameSlots { dt: 1.0 / 30.0 },
    ] {
        for (label, scene) in [
            ("slots 2D", &s2),
            ("slots gravity kinematic 2D", &f2),
            ("slots peg board", &board),
            ("slots filtered 2D", &filtered),
            ("slots thermostat kinematic 2D", &heated),
            ("slots growth 2D", &grown),
        ] {
            let oracle = reference(label, scene, 1500, drive);
            for (name, options) in variants() {
                check_run(label, scene, name, &options, 1500, drive, &oracle);
            }
        }
        let oracle = reference("slots 3D", &s3, 1200, drive);
        for (name, options) in variants() {
            check_run("slots 3D", &s3, name, &options, 1200, drive, &oracle);
        }
        check_periodic("slots periodic 2D", &p2, 1500, drive);
        check_periodic("slots periodic 3D", &p3, 1200, drive);
        check_periodic(
            "slots periodic growth 2D",
            &growing(p2.clone(), 0.02),
            1500,
            drive,
        );
    }
}

#[test]
fn moving_walls() {
    // A piston and a paddle steered every frame, and left at their velocities: contacts
    // with moving planes and segments (faces and ends), with and without gravity, with
    // kinematic bodies (which meet no wall) and edits; every finder's run file equals the
    // oracle's, whose runs verify.
    for &seed in &SMALL_SEEDS[..2] {
        let s2 = with_moving_walls(gas_scene::<2>(100, 0.3, (0.2, 1.0), seed));
        let s3 = with_moving_walls(gas_scene::<3>(70, 0.15, (0.5, 0.5), seed));
        let fall2 = falling(s2.clone(), [0.3, 9.81]);
        // Gravity towards the piston, which then meets the bodies often.
        let fall3 = falling(s3.clone(), [0.0, 0.0, 9.81]);
        let kin = with_kinematic(fall2.clone(), 4);
        let board = with_moving_walls(peg_board(4, 24, seed));
        for drive in [Drive::Events, Drive::FrameWalls { dt: 0.05 }] {
            let runs = [
                ("2D", &s2, 1500),
                ("falling 2D", &fall2, 1500),
                ("kinematic", &kin, 1500),
                ("peg board", &board, 1500),
            ];
            for (what, scene, events) in runs {
                let label = format!("moving walls {what} seed {seed} {drive:?}");
                let oracle = check_all_driven(&label, scene, events, drive);
                let hits = moving_wall_hits(scene, &oracle);
                assert!(hits.iter().all(|&h| h >= 3), "{label}: few hits {hits:?}");
            }
            for (what, scene) in [("3D", &s3), ("falling 3D", &fall3)] {
                let label = format!("moving walls {what} seed {seed} {drive:?}");
                let oracle = check_all_driven(&label, scene, 1200, drive);
                let hits = moving_wall_hits(scene, &oracle);
                assert!(hits.iter().all(|&h| h >= 3), "{label}: few hits {hits:?}");
            }
        }
        let slots = Drive::Slots { every: 37 };
        check_all_driven(
            &format!("moving walls slots 2D {seed}"),
            &fall2,
            1200,
            slots,
        );
    }
}
