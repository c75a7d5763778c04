//! Growing radii (Lubachevsky–Stillinger): run files (format version 3) that `verify`
//! checks with the growth rule, scene validation, compression to jammed packings, and growth
//! combined with moving walls, per-body restitution and kinematic bodies.

use ccdsim::generate::{gas, GasConfig};
use ccdsim::packing::{
    compress, dilute_start, CompressConfig, CompressStop, SizeMix, MAX_DEFAULT_CONTACT_TOLERANCE,
};
use ccdsim::record::RunWriter;
use ccdsim::verify::VerifyReport;
use ccdsim::Growth;
use ccdsim::{BodySpec, EventKind, MovingWall, Scene, SceneError, Simulation, Vector, Wall};
use replay::{records, replay};

use crate::replay;

fn growing<const D: usize>(n: usize, periodic: bool, rate: f64) -> Scene<D> {
    let mut scene = gas::<D>(&GasConfig {
        n,
        packing: 0.25,
        radius_min: 0.3,
        radius_max: 0.6,
        periodic,
        seed: 11,
        ..Default::default()
    })
    .unwrap();
    scene.settings.growth = Some(Growth { rate });
    scene
}

/// The run file of `events` events of `scene` with `finder`, in memory.
fn run_file<const D: usize>(scene: &Scene<D>, finder: &str, events: u64) -> Vec<u8> {
    let mut sim = Simulation::new(scene, finder).unwrap();
    let mut w = RunWriter::new(Vec::new(), finder.to_string(), scene).unwrap();
    sim.run_events_with(events, |c| w.write_event(c).unwrap());
    w.finish(sim.time()).unwrap()
}

#[test]
fn growing_runs_are_version_3_and_verify() {
    for (periodic, rate) in [(false, 0.05), (true, 0.2)] {
        let s2 = growing::<2>(200, periodic, rate);
        let bytes = run_file(&s2, "cells", 20_000);
        assert_eq!(u32::from_le_bytes(bytes[8..12].try_into().unwrap()), 3);
        let (scene, events, end) = records::<2>(&bytes);
        assert_eq!(scene.settings.growth, s2.settings.growth);
        for all_pairs in [false, true] {
            let report = replay(&scene, &events, end, all_pairs).unwrap();
            assert_eq!(report.events, 20_000);
            // Growth collisions heat the gas.
            assert!(report.kinetic_energy_end > report.kinetic_energy_start);
        }
        let s3 = growing::<3>(150, periodic, rate);
        let (scene, events, end) = records::<3>(&run_file(&s3, "cells", 10_000));
        replay(&scene, &events, end, false).unwrap();
    }
}

#[test]
fn verify_catches_runs_that_break_the_growth() {
    let s = growing::<2>(150, true, 0.2);
    let (scene, events, end) = records::<2>(&run_file(&s, "cells", 5_000));
    // Read as if radii were fixed: contacts come at distances that fixed radii never reach.
    let mut fixed = scene.clone();
    fixed.settings.growth = None;
    let err = replay(&fixed, &events, end, false).unwrap_err();
    assert!(err.contains("at a distance"), "{err}");
    // A collision that reverses the centres' approach instead of the surfaces'.
    let k = events
        .iter()
        .position(|c| c.event.kind == ccdsim::EventKind::Body)
        .unwrap();
    let mut tampered = events.clone();
    let (i, j) = (tampered[k].event.a as usize, tampered[k].event.b as usize);
    let (mi, mj) = (
        scene.bodies[i].effective_mass(),
        scene.bodies[j].effective_mass(),
    );
    // An extra impulse along the line of centres: momentum stays, the normal speed does not.
    let n = tampered[k].pos[1] - tampered[k].pos[0];
    let n = n * (1e-3 / n.norm());
    tampered[k].vel[0] -= n * (1.0 / mi);
    tampered[k].vel[1] += n * (1.0 / mj);
    let err = replay(&scene, &tampered, end, false).unwrap_err();
    assert!(err.contains("growth rule"), "{err}");
    // Radii grown faster than the run grew them: the bodies' contacts come too late.
    let mut faster = scene.clone();
    faster.settings.growth = Some(Growth { rate: 0.25 });
    assert!(replay(&faster, &events, end, false).is_err());
}

