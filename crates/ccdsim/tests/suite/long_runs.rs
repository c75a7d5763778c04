//! Whole runs of 10⁵ events: no overlap beyond 1e-9 of a contact distance at any moment,
//! kinetic energy drift below 1e-10, momentum conserved in every body–body collision — all
//! checked by the independent verifier on the recorded run file.

use ccdsim::generate::{rack, RackConfig};
use ccdsim::record::{RunReader, RunWriter};
use ccdsim::verify::Verifier;
use ccdsim::{Scene, Simulation};

const EVENTS: u64 = 100_000;

fn long_run<const D: usize>(scene: &Scene<D>, finder: &str) {
    let mut sim = Simulation::new(scene, finder).unwrap();
    let mut w = RunWriter::new(Vec::new(), "memory".into(), scene).unwrap();
    let done = sim.run_events_with(EVENTS, |c| w.write_event(c).unwrap());
    assert_eq!(done, EVENTS);
    let bytes = w.finish(sim.time()).unwrap();
    let stats = *sim.stats();
    assert!(
        stats.max_overlap <= 1e-9,
        "overlap {} at a contact",
        stats.max_overlap
    );
    let drift = (sim.world().kinetic_energy() - stats.kinetic_energy_start).abs()
        / stats.kinetic_energy_start;
    assert!(drift < 1e-10, "kinetic energy drift {drift}");

    let mut reader = RunReader::<_, D>::new(&bytes[..], "memory".into()).unwrap();
    let mut verifier = Verifier::new(reader.scene());
    let (events, end) = reader.read_events().unwrap();
    assert_eq!(events.len() as u64, EVENTS);
    for c in &events {
        verifier.check(c).unwrap();
    }
    let report = verifier.finish(end.unwrap()).unwrap();
    assert!(report.max_overlap <= 1e-9);
    let drift = (report.kinetic_energy_end - report.kinetic_energy_start).abs()
        / report.kinetic_energy_start;
    assert!(drift < 1e-10, "verifier's kinetic energy drift {drift}");
}

#[test]
fn billiard_break_1e5_events() {
    long_run(&rack(&RackConfig::default()), "all-pairs");
}

/// 1,000 bodies: the exact priority-queue finder gives the oracle's run (the finder suite checks
/// that event by event) at a fraction of the all-pairs cost.
const GAS_FINDER: &str = "sedgewick";

fn gas_scene<const D: usize>(seed: u64) -> Scene<D> {
    ccdsim::generate::gas(&ccdsim::generate::GasConfig {
        n: 1000,
        packing: 0.3,
        radius_min: 0.5,
        radius_max: 1.0,
        speed_min: 0.0,
        speed_max: 1.0,
        seed,
        ..ccdsim::generate::GasConfig::default()
    })
    .unwrap()
}

#[test]
fn gas_2d_1000_bodies_1e5_events() {
    long_run(&gas_scene::<2>(21), GAS_FINDER);
}

#[test]
fn gas_3d_1000_bodies_1e5_events() {
    long_run(&gas_scene::<3>(31), GAS_FINDER);
}
