//! Bodies resting on walls: sliding, ledges, rolling over a segment's end and sliding off it.

use super::*;

/// `scene` (from [`resting`], 2D) with shelves to rest on and slide off: a level one in
/// two collinear pieces, and a tilted one; bodies that overlap them are dropped.
fn with_shelves(mut scene: Scene<2>) -> Scene<2> {
    let (Wall::Plane { point: lo, .. }, Wall::Plane { point: hi, .. }) =
        (scene.walls[0], scene.walls[1])
    else {
        unreachable!("`resting` puts the box's planes first");
    };
    let at =
        |fx: f64, fy: f64| Vector([lo[0] + fx * (hi[0] - lo[0]), lo[1] + fy * (hi[1] - lo[1])]);
    let segment = |a: Vector<2>, b: Vector<2>| Wall::Segment { a, b };
    let shelves = [
        segment(at(0.3, 0.5), at(0.55, 0.5)),
        segment(at(0.8, 0.5), at(0.55, 0.5)),
        segment(at(0.1, 0.75), at(0.45, 0.65)),
    ];
    scene.bodies.retain(|b| {
        shelves
            .iter()
            .all(|w| ccdsim::wall::wall_clearance(w, b.pos) > b.radius)
    });
    scene.walls.extend(shelves);
    scene
}

/// How many times the bodies of a run file come to rest on a wall from `first_shelf` on,
/// and how many times one reaches the end of the segment it slides on and flies off (or
/// rolls over it).
fn shelf_use(run: &Recorded, first_shelf: u32) -> (usize, usize) {
    let mut r =
        ccdsim::record::RunReader::<_, 2>::new(&run.bytes[..], "run".into()).expect("header");
    let (events, _) = r.read_events().expect("records");
    let mut supports = std::collections::HashMap::new();
    let (mut rests, mut leaves) = (0, 0);
    for c in &events {
        let (a, b) = (c.event.a, c.event.b);
        match c.event.kind {
            EventKind::Wall if c.rests[0] => {
                rests += usize::from(b >= first_shelf);
                supports.insert(a, b);
            }
            EventKind::Wall => {
                leaves += usize::from(supports.remove(&a) == Some(b));
            }
            EventKind::Body => {
                for (s, i) in [(0, a), (1, b)] {
                    if !c.rests[s] {
                        supports.remove(&i);
                    }
                }
            }
            _ => {
                supports.remove(&a);
            }
        }
    }
    (rests, leaves)
}

/// How many times the bodies of a run file come to rest on a wall.
fn rests_in<const D: usize>(run: &Recorded) -> usize {
    let mut r =
        ccdsim::record::RunReader::<_, D>::new(&run.bytes[..], "run".into()).expect("header");
    let (events, _) = r.read_events().expect("records");
    events
        .iter()
        .filter(|c| c.event.kind == EventKind::Wall && c.rests[0])
        .count()
}

/// Balls thrown across shelves in a walled box under gravity, resting on them (see
/// `ccdsim::contact::ledge`): a level shelf in three collinear pieces, a shorter one and a ramp.
/// Random horizontal speeds of `speeds.0` to `speeds.0 + speeds.1` m/s: above `√(r g)` ≈ 1
/// most fly off the ends, below it most roll over them (see `ccdsim::motion::pivot`).
fn ledge_scene(n: usize, seed: u64, speeds: (f64, f64)) -> Scene<2> {
    let mut state = seed.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1);
    let mut uniform = move || {
        state = state
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    let segment = |a: [f64; 2], b: [f64; 2]| Wall::Segment {
        a: Vector(a),
        b: Vector(b),
    };
    let plane = |point: [f64; 2], normal: [f64; 2]| Wall::Plane {
        point: Vector(point),
        normal: Vector(normal),
    };
    let walls = vec![
        plane([0.0, 0.0], [0.0, 1.0]),
        plane([0.0, 0.0], [1.0, 0.0]),
        plane([10.0, 0.0], [-1.0, 0.0]),
        segment([1.0, 3.0], [2.5, 3.0]),
        segment([4.0, 3.0], [2.5, 3.0]),
        segment([4.0, 3.0], [5.5, 3.0]),
        segment([6.5, 5.0], [9.0, 5.0]),
        segment([5.0, 1.5], [8.5, 2.2]),
    ];
    let r = 0.1;
    let bodies = (0..n)
        .map(|k| {
            let x = 0.5 + 9.0 * ((k as f64 + 0.4 * uniform()) / n as f64);
            let y = 3.5 + 3.0 * uniform();
            let speed =
                (speeds.0 + speeds.1 * uniform()) * if uniform() < 0.5 { -1.0 } else { 1.0 };
            BodySpec::new(Vector([x, y]), Vector([speed, 0.0]), r)
        })
        .filter(|b| {
            walls
                .iter()
                .all(|w| ccdsim::wall::wall_clearance(w, b.pos) > 2.0 * r)
        })
        .collect();
    Scene {
        settings: ccdsim::Settings {
            restitution: 0.5,
            gravity: ccdsim::Gravity::new(&[0.0, -9.81]),
            rest_speed: Some(0.8),
            ..ccdsim::Settings::default()
        },
        bodies,
        walls,
        ..Scene::default()
    }
}

