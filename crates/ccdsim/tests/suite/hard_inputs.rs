//! Inputs at the edges of `f64` (issue 20): contacts at tiny speeds, contacts beyond the
//! largest time, and times or coordinates too large to resolve a body. Every finder must
//! give the oracle's events and stop at the same place for the same reason.

use ccdsim::{
    make_finder, BodySpec, Collision, FinderOptions, Scene, SceneError, Settings, Simulation,
    Vector, Wall, FINDER_NAMES,
};
use ccdsim::{Halt, Partner};

/// Every finder's collisions over at most `events` events, and where each stopped.
fn run_every_finder<const D: usize>(
    scene: &Scene<D>,
    events: u64,
) -> Vec<(&'static str, Vec<Collision<D>>, Option<Halt>, f64)> {
    FINDER_NAMES
        .iter()
        .map(|&name| {
            let finder = make_finder::<D>(name, &FinderOptions::default()).unwrap();
            let mut sim = Simulation::with_finder(scene, finder).unwrap();
            let mut out = Vec::new();
            sim.run_events_with(events, |c| out.push(*c));
            (name, out, sim.halt(), sim.time())
        })
        .collect()
}

/// Asserts that every finder gave the oracle's collisions bit for bit and stopped alike.
fn assert_all_agree<const D: usize>(runs: &[(&str, Vec<Collision<D>>, Option<Halt>, f64)]) {
    let (_, oracle, halt, time) = &runs[0];
    for (name, got, h, t) in &runs[1..] {
        assert_eq!(got.len(), oracle.len(), "{name}: event count");
        for (k, (a, b)) in got.iter().zip(oracle).enumerate() {
            assert_eq!(a.event, b.event, "{name}: event {k}");
            assert_eq!(
                a.event.time.to_bits(),
                b.event.time.to_bits(),
                "{name}: {k}"
            );
            assert_eq!(a.vel, b.vel, "{name}: event {k}");
        }
        assert_eq!(h, halt, "{name}: halt");
        assert_eq!(t.to_bits(), time.to_bits(), "{name}: final time");
    }
}

fn ball<const D: usize>(pos: [f64; D], vel: [f64; D], radius: f64) -> BodySpec<D> {
    BodySpec::new(Vector(pos), Vector(vel), radius)
}

fn square_table(side: f64) -> Vec<Wall<2>> {
    let c = [[0.0, 0.0], [side, 0.0], [side, side], [0.0, side]];
    (0..4)
        .map(|k| Wall::Segment {
            a: Vector(c[k]),
            b: Vector(c[(k + 1) % 4]),
        })
        .collect()
}

fn cube(side: f64) -> Vec<Wall<3>> {
    (0..3)
        .flat_map(|d| {
            let mut n = [0.0; 3];
            n[d] = 1.0;
            let mut far = [0.0; 3];
            far[d] = side;
            [
                Wall::Plane {
                    point: Vector([0.0; 3]),
                    normal: Vector(n),
                },
                Wall::Plane {
                    point: Vector(far),
                    normal: Vector(n.map(|c| -c)),
                },
            ]
        })
        .collect()
}

/// Two balls closing at 2·10⁻²⁸⁰ m/s used to pass through each other (no event at all).
#[test]
fn pairs_at_tiny_speeds_collide() {
    for speed in [1e-280, 1e-300, 1e-307] {
        let scene = Scene::<2> {
            bodies: vec![
                ball([1.0, 1.0], [speed, 0.0], 0.5),
                ball([3.0, 1.0], [-speed, 0.0], 0.5),
            ],
            ..Scene::default()
        };
        let runs = run_every_finder(&scene, 10);
        assert_all_agree(&runs);
        let hits = &runs[0].1;
        assert_eq!(hits.len(), 1, "speed {speed:e}: the contact must be found");
        let t = hits[0].event.time;
        assert!(
            (t * speed - 0.5).abs() < 1e-12,
            "t = {t:e} at speed {speed:e}"
        );
        assert_eq!(runs[0].2, None, "a contact at a finite time is no halt");
    }
    // 3D, off the axes.
    let v = [3e-295, -2e-295, 1e-295];
    let scene = Scene::<3> {
        bodies: vec![
            ball([1.0, 1.0, 1.0], v, 0.5),
            ball([2.2, 0.2, 1.4], v.map(|c| -c), 0.5),
        ],
        ..Scene::default()
    };
    let runs = run_every_finder(&scene, 10);
    assert_all_agree(&runs);
    assert_eq!(runs[0].1.len(), 1);
}

