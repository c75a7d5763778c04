//! Resting on segments and the edge model (`ccdsim::contact::ledge`): a ball slides along a shelf,
//! flies off its end when fast enough, goes straight on along a shelf drawn in pieces, falls
//! back onto the top of an incline it was thrown over, and rolls over an edge when too slow to
//! fly clear (coming off it, landing on the next slope, or swinging back); the same with
//! every finder, recorded and verified, and forged runs refused.

use crate::replay;

use ccdsim::record::RunWriter;
use ccdsim::Gravity;
use ccdsim::{BodySpec, Collision, EventKind, Halt, Scene, Settings, Simulation, Vector, Wall};

const FINDERS: [&str; 4] = ["all-pairs", "bvh", "sedgewick", "cells"];

fn segment(a: [f64; 2], b: [f64; 2]) -> Wall<2> {
    Wall::Segment {
        a: Vector(a),
        b: Vector(b),
    }
}

fn floor() -> Wall<2> {
    Wall::Plane {
        point: Vector([0.0, 0.0]),
        normal: Vector([0.0, 1.0]),
    }
}

/// Restitution 0.5, gravity 10 m/s² down, resting below `rest_speed`.
fn scene(bodies: Vec<BodySpec<2>>, walls: Vec<Wall<2>>, rest_speed: f64) -> Scene<2> {
    Scene {
        settings: Settings {
            restitution: 0.5,
            gravity: Gravity::new(&[0.0, -10.0]),
            rest_speed: Some(rest_speed),
            ..Settings::default()
        },
        bodies,
        walls,
        ..Scene::default()
    }
}

/// A ball of radius 0.2 put a hair above a shelf at y = 1 from x = 0 to 2 (over a floor),
/// at `x` moving right at `speed` m/s; it rests on the shelf at once.
fn on_shelf(x: f64, speed: f64) -> Scene<2> {
    let r = 0.2;
    scene(
        vec![BodySpec::new(
            Vector([x, 1.0 + r + 1e-6]),
            Vector([speed, 0.0]),
            r,
        )],
        vec![floor(), segment([0.0, 1.0], [2.0, 1.0])],
        1.0,
    )
}

/// The run of `scene` with `finder` up to `until`: its run file and its events.
fn run(scene: &Scene<2>, finder: &str, until: f64) -> (Vec<u8>, Vec<Collision<2>>, Simulation<2>) {
    let mut sim = Simulation::new(scene, finder).unwrap();
    let mut file = RunWriter::new(Vec::new(), "ledge".into(), scene).unwrap();
    let mut events = Vec::new();
    sim.run_until_with(until, |c| {
        file.write_event(c).unwrap();
        events.push(*c);
    });
    (file.finish(sim.time()).unwrap(), events, sim)
}

/// Runs `scene` with every finder: all write the oracle's run file, which verifies; returns
/// the oracle's events and simulation.
fn every_finder(scene: &Scene<2>, until: f64) -> (Vec<Collision<2>>, Simulation<2>) {
    let (oracle, events, sim) = run(scene, "all-pairs", until);
    for finder in &FINDERS[1..] {
        let (bytes, _, other) = run(scene, finder, until);
        assert!(bytes == oracle, "[{finder}] writes another run file");
        assert_eq!(other.halt(), sim.halt(), "[{finder}]");
    }
    let (s, recorded, end) = replay::records::<2>(&oracle);
    replay::replay(&s, &recorded, end, true).unwrap();
    replay::replay(&s, &recorded, end, false).unwrap();
    (events, sim)
}

#[test]
fn a_fast_ball_slides_along_a_shelf_and_flies_off_its_end() {
    // Put a hair above a shelf at y = 1 from x = 0 to 2, moving right at 2 m/s: it rests at
    // once and slides at 2 m/s; 2² > r g = 0.2 · 10, so at x = 2 it flies clear, falls
    // 1 m onto the floor and bounces there.
    let s = on_shelf(0.5, 2.0);
    let (events, _) = every_finder(&s, 3.0);
    let land = &events[0];
    assert!(land.rests[0] && land.event.b == 1, "{land:?}");
    assert_eq!(
        land.vel[0].0,
        [2.0, 0.0],
        "it keeps its speed along the shelf"
    );
    let end = &events[1];
    assert_eq!(
        (end.event.kind, end.event.b, end.rests[0]),
        (EventKind::Wall, 1, false)
    );
    assert!(
        (end.pos[0][0] - 2.0).abs() < 1e-12,
        "at the shelf's end: {end:?}"
    );
    let slide = (2.0 - land.pos[0][0]) / 2.0;
    assert!((end.event.time - land.event.time - slide).abs() < 1e-12);
    assert_eq!(end.vel[0], land.vel[0], "flying off changes no velocity");
    // Next the floor, from 1 m up after a free fall of √(2 · 1 / 10) s.
    let floor_hit = &events[2];
    assert_eq!(floor_hit.event.b, 0);
    assert!((floor_hit.event.time - end.event.time - 0.2f64.sqrt()).abs() < 1e-9);
    assert!((floor_hit.pos[0][0] - (2.0 + 2.0 * 0.2f64.sqrt())).abs() < 1e-9);
}

