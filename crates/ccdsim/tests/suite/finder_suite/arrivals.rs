//! Arrivals (bodies a scene brings in at given times): every finder must give the oracle's
//! run file byte for byte, the additions recorded as edits, and halt alike when an arrival
//! finds its place taken. The arrivals are adversarial: integer and half-integer coordinates
//! (cell faces), several at one instant, some onto bodies, with gravity, walls, kinematic
//! pegs, inelastic collisions and periodic boxes.

use super::*;
use ccdsim::generate::{galton, GaltonConfig};
use ccdsim::Arrival;

/// `scene` with `count` arrivals, one every `every` seconds, pairs of them at one instant,
/// at half-integer points of its bounds with small integer velocities (some land on bodies,
/// and the run halts there).
fn with_arrivals<const D: usize>(mut scene: Scene<D>, count: usize, every: f64) -> Scene<D> {
    let (lo, hi) = teleport_bounds(&scene);
    let r = scene
        .bodies
        .iter()
        .map(|b| b.radius)
        .fold(f64::INFINITY, f64::min);
    let mut state = 0x5eed_u64;
    for k in 0..count {
        let mut pos = Vector::<D>::ZERO;
        let mut vel = Vector::<D>::ZERO;
        for d in 0..D {
            state = state
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            let span = ((hi[d] - lo[d] - 2.0 * r) * 2.0).floor().max(0.0);
            let steps = (state >> 33) % (span as u64 + 1);
            pos[d] = ((lo[d] + r) * 2.0).ceil() / 2.0 + steps as f64 / 2.0;
            vel[d] = ((state >> 20) % 5) as f64 - 2.0;
        }
        scene.arrivals.push(Arrival {
            time: scene.start_time + (k / 2 + 1) as f64 * every,
            body: BodySpec::new(pos, vel, r),
        });
    }
    // Arrivals that would cross a wall are left out (the scene refuses them).
    let walls = scene.walls.clone();
    scene.arrivals.retain(|a| {
        walls
            .iter()
            .all(|w| ccdsim::scene::wall_clearance(w, a.body.pos) >= a.body.radius)
    });
    scene.validate().expect("valid arrivals");
    scene
}

/// Bodies that arrived in `scene`'s run of `events` events with the `cells` finder.
fn arrived<const D: usize>(scene: &Scene<D>, events: u64) -> u64 {
    let mut sim = Simulation::new(scene, "cells").unwrap();
    sim.run_events(events);
    sim.stats().arrivals
}

fn check_arrivals<const D: usize>() {
    // Dilute, so that most arrivals find their place free (one that does not stops the run).
    let walled = with_arrivals(
        gas_scene::<D>(30, 0.005, (0.3, 0.5), SMALL_SEEDS[0]),
        16,
        0.25,
    );
    check_all("arrivals, walled gas", &walled, 1500);
    let periodic = with_arrivals(
        periodic_gas::<D>(30, 0.005, (0.3, 0.5), SMALL_SEEDS[1]),
        16,
        0.25,
    );
    check_periodic("arrivals, periodic gas", &periodic, 1500, Drive::Events);
    let mut g = [0.0; D];
    g[1] = -9.81;
    let falling_in = with_arrivals(
        inelastic(
            with_kinematic(
                falling(gas_scene::<D>(30, 0.005, (0.4, 0.4), SMALL_SEEDS[2]), g),
                4,
            ),
            Some(1e-3),
        ),
        20,
        0.125,
    );
    check_all(
        "arrivals under gravity, inelastic, kinematic",
        &falling_in,
        3000,
    );
    // The runs compared did bring bodies in.
    assert!(arrived(&walled, 1500) >= 6, "walled");
    assert!(arrived(&periodic, 1500) >= 6, "periodic");
    assert!(arrived(&falling_in, 3000) >= 6, "falling");
}

#[test]
fn arrivals_2d() {
    check_arrivals::<2>();
}

#[test]
fn arrivals_3d() {
    check_arrivals::<3>();
}

/// A small Galton board: balls released one by one onto round kinematic pegs, bouncing
/// under the TC model into walled bins.
#[test]
fn galton_boards() {
    let scene = galton(&GaltonConfig {
        rows: 4,
        balls: 12,
        ..GaltonConfig::default()
    })
    .unwrap();
    check_all("galton board", &scene, 20_000);
    assert_eq!(arrived(&scene, 20_000), 12);
}

/// Every arrival of a scene in one place: the second finds it taken, and every finder stops
/// there alike.
#[test]
fn a_blocked_arrival_stops_every_finder_alike() {
    let mut scene = gas_scene::<2>(20, 0.2, (0.4, 0.4), SMALL_SEEDS[2]);
    let body = BodySpec::new(scene.bodies[0].pos, Vector([0.0, 0.0]), 0.4);
    scene.arrivals.push(Arrival {
        time: 0.0,
        body: body.clone(),
    });
    // At time 0 body 0 is there: blocked at once.
    check_all("blocked arrival", &scene, 500);
    let sim = {
        let mut sim = Simulation::new(&scene, "cells").unwrap();
        sim.run_until(1.0);
        sim
    };
    assert!(
        matches!(sim.halt(), Some(Halt::ArrivalBlocked { time, arrival: 0 }) if time == 0.0),
        "{:?}",
        sim.halt()
    );
    if let Some(Halt::ArrivalBlocked { arrival, .. }) = sim.halt() {
        let a = &scene.arrivals[arrival];
        let near: Vec<(usize, f64)> = (0..sim.world().len())
            .filter(|&j| !sim.world().is_vacant(j))
            .map(|j| {
                (
                    j,
                    (sim.position(j) - a.body.pos).norm() - sim.radius(j) - a.body.radius,
                )
            })
            .filter(|&(_, gap)| gap < 0.0)
            .collect();
        eprintln!(
            "  blocked at {:?} by {near:?}; previous at {:?}",
            a.body.pos.0,
            scene.arrivals[arrival - arrival.min(1)].body.pos.0
        );
    }
}