/// A ball bouncing between floor and ceiling with restitution 0.5 used to miss the ceiling
/// after 901 bounces and fly off. Now it bounces until its next contact lies beyond the
/// largest time, and the run says so.
#[test]
fn inelastic_bounces_continue_until_the_time_is_not_representable() {
    let scene = Scene::<2> {
        bodies: vec![ball([1.0, 1.0], [0.0, 1.0], 0.25)],
        walls: square_table(2.0),
        settings: Settings {
            restitution: 0.5,
            ..Settings::default()
        },
        ..Scene::default()
    };
    let runs = run_every_finder(&scene, 5000);
    assert_all_agree(&runs);
    let (_, hits, halt, time) = &runs[0];
    assert!(hits.len() > 1000, "only {} bounces", hits.len());
    // Floor (wall 0) and ceiling (wall 2) alternate to the end.
    for (k, c) in hits.iter().enumerate() {
        assert_eq!(c.event.b, if k % 2 == 0 { 2 } else { 0 }, "bounce {k}");
        let y = c.pos[0][1];
        assert!(
            (y - 1.75).abs() < 1e-9 || (y - 0.25).abs() < 1e-9,
            "bounce {k} at {y}"
        );
    }
    assert!(time.is_finite());
    match halt {
        Some(Halt::BeyondRange {
            body: 0, partner, ..
        }) => {
            assert!(matches!(partner, Partner::Wall(0 | 2)), "{partner:?}")
        }
        other => panic!("expected a halt beyond the largest time, got {other:?}"),
    }
    // The same in 3D between planes.
    let scene = Scene::<3> {
        bodies: vec![ball([1.0, 1.0, 1.0], [0.0, 0.0, 1.0], 0.25)],
        walls: cube(2.0),
        settings: Settings {
            restitution: 0.5,
            ..Settings::default()
        },
        ..Scene::default()
    };
    let runs = run_every_finder(&scene, 5000);
    assert_all_agree(&runs);
    assert!(runs[0].1.len() > 1000);
    assert!(matches!(runs[0].2, Some(Halt::BeyondRange { .. })));
}

/// Bodies at rest and bodies flying apart in an open world are no halt: nothing will happen.
#[test]
fn worlds_with_nothing_left_to_happen_do_not_halt() {
    let scene = Scene::<2> {
        bodies: vec![
            ball([1.0, 1.0], [0.0, 0.0], 0.5),
            ball([3.0, 1.0], [0.0, 0.0], 0.5),
            ball([5.0, 1.0], [1.0, 0.0], 0.5),
            ball([5.0, 3.0], [1.0, 0.0], 0.5),
        ],
        ..Scene::default()
    };
    let runs = run_every_finder(&scene, 10);
    assert_all_agree(&runs);
    assert!(runs[0].1.is_empty());
    assert_eq!(runs[0].2, None);
}

/// Two bodies moving in parallel whose velocities differ by a subnormal amount meet only
/// after more than the largest time: the halt names the pair.
#[test]
fn a_pair_beyond_the_largest_time_is_named() {
    let scene = Scene::<2> {
        bodies: vec![
            ball([1.0, 1.0], [1.0, 0.0], 0.5),
            ball([4.0, 1.0], [1.0, 0.0], 0.5),
            ball([1.0, 5.0], [1e-320, 0.0], 0.5),
            ball([4.0, 5.0], [0.0, 0.0], 0.5),
        ],
        ..Scene::default()
    };
    let runs = run_every_finder(&scene, 10);
    assert_all_agree(&runs);
    assert!(runs[0].1.is_empty());
    assert!(
        matches!(
            runs[0].2,
            Some(Halt::BeyondRange {
                body: 2,
                partner: Partner::Body(3),
                ..
            })
        ),
        "{:?}",
        runs[0].2
    );
}

/// A start time of 10¹⁷ s (the clock moves in steps of 16 s) used to invent collisions.
#[test]
fn scenes_whose_start_time_cannot_resolve_contacts_are_refused() {
    let scene = Scene::<2> {
        bodies: vec![
            ball([1.0, 1.0], [1.0, 0.0], 0.5),
            ball([3.0, 1.0], [-1.0, 0.0], 0.5),
        ],
        start_time: 1e17,
        ..Scene::default()
    };
    match scene.validate() {
        Err(e @ SceneError::Resolution { .. }) => {
            let msg = e.to_string();
            assert!(
                msg.contains("body 0") && msg.contains("start_time"),
                "{msg}"
            );
        }
        other => panic!("expected a resolution error, got {other:?}"),
    }
    // Bodies at rest are resolved at any time.
    let resting = Scene::<2> {
        bodies: vec![ball([1.0, 1.0], [0.0, 0.0], 0.5)],
        start_time: 1e17,
        ..Scene::default()
    };
    assert_eq!(resting.validate(), Ok(()));
}