#[test]
fn a_slow_ball_at_the_end_of_a_shelf_rolls_over_the_edge() {
    // At 1 m/s, 1² < r g = 2: at the end it rolls over the edge, turning about the end point
    // until the point stops pushing it, at cos θ = 2/3 + v²/(3 g r) = 5/6 from the top; it
    // falls from there onto the floor. The same with every finder, and it verifies.
    let s = on_shelf(1.5, 1.0);
    let (events, sim) = every_finder(&s, 3.0);
    assert_eq!(sim.halt(), None);
    let kinds: Vec<_> = events
        .iter()
        .map(|c| (c.event.b, c.rests[0], c.pivots[0]))
        .collect();
    assert_eq!(
        &kinds[..4],
        &[
            (1, true, false),
            (1, false, true),
            (1, false, false),
            (0, false, false)
        ],
        "land, roll over, come off, the floor: {events:?}"
    );
    let (start, off) = (&events[1], &events[2]);
    let slide = 2.0 - events[0].pos[0][0];
    assert!((start.event.time - events[0].event.time - slide).abs() < 1e-12);
    assert_eq!(
        start.vel[0].0,
        [1.0, 0.0],
        "it turns from the speed it slid at"
    );
    let r = 0.2;
    let from_end = off.pos[0] - Vector([2.0, 1.0]);
    assert!((from_end.norm() - r).abs() < 1e-12);
    assert!((from_end[1] / r - 5.0 / 6.0).abs() < 1e-12, "{from_end:?}");
    // Energy: what the drop of r (1 − cos θ) gave it.
    let speed2 = off.vel[0].norm_sq();
    assert!(
        (speed2 - (1.0 + 2.0 * 10.0 * r / 6.0)).abs() < 1e-10,
        "{speed2}"
    );
    // Along the circle: its velocity is perpendicular to the offset.
    assert!(off.vel[0].dot(from_end).abs() < 1e-12);
}

#[test]
fn a_program_pushes_a_ball_while_it_rolls_over_the_edge() {
    // A game loop stops the clock while the ball turns about the shelf's end, and kicks it
    // up: it leaves the point from where it was on its turn, flies and falls onto the floor,
    // the same with every finder.
    let s = on_shelf(1.5, 1.0);
    let mut runs = Vec::new();
    for finder in FINDERS {
        let mut sim = Simulation::new(&s, finder).unwrap();
        assert_eq!(
            sim.run_until(0.55),
            2,
            "[{finder}] the landing and the roll over"
        );
        let (pivot, wall) = sim.world().pivot(0).expect("it turns");
        assert_eq!(wall, 1);
        let at = sim.position(0);
        assert!((at - Vector([pivot.position(0.55)[0], pivot.position(0.55)[1]])).norm() < 1e-15);
        sim.set_velocity(0, Vector([0.5, 3.0])).unwrap();
        assert!(
            sim.world().pivot(0).is_none(),
            "[{finder}] an edit ends the turn"
        );
        let mut events = Vec::new();
        sim.run_until_with(3.0, |c| events.push(*c));
        assert_eq!(sim.halt(), None, "[{finder}]");
        assert_eq!(
            events[0].event.b, 0,
            "[{finder}] the floor next: {events:?}"
        );
        runs.push(events.iter().map(|c| c.event).collect::<Vec<_>>());
    }
    assert!(
        runs.windows(2).all(|w| w[0] == w[1]),
        "the finders' events differ"
    );
}

