//! The isostatic finish: compressed packings taken to their jamming point, whose contacts then
//! hold them rigid at fixed radii.

use ccdsim::packing::{
    compress, dilute_start, finish_isostatic, CompressConfig, CompressError, IsostaticConfig,
    Packed, SizeMix,
};
use ccdsim::{Scene, Simulation};

/// `n` bodies compressed at Γ = 0.05 until the reduced pressure passes 10⁴.
fn compressed<const D: usize>(n: usize, mix: SizeMix, periodic: bool, seed: u64) -> Packed<D> {
    let start = dilute_start::<D>(n, if D == 2 { 0.3 } else { 0.2 }, mix, periodic, seed).unwrap();
    let config = CompressConfig {
        rate: 0.05,
        until_pressure: 1e4,
        ..CompressConfig::default()
    };
    compress(&start, "cells", &config, |_| {}).unwrap()
}

/// The reduced pressure `P V / (N kT)` of `scene` at fixed radii over `events` events, from
/// the collision virial.
fn pressure_at_fixed_radii<const D: usize>(scene: &Scene<D>, events: u64) -> f64 {
    let mut sim = Simulation::new(scene, "cells").unwrap();
    assert_eq!(sim.run_events(events), events);
    sim.observables().compressibility.unwrap()
}

#[test]
fn an_isostatic_finish_makes_3d_spheres_rigid() {
    let packed = compressed::<3>(250, SizeMix::Monodisperse, true, 5);
    let done = finish_isostatic(&packed, &IsostaticConfig::default(), |_| {}).unwrap();
    let c = &done.contacts;
    let finish = done.finish.unwrap();
    assert!(
        c.is_rigid(),
        "{} < {}",
        c.held_contacts,
        c.isostatic_contacts
    );
    assert!(c.mean_contacts >= 5.95, "{}", c.mean_contacts);
    assert!(c.rattlers.len() <= 12, "{} rattlers", c.rattlers.len());
    assert!(
        finish.mean_overlap <= 1e-6 && finish.minimizations >= 2,
        "{finish:?}"
    );
    assert!(
        finish.radius_scale > 1.0 && finish.radius_scale < 1.01,
        "{finish:?}"
    );
    assert!(done.packing_fraction > packed.packing_fraction);
    // The hard packing: contacts within the tolerance, and at fixed radii a pressure near
    // D / gap (it was 10⁴ under growth, and an unjammed packing's falls).
    let z = pressure_at_fixed_radii(&done.scene, 20 * 250);
    assert!(z > 3e4, "Z = {z}");
    assert!(pressure_at_fixed_radii(&packed.scene, 20 * 250) < z / 3.0);
}

#[test]
fn an_isostatic_finish_holds_discs_between_walls() {
    let packed = compressed::<2>(160, SizeMix::Bidisperse(1.4), false, 2);
    let done = finish_isostatic(&packed, &IsostaticConfig::default(), |_| {}).unwrap();
    let c = &done.contacts;
    assert!(
        c.is_rigid(),
        "{} < {}",
        c.held_contacts,
        c.isostatic_contacts
    );
    assert!(!c.walls.is_empty());
    // Between walls every held disc's two degrees of freedom count.
    let held = 160 - c.rattlers.len();
    assert_eq!(c.isostatic_contacts, 2 * held);
    // The packing reads back as a scene without overlaps.
    Simulation::new(&done.scene, "all-pairs").unwrap();
}

#[test]
fn the_finish_is_deterministic_and_reports_each_jammed_minimum() {
    let packed = compressed::<2>(120, SizeMix::Bidisperse(1.4), true, 7);
    let mut seen = Vec::new();
    let a = finish_isostatic(&packed, &IsostaticConfig::default(), |o| seen.push(o)).unwrap();
    let b = finish_isostatic(&packed, &IsostaticConfig::default(), |_| {}).unwrap();
    assert_eq!(a.scene.to_json(), b.scene.to_json());
    assert_eq!(a.finish, b.finish);
    assert_eq!(*seen.last().unwrap(), a.finish.unwrap().mean_overlap);
    assert!(
        seen.len() >= 2 && seen[0] > seen[seen.len() - 1],
        "{seen:?}"
    );
}

#[test]
fn finishes_that_cannot_work_are_refused() {
    let packed = compressed::<2>(60, SizeMix::Bidisperse(1.4), true, 1);
    for overlap in [0.0, -1.0, 0.5, f64::NAN] {
        let config = IsostaticConfig {
            overlap,
            ..IsostaticConfig::default()
        };
        assert!(matches!(
            finish_isostatic(&packed, &config, |_| {}),
            Err(CompressError::Config(_))
        ));
    }
    // A dilute gas is nowhere near jammed.
    let gas = dilute_start::<2>(60, 0.1, SizeMix::Monodisperse, true, 1).unwrap();
    let dilute = Packed {
        scene: gas,
        ..packed
    };
    let err = finish_isostatic(&dilute, &IsostaticConfig::default(), |_| {}).unwrap_err();
    assert!(err.to_string().contains("far from jammed"), "{err}");
}
