//! The `sedgewick` finder against the all-pairs oracle on every event of whole runs: random
//! gases in 2D and 3D, the billiard break, and a lattice built so that many events tie exactly.

use ccdsim::finder::all_pairs_next_event;
use ccdsim::generate::{gas, rack, GasConfig, RackConfig};
use ccdsim::{BodySpec, Scene, Simulation, Vector, Wall};

/// Steps `sim` for up to `events` events, checking before each that the finder's next event is
/// the oracle's bit for bit. Returns the number of events checked.
fn check_run<const D: usize>(sim: &mut Simulation<D>, events: u64) -> u64 {
    let mut checked = 0;
    while checked < events {
        let oracle = all_pairs_next_event(sim.world());
        let got = sim.peek_event();
        match (oracle, got) {
            (None, None) => break,
            (Some(o), Some(g)) => {
                assert_eq!(
                    (o.time.to_bits(), o.kind, o.a, o.b),
                    (g.time.to_bits(), g.kind, g.a, g.b),
                    "event {checked}: oracle {o:?}, sedgewick {g:?}"
                );
            }
            (o, g) => panic!("event {checked}: oracle {o:?}, sedgewick {g:?}"),
        }
        sim.step_event();
        checked += 1;
    }
    checked
}

fn gas_cfg(n: usize, seed: u64) -> GasConfig {
    GasConfig {
        n,
        packing: 0.25,
        radius_min: 0.2,
        radius_max: 1.0,
        speed_min: 0.0,
        speed_max: 5.0,
        seed,
        ..GasConfig::default()
    }
}

const SEEDS: [u64; 3] = [1, 2, 0xC0FFEE];

#[test]
fn gas_2d_every_event() {
    for seed in SEEDS {
        let scene: Scene<2> = gas(&gas_cfg(120, seed)).unwrap();
        let mut sim = Simulation::new(&scene, "sedgewick").unwrap();
        assert_eq!(check_run(&mut sim, 4000), 4000);
    }
}

#[test]
fn gas_3d_every_event() {
    for seed in SEEDS {
        let scene: Scene<3> = gas(&gas_cfg(80, seed)).unwrap();
        let mut sim = Simulation::new(&scene, "sedgewick").unwrap();
        assert_eq!(check_run(&mut sim, 3000), 3000);
    }
}

#[test]
fn billiard_break_every_event() {
    let mut sim = Simulation::new(&rack(&RackConfig::default()), "sedgewick").unwrap();
    assert_eq!(check_run(&mut sim, 3000), 3000);
}

/// Bodies whose events tie exactly: in the left half of a 20 × 10 box, five bodies bounce
/// vertically in step between floor and ceiling; in the right half, behind a dividing wall,
/// four rows of two bodies bounce off each other and the side walls in step. Positions, radii
/// and speeds are exact binary fractions, so tied events are truly equal and only the
/// tie-break (kind, a, b) orders them.
fn tie_scene() -> Scene<2> {
    let mut bodies = Vec::new();
    for k in 0..5 {
        let up = if k % 2 == 0 { 1.0 } else { -1.0 };
        bodies.push(BodySpec::new(
            Vector([1.0 + 2.0 * k as f64, 5.0]),
            Vector([0.0, up]),
            0.5,
        ));
    }
    for row in 0..4 {
        let y = 1.5 + 2.0 * row as f64;
        bodies.push(BodySpec::new(Vector([13.0, y]), Vector([1.0, 0.0]), 0.5));
        bodies.push(BodySpec::new(Vector([17.0, y]), Vector([-1.0, 0.0]), 0.5));
    }
    let seg = |a: [f64; 2], b: [f64; 2]| Wall::Segment {
        a: Vector(a),
        b: Vector(b),
    };
    let walls = vec![
        seg([0.0, 0.0], [20.0, 0.0]),
        seg([20.0, 0.0], [20.0, 10.0]),
        seg([20.0, 10.0], [0.0, 10.0]),
        seg([0.0, 10.0], [0.0, 0.0]),
        seg([10.0, 0.0], [10.0, 10.0]),
    ];
    Scene {
        bodies,
        walls,
        ..Scene::default()
    }
}

#[test]
fn ties_resolve_in_the_oracle_order() {
    let scene = tie_scene();
    let mut sim = Simulation::new(&scene, "sedgewick").unwrap();
    // Count how many events share their time with the previous one: the test is only meaningful
    // if ties really happen.
    let mut ties = 0;
    let mut last = f64::NAN;
    for _ in 0..500 {
        let checked = check_run(&mut sim, 1);
        assert_eq!(checked, 1);
        let t = sim.time();
        if t == last {
            ties += 1;
        }
        last = t;
    }
    assert!(ties > 300, "only {ties} tied events");
}

#[test]
fn whole_runs_are_identical_to_all_pairs() {
    let scene: Scene<2> = gas(&gas_cfg(150, 11)).unwrap();
    let mut a = Simulation::new(&scene, "all-pairs").unwrap();
    let mut b = Simulation::new(&scene, "sedgewick").unwrap();
    let (mut ca, mut cb) = (Vec::new(), Vec::new());
    a.run_until_with(20.0, |c| ca.push(*c));
    b.run_until_with(20.0, |c| cb.push(*c));
    assert!(ca.len() > 1000);
    assert_eq!(ca, cb);
    assert_eq!(a.stats(), b.stats());
}

#[test]
fn velocity_edits_are_followed() {
    let scene: Scene<3> = gas(&gas_cfg(60, 5)).unwrap();
    let mut sim = Simulation::new(&scene, "sedgewick").unwrap();
    for k in 0..50 {
        check_run(&mut sim, 40);
        let i = (k * 7) % 60;
        let v = Vector([k as f64 * 0.1 - 2.0, 1.0, -0.5]);
        sim.set_velocity(i, v).unwrap();
    }
}

#[test]
fn registered_and_reports_memory() {
    assert!(ccdsim::FINDER_NAMES.contains(&"sedgewick"));
    let scene: Scene<2> = gas(&gas_cfg(50, 4)).unwrap();
    let mut sim = Simulation::new(&scene, "sedgewick").unwrap();
    sim.run_events(1000);
    let (finder, _) = sim.finder_mut();
    assert_eq!(finder.name(), "sedgewick");
    let mem = finder.memory().unwrap();
    assert!(mem.peak_bytes >= mem.bytes && mem.bytes > 0);
}