#[test]
fn a_slow_ball_rolls_over_an_obtuse_corner_onto_the_next_slope() {
    // A level shelf ending in a 25° slope down: at 0.5 m/s the ball turns about the corner
    // and lands on the slope before the point would let it go (25° < the ~35° it would come
    // off at), resting on it and sliding down; at 2 m/s it flies clear.
    let r = 0.2;
    let a = 25f64.to_radians();
    let walls = vec![
        floor(),
        segment([0.0, 1.0], [2.0, 1.0]),
        segment([2.0, 1.0], [2.0 + 1.5 * a.cos(), 1.0 - 1.5 * a.sin()]),
    ];
    let slow = scene(
        vec![BodySpec::new(
            Vector([1.5, 1.0 + r + 1e-6]),
            Vector([0.5, 0.0]),
            r,
        )],
        walls.clone(),
        1.0,
    );
    let (events, _) = every_finder(&slow, 2.0);
    let kinds: Vec<_> = events
        .iter()
        .map(|c| (c.event.b, c.rests[0], c.pivots[0]))
        .collect();
    assert_eq!(
        &kinds[..3],
        &[(1, true, false), (1, false, true), (2, true, false)],
        "{events:?}"
    );
    let land = &events[2];
    let down = Vector([a.cos(), -a.sin()]);
    let normal = Vector([a.sin(), a.cos()]);
    assert!(((land.pos[0] - Vector([2.0, 1.0])).dot(normal) - r).abs() < 1e-12);
    assert!(land.vel[0].dot(normal).abs() < 1e-12 && land.vel[0].dot(down) > 0.5);
    // Then it slides down the slope to its lower end.
    assert_eq!(
        (events[3].event.b, events[3].rests[0]),
        (2, false),
        "{events:?}"
    );
}

#[test]
fn a_slow_ball_off_the_top_of_an_incline_swings_back_onto_it() {
    // Up a 20° incline and off its top end slowly: it turns towards the top, stops short of
    // it, swings back onto the incline and slides down again.
    let r = 0.2;
    let a = 20f64.to_radians();
    let (c, s) = (a.cos(), a.sin());
    let top = [2.0 * c, 1.0 + 2.0 * s];
    let start = [1.5 * c - s * (r + 1e-7), 1.0 + 1.5 * s + c * (r + 1e-7)];
    // Fast enough to reach the top at about 0.3 m/s.
    let v0 = (0.3f64 * 0.3 + 2.0 * 10.0 * s * 0.5).sqrt();
    let sc = scene(
        vec![BodySpec::new(Vector(start), Vector([v0 * c, v0 * s]), r)],
        vec![floor(), segment([0.0, 1.0], top)],
        1.0,
    );
    let (events, _) = every_finder(&sc, 4.0);
    let kinds: Vec<_> = events
        .iter()
        .map(|c| (c.event.b, c.rests[0], c.pivots[0]))
        .collect();
    assert_eq!(
        &kinds[..4],
        &[
            (1, true, false),
            (1, false, true),
            (1, true, false),
            (1, false, false)
        ],
        "land, roll over the top, back on it, off its lower end: {events:?}"
    );
    let (over, back) = (&events[1], &events[2]);
    assert!(
        (back.pos[0] - over.pos[0]).norm() < 1e-12,
        "back where it turned"
    );
    assert!(
        (back.vel[0] + over.vel[0]).norm() < 1e-12,
        "as fast, the other way"
    );
}

#[test]
fn a_shelf_drawn_in_pieces_is_one_shelf() {
    // Three collinear pieces, the middle one drawn backwards: a ball too slow to fly off an
    // edge slides across both joints, going on along each next piece, and rolls over an
    // edge only at the far end, x = 3.
    let r = 0.2;
    let s = scene(
        vec![BodySpec::new(
            Vector([0.5, 1.0 + r + 1e-6]),
            Vector([1.0, 0.0]),
            r,
        )],
        vec![
            floor(),
            segment([0.0, 1.0], [1.0, 1.0]),
            segment([2.0, 1.0], [1.0, 1.0]),
            segment([2.0, 1.0], [3.0, 1.0]),
        ],
        1.0,
    );
    let (events, sim) = every_finder(&s, 5.0);
    assert_eq!(sim.halt(), None);
    let named: Vec<(u32, bool)> = events.iter().map(|c| (c.event.b, c.rests[0])).collect();
    assert_eq!(&named[..3], [(1, true), (2, true), (3, true)], "{events:?}");
    for c in &events[..3] {
        assert_eq!(c.vel[0].0, [1.0, 0.0]);
        assert_eq!(
            c.pos[0][1], events[0].pos[0][1],
            "on the shelf to the last bit"
        );
    }
    assert!((events[1].pos[0][0] - 1.0).abs() < 1e-12);
    assert!((events[2].pos[0][0] - 2.0).abs() < 1e-12);
    let over = &events[3];
    assert_eq!((over.event.b, over.pivots[0]), (3, true), "{events:?}");
    let time = over.event.time;
    assert!((time - events[0].event.time - (3.0 - events[0].pos[0][0])).abs() < 1e-12);
}

