//! The `cells` finder against the all-pairs oracle on every event of whole runs, on what
//! stresses a grid beyond the generic finder suite (`finder_suite.rs`, which runs every
//! finder): dense and strongly polydisperse gases, tables of many walls, tilted planes, open
//! worlds that bodies leave, periodic boxes (small ones too), velocity edits after peeking.

use ccdsim::finder::all_pairs_next_event;
use ccdsim::generate::{box_walls, gas, rack, GasConfig, RackConfig};
use ccdsim::{BodySpec, Scene, Simulation, Vector, Wall};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

const SEEDS: [u64; 3] = [1, 2, 0xC0FFEE];

/// Steps `sim` for up to `events` events, checking before each that its next event is the
/// oracle's bit for bit. Returns the number of events checked. (In periodic worlds, peeking
/// applies the box exits before the next collision, so the oracle is asked after the peek;
/// the exits themselves are compared one by one in the finder's unit tests.)
fn check_run<const D: usize>(sim: &mut Simulation<D>, events: u64) -> u64 {
    let mut checked = 0;
    while checked < events {
        let got = sim.peek_event();
        let oracle = all_pairs_next_event(sim.world());
        match (oracle, got) {
            (None, None) => break,
            (Some(o), Some(g)) => assert_eq!(
                (o.time.to_bits(), o.kind, o.a, o.b),
                (g.time.to_bits(), g.kind, g.a, g.b),
                "event {checked}: oracle {o:?}, cells {g:?}"
            ),
            (o, g) => panic!("event {checked}: oracle {o:?}, cells {g:?}"),
        }
        sim.step_event();
        checked += 1;
    }
    checked
}

fn cfg(n: usize, packing: f64, radii: (f64, f64), seed: u64) -> GasConfig {
    GasConfig {
        n,
        packing,
        radius_min: radii.0,
        radius_max: radii.1,
        speed_min: 0.0,
        speed_max: 5.0,
        seed,
        ..GasConfig::default()
    }
}

fn cells<const D: usize>(scene: &Scene<D>) -> Simulation<D> {
    Simulation::new(scene, "cells").unwrap()
}

#[test]
fn gases_2d() {
    for seed in SEEDS {
        for (n, packing, radii) in [
            (300, 0.3, (0.5, 0.5)),
            (250, 0.45, (0.5, 0.5)),
            (200, 0.25, (0.2, 1.0)),
            (120, 0.02, (0.5, 0.5)),
            (150, 0.2, (0.05, 1.5)),
        ] {
            let scene: Scene<2> = gas(&cfg(n, packing, radii, seed)).unwrap();
            let mut sim = cells(&scene);
            assert_eq!(check_run(&mut sim, 2500), 2500, "n {n} packing {packing}");
        }
    }
}

#[test]
fn gases_3d() {
    for seed in SEEDS {
        for (n, packing, radii) in [
            (250, 0.3, (0.5, 0.5)),
            (200, 0.27, (0.5, 0.5)),
            (150, 0.2, (0.2, 1.0)),
            (100, 0.02, (0.5, 0.5)),
        ] {
            let scene: Scene<3> = gas(&cfg(n, packing, radii, seed)).unwrap();
            let mut sim = cells(&scene);
            assert_eq!(check_run(&mut sim, 2000), 2000, "n {n} packing {packing}");
        }
    }
}

#[test]
fn billiard_break() {
    let mut sim = cells(&rack(&RackConfig::default()));
    assert_eq!(check_run(&mut sim, 3000), 3000);
}

/// A gas in a table whose four sides are cut into many collinear segments, with short free
/// segments (pins) scattered where they touch no body.
fn pinball(seed: u64, pieces: usize, pins: usize) -> Scene<2> {
    let mut scene: Scene<2> = gas(&cfg(150, 0.15, (0.3, 0.6), seed)).unwrap();
    let Wall::Segment { b: corner, .. } = scene.walls[0] else {
        unreachable!()
    };
    let side = corner[0];
    let c = [[0.0, 0.0], [side, 0.0], [side, side], [0.0, side]];
    let mut walls = Vec::new();
    for k in 0..4 {
        let (a, b) = (Vector(c[k]), Vector(c[(k + 1) % 4]));
        for p in 0..pieces {
            let s0 = p as f64 / pieces as f64;
            let s1 = (p + 1) as f64 / pieces as f64;
            let end = if p + 1 == pieces { b } else { a + (b - a) * s1 };
            walls.push(Wall::Segment {
                a: if p == 0 { a } else { a + (b - a) * s0 },
                b: end,
            });
        }
    }
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut placed = 0;
    while placed < pins {
        let a = Vector([
            rng.random_range(1.0..side - 1.0),
            rng.random_range(1.0..side - 1.0),
        ]);
        let b = a + Vector([rng.random_range(-1.5..1.5), rng.random_range(-1.5..1.5)]);
        let wall = Wall::Segment { a, b };
        if scene
            .bodies
            .iter()
            .all(|body| ccdsim::scene::wall_clearance(&wall, body.pos) > body.radius * 1.01)
        {
            walls.push(wall);
            placed += 1;
        }
    }
    scene.walls = walls;
    scene.validate().unwrap();
    scene
}

