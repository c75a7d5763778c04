//! Moving walls (pistons, paddles): exact contacts with every finder, a program steering
//! them, recorded runs that `verify` replays and forged ones it rejects, and the scene
//! rules.

use crate::replay;

use ccdsim::discrete::DiscreteStepper;
use ccdsim::generate::box_walls;
use ccdsim::record::RunWriter;
use ccdsim::{
    BodySpec, Collision, EventKind, MovingWall, Scene, SceneError, Settings, Simulation, Vector,
    Wall,
};

const FINDERS: [&str; 4] = ["all-pairs", "bvh", "sedgewick", "cells"];

fn plane(point: [f64; 2], normal: [f64; 2], velocity: [f64; 2]) -> MovingWall<2> {
    MovingWall {
        wall: Wall::Plane {
            point: Vector(point),
            normal: Vector(normal),
        },
        velocity: Vector(velocity),
    }
}

#[test]
fn a_ball_between_a_wall_and_a_closing_piston_gains_twice_the_piston_speed_per_bounce() {
    // Fermi acceleration: a ball bouncing between a fixed wall at x = 0 and a piston closing
    // at w = 0.25 m/s leaves the piston 2w faster each time, and the times follow in closed
    // form: all exactly representable here.
    let scene = Scene::<2> {
        bodies: vec![BodySpec::new(Vector([5.0, 0.0]), Vector([1.0, 0.0]), 0.5)],
        walls: vec![Wall::Plane {
            point: Vector([0.0, 0.0]),
            normal: Vector([1.0, 0.0]),
        }],
        moving_walls: vec![plane([16.5, 0.0], [-1.0, 0.0], [-0.25, 0.0])],
        ..Scene::default()
    };
    for finder in FINDERS {
        let mut sim = Simulation::new(&scene, finder).unwrap();
        // The ball's right edge at 5.5 + t meets the piston at 16.5 − t/4 when t = 8.8.
        let hit = sim.step_event().unwrap();
        assert_eq!(
            (hit.event.kind, hit.event.b),
            (EventKind::Wall, 1),
            "[{finder}]"
        );
        assert_eq!(hit.event.time, 8.8, "[{finder}]");
        assert_eq!(hit.vel[0].0, [-1.5, 0.0], "[{finder}]");
        let back = sim.step_event().unwrap();
        assert_eq!(back.event.b, 0, "[{finder}] the fixed wall");
        assert_eq!(back.vel[0].0, [1.5, 0.0], "[{finder}]");
        let again = sim.step_event().unwrap();
        assert_eq!(again.event.b, 1, "[{finder}]");
        assert_eq!(again.vel[0].0, [-2.0, 0.0], "[{finder}]");
        // Stopped, the piston returns the ball as a static wall would.
        sim.set_wall_velocity(0, Vector::ZERO).unwrap();
        sim.step_event().unwrap();
        let still = sim.step_event().unwrap();
        assert_eq!(
            (still.event.b, still.vel[0].0),
            (1, [-2.0, 0.0]),
            "[{finder}]"
        );
    }
}

#[test]
fn a_paddle_segment_is_met_on_its_faces_and_at_its_ends() {
    // A vertical paddle from (5, 2) to (5, 4) sliding right at 1 m/s: a ball ahead of it at
    // y = 3 is struck by its face, one at y = 5 (above its top end) by its end point.
    let paddle = MovingWall {
        wall: Wall::Segment {
            a: Vector([5.0, 2.0]),
            b: Vector([5.0, 4.0]),
        },
        velocity: Vector([1.0, 0.0]),
    };
    let face = Scene::<2> {
        bodies: vec![BodySpec::new(Vector([8.0, 3.0]), Vector::ZERO, 0.5)],
        moving_walls: vec![paddle],
        ..Scene::default()
    };
    let mut end = face.clone();
    end.bodies[0].pos = Vector([8.0, 4.3]);
    for finder in FINDERS {
        let hit = Simulation::new(&face, finder)
            .unwrap()
            .step_event()
            .unwrap();
        assert_eq!(hit.event.time, 2.5, "[{finder}]");
        assert_eq!(hit.vel[0].0, [2.0, 0.0], "[{finder}]");
        let hit = Simulation::new(&end, finder).unwrap().step_event().unwrap();
        // The end point (5 + t, 4) comes within 0.5 of (8, 4.3) when 3 − t = 0.4.
        assert!(
            (hit.event.time - 2.6).abs() < 1e-12,
            "[{finder}] {}",
            hit.event.time
        );
        assert!(hit.vel[0][1] > 0.0 && hit.vel[0][0] > 0.0, "[{finder}]");
    }
}

