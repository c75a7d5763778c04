//! Rods (segment walls in 3D) under gravity: scene validation, analytic contacts in whole
//! runs with every finder, run files that verify, and how bounces that die away on a rod end.

use ccdsim::generate::box_walls;
use ccdsim::record::{RunReader, RunWriter};
use ccdsim::verify::Verifier;
use ccdsim::Gravity;
use ccdsim::{BodySpec, EventKind, Halt, MovingWall, Scene, Simulation, Vector, Wall};

const FINDERS: [&str; 4] = ["all-pairs", "bvh", "sedgewick", "cells"];
const G: f64 = 9.81;

/// A box 8 × 8 × 12 m with a level rod along x at `(·, 4, 3)`, and one ball of radius 0.5
/// at `pos` moving at `vel`, under gravity along −z, with the given restitution.
fn rod_scene(pos: [f64; 3], vel: [f64; 3], restitution: f64) -> Scene<3> {
    let mut walls = box_walls(Vector([8.0, 8.0, 12.0]));
    walls.push(Wall::Segment {
        a: Vector([2.0, 4.0, 3.0]),
        b: Vector([6.0, 4.0, 3.0]),
    });
    let mut scene = Scene::<3> {
        bodies: vec![BodySpec::new(Vector(pos), Vector(vel), 0.5)],
        walls,
        ..Scene::default()
    };
    scene.settings.gravity = Gravity::new(&[0.0, 0.0, -G]);
    scene.settings.restitution = restitution;
    scene
}

/// The index of the rod in [`rod_scene`]: after the box's six planes.
const ROD: u32 = 6;

/// Runs `scene` with `finder` for at most `events` events, recording it; checks that the
/// run file verifies, and returns it with the simulation.
fn recorded(scene: &Scene<3>, finder: &str, events: u64) -> (Vec<u8>, Simulation<3>) {
    let mut sim = Simulation::new(scene, finder).unwrap();
    let mut w = RunWriter::new(Vec::new(), finder.into(), scene).unwrap();
    sim.run_events_with(events, |c| w.write_event(c).unwrap());
    let bytes = w.finish(sim.time()).unwrap();
    let mut r = RunReader::<_, 3>::new(&bytes[..], finder.into()).unwrap();
    let (records, end) = r.read_events().unwrap();
    let mut v = Verifier::new(scene);
    for c in &records {
        v.check(c)
            .unwrap_or_else(|e| panic!("[{finder}] fails verify: {e}"));
    }
    v.finish(end.unwrap())
        .unwrap_or_else(|e| panic!("[{finder}] fails verify: {e}"));
    (bytes, sim)
}

#[test]
fn rods_are_accepted_under_gravity_static_and_moving() {
    let mut scene = rod_scene([4.0, 4.0, 6.0], [0.0, 0.0, 0.0], 1.0);
    assert_eq!(scene.validate(), Ok(()));
    scene.moving_walls.push(MovingWall {
        wall: Wall::Segment {
            a: Vector([1.0, 1.0, 8.0]),
            b: Vector([7.0, 1.0, 8.0]),
        },
        velocity: Vector([0.0, 0.5, 0.0]),
    });
    assert_eq!(scene.validate(), Ok(()));
    // What stays refused is refused for its own reason: a ball on the rod.
    scene.bodies[0].pos = Vector([4.0, 4.0, 3.2]);
    let e = scene.validate().unwrap_err().to_string();
    assert!(e.contains("body 0") && e.contains("wall 6"), "{e}");
}

#[test]
fn an_elastic_ball_bounces_on_a_rod_with_the_free_fall_period() {
    // Dropped from rest right above the rod, its centre 2 m above the contact height 3.5:
    // it bounces straight back up, every 2·√(2·2/g), with every finder alike.
    let scene = rod_scene([4.5, 4.0, 5.5], [0.0, 0.0, 0.0], 1.0);
    let fall = (4.0 / G).sqrt();
    let mut files = Vec::new();
    for finder in FINDERS {
        let (bytes, _) = recorded(&scene, finder, 10);
        let mut sim = Simulation::new(&scene, finder).unwrap();
        for k in 0..10 {
            let c = sim.step_event().unwrap();
            assert_eq!((c.event.kind, c.event.b), (EventKind::Wall, ROD));
            let want = fall * (1.0 + 2.0 * f64::from(k));
            assert!(
                (c.event.time - want).abs() < 1e-12 * (1.0 + want),
                "[{finder}] bounce {k} at {} not {want}",
                c.event.time
            );
            assert!((c.pos[0][2] - 3.5).abs() < 1e-12, "{:?}", c.pos[0]);
            assert!((c.vel[0][2] - (2.0 * G * 2.0).sqrt()).abs() < 1e-10);
        }
        files.push(bytes);
    }
    assert!(files.windows(2).all(|w| w[0] == w[1]), "run files differ");
}