/// How many times the bodies of a run file start turning about a segment's end, and how
/// many of their collisions with other bodies happen while one turns.
fn turns_in(run: &Recorded) -> (usize, usize) {
    let mut r =
        ccdsim::record::RunReader::<_, 2>::new(&run.bytes[..], "run".into()).expect("header");
    let (events, _) = r.read_events().expect("records");
    let mut turning = std::collections::HashSet::new();
    let (mut turns, mut hits) = (0, 0);
    for c in &events {
        let bodies = [c.event.a, c.event.b];
        let n = if c.event.kind == EventKind::Body {
            2
        } else {
            1
        };
        if c.event.kind == EventKind::Body && bodies.iter().any(|i| turning.contains(i)) {
            hits += 1;
        }
        for (s, i) in bodies[..n].iter().enumerate() {
            if c.pivots[s] {
                turns += usize::from(turning.insert(*i));
            } else {
                turning.remove(i);
            }
        }
    }
    (turns, hits)
}

#[test]
fn resting_and_sliding() {
    // Bodies whose bounces die away come to rest on the floor, the side walls' planes and an
    // incline, and slide along them with their own accelerations, while others fall onto
    // them; kicks, teleports, frames, bodies added and removed and kinematic bodies lift
    // them off. Every finder and cells mode writes the oracle's run file, whose runs verify.
    for &seed in &SMALL_SEEDS[..2] {
        let s2 = resting(gas_scene::<2>(40, 0.1, (0.2, 1.0), seed), [0.0, -9.81]);
        // A tilted gravity in 3D: bodies slide along the floor plane.
        let s3 = resting(
            gas_scene::<3>(70, 0.15, (0.5, 0.5), seed),
            [1.5, -0.5, -9.81],
        );
        let kin = with_kinematic(s2.clone(), 3);
        let shelves = with_shelves(s2.clone());
        let drives = [
            Drive::Events,
            Drive::Kicks { every: 37 },
            Drive::FrameTeleports { dt: 0.05 },
            Drive::Slots { every: 41 },
        ];
        for drive in drives {
            for (what, scene) in [
                ("2D", &s2),
                ("kinematic 2D", &kin),
                ("shelves 2D", &shelves),
            ] {
                let label = format!("resting {what} seed {seed} {drive:?}");
                let oracle = check_all_driven(&label, scene, 1500, drive);
                verifies(&label, scene, &oracle);
                assert!(rests_in::<2>(&oracle) >= 3, "{label}: few rests");
                if what.starts_with("shelves") {
                    let (rests, _) = shelf_use(&oracle, 5);
                    assert!(rests >= 1, "{label}: no rest on the shelves");
                }
            }
            let label = format!("resting 3D seed {seed} {drive:?}");
            let oracle = check_all_driven(&label, &s3, 1200, drive);
            verifies(&label, &s3, &oracle);
            assert!(rests_in::<3>(&oracle) >= 3, "{label}: few rests");
        }
    }
}

#[test]
fn rolling_over_ledges() {
    // Slow balls (0.1–0.9 m/s, below √(r g)) roll over the shelves' ends, turning about the
    // end points, while others fall onto them and hit them, with kicks, teleports and bodies
    // added and removed ending their turns. Every finder writes the oracle's run file (the
    // pivots' events found by the simulation itself, checked against a brute-force oracle),
    // whose runs verify.
    let (mut turns, mut hits) = (0, 0);
    for (k, &seed) in SMALL_SEEDS.iter().enumerate() {
        let mut scene = ledge_scene(30, seed, (0.1, 0.8));
        // Slow balls gather on the shelves: bounces between them stay elastic within 10 ms
        // (the TC model), so that they do not end the run resting on one another.
        scene.settings.tc = Some(0.01);
        // A slow ball set down near the free end of the shelf at y = 3, and a faster one behind
        // it that catches it while it turns about the end point (from 0.15 s, for 0.1 s or
        // so), before the others, dropped from 0.5 m higher at least, come down.
        let on_shelf =
            |x: f64, v: f64| BodySpec::new(Vector([x, 3.1 + 1e-6]), Vector([v, 0.0]), 0.1);
        scene.bodies.push(on_shelf(5.455, 0.3));
        scene.bodies.push(on_shelf(5.175, 0.66 + 0.04 * k as f64));
        for drive in [
            Drive::Events,
            Drive::Kicks { every: 37 },
            Drive::FrameTeleports { dt: 0.05 },
            Drive::Slots { every: 41 },
        ] {
            let label = format!("rolling seed {seed} {drive:?}");
            let oracle = check_all_driven(&label, &scene, 1500, drive);
            verifies(&label, &scene, &oracle);
            let (t, h) = turns_in(&oracle);
            turns += t;
            hits += h;
        }
    }
    assert!(turns >= 80, "{turns} turns about segment ends");
    assert!(hits >= 12, "{hits} collisions with turning balls");
}

#[test]
fn sliding_off_ledges() {
    // Balls land on shelves, rest, slide, go straight on across the joints of a shelf drawn
    // in pieces, fly off ends or roll over them (meeting other balls while they turn), with
    // kicks, teleports and bodies added and removed lifting them off. Every finder writes
    // the oracle's run file, whose runs verify.
    for &seed in &SMALL_SEEDS {
        let scene = ledge_scene(24, seed, (1.5, 1.5));
        let mut slide_offs = 0;
        for drive in [
            Drive::Events,
            Drive::Kicks { every: 37 },
            Drive::FrameTeleports { dt: 0.05 },
            Drive::Slots { every: 41 },
        ] {
            let label = format!("ledges seed {seed} {drive:?}");
            let oracle = check_all_driven(&label, &scene, 1500, drive);
            verifies(&label, &scene, &oracle);
            let (rests, leaves) = shelf_use(&oracle, 3);
            assert!(rests >= 3, "{label}: {rests} rests on shelves");
            slide_offs += leaves;
        }
        assert!(slide_offs >= 4, "seed {seed}: {slide_offs} slide-offs");
    }
}