/// Positions near 10⁶ m with 1 mm balls: runs that `verify` then rejected.
#[test]
fn scenes_whose_coordinates_cannot_resolve_contacts_are_refused() {
    let scene = Scene::<3> {
        bodies: vec![
            ball([1e6, 0.0, 0.0], [1.0, 0.0, 0.0], 1e-3),
            ball([1e6 + 0.01, 0.0, 0.0], [-1.0, 0.0, 0.0], 1e-3),
        ],
        ..Scene::default()
    };
    match scene.validate() {
        Err(e @ SceneError::Resolution { .. }) => {
            assert!(e.to_string().contains("coordinates"), "{e}")
        }
        other => panic!("expected a resolution error, got {other:?}"),
    }
}

/// A run that goes on until the clock can no longer resolve the bodies stops before the
/// first unresolved event, with every finder at the same event.
#[test]
fn runs_stop_where_time_no_longer_resolves_the_bodies() {
    let scene = Scene::<2> {
        bodies: vec![
            ball([1.0, 1.0], [3.0, 1.0], 0.2),
            ball([3.0, 1.5], [-2.0, 1.5], 0.3),
        ],
        walls: square_table(4.0),
        start_time: 2f64.powi(30),
        ..Scene::default()
    };
    // At 2³⁰ s the clock resolves 2⁻²² s: at 3 m/s that is 7·10⁻⁷ m, far beyond 5·10⁻¹⁰ of a
    // radius, so the scene is refused. Started at 0 instead, the run reaches the same limit
    // on its own (near 2¹⁸ s, where the clock resolves 2⁻³⁴ s) and must stop there.
    assert!(matches!(
        scene.validate(),
        Err(SceneError::Resolution { .. })
    ));
    let scene = Scene::<2> {
        start_time: 0.0,
        ..scene
    };
    let mut sim = Simulation::new(&scene, "cells").unwrap();
    sim.run_until(1e9);
    let Some(Halt::Resolution { time, body, error }) = sim.halt() else {
        panic!("expected a resolution halt, got {:?}", sim.halt());
    };
    assert!(error > ccdsim::RESOLUTION_LIMIT * scene.bodies[body].radius);
    assert!(time > 1e3 && time < 1e9, "{time}");
    assert!(sim.time() < time, "the unresolved event is not resolved");
    let events = sim.stats().events;
    let runs = run_every_finder(&scene, events + 10);
    assert_all_agree(&runs);
    assert_eq!(runs[0].1.len() as u64, events);
    assert_eq!(runs[0].2, sim.halt());
}

/// A halt ahead of the clock does not keep `run_until` from reaching a time before it: the
/// frames of a game loop go on up to the unresolved event, and stop there.
#[test]
fn run_until_reaches_times_before_the_unresolved_event() {
    let scene = Scene::<2> {
        bodies: vec![
            ball([1.0, 1.0], [3.0, 1.0], 0.2),
            ball([3.0, 1.5], [-2.0, 1.5], 0.3),
        ],
        walls: square_table(4.0),
        ..Scene::default()
    };
    let mut probe = Simulation::new(&scene, "cells").unwrap();
    probe.run_until(1e9);
    let Some(Halt::Resolution { time: stop, .. }) = probe.halt() else {
        panic!("expected a resolution halt, got {:?}", probe.halt());
    };
    let mut sim = Simulation::new(&scene, "cells").unwrap();
    let before = stop * (1.0 - 1e-12);
    sim.run_until(before);
    assert!(sim.halt().is_some(), "the next event is the unresolved one");
    assert_eq!(sim.time(), before, "the clock reaches the time asked for");
    sim.run_until(stop * 2.0);
    assert!(sim.time() < stop, "but not past the unresolved event");
    // Bodies flying apart for ever in an open world: nothing is left, no halt, the clock moves.
    let apart = Scene::<2> {
        bodies: vec![
            ball([1.0, 1.0], [-1.0, 0.0], 0.5),
            ball([3.0, 1.0], [1.0, 0.0], 0.5),
        ],
        ..Scene::default()
    };
    let mut sim = Simulation::new(&apart, "cells").unwrap();
    sim.run_until(50.0);
    assert_eq!((sim.time(), sim.halt()), (50.0, None));
}