#[test]
fn a_growing_ball_dropped_onto_a_rod_meets_it_when_its_grown_radius_does() {
    // Dropped from rest with its centre at 5.5, 2.5 above the rod at height 3, its radius
    // 0.5·(1 + Γt): it meets the rod when 2.5 − ½·g·t² = 0.5·(1 + Γt), the positive root of
    // ½·g·t² + 0.5·Γ·t − 2 = 0; every finder alike, and the run file verifies.
    let rate = 0.4;
    let mut scene = rod_scene([4.5, 4.0, 5.5], [0.0, 0.0, 0.0], 1.0);
    scene.settings.growth = Some(ccdsim::Growth { rate });
    let (b, c) = (0.5 * rate, -2.0);
    let want = (-b + (b * b - 4.0 * (0.5 * G) * c).sqrt()) / G;
    let mut times = Vec::new();
    for finder in FINDERS {
        let mut sim = Simulation::new(&scene, finder).unwrap();
        let hit = sim.step_event().unwrap();
        assert_eq!(
            (hit.event.kind, hit.event.b),
            (EventKind::Wall, ROD),
            "[{finder}]"
        );
        let t = hit.event.time;
        assert!((t - want).abs() < 1e-12, "[{finder}] at {t}, not {want}");
        let grown = 0.5 * (1.0 + rate * t);
        assert!(
            (hit.pos[0][2] - 3.0 - grown).abs() < 1e-12,
            "{:?}",
            hit.pos[0]
        );
        // The growth rule sends it up at (1 + e)·ṙ − e·u with e = 1 and u = −g·t: 2·ṙ + g·t.
        let up = 2.0 * 0.5 * rate + G * t;
        assert!((hit.vel[0][2] - up).abs() < 1e-10, "{:?}", hit.vel[0]);
        times.push(t.to_bits());
        recorded(&scene, finder, 200);
    }
    assert!(times.windows(2).all(|w| w[0] == w[1]), "{times:?}");
}

#[test]
fn a_ball_thrown_past_the_rod_falls_back_onto_it() {
    // Thrown up from below and beyond the rod's end (x = 6): it rises past the end, clear of
    // it, and comes down onto the rod's top; the first event is that landing.
    let scene = rod_scene([7.5, 4.1, 1.0], [-2.5, 0.0, 8.0], 1.0);
    let mut times = Vec::new();
    for finder in FINDERS {
        let mut sim = Simulation::new(&scene, finder).unwrap();
        let c = sim.step_event().unwrap();
        assert_eq!(
            (c.event.kind, c.event.b),
            (EventKind::Wall, ROD),
            "[{finder}]"
        );
        let p = c.pos[0];
        let lateral = ((p[1] - 4.0).powi(2) + (p[2] - 3.0).powi(2)).sqrt();
        assert!((lateral - 0.5).abs() < 1e-12, "[{finder}] {p:?}");
        assert!(
            p[0] > 2.0 && p[0] < 6.0 && p[2] > 3.0,
            "[{finder}] on top: {p:?}"
        );
        // It had been beyond the end when it rose through the rod's height.
        let rise = (8.0 - (64.0f64 - 2.0 * G * 2.0).sqrt()) / G;
        assert!(7.5 - 2.5 * rise > 6.5, "rose at x = {}", 7.5 - 2.5 * rise);
        times.push(c.event.time.to_bits());
        recorded(&scene, finder, 200);
    }
    assert!(times.windows(2).all(|w| w[0] == w[1]), "{times:?}");
}

#[test]
fn bounces_that_die_away_on_a_rod_halt_the_run() {
    // Restitution 0.5 right above the rod: the bounces die away as on a floor, and since a
    // rod holds no body (it would roll off around it), the run stops with `Halt::Resting` at
    // the Zeno time, the same event for every finder, with or without `rest_speed`.
    for rest_speed in [None, Some(0.5)] {
        let mut scene = rod_scene([4.5, 4.0, 4.5], [0.0, 0.0, 0.0], 0.5);
        scene.settings.rest_speed = rest_speed;
        let mut ends = Vec::new();
        for finder in FINDERS {
            let (bytes, sim) = recorded(&scene, finder, 100_000);
            let Some(Halt::Resting { body, wall, time }) = sim.halt() else {
                panic!("[{finder}] expected a resting halt, got {:?}", sim.halt());
            };
            assert_eq!((body, wall), (0, ROD as usize), "[{finder}]");
            // t₁ (1 + 2e/(1 − e)) = 3 t₁, t₁ = √(2·1/g) the first fall.
            let t1 = (2.0 / G).sqrt();
            assert!((time - 3.0 * t1).abs() < 1e-6, "[{finder}] rests at {time}");
            assert!(sim.stats().events < 100_000, "[{finder}] the run stops");
            ends.push((bytes, time.to_bits()));
        }
        assert!(ends.windows(2).all(|w| w[0] == w[1]), "{rest_speed:?}");
    }
}

#[test]
fn a_slow_ball_off_the_top_of_a_rod_leaves_it() {
    // Dropped 0.1 m to the side of the rod's top, with restitution 0.5 and `rest_speed`:
    // it does not rest on the rod; its bounces push it round and off, and it ends on the
    // floor (or the run halts there), in finitely many events, alike for every finder.
    let mut scene = rod_scene([4.5, 4.1, 4.5], [0.0, 0.0, 0.0], 0.5);
    scene.settings.rest_speed = Some(0.5);
    let mut files = Vec::new();
    for finder in FINDERS {
        let (bytes, sim) = recorded(&scene, finder, 100_000);
        assert!(sim.stats().events < 100_000, "[{finder}] the run ends");
        let w = sim.world();
        let z = w.position_at(0, sim.time())[2];
        assert!(z < 2.0, "[{finder}] ended at height {z} ({:?})", sim.halt());
        files.push(bytes);
    }
    assert!(files.windows(2).all(|w| w[0] == w[1]), "run files differ");
}