#[test]
fn growth_settings_are_validated() {
    for (text, field) in [
        (r#"{"rate": 0}"#, "settings.growth.rate"),
        (r#"{"rate": -1}"#, "settings.growth.rate"),
        (r#"{"speed": 1}"#, "unknown field"),
    ] {
        let json = format!(
            r#"{{"dim": 2, "settings": {{"growth": {text}}}, "bodies": [{{"pos": [0, 0], "vel": [1, 0], "radius": 1}}]}}"#
        );
        let err = Scene::<2>::from_json(&json).unwrap_err();
        assert!(err.to_string().contains(field), "{text}: {err}");
        if field.starts_with("settings") {
            assert!(matches!(err, SceneError::NonPositive(_)), "{err:?}");
        }
    }
}

#[test]
fn a_binary_mixture_compresses_past_0_7_in_2d() {
    // DynamO's issue 76: compression of a 2D binary mixture fails near φ = 0.7. Here it jams
    // near 0.84, the random close packing of the 1:1.4 mixture.
    let scene = dilute_start::<2>(400, 0.3, SizeMix::Bidisperse(1.4), true, 7).unwrap();
    let config = CompressConfig {
        rate: 0.02,
        until_pressure: 1e9,
        ..CompressConfig::default()
    };
    let mut blocks = 0;
    let mut last = 0.0;
    let packed = compress(&scene, "cells", &config, |b| {
        assert!(
            b.packing_fraction >= last,
            "the packing fraction only grows"
        );
        last = b.packing_fraction;
        blocks += 1;
    })
    .unwrap();
    assert_eq!(packed.stop, CompressStop::Pressure);
    assert!(packed.reduced_pressure >= 1e9);
    assert!(
        (0.82..0.86).contains(&packed.packing_fraction),
        "{}",
        packed.packing_fraction
    );
    assert!(blocks > 10);
    // Jammed: most bodies are held by at least D + 1 contacts, about 2D on average.
    assert!(
        packed.contacts.rattlers.len() < 400 / 5,
        "{:?}",
        packed.contacts.rattlers.len()
    );
    assert!(
        (3.6..=4.0).contains(&packed.contacts.mean_contacts),
        "{}",
        packed.contacts.mean_contacts
    );
    // The packing reads back as a valid scene, its radii fixed and its pressure high: a short
    // run keeps every pair apart and collides often.
    let text = packed.scene.to_json();
    let back = Scene::<2>::from_json(&text).unwrap();
    assert!(back.settings.growth.is_none());
    let mut sim = Simulation::new(&back, "cells").unwrap();
    assert_eq!(sim.run_events(10_000), 10_000);
    assert!(sim.stats().max_overlap < 1e-9);
}

#[test]
fn every_finder_compresses_to_the_same_packing() {
    let scene = dilute_start::<3>(60, 0.2, SizeMix::Polydisperse(0.2), false, 3).unwrap();
    let config = CompressConfig {
        rate: 0.05,
        until_pressure: 1e5,
        ..CompressConfig::default()
    };
    let reference = compress(&scene, "all-pairs", &config, |_| {}).unwrap();
    assert_eq!(reference.stop, CompressStop::Pressure);
    for name in ["bvh", "sedgewick", "cells"] {
        let packed = compress(&scene, name, &config, |_| {}).unwrap();
        assert_eq!(packed, reference, "{name}");
    }
}

#[test]
fn a_compression_stopped_at_a_low_pressure_counts_only_near_gaps_as_contacts() {
    // 100 · D / Z would be 10 contact distances at Z = 30: every pair in reach a "contact".
    let scene = dilute_start::<3>(300, 0.2, SizeMix::Monodisperse, true, 2).unwrap();
    let config = CompressConfig {
        rate: 0.05,
        until_pressure: 30.0,
        ..CompressConfig::default()
    };
    let packed = compress(&scene, "cells", &config, |_| {}).unwrap();
    assert_eq!(packed.stop, CompressStop::Pressure);
    assert_eq!(packed.contact_tolerance, MAX_DEFAULT_CONTACT_TOLERANCE);
    // The nearest shell of neighbours (about 8 a body here), not every body in reach (the
    // old rule counted all 299 others).
    assert!(
        packed.contacts.mean_contacts < 13.0,
        "{}",
        packed.contacts.mean_contacts
    );
    // Past a reduced pressure of 1000 · D the rule is unchanged.
    let tight = CompressConfig {
        until_pressure: 1e4,
        max_events: Some(1),
        ..config
    };
    let packed = compress(&scene, "cells", &tight, |_| {}).unwrap();
    assert_eq!(packed.contact_tolerance, 100.0 * 3.0 / 1e4);
}

#[test]
fn bad_compressions_are_refused() {
    let scene = dilute_start::<2>(20, 0.2, SizeMix::Monodisperse, true, 1).unwrap();
    for config in [
        CompressConfig {
            rate: 0.0,
            ..CompressConfig::default()
        },
        CompressConfig {
            until_pressure: 0.5,
            ..CompressConfig::default()
        },
        CompressConfig {
            temperature: f64::NAN,
            ..CompressConfig::default()
        },
    ] {
        assert!(
            compress(&scene, "cells", &config, |_| {}).is_err(),
            "{config:?}"
        );
    }
    let mut open = scene.clone();
    open.periodic = None;
    let err = compress(&open, "cells", &CompressConfig::default(), |_| {}).unwrap_err();
    assert!(err.to_string().contains("volume"), "{err}");
}

/// A periodic growing packing in which, every 0.1 s, a body is taken out and a body of its
/// current radius put back where it was, moving the other way: the run file of `finder`.
fn refilled_run(finder: &str) -> (Vec<u8>, Vec<(f64, f64, f64)>) {
    let scene = growing::<2>(60, true, 0.05);
    let mut sim = Simulation::new(&scene, finder).unwrap();
    let mut run = RunWriter::new_steered(Vec::new(), finder.into(), &scene).unwrap();
    sim.record_edits(true);
    let mut radii = Vec::new();
    for frame in 0..30u32 {
        for c in sim.advance(0.1) {
            run.write_event(&c).unwrap();
        }
        let i = (frame as usize * 7) % 60;
        let (pos, vel, r) = (
            sim.position(i),
            sim.world().velocity_at(i, sim.time()),
            sim.radius(i),
        );
        sim.remove_body(i).unwrap();
        let spec = ccdsim::BodySpec::new(pos, -vel, r);
        assert_eq!(
            sim.add_body(spec).unwrap(),
            i,
            "the slot just vacated is filled"
        );
        radii.push((sim.time(), r, sim.radius(i)));
        for c in sim.take_edits() {
            run.write_event(&c).unwrap();
        }
    }
    let end = sim.time();
    for c in sim.advance(0.5) {
        run.write_event(&c).unwrap();
    }
    let last = sim.radius(29 * 7 % 60);
    radii.push((end, last, sim.radius(29 * 7 % 60)));
    (run.finish(sim.time()).unwrap(), radii)
}

#[test]
fn bodies_added_to_a_growing_packing_grow_with_it_and_every_finder_agrees() {
    let (want, radii) = refilled_run("all-pairs");
    for &(t, given, now) in &radii[..radii.len() - 1] {
        // The added body's radius is the one given, up to the rounding of the stored one.
        assert!(
            (now - given).abs() <= 4.0 * f64::EPSILON * given,
            "{t}: {given} {now}"
        );
    }
    // From then on it grows with every other: by the growth factor 1 + 0.05 t, relatively.
    let &(t1, r1, _) = &radii[radii.len() - 2];
    let &(t2, _, r2) = radii.last().unwrap();
    let ratio = (1.0 + 0.05 * (t2 + 0.5)) / (1.0 + 0.05 * t1);
    assert!((r2 / r1 - ratio).abs() < 1e-12, "{} vs {ratio}", r2 / r1);
    for finder in ["bvh", "sedgewick", "cells"] {
        assert!(
            refilled_run(finder).0 == want,
            "[{finder}] run files differ"
        );
    }
    let (scene, events, end) = records::<2>(&want);
    let adds = events
        .iter()
        .filter(|c| c.event.kind == ccdsim::EventKind::Edit && c.event.b == 1)
        .count();
    assert_eq!(adds, 30);
    for all_pairs in [false, true] {
        replay(&scene, &events, end, all_pairs).unwrap();
    }
}

/// Every finder, for the runs that must agree bit for bit.
const FINDERS: [&str; 4] = ["all-pairs", "bvh", "sedgewick", "cells"];

/// A 2D moving wall: a plane through `point` facing `normal`, translating at `velocity`.
fn moving_plane(point: [f64; 2], normal: [f64; 2], velocity: [f64; 2]) -> MovingWall<2> {
    MovingWall {
        wall: Wall::Plane {
            point: Vector(point),
            normal: Vector(normal),
        },
        velocity: Vector(velocity),
    }
}

/// `scene`'s radii growing at `rate` per second.
fn with_growth<const D: usize>(mut scene: Scene<D>, rate: f64) -> Scene<D> {
    scene.settings.growth = Some(Growth { rate });
    scene
}

#[test]
fn a_growing_ball_meets_a_receding_piston_when_it_outgrows_it() {
    // Radius 1 growing at Γ·r = 0.5 m/s, at rest at x = 0; the piston's face at x = 4 recedes
    // at 0.25 m/s: the gap 4 + 0.25 t − (1 + 0.5 t) closes at t = 12.
    let scene = with_growth(
        Scene::<2> {
            bodies: vec![BodySpec::new(Vector([0.0, 0.0]), Vector([0.0, 0.0]), 1.0)],
            moving_walls: vec![moving_plane([4.0, 0.0], [-1.0, 0.0], [0.25, 0.0])],
            ..Scene::default()
        },
        0.5,
    );
    for finder in FINDERS {
        let mut sim = Simulation::new(&scene, finder).unwrap();
        let hit = sim.step_event().unwrap();
        assert_eq!(
            (hit.event.kind, hit.event.b),
            (EventKind::Wall, 0),
            "[{finder}]"
        );
        assert_eq!(hit.event.time, 12.0, "[{finder}]");
        // The surface approached the piston at σ̇ − u = 0.5 − 0.25 and leaves it at 0.25:
        // u' = 2σ̇ − u = 0.75 relative to the piston, so the ball moves at −0.5.
        assert_eq!(hit.vel[0].0, [-0.5, 0.0], "[{finder}]");
        assert_eq!(sim.radius(0), 7.0, "[{finder}]");
        // It now recedes at 0.75 from a piston it outgrows at 0.5 m/s only: they never meet.
        assert!(sim.step_event().is_none(), "[{finder}]");
    }
}

#[test]
fn a_growing_ball_between_a_wall_and_a_closing_piston() {
    // Radius 0.5 growing at 0.25 m/s, moving right at 1 m/s from x = 5; a fixed wall at x = 0
    // and a piston at x = 14.5 closing at 0.25 m/s. Every time and speed below is exact.
    let scene = with_growth(
        Scene::<2> {
            bodies: vec![BodySpec::new(Vector([5.0, 0.0]), Vector([1.0, 0.0]), 0.5)],
            walls: vec![Wall::Plane {
                point: Vector([0.0, 0.0]),
                normal: Vector([1.0, 0.0]),
            }],
            moving_walls: vec![moving_plane([14.5, 0.0], [-1.0, 0.0], [-0.25, 0.0])],
            ..Scene::default()
        },
        0.5,
    );
    // (time, wall, velocity after): the right edge 5.5 + 1.25 t meets the piston at
    // 14.5 − 0.25 t at t = 6 (u = −1.25 relative to it, u' = 2·0.25 + 1.25 = 1.75); the left
    // edge 11 − 2.25 (t − 6) meets the wall at t = 10 (u = −2, u' = 2.5); the right edge
    // 6 + 2.75 (t − 10) meets the piston at 12 − 0.25 (t − 10) at t = 12 (u = −2.75,
    // u' = 3.25 relative to the piston: −3.5 in the lab).
    let expected = [(6.0, 1, -2.0), (10.0, 0, 2.5), (12.0, 1, -3.5)];
    let mut files = Vec::new();
    for finder in FINDERS {
        let mut sim = Simulation::new(&scene, finder).unwrap();
        let mut w = RunWriter::new(Vec::new(), finder.into(), &scene).unwrap();
        for (t, wall, v) in expected {
            let hit = sim.step_event().unwrap();
            w.write_event(&hit).unwrap();
            assert_eq!(
                (hit.event.time, hit.event.b, hit.vel[0].0),
                (t, wall, [v, 0.0]),
                "[{finder}]"
            );
        }
        files.push(w.finish(sim.time()).unwrap());
    }
    let (back, events, end) = records::<2>(&files[0]);
    let report = replay(&back, &events, end, true).unwrap();
    // The piston did work on the ball, the growth too: kinetic energy only grew, and the
    // moving wall's collisions account for their share.
    let m = scene.bodies[0].effective_mass();
    let end_energy = 0.5 * m * 3.5 * 3.5;
    assert!((report.kinetic_energy_end - end_energy).abs() < 1e-12 * end_energy);
    let work = 0.5 * m * ((2.0f64 * 2.0 - 1.0) + (3.5 * 3.5 - 2.5 * 2.5));
    assert!((report.wall_work - work).abs() < 1e-12 * work, "{report:?}");
    assert!(files.windows(2).all(|f| f[0] == f[1]));
}

#[test]
fn a_growing_ball_meets_the_end_of_a_moving_segment() {
    // A segment from (8, 3) up to (8, 10) sweeps left at 0.5 m/s towards a ball of radius 1
    // at rest at the origin, growing at 0.5 m/s. In the segment's frame the ball moves right
    // at 0.5: it would reach the segment's line at t = 7, below the segment's end, so the
    // end point, at distance √(64 − 8t + t²/4 + 9) = 1 + t/2, comes first: t = 8, at radius 5,
    // with the end at (4, 3) from the ball.
    let scene = with_growth(
        Scene::<2> {
            bodies: vec![BodySpec::new(Vector([0.0, 0.0]), Vector([0.0, 0.0]), 1.0)],
            moving_walls: vec![MovingWall {
                wall: Wall::Segment {
                    a: Vector([8.0, 3.0]),
                    b: Vector([8.0, 10.0]),
                },
                velocity: Vector([-0.5, 0.0]),
            }],
            ..Scene::default()
        },
        0.5,
    );
    for finder in FINDERS {
        let mut sim = Simulation::new(&scene, finder).unwrap();
        let hit = sim.step_event().unwrap();
        assert_eq!((hit.event.time, hit.event.b), (8.0, 0), "[{finder}]");
        // Along n = −(4, 3)/5 (from the end to the ball): u = (v − w)·n = −0.4 and σ̇ = 0.5,
        // so the surface approached at 0.9 and leaves at 0.9: u' = 1.4, v' = 1.8 n.
        let n = Vector([-0.8, -0.6]);
        let v = hit.vel[0];
        assert!((v - n * 1.8).norm() < 1e-12, "[{finder}] {v:?}");
        let parting = (v - Vector([-0.5, 0.0])).dot(n) - 0.5;
        assert!((parting - 0.9).abs() < 1e-12, "[{finder}] {parting}");
    }
}

/// A gas of `n` growing bodies in a walled box with a piston (a plane closing from the top)
/// and, in 2D, a paddle (a segment sweeping across).
fn growing_gas_with_moving_walls<const D: usize>(n: usize, seed: u64) -> Scene<D> {
    let mut scene = gas::<D>(&GasConfig {
        n,
        packing: 0.2,
        radius_min: 0.3,
        radius_max: 0.6,
        seed,
        ..Default::default()
    })
    .unwrap();
    let (lo, hi) = ccdsim::wall::walls_bounds(&scene.walls).unwrap();
    let top = D - 1;
    let mut normal = Vector::<D>::ZERO;
    normal[top] = -1.0;
    let mut point = lo;
    point[top] = hi[top];
    scene.moving_walls.push(MovingWall {
        wall: Wall::Plane { point, normal },
        velocity: normal * 0.3,
    });
    if D == 2 {
        let (mut a, mut b) = (lo, lo);
        a[1] = lo[1] + 0.5 * (hi[1] - lo[1]);
        b[1] = lo[1] + 0.8 * (hi[1] - lo[1]);
        let mut v = Vector::<D>::ZERO;
        v[0] = 0.4;
        scene.moving_walls.push(MovingWall {
            wall: Wall::Segment { a, b },
            velocity: v,
        });
    }
    with_growth(scene, 0.05)
}

/// The run files of `events` events of `scene` with every finder, after asserting that they
/// are byte-identical, and the all-pairs one verified in grid and all-pairs mode.
fn same_run_with_every_finder<const D: usize>(scene: &Scene<D>, events: u64) -> VerifyReport {
    let files: Vec<Vec<u8>> = FINDERS.iter().map(|f| run_file(scene, f, events)).collect();
    for (f, bytes) in FINDERS.iter().zip(&files) {
        assert!(bytes == &files[0], "[{f}] run file differs from all-pairs'");
    }
    let (back, recorded, end) = records::<D>(&files[0]);
    assert_eq!(recorded.len() as u64, events);
    replay(&back, &recorded, end, true).unwrap();
    replay(&back, &recorded, end, false).unwrap()
}

#[test]
fn growing_gases_with_moving_walls_run_alike_with_every_finder_and_verify() {
    for seed in [3, 8] {
        let s2 = growing_gas_with_moving_walls::<2>(60, seed);
        let report = same_run_with_every_finder(&s2, 3000);
        assert!(report.wall_work != 0.0, "the walls were met");
        let s3 = growing_gas_with_moving_walls::<3>(40, seed);
        let report = same_run_with_every_finder(&s3, 2000);
        assert!(report.wall_work != 0.0, "the piston was met");
    }
}

#[test]
fn verify_rejects_a_moving_wall_bounce_that_ignores_the_growth() {
    let scene = growing_gas_with_moving_walls::<2>(60, 3);
    let (scene, events, end) = records::<2>(&run_file(&scene, "cells", 3000));
    let first_moving = scene.walls.len() as u32;
    let k = events
        .iter()
        .position(|c| c.event.kind == EventKind::Wall && c.event.b >= first_moving)
        .expect("a moving wall is met");
    // The bounce of fixed radii: the centre's velocity relative to the wall reflected, which
    // keeps the kinetic energy in the wall's frame but leaves the surfaces approaching.
    let c = events[k];
    let i = c.event.a as usize;
    let m = ccdsim::motion::start_motions(&scene.moving_walls, scene.start_time)
        [(c.event.b - first_moving) as usize];
    let wall = ccdsim::motion::translated(
        &scene.moving_walls[(c.event.b - first_moving) as usize].wall,
        m.offset_at(c.event.time),
    );
    let n = ccdsim::contact::narrow::wall_normal(&wall, c.pos[0]).unwrap();
    let before = events[..k]
        .iter()
        .rev()
        .find_map(|p| match p.event.kind {
            EventKind::Body if p.event.a as usize == i => Some(p.vel[0]),
            EventKind::Body if p.event.b as usize == i => Some(p.vel[1]),
            EventKind::Wall if p.event.a as usize == i => Some(p.vel[0]),
            _ => None,
        })
        .unwrap_or(scene.bodies[i].vel);
    let relative = before - m.velocity;
    let mut forged = events.clone();
    forged[k].vel[0] = before - n * (2.0 * relative.dot(n));
    let err = replay(&scene, &forged, end, false).unwrap_err();
    assert!(
        err.contains("growth rule") && err.contains(&format!("event {k}")),
        "{err}"
    );
    // The run as recorded passes.
    replay(&scene, &events, end, false).unwrap();
}

/// Two growing balls (radius 0.5, growing at 0.25 m/s each) approaching head on at 1 m/s
/// between planes at x = ±4.125, with restitutions 0.5 and 1.
fn inelastic_pair() -> Scene<2> {
    let ball = |x: f64, v: f64, e: f64| BodySpec {
        restitution: Some(e),
        ..BodySpec::new(Vector([x, 0.0]), Vector([v, 0.0]), 0.5)
    };
    let plane = |x: f64, nx: f64| Wall::Plane {
        point: Vector([x, 0.0]),
        normal: Vector([nx, 0.0]),
    };
    with_growth(
        Scene::<2> {
            bodies: vec![ball(-2.0, 0.5, 0.5), ball(2.0, -0.5, 1.0)],
            walls: vec![plane(-4.125, 1.0), plane(4.125, -1.0)],
            ..Scene::default()
        },
        0.5,
    )
}

#[test]
fn growth_bounces_take_each_pair_restitution() {
    let scene = inelastic_pair();
    // (time, kind, body, velocities after). The gap 4 − t between the centres meets the
    // contact distance 1 + 0.5 t at t = 2; with u = −1, σ̇ = 0.5 and the pair's e = 0.75,
    // u' = 1.75·0.5 + 0.75 = 1.625: ±0.8125. Each ball, radius 1 then, meets its wall
    // 2.125 m away at t = 4 (closing at 0.8125 + 0.25); ball 0 (e = 0.5) leaves at
    // 1.5·0.25 + 0.5·0.8125 = 0.78125, ball 1 (e = 1) at 2·0.25 + 0.8125 = 1.3125.
    let expected = [
        (2.0, EventKind::Body, 0, [-0.8125, 0.8125]),
        (4.0, EventKind::Wall, 0, [0.78125, 0.0]),
        (4.0, EventKind::Wall, 1, [-1.3125, 0.0]),
    ];
    let mut files = Vec::new();
    for finder in FINDERS {
        let mut sim = Simulation::new(&scene, finder).unwrap();
        let mut w = RunWriter::new(Vec::new(), finder.into(), &scene).unwrap();
        for (t, kind, a, v) in expected {
            let c = sim.step_event().unwrap();
            w.write_event(&c).unwrap();
            assert_eq!(
                (c.event.time, c.event.kind, c.event.a),
                (t, kind, a),
                "[{finder}]"
            );
            assert_eq!([c.vel[0][0], c.vel[1][0]], v, "[{finder}]");
        }
        files.push(w.finish(sim.time()).unwrap());
    }
    assert!(files.windows(2).all(|f| f[0] == f[1]));
    let (back, events, end) = records::<2>(&files[0]);
    replay(&back, &events, end, true).unwrap();
    // Read with the scene's restitution for every collision, the pair's bounce breaks the
    // growth rule.
    let mut one = back.clone();
    for b in &mut one.bodies {
        b.restitution = None;
    }
    let err = replay(&one, &events, end, true).unwrap_err();
    assert!(
        err.contains("event 0") && err.contains("growth rule"),
        "{err}"
    );
    // And with ball 1's restitution for ball 0, its wall bounce does.
    let mut swapped = back.clone();
    swapped.bodies[0].restitution = Some(1.0);
    swapped.bodies[1].restitution = Some(0.5);
    let err = replay(&swapped, &events[..2], end, true).unwrap_err();
    assert!(
        err.contains("event 1") && err.contains("growth rule"),
        "{err}"
    );
}

/// A growing gas whose bodies have restitutions 0.3 to 1, and the TC model.
fn inelastic_growing_gas<const D: usize>(n: usize, seed: u64) -> Scene<D> {
    let mut scene = gas::<D>(&GasConfig {
        n,
        packing: 0.25,
        radius_min: 0.3,
        radius_max: 0.6,
        seed,
        ..Default::default()
    })
    .unwrap();
    scene.settings.restitution = 0.9;
    scene.settings.tc = Some(1e-3);
    for (k, b) in scene.bodies.iter_mut().enumerate() {
        b.restitution = [Some(0.3), None, Some(1.0), Some(0.7)][k % 4];
    }
    with_growth(scene, 0.1)
}

#[test]
fn inelastic_growing_gases_run_alike_with_every_finder_and_verify() {
    for seed in [5, 9] {
        let s2 = inelastic_growing_gas::<2>(80, seed);
        same_run_with_every_finder(&s2, 4000);
        let s3 = inelastic_growing_gas::<3>(50, seed);
        same_run_with_every_finder(&s3, 3000);
    }
}

/// A kinematic ball (radius 0.5, from x = 0 at 1 m/s) overtaking a ball at rest at x = 4,
/// both growing at 0.25 m/s, in front of a plane at x = 8.25.
fn kinematic_push() -> Scene<2> {
    with_growth(
        Scene::<2> {
            bodies: vec![
                BodySpec {
                    kinematic: true,
                    ..BodySpec::new(Vector([0.0, 0.0]), Vector([1.0, 0.0]), 0.5)
                },
                BodySpec::new(Vector([4.0, 0.0]), Vector([0.0, 0.0]), 0.5),
            ],
            walls: vec![Wall::Plane {
                point: Vector([8.25, 0.0]),
                normal: Vector([-1.0, 0.0]),
            }],
            ..Scene::default()
        },
        0.5,
    )
}

#[test]
fn a_kinematic_body_pushes_a_growing_ball_by_the_growth_rule() {
    let scene = kinematic_push();
    // The gap 4 − t meets the contact distance 1 + 0.5 t at t = 2: u = −1, σ̇ = 0.5, so
    // u' = 2σ̇ − u = 2 and the ball, taking all of the change, leaves at 3 m/s; the
    // kinematic ball keeps its 1 m/s. The ball, radius 1, then meets the plane 3.25 m away
    // at t = 3 (closing at 3 + 0.25) and leaves at −(2·0.25 + 3) = −3.5.
    let mut files = Vec::new();
    for finder in FINDERS {
        let mut sim = Simulation::new(&scene, finder).unwrap();
        let mut w = RunWriter::new(Vec::new(), finder.into(), &scene).unwrap();
        let push = sim.step_event().unwrap();
        assert_eq!(
            (
                push.event.time,
                push.event.kind,
                push.vel[0].0,
                push.vel[1].0
            ),
            (2.0, EventKind::Body, [1.0, 0.0], [3.0, 0.0]),
            "[{finder}]"
        );
        // The surfaces part as fast as they approached: 3 − 1 − 0.5 = σ̇ − u = 1.5.
        assert_eq!(
            sim.radius(0),
            1.0,
            "[{finder}] the kinematic ball grows too"
        );
        let bounce = sim.step_event().unwrap();
        assert_eq!(
            (bounce.event.time, bounce.event.kind, bounce.vel[0].0),
            (3.0, EventKind::Wall, [-3.5, 0.0]),
            "[{finder}]"
        );
        w.write_event(&push).unwrap();
        w.write_event(&bounce).unwrap();
        sim.run_events_with(200, |c| w.write_event(c).unwrap());
        files.push(w.finish(sim.time()).unwrap());
    }
    assert!(files.windows(2).all(|f| f[0] == f[1]));
    let (back, events, end) = records::<2>(&files[0]);
    assert!(events.len() > 5, "the kinematic ball keeps pushing");
    replay(&back, &events, end, true).unwrap();
    // A forged push that moves the kinematic ball, or that reverses the centres' approach
    // (u' = 1: the ball at 2 m/s), is rejected.
    let mut moved = events.clone();
    moved[0].vel[0] = Vector([0.5, 0.0]);
    let err = replay(&back, &moved, end, true).unwrap_err();
    assert!(err.contains("kinematic body 0 changes velocity"), "{err}");
    let mut fixed = events.clone();
    fixed[0].vel[1] = Vector([2.0, 0.0]);
    let err = replay(&back, &fixed[..1], end, true).unwrap_err();
    assert!(
        err.contains("event 0") && err.contains("growth rule"),
        "{err}"
    );
}

#[test]
fn growing_gases_with_kinematic_bodies_run_alike_with_every_finder_and_verify() {
    // Kinematic bodies as fast as the others, and three times as fast.
    for speed_up in [1.0, 3.0] {
        let mut s2 = growing::<2>(80, false, 0.1);
        let mut s3 = growing::<3>(50, false, 0.1);
        for b in s2.bodies.iter_mut().take(4) {
            b.kinematic = true;
            b.vel = b.vel * speed_up;
        }
        for b in s3.bodies.iter_mut().take(3) {
            b.kinematic = true;
            b.vel = b.vel * speed_up;
        }
        let (events2, events3) = (3000, 2000);
        let report = same_run_with_every_finder(&s2, events2);
        assert!(report.body_collisions > 0);
        same_run_with_every_finder(&s3, events3);
    }
}