/// A table under gravity with balls and a kinematic puck, a piston floor and a paddle the
/// program steers every frame after the lowest ball, recorded.
fn steered_run(finder: &str) -> Vec<u8> {
    let scene = Scene::<2> {
        bodies: (0..20)
            .map(|k| {
                let (x, y) = (1.0 + 1.4 * (k % 8) as f64, 4.0 + 1.4 * (k / 8) as f64);
                let v = Vector([f64::from(k % 5) - 2.0, f64::from(k % 3)]);
                BodySpec {
                    kinematic: k == 19,
                    ..BodySpec::new(Vector([x, y]), v, 0.4)
                }
            })
            .collect(),
        walls: box_walls(Vector([12.0, 10.0])),
        moving_walls: vec![
            plane([0.0, 1.0], [0.0, 1.0], [0.0, 0.0]),
            MovingWall {
                wall: Wall::Segment {
                    a: Vector([5.0, 2.0]),
                    b: Vector([7.0, 2.0]),
                },
                velocity: Vector::ZERO,
            },
        ],
        settings: Settings {
            gravity: ccdsim::Gravity::new(&[0.0, -9.81]),
            ..Settings::default()
        },
        ..Scene::default()
    };
    let mut sim = Simulation::new(&scene, finder).unwrap();
    let mut run = RunWriter::new_steered(Vec::new(), "paddle".into(), &scene).unwrap();
    sim.record_edits(true);
    for frame in 0..180u32 {
        let t = sim.time();
        // The floor pumps up and down around y = 1; the paddle chases the lowest ball.
        let floor = sim.world().wall_motion(0).offset_at(t)[1];
        let pump = if frame % 40 < 20 { 0.5 } else { -0.5 };
        sim.set_wall_velocity(0, Vector([0.0, if floor < -0.5 { 0.5 } else { pump }]))
            .unwrap();
        let paddle = 6.0 + sim.world().wall_motion(1).offset_at(t)[0];
        let lowest = (0..19)
            .min_by(|&i, &j| sim.position(i)[1].total_cmp(&sim.position(j)[1]))
            .unwrap();
        let chase = (sim.position(lowest)[0] - paddle).clamp(-3.0, 3.0);
        let chase = if (paddle < 2.0 && chase < 0.0) || (paddle > 10.0 && chase > 0.0) {
            0.0
        } else {
            chase
        };
        sim.set_wall_velocity(1, Vector([chase, 0.0])).unwrap();
        for record in sim.take_edits().iter().chain(&sim.advance(1.0 / 30.0)) {
            run.write_event(record).unwrap();
        }
    }
    assert!(sim.halt().is_none(), "[{finder}] {:?}", sim.halt());
    run.finish(sim.time()).unwrap()
}

#[test]
fn steered_moving_walls_record_the_same_run_with_every_finder_and_verify() {
    let want = steered_run("all-pairs");
    assert_eq!(
        u32::from_le_bytes(want[8..12].try_into().unwrap()),
        ccdsim::record::VERSION_MOVING_WALLS
    );
    for finder in ["bvh", "sedgewick", "cells"] {
        assert!(steered_run(finder) == want, "[{finder}] run files differ");
    }
    let (scene, events, end) = replay::records::<2>(&want);
    let hits = |w: u32| {
        events
            .iter()
            .filter(|c| c.event.kind == EventKind::Wall && c.event.b == w)
            .count()
    };
    let (floor, paddle) = (hits(4), hits(5));
    assert!(
        floor > 20 && paddle > 5,
        "{floor} floor hits, {paddle} paddle hits"
    );
    for all_pairs in [false, true] {
        let report = replay::replay(&scene, &events, end, all_pairs).unwrap();
        assert_eq!(report.edits, 2 * 180);
        assert!(report.wall_work != 0.0);
    }
}