#[test]
fn a_ball_thrown_over_the_top_of_an_incline_falls_back_onto_its_end() {
    // A 10° incline 2 m long under a gravity tilted to pull hard back along it (−8.4 m/s²
    // along it, 1.6 m/s² onto it): the ball starts on it moving up at 4.45 m/s, passes the
    // top at √3 m/s, fast enough to fly clear (3 > r g_n) but slow enough (3 < r |g|²/g_n)
    // for gravity to bring it back onto the end point: a contact with the end.
    let r = 0.1;
    let (c, s) = (10f64.to_radians().cos(), 10f64.to_radians().sin());
    let top = [2.0 * c, 2.0 * s];
    let normal = [-s, c];
    let start = [
        1.0 * c + normal[0] * (r + 1e-7),
        1.0 * s + normal[1] * (r + 1e-7),
    ];
    let speed = 4.45;
    let mut sc = scene(
        vec![BodySpec::new(
            Vector(start),
            Vector([speed * c, speed * s]),
            r,
        )],
        vec![floor(), segment([0.0, 0.0], top)],
        1.0,
    );
    sc.settings.gravity = Gravity::new(&[-8.0, -3.0]);
    // Until before it lands on the floor and slides into the wedge under the incline.
    let (events, _) = every_finder(&sc, 0.9);
    let kinds: Vec<(u32, bool)> = events.iter().map(|c| (c.event.b, c.rests[0])).collect();
    assert_eq!(&kinds[..2], [(1, true), (1, false)], "{events:?}");
    let back = &events[2];
    assert_eq!(back.event.b, 1, "it comes back to the segment: {events:?}");
    let from_top = back.pos[0] - Vector(top);
    assert!(
        (from_top.norm() - r).abs() < 1e-9,
        "at the end point: {back:?}"
    );
    let t = back.event.time - events[1].event.time;
    assert!(t > 0.01, "{t}");
}

#[test]
fn verify_refuses_a_forged_slide_off() {
    let s = on_shelf(0.5, 2.0);
    let (bytes, _, _) = run(&s, "all-pairs", 3.0);
    let (scene, events, end) = replay::records::<2>(&bytes);
    assert!(replay::replay(&scene, &events, end, true).is_ok());
    // Leaving the shelf half-way along it.
    let mut early = events.clone();
    let dt = 0.3;
    early[1].event.time = events[0].event.time + dt;
    early[1].pos[0] = events[0].pos[0] + events[0].vel[0] * dt;
    let err = replay::replay(&scene, &early[..2], early[1].event.time, true).unwrap_err();
    assert!(err.contains("not at an end"), "{err}");
    // Leaving with a new velocity.
    let mut kicked = events.clone();
    kicked[1].vel[0] = Vector([2.0, 0.5]);
    let err = replay::replay(&scene, &kicked[..2], kicked[1].event.time, true).unwrap_err();
    assert!(err.contains("leaves segment 1 with velocity"), "{err}");
    // Too slow to clear the edge: the same run at 1 m/s, the halt's event forged in.
    let slow = on_shelf(0.5, 1.0);
    let (bytes, slow_events, _) = run(&slow, "all-pairs", 3.0);
    let (slow_scene, _, _) = replay::records::<2>(&bytes);
    let mut forged = slow_events[..1].to_vec();
    let mut off = forged[0];
    let slide = 2.0 - off.pos[0][0];
    off.event.time += slide;
    off.pos[0] += off.vel[0] * slide;
    off.rests = [false; 2];
    forged.push(off);
    let err = replay::replay(&slow_scene, &forged, off.event.time, true).unwrap_err();
    assert!(err.contains("too slowly to clear"), "{err}");
}

#[test]
fn balls_do_not_rest_on_the_underside_of_a_shelf_nor_on_a_post() {
    // Thrown up against a shelf's underside, a ball bounces off it however slowly; landing
    // on a vertical post's top end, it does not rest on the post.
    let r = 0.2;
    let s = scene(
        vec![
            BodySpec::new(Vector([0.5, 1.0 - r - 0.05]), Vector([0.0, 1.1]), r),
            BodySpec::new(Vector([3.0, 1.0 + r + 0.1]), Vector([0.0, 0.0]), r),
        ],
        vec![
            floor(),
            segment([0.0, 1.0], [2.0, 1.0]),
            segment([3.0, 0.0], [3.0, 1.0]),
        ],
        1.0,
    );
    let (events, _) = every_finder(&s, 0.3);
    assert!(
        events.iter().all(|c| !(c.rests[0] && c.event.b >= 1)),
        "{events:?}"
    );
    assert!(events.iter().any(|c| c.event.a == 0 && c.event.b == 1));
}