#[test]
fn many_walls() {
    for seed in SEEDS {
        let scene = pinball(seed, 400, 60);
        assert!(scene.walls.len() > 1600);
        let mut sim = cells(&scene);
        assert_eq!(check_run(&mut sim, 1500), 1500);
    }
}

#[test]
fn tilted_planes_3d() {
    for seed in SEEDS {
        let mut scene: Scene<3> = gas(&cfg(200, 0.2, (0.3, 0.7), seed)).unwrap();
        let Wall::Plane { point: far, .. } = scene.walls[1] else {
            unreachable!()
        };
        let side = far[0];
        // Cut two corners and add a sloping floor.
        scene.walls.push(Wall::Plane {
            point: Vector([0.0, 0.0, side * 0.3]),
            normal: Vector([1.0, 1.0, 0.0]),
        });
        scene.walls.push(Wall::Plane {
            point: Vector([side, side, side]),
            normal: Vector([-1.0, -1.0, -1.0]),
        });
        scene.walls.push(Wall::Plane {
            point: Vector([0.0, 0.0, side * 0.1]),
            normal: Vector([0.1, 0.2, 1.0]),
        });
        let walls = scene.walls.clone();
        scene.bodies.retain(|b| {
            walls
                .iter()
                .all(|w| ccdsim::scene::wall_clearance(w, b.pos) > b.radius)
        });
        scene.validate().unwrap();
        let mut sim = cells(&scene);
        assert_eq!(check_run(&mut sim, 2000), 2000);
    }
}

#[test]
fn open_world_bodies_fly_away() {
    for seed in SEEDS {
        let mut scene: Scene<2> = gas(&cfg(150, 0.3, (0.3, 0.8), seed)).unwrap();
        scene.walls.clear();
        let mut sim = cells(&scene);
        let n = check_run(&mut sim, 100_000);
        assert!(n > 100 && n < 100_000, "{n} events");
        let mut scene: Scene<3> = gas(&cfg(120, 0.3, (0.3, 0.8), seed)).unwrap();
        scene.walls.clear();
        let mut sim = cells(&scene);
        let n = check_run(&mut sim, 100_000);
        assert!(n > 50 && n < 100_000, "{n} events");
    }
}

#[test]
fn newtons_cradle_and_touching_bodies() {
    let mut bodies: Vec<BodySpec<2>> = (0..6)
        .map(|k| BodySpec::new(Vector([3.0 + k as f64, 2.0]), Vector([0.0, 0.0]), 0.5))
        .collect();
    bodies[0].pos = Vector([1.0, 2.0]);
    bodies[0].vel = Vector([1.0, 0.0]);
    let scene = Scene {
        bodies,
        walls: box_walls(Vector([12.0, 4.0])),
        ..Scene::default()
    };
    let mut sim = cells(&scene);
    assert_eq!(check_run(&mut sim, 500), 500);
}

#[test]
fn degenerate_scenes() {
    // Everything at rest: no event ever.
    let rest = Scene::<2> {
        bodies: vec![
            BodySpec::new(Vector([1.0, 1.0]), Vector([0.0, 0.0]), 0.5),
            BodySpec::new(Vector([2.0, 1.0]), Vector([0.0, 0.0]), 0.5),
        ],
        walls: box_walls(Vector([4.0, 4.0])),
        ..Scene::default()
    };
    assert_eq!(check_run(&mut cells(&rest), 10), 0);
    // One body in a box, one body in the void, no body at all.
    let one = Scene::<3> {
        bodies: vec![BodySpec::new(
            Vector([1.0, 2.0, 3.0]),
            Vector([0.3, -1.0, 0.7]),
            0.5,
        )],
        walls: box_walls(Vector([4.0, 5.0, 6.0])),
        ..Scene::default()
    };
    assert_eq!(check_run(&mut cells(&one), 200), 200);
    let void = Scene::<3> {
        walls: Vec::new(),
        ..one.clone()
    };
    assert_eq!(check_run(&mut cells(&void), 10), 0);
    let empty = Scene::<2>::default();
    assert_eq!(check_run(&mut cells(&empty), 10), 0);
    // Walls only.
    let walls_only = Scene::<2> {
        walls: box_walls(Vector([4.0, 4.0])),
        ..Scene::default()
    };
    assert_eq!(check_run(&mut cells(&walls_only), 10), 0);
}