#[test]
fn the_energy_a_piston_gives_is_the_work_verify_reports() {
    // Without kinematic bodies, elastic collisions keep the energy: what changes it is the
    // work the moving walls did.
    let mut scene = Scene::<2> {
        bodies: (0..30)
            .map(|k| {
                let (x, y) = (1.0 + 1.2 * (k % 8) as f64, 1.0 + 1.2 * (k / 8) as f64);
                BodySpec::new(Vector([x, y]), Vector([f64::from(k % 7) - 3.0, 1.0]), 0.4)
            })
            .collect(),
        walls: box_walls(Vector([10.0, 8.0])),
        moving_walls: vec![plane([0.0, 7.5], [0.0, -1.0], [0.0, -0.4])],
        ..Scene::default()
    };
    for gravity in [false, true] {
        scene.settings.gravity = gravity.then(|| ccdsim::Gravity::new(&[0.5, -3.0]).unwrap());
        let mut sim = Simulation::new(&scene, "cells").unwrap();
        let mut run = RunWriter::new(Vec::new(), "piston".into(), &scene).unwrap();
        sim.run_until_with(6.0, |c| run.write_event(c).unwrap());
        let bytes = run.finish(sim.time()).unwrap();
        let (scene, events, end) = replay::records::<2>(&bytes);
        let report = replay::replay(&scene, &events, end, false).unwrap();
        assert!(report.wall_work > 0.0, "a closing piston heats the gas");
        let balance = report.energy_start() + report.wall_work - report.energy_end();
        assert!(
            balance.abs() < 1e-9 * report.energy_end().abs().max(1.0),
            "gravity {gravity}: energy off by {balance}"
        );
        assert!(report.max_overlap < 1e-9);
    }
}

#[test]
fn verify_rejects_a_body_through_a_moving_wall_and_a_wall_that_jumps() {
    let want = steered_run("cells");
    let (scene, events, end) = replay::records::<2>(&want);
    let forge = |f: &dyn Fn(&mut Vec<Collision<2>>)| {
        let mut forged = events.clone();
        f(&mut forged);
        replay::replay(&scene, &forged, end, false).unwrap_err()
    };
    // A paddle hit replaced by the ball going on as if nothing were there.
    let hit = events
        .iter()
        .position(|c| c.event.kind == EventKind::Wall && c.event.b == 5)
        .unwrap();
    let e = forge(&|v| {
        let c = v[hit];
        let i = c.event.a as usize;
        // Its velocity before the hit, under gravity: the recorded one never changed.
        let before = events[..hit]
            .iter()
            .rev()
            .find(|p| {
                (p.event.kind != EventKind::Edit && p.event.a as usize == i)
                    || (p.event.kind == EventKind::Body && p.event.b as usize == i)
            })
            .map(|p| {
                let s = usize::from(p.event.kind == EventKind::Body && p.event.b as usize == i);
                (p.vel[s], p.event.time)
            })
            .unwrap();
        v[hit].vel[0] = before.0 + Vector([0.0, -9.81]) * (c.event.time - before.1);
    });
    assert!(e.contains("crosses wall 5"), "{e}");
    // A wall edit that moves the wall elsewhere.
    let edit = events
        .iter()
        .position(|c| c.event.kind == EventKind::Edit && c.event.b == 5 && c.event.a == 1)
        .unwrap();
    let e = forge(&|v| v[edit + 2].pos[0][0] += 0.5);
    assert!(e.contains("recorded displaced"), "{e}");
}

