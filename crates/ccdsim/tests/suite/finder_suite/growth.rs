//! Growing radii, alone and with edits and rescales, moving walls, per-body restitution and
//! kinematic bodies.

use super::*;

#[test]
fn growing_radii() {
    // Lubachevsky–Stillinger growth: every pair and wall contact through the growing
    // functions, the cells grid rebuilt at its horizons, checked against the oracle before
    // every step; run files byte-identical across finders (and every cells mode).
    for (k, &seed) in SMALL_SEEDS.iter().enumerate() {
        let rate = [0.02, 0.1, 0.5][k];
        for (disp, radii) in DISPERSITIES {
            let s2 = growing(gas_scene::<2>(120, 0.35, radii, seed), rate);
            let s3 = growing(gas_scene::<3>(80, 0.2, radii, seed), rate);
            check_all(&format!("growing {disp} walls 2D seed {seed}"), &s2, 2000);
            check_all(&format!("growing {disp} walls 3D seed {seed}"), &s3, 1500);
            let p2 = growing(periodic_gas::<2>(150, 0.35, radii, seed), rate);
            let p3 = growing(periodic_gas::<3>(100, 0.2, radii, seed), rate);
            check_periodic(
                &format!("growing {disp} 2D seed {seed}"),
                &p2,
                2000,
                Drive::Events,
            );
            check_periodic(
                &format!("growing {disp} 3D seed {seed}"),
                &p3,
                1500,
                Drive::Events,
            );
        }
        // An open world: bodies that fly apart may outrun the growth for ever.
        let o2 = growing(
            without_walls(gas_scene::<2>(40, 0.2, (0.3, 0.6), seed)),
            rate,
        );
        check_all(&format!("growing open 2D seed {seed}"), &o2, 800);
    }
}

#[test]
fn growing_radii_with_edits_and_rescales() {
    // Kicks and frames interleaved with growth, and whole-world velocity rescales (the
    // compression's cooling), in periodic boxes.
    let p2 = growing(
        periodic_gas::<2>(150, 0.4, (0.3, 0.42), SMALL_SEEDS[1]),
        0.2,
    );
    let p3 = growing(
        periodic_gas::<3>(100, 0.25, (0.5, 0.5), SMALL_SEEDS[2]),
        0.2,
    );
    for drive in [
        Drive::Kicks { every: 7 },
        Drive::Frames { dt: 0.05 },
        Drive::Rescale { every: 200 },
    ] {
        check_periodic("growing edits 2D", &p2, 2500, drive);
        check_periodic("growing edits 3D", &p3, 2000, drive);
    }
}

#[test]
fn growing_radii_with_moving_walls() {
    // A piston and a paddle, left at their velocities or steered every frame, against
    // growing bodies: their contacts are the growing ones in the walls' frames, the bounces
    // reverse the surfaces' approach there; run files equal the oracle's, which verify.
    for (k, &seed) in SMALL_SEEDS[..2].iter().enumerate() {
        let rate = [0.05, 0.2][k];
        let s2 = growing(
            with_moving_walls(gas_scene::<2>(80, 0.3, (0.2, 0.6), seed)),
            rate,
        );
        let s3 = growing(
            with_moving_walls(gas_scene::<3>(50, 0.15, (0.5, 0.5), seed)),
            rate,
        );
        for drive in [Drive::Events, Drive::FrameWalls { dt: 0.05 }] {
            let label = format!("growing moving walls 2D seed {seed} {drive:?}");
            let oracle = check_all_driven(&label, &s2, 1200, drive);
            verifies(&label, &s2, &oracle);
            let hits = moving_wall_hits(&s2, &oracle);
            assert!(hits.iter().all(|&h| h >= 3), "{label}: few hits {hits:?}");
            let label = format!("growing moving walls 3D seed {seed} {drive:?}");
            let oracle = check_all_driven(&label, &s3, 1000, drive);
            verifies(&label, &s3, &oracle);
            let hits = moving_wall_hits(&s3, &oracle);
            assert!(hits.iter().all(|&h| h >= 3), "{label}: few hits {hits:?}");
        }
    }
}

#[test]
fn growing_radii_with_per_body_restitution() {
    // Growth bounces with each pair's restitution (the mean of the bodies'; 1 under the TC
    // model soon after another), at walls with the body's own, plain and kicked: run files
    // equal the oracle's, which verify.
    for (k, &seed) in SMALL_SEEDS[..2].iter().enumerate() {
        let tc = [None, Some(1e-3)][k];
        let s2 = growing(
            inelastic(gas_scene::<2>(100, 0.3, (0.2, 0.6), seed), tc),
            0.1,
        );
        let s3 = growing(
            inelastic(gas_scene::<3>(60, 0.15, (0.5, 0.5), seed), tc),
            0.1,
        );
        let p2 = growing(
            inelastic(periodic_gas::<2>(100, 0.35, (0.3, 0.42), seed), tc),
            0.2,
        );
        for drive in [Drive::Events, Drive::Kicks { every: 11 }] {
            let label = format!("growing restitution 2D seed {seed} {drive:?}");
            let oracle = check_all_driven(&label, &s2, 1500, drive);
            verifies(&label, &s2, &oracle);
            let label = format!("growing restitution 3D seed {seed} {drive:?}");
            let oracle = check_all_driven(&label, &s3, 1200, drive);
            verifies(&label, &s3, &oracle);
        }
        let label = format!("growing restitution periodic 2D seed {seed}");
        check_periodic(&label, &p2, 1500, Drive::Events);
    }
}

#[test]
fn growing_radii_with_kinematic_bodies() {
    // Kinematic bodies grow like the others and push growing bodies by the growth rule;
    // kicks steer them (kinematic ones included), frames interleave; run files equal the
    // oracle's, which verify.
    for (k, &seed) in SMALL_SEEDS[..2].iter().enumerate() {
        let rate = [0.05, 0.2][k];
        let s2 = growing(
            with_kinematic(gas_scene::<2>(80, 0.3, (0.2, 0.6), seed), 4),
            rate,
        );
        let s3 = growing(
            with_kinematic(gas_scene::<3>(50, 0.15, (0.3, 0.5), seed), 3),
            rate,
        );
        let walled = growing(
            with_moving_walls(with_kinematic(
                inelastic(gas_scene::<2>(80, 0.3, (0.2, 0.6), seed), Some(1e-3)),
                3,
            )),
            rate,
        );
        for drive in [
            Drive::Events,
            Drive::Kicks { every: 5 },
            Drive::Frames { dt: 0.05 },
        ] {
            let label = format!("growing kinematic 2D seed {seed} {drive:?}");
            let oracle = check_all_driven(&label, &s2, 1500, drive);
            verifies(&label, &s2, &oracle);
            let label = format!("growing kinematic 3D seed {seed} {drive:?}");
            let oracle = check_all_driven(&label, &s3, 1200, drive);
            verifies(&label, &s3, &oracle);
        }
        // All three together: kinematic bodies, per-body restitution with tc, moving walls.
        let label = format!("growing kinematic restitution moving walls seed {seed}");
        let oracle = check_all_driven(&label, &walled, 1500, Drive::FrameWalls { dt: 0.05 });
        verifies(&label, &walled, &oracle);
    }
}