#[test]
fn velocity_edits_after_peeking() {
    for seed in SEEDS {
        let scene: Scene<2> = gas(&cfg(150, 0.3, (0.3, 0.7), seed)).unwrap();
        let mut sim = cells(&scene);
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        for _ in 0..100 {
            check_run(&mut sim, 30);
            // Peek far ahead, then change a velocity at the current time: the finder has
            // processed crossings beyond it and must undo them.
            sim.peek_event();
            let i = rng.random_range(0..150);
            let v = Vector([rng.random_range(-8.0..8.0), rng.random_range(-8.0..8.0)]);
            sim.set_velocity(i, v).unwrap();
            let dt = rng.random_range(0.0..0.05);
            sim.run_until(sim.time() + dt);
        }
    }
}

#[test]
fn whole_runs_are_identical_to_all_pairs() {
    let scene: Scene<3> = gas(&cfg(150, 0.3, (0.3, 0.7), 11)).unwrap();
    let mut a = Simulation::new(&scene, "all-pairs").unwrap();
    let mut b = cells(&scene);
    let (mut ca, mut cb) = (Vec::new(), Vec::new());
    a.run_until_with(10.0, |c| ca.push(*c));
    b.run_until_with(10.0, |c| cb.push(*c));
    assert!(ca.len() > 1000);
    assert_eq!(ca, cb);
    assert_eq!(a.stats(), b.stats());
}

#[test]
fn registered_and_reports_memory() {
    assert!(ccdsim::FINDER_NAMES.contains(&"cells"));
    let scene: Scene<2> = gas(&cfg(100, 0.3, (0.5, 0.5), 4)).unwrap();
    let mut sim = cells(&scene);
    sim.run_events(1000);
    let (finder, world) = sim.finder_mut();
    assert_eq!(finder.name(), "cells");
    let mem = finder.memory().unwrap();
    assert!(mem.peak_bytes >= mem.bytes && mem.bytes > 0);
    assert!(!finder.debug_boxes(world).is_empty());
}

fn periodic_cfg(n: usize, packing: f64, radii: (f64, f64), seed: u64) -> GasConfig {
    GasConfig {
        periodic: true,
        ..cfg(n, packing, radii, seed)
    }
}

#[test]
fn periodic_gases_2d() {
    for seed in SEEDS {
        for (n, packing, radii) in [
            (200, 0.35, (0.5, 0.5)),
            (150, 0.25, (0.2, 1.0)),
            (60, 0.02, (0.5, 0.5)),
        ] {
            let scene: Scene<2> = gas(&periodic_cfg(n, packing, radii, seed)).unwrap();
            let mut sim = cells(&scene);
            assert_eq!(check_run(&mut sim, 1500), 1500, "n {n} packing {packing}");
            assert!(sim.stats().exits > 0);
        }
    }
}

#[test]
fn periodic_gases_3d() {
    for seed in SEEDS {
        for (n, packing, radii) in [(150, 0.25, (0.5, 0.5)), (100, 0.15, (0.2, 1.0))] {
            let scene: Scene<3> = gas(&periodic_cfg(n, packing, radii, seed)).unwrap();
            let mut sim = cells(&scene);
            assert_eq!(check_run(&mut sim, 1200), 1200, "n {n} packing {packing}");
        }
    }
}

