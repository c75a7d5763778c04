//! Rough bodies (spins, inertia factors, tangential restitution): collisions change spins
//! and tangential velocities but never the times of contact, so every finder must still give
//! the oracle's run file byte for byte, alone and with gravity, growth, inelastic collisions,
//! kinematic bodies, edits and periodic boxes; and `verify` must accept the oracle's runs.

use super::*;

/// `scene` made rough: tangential restitution `beta` for all, every third body with its own
/// (0.3) and inertia factor (0.25), every other body spinning.
fn rough<const D: usize>(mut scene: Scene<D>, beta: f64) -> Scene<D> {
    scene.settings.tangential_restitution = Some(beta);
    for (k, b) in scene.bodies.iter_mut().enumerate() {
        if k % 3 == 2 {
            b.tangential_restitution = Some(0.3);
            b.inertia = Some(0.25);
        }
        if k % 2 == 0 {
            let w = [1.5, -0.75, 3.0];
            b.spin = Some(if D == 2 {
                ccdsim::Spin::Planar(w[k % 3])
            } else {
                ccdsim::Spin::Spatial(w)
            });
        }
    }
    scene
}

fn check_rough<const D: usize>() {
    for (k, beta) in [1.0, 0.5, -0.5].into_iter().enumerate() {
        let walled = rough(gas_scene::<D>(40, 0.3, (0.3, 0.6), SMALL_SEEDS[k]), beta);
        let label = format!("rough gas β {beta}");
        let run = check_all_run(&label, &walled, 800);
        verifies(&label, &walled, &run);
        let periodic = rough(periodic_gas::<D>(40, 0.3, (0.3, 0.6), SMALL_SEEDS[k]), beta);
        let label = format!("rough periodic gas β {beta}");
        let run = check_all_driven(&label, &periodic, 800, Drive::Events);
        verifies(&label, &periodic, &run);
    }
    let scene = rough(gas_scene::<D>(30, 0.25, (0.4, 0.4), SMALL_SEEDS[1]), 1.0);
    let mut g = [0.0; D];
    g[D - 1] = -9.81;
    for (label, scene) in [
        ("rough under gravity", falling(scene.clone(), g)),
        ("rough and growing", growing(scene.clone(), 0.05)),
        ("rough and inelastic", inelastic(scene.clone(), Some(1e-3))),
        (
            "rough with kinematic bodies",
            with_kinematic(scene.clone(), 3),
        ),
    ] {
        let run = check_all_run(label, &scene, 600);
        verifies(label, &scene, &run);
    }
    for drive in [
        Drive::Kicks { every: 7 },
        Drive::Frames { dt: 0.13 },
        Drive::Slots { every: 11 },
    ] {
        check_all_driven("rough, steered", &scene, 600, drive);
    }
}

#[test]
fn rough_bodies_2d() {
    check_rough::<2>();
}

#[test]
fn rough_bodies_3d() {
    check_rough::<3>();
}