#[test]
fn a_ball_wedged_in_a_trough_stops_the_run_instead_of_looping_at_one_instant() {
    // A V of two walls that both hold it: resting on one, the ball slides into the other and
    // rests on that, whose slide brings it back, each time at the same instant. Once its
    // speed has died away that cycle changes nothing, and the run stops there; before the
    // fix it looped for ever, writing a run file of tens of gigabytes.
    let ball = || vec![BodySpec::new(Vector([0.3, 2.0]), Vector([0.0, 0.0]), 0.1)];
    let segments = scene(
        ball(),
        vec![
            segment([-1.0, 1.0], [0.0, 0.0]),
            segment([0.0, 0.0], [1.0, 1.2]),
        ],
        0.5,
    );
    let planes = scene(
        ball(),
        vec![
            Wall::Plane {
                point: Vector([0.0, 0.0]),
                normal: Vector([1.0, 1.0]),
            },
            Wall::Plane {
                point: Vector([0.0, 0.0]),
                normal: Vector([-1.2, 1.0]),
            },
        ],
        0.5,
    );
    for (what, s) in [("segments", &segments), ("planes", &planes)] {
        let (events, sim) = every_finder(s, 10.0);
        assert!(
            matches!(sim.halt(), Some(Halt::Resting { body: 0, .. })),
            "{what}: {:?}",
            sim.halt()
        );
        assert!(events.len() < 2000, "{what}: {} events", events.len());
    }
}

#[test]
fn a_ball_pushed_into_a_wedge_under_an_incline_stops_the_run() {
    // Sliding along the floor under a tilted gravity into the acute wedge under an incline
    // (a segment's underside, which holds nothing): it bounces between the two at one
    // instant, ever slower, into subnormal speeds where rounding could cycle for ever; the
    // run stops after `WEDGED_AFTER` such events.
    let r = 0.1;
    let (c, s) = (10f64.to_radians().cos(), 10f64.to_radians().sin());
    let mut sc = scene(
        vec![BodySpec::new(
            Vector([3.0, r + 1e-7]),
            Vector([-1.0, 0.0]),
            r,
        )],
        vec![floor(), segment([0.0, 0.0], [2.0 * c, 2.0 * s])],
        1.0,
    );
    sc.settings.gravity = Gravity::new(&[-8.0, -3.0]);
    let (events, sim) = every_finder(&sc, 5.0);
    assert!(
        matches!(sim.halt(), Some(Halt::Resting { body: 0, .. })),
        "{:?}",
        sim.halt()
    );
    assert!(
        events.len() <= ccdsim::sim::WEDGED_AFTER as usize + 100,
        "{}",
        events.len()
    );
}

#[test]
fn the_rolling_example_rolls_over_a_shelf_end_and_an_obtuse_corner() {
    // `examples/rolling.json`: a ball slowed by one falling onto the shelf rolls over the
    // shelf's end and comes off; another rolls over an obtuse corner and lands on the slope
    // beyond it. Every finder writes the same run file, which verifies.
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/rolling.json");
    let scene = Scene::from_json(&std::fs::read_to_string(path).unwrap()).unwrap();
    let (events, sim) = every_finder(&scene, 10.0);
    assert_eq!(sim.halt(), None);
    assert_eq!(events.len(), 51);
    let turns: Vec<(u32, u32)> = events
        .iter()
        .filter(|c| c.pivots[0])
        .map(|c| (c.event.a, c.event.b))
        .collect();
    assert_eq!(turns, [(1, 4), (0, 3)], "{turns:?}");
    // Each turn's next record: body 1 lands on the slope (segment 5) and rests; body 0
    // comes off the shelf's end (segment 3, no rest) and falls to the floor.
    let after = |body: u32, from: usize| {
        events[from + 1..]
            .iter()
            .find(|c| c.event.a == body || (c.event.kind == EventKind::Body && c.event.b == body))
            .copied()
            .unwrap()
    };
    let start = |body| {
        events
            .iter()
            .position(|c| c.pivots[0] && c.event.a == body)
            .unwrap()
    };
    let land = after(1, start(1));
    assert_eq!(
        (land.event.kind, land.event.b, land.rests[0]),
        (EventKind::Wall, 5, true)
    );
    let off = after(0, start(0));
    assert_eq!(
        (off.event.kind, off.event.b, off.rests[0]),
        (EventKind::Wall, 3, false)
    );
    assert_eq!(
        after(0, events.iter().position(|c| *c == off).unwrap())
            .event
            .b,
        0
    );
}