#[test]
fn exports_name_moving_walls_as_wall_events_do() {
    let bytes = steered_run("cells");
    let mut r = ccdsim::record::RunReader::<_, 2>::new(&bytes[..], "paddle".into()).unwrap();
    let mut out = Vec::new();
    ccdsim::record::export_jsonl(&mut r, &mut out).unwrap();
    let text = String::from_utf8(out).unwrap();
    let header: serde_json::Value = serde_json::from_str(text.lines().next().unwrap()).unwrap();
    assert_eq!(header["version"], 10);
    assert_eq!(
        header["moving_walls"][1]["a"],
        serde_json::json!([5.0, 2.0])
    );
    assert_eq!(
        header["moving_walls"][0]["velocity"],
        serde_json::json!([0.0, 0.0])
    );
    let steer: Vec<serde_json::Value> = text
        .lines()
        .map(|l| serde_json::from_str::<serde_json::Value>(l).unwrap())
        .filter(|l| l["kind"] == "wall_velocity")
        .collect();
    assert_eq!(steer.len(), 2 * 180);
    assert!(steer.iter().all(|l| l["a"] == 4 || l["a"] == 5));
    assert!(text.contains(r#""kind":"wall","a":"#));
}

#[test]
fn bad_moving_walls_and_bad_steering_are_refused() {
    let base = Scene::<2> {
        bodies: vec![BodySpec::new(Vector([1.0, 1.0]), Vector([1.0, 0.0]), 0.5)],
        walls: box_walls(Vector([10.0, 4.0])),
        moving_walls: vec![plane([0.0, 3.0], [0.0, -1.0], [0.0, 0.0])],
        ..Scene::default()
    };
    let mut sim = Simulation::new(&base, "cells").unwrap();
    let e = sim.set_wall_velocity(1, Vector::ZERO).unwrap_err();
    assert!(
        e.to_string().contains("moving wall 1 does not exist"),
        "{e}"
    );
    let e = sim
        .set_wall_velocity(0, Vector([f64::NAN, 0.0]))
        .unwrap_err();
    assert!(e.to_string().contains("not finite"), "{e}");
    // A body added or moved across a moving wall is refused, as across a static one.
    sim.set_wall_velocity(0, Vector([0.0, -1.0])).unwrap();
    sim.run_until(1.0);
    let e = sim.set_position(0, Vector([5.0, 2.0])).unwrap_err();
    assert!(e.to_string().contains("would cross wall 4"), "{e}");

    let invalid = |f: &dyn Fn(&mut Scene<2>)| {
        let mut s = base.clone();
        f(&mut s);
        s.validate().unwrap_err()
    };
    let e = invalid(&|s| s.moving_walls[0].wall = plane([0.0, 1.2], [0.0, -1.0], [0.0; 2]).wall);
    assert!(matches!(e, SceneError::CrossesWall { wall: 4, .. }), "{e}");
    let e = invalid(&|s| s.moving_walls[0].velocity = Vector([f64::INFINITY, 0.0]));
    assert!(e.to_string().contains("moving_walls[0].velocity"), "{e}");
    let e = invalid(&|s| {
        s.moving_walls[0].wall = Wall::Segment {
            a: Vector([1.0, 3.0]),
            b: Vector([1.0, 3.0]),
        }
    });
    assert!(
        e.to_string().contains("moving_walls[0]") && e.to_string().contains("degenerate"),
        "{e}"
    );
    let e = invalid(&|s| {
        s.walls.clear();
        s.periodic = Some(Vector([10.0, 10.0]));
    });
    assert!(e.to_string().contains("moving_walls"), "{e}");
    let e = DiscreteStepper::new(&base).unwrap_err();
    assert!(e.to_string().contains("static walls only"), "{e}");

    // The scene file's form.
    let text = r#"{"dim": 2, "bodies": [{"pos": [1, 1], "vel": [0, 0], "radius": 0.5}],
        "moving_walls": [{"a": [3, 0], "b": [3, 2], "velocity": [-1, 0]}]}"#;
    let ccdsim::AnyScene::D2(s) = ccdsim::AnyScene::from_json(text).unwrap() else {
        panic!("2D")
    };
    let hit = Simulation::new(&s, "bvh").unwrap().step_event().unwrap();
    assert_eq!((hit.event.time, hit.event.b), (1.5, 0));
}

#[test]
fn a_ball_squeezed_by_a_piston_stops_the_run_with_a_reason_instead_of_hanging() {
    // The gap closes to less than the ball's diameter: its bounces come ever faster, with
    // ever more speed, until f64 no longer resolves them.
    let scene = Scene::<2> {
        bodies: vec![BodySpec::new(Vector([1.0, 0.0]), Vector([1.0, 0.0]), 0.5)],
        walls: vec![Wall::Plane {
            point: Vector([0.0, 0.0]),
            normal: Vector([1.0, 0.0]),
        }],
        moving_walls: vec![plane([3.0, 0.0], [-1.0, 0.0], [-1.0, 0.0])],
        ..Scene::default()
    };
    for finder in FINDERS {
        let mut sim = Simulation::new(&scene, finder).unwrap();
        let events = sim.run_until(10.0);
        let halt = sim.halt().unwrap_or_else(|| panic!("[{finder}] no halt"));
        assert!(sim.time() < 2.0, "[{finder}] {halt}: at {}", sim.time());
        assert!(events > 100, "[{finder}] {events} events, {halt}");
        // Opening the piston again lets the game go on.
        sim.set_wall_velocity(0, Vector([1.0, 0.0])).unwrap();
        assert!(sim.halt().is_none());
    }
}

mod properties {
    use super::*;
    use ccdsim::wall::wall_clearance;
    use ccdsim::world::toi_body_moving_wall;
    use proptest::prelude::*;

    fn vec2(range: f64) -> impl Strategy<Value = Vector<2>> {
        (-range..range, -range..range).prop_map(|(x, y)| Vector([x, y]))
    }

    /// Body 0's clearance from moving wall 0 at `t` (its distance less its radius), metres.
    fn gap(sim: &Simulation<2>, t: f64) -> f64 {
        let w = sim.world();
        wall_clearance(&w.wall_at(w.walls().len(), t), w.position_at(0, t)) - w.radius(0)
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(600))]

        /// The contact found in the wall's frame is a contact in the lab frame: the body
        /// touches the wall where the wall has moved to then, and clears it at every sampled
        /// time before, whatever the two motions, gravity, and which reference time is later.
        #[test]
        fn a_moving_wall_contact_is_the_first_touch_in_the_lab_frame(
            segment in any::<bool>(), a in vec2(4.0), b in vec2(4.0), pos in vec2(8.0),
            vel in vec2(3.0), w0 in vec2(2.0), w1 in vec2(2.0), r in 0.05..1.0f64,
            falling in any::<bool>(), g in vec2(10.0), t1 in 0.0..1.5f64,
        ) {
            let wall = if segment {
                prop_assume!((b - a).norm() > 0.1);
                Wall::Segment { a, b }
            } else {
                prop_assume!(b.norm() > 0.1);
                Wall::Plane { point: a, normal: b }
            };
            let scene = Scene::<2> {
                bodies: vec![BodySpec::new(pos, vel, r)],
                moving_walls: vec![MovingWall { wall, velocity: w0 }],
                settings: Settings {
                    gravity: falling.then(|| ccdsim::Gravity::new(&g.0).unwrap()),
                    ..Settings::default()
                },
                ..Scene::default()
            };
            prop_assume!(scene.validate().is_ok());
            let mut sim = Simulation::new(&scene, "cells").unwrap();
            // Events before t1 restate the body; then the wall turns: the later reference
            // time is either one's.
            sim.run_until(t1);
            sim.set_wall_velocity(0, w1).unwrap();
            let now = sim.time();
            let found = toi_body_moving_wall(sim.world(), 0, 0).filter(|t| *t >= now);
            let horizon = found.unwrap_or(now + 10.0);
            let speed = 1.0 + vel.norm() + w0.norm() + w1.norm() + g.norm() * (horizon + 1.0);
            let tol = 1e-9 * (1.0 + pos.norm() + speed * (horizon + 1.0));
            for k in 0..200 {
                let t = now + (horizon - now) * f64::from(k) / 200.0;
                prop_assert!(gap(&sim, t) > -tol, "overlap {} at {t} before the contact {found:?}", gap(&sim, t));
            }
            if let Some(t) = found {
                prop_assert!(gap(&sim, t).abs() <= tol.max(1e-9), "gap {} at the contact {t}", gap(&sim, t));
            }
        }
    }
}