/// Boxes too short for three cells along some axis: every image is scanned there.
#[test]
fn small_periodic_boxes() {
    let mut rng = ChaCha8Rng::seed_from_u64(5);
    for (size, n) in [
        ([2.5, 2.5], 2),
        ([2.5, 9.0], 5),
        ([9.0, 3.2], 6),
        ([4.5, 4.5], 4),
    ] {
        let mut bodies: Vec<BodySpec<2>> = Vec::new();
        while bodies.len() < n {
            let p = Vector([
                rng.random_range(0.0..size[0]),
                rng.random_range(0.0..size[1]),
            ]);
            let ok = bodies.iter().all(|b| {
                ccdsim::contact::periodic::min_image(b.pos - p, &Vector(size)).norm() > 1.0
            });
            if ok {
                let v = Vector([rng.random_range(-2.0..2.0), rng.random_range(-2.0..2.0)]);
                bodies.push(BodySpec::new(p, v, 0.5));
            }
        }
        let scene = Scene {
            bodies,
            periodic: Some(Vector(size)),
            ..Scene::default()
        };
        scene.validate().unwrap();
        let mut sim = cells(&scene);
        assert_eq!(check_run(&mut sim, 2000), 2000, "box {size:?}");
    }
    let size = Vector([2.5, 2.6, 9.0]);
    let scene = Scene::<3> {
        bodies: vec![
            BodySpec::new(Vector([0.5, 0.5, 0.5]), Vector([1.0, 0.3, -0.2]), 0.5),
            BodySpec::new(Vector([1.7, 1.8, 4.0]), Vector([-0.4, 0.9, 1.1]), 0.5),
            BodySpec::new(Vector([1.2, 0.4, 7.0]), Vector([0.2, -1.1, 0.7]), 0.5),
        ],
        periodic: Some(size),
        ..Scene::default()
    };
    assert_eq!(check_run(&mut cells(&scene), 2000), 2000);
}

/// Two bodies that cross the box many times before they meet, and two that never do.
#[test]
fn long_flights_in_a_periodic_box() {
    let size = Vector([50.0, 50.0]);
    let scene = Scene::<2> {
        bodies: vec![
            BodySpec::new(Vector([1.0, 1.0]), Vector([3.0, 0.37]), 0.5),
            BodySpec::new(Vector([25.0, 30.0]), Vector([-1.0, 0.05]), 0.5),
        ],
        periodic: Some(size),
        ..Scene::default()
    };
    let mut sim = cells(&scene);
    assert_eq!(check_run(&mut sim, 20), 20);
    assert!(sim.stats().exits > 20);
    let parallel = Scene::<2> {
        bodies: vec![
            BodySpec::new(Vector([1.0, 1.0]), Vector([1.0, 0.0]), 0.5),
            BodySpec::new(Vector([1.0, 3.0]), Vector([2.0, 0.0]), 0.5),
        ],
        periodic: Some(size),
        ..Scene::default()
    };
    let mut sim = cells(&parallel);
    assert!(sim.peek_event().is_none());
    assert!(sim.stats().exits > 1000);
    let mut oracle = Simulation::new(&parallel, "all-pairs").unwrap();
    let mut n = 0;
    oracle.run_until_with(400.0, |_| n += 1);
    assert_eq!(n, 0);
    assert!(oracle.stats().exits > 10);
}

#[test]
fn periodic_runs_pass_the_verifier_and_match_all_pairs() {
    use ccdsim::verify::Verifier;
    let scene: Scene<2> = gas(&periodic_cfg(150, 0.3, (0.3, 0.7), 21)).unwrap();
    let mut a = Simulation::new(&scene, "all-pairs").unwrap();
    let mut b = cells(&scene);
    let (mut ca, mut cb) = (Vec::new(), Vec::new());
    a.run_until_with(15.0, |c| ca.push(*c));
    b.run_until_with(15.0, |c| cb.push(*c));
    assert!(ca.len() > 1000);
    assert_eq!(ca, cb);
    assert_eq!(a.stats(), b.stats());
    let mut v = Verifier::new(&scene);
    for c in &cb {
        v.check(c).unwrap();
    }
    let report = v.finish(15.0).unwrap();
    assert!(report.max_overlap < 1e-9);
    let scene: Scene<3> = gas(&periodic_cfg(100, 0.2, (0.5, 0.5), 22)).unwrap();
    let mut sim = cells(&scene);
    let mut v = Verifier::new(&scene);
    sim.run_until_with(10.0, |c| v.check(c).unwrap());
    v.finish(10.0).unwrap();
}

#[test]
fn periodic_velocity_edits() {
    let scene: Scene<2> = gas(&periodic_cfg(120, 0.3, (0.3, 0.7), 8)).unwrap();
    let mut sim = cells(&scene);
    let mut rng = ChaCha8Rng::seed_from_u64(8);
    for _ in 0..100 {
        check_run(&mut sim, 30);
        sim.peek_event();
        let i = rng.random_range(0..120);
        let v = Vector([rng.random_range(-8.0..8.0), rng.random_range(-8.0..8.0)]);
        sim.set_velocity(i, v).unwrap();
        sim.run_until(sim.time() + rng.random_range(0.0..0.05));
    }
}
