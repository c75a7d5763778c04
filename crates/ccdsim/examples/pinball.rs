//! A pinball-like table: a ball on a table tilted by 7° (gravity 1.2 m/s² down the table),
//! launched up the plunger lane, bouncing off round and triangular bumpers (wall segments)
//! and walls, scoring when it passes through target sensors, and drained at the bottom into
//! a sensor that puts it back in the plunger lane for the next ball (a ball that rolls back
//! into the lane is launched again). Every bounce is exact; so are the times the ball
//! crosses the targets.
//!
//! ```sh
//! cargo run --release -p ccdsim --example pinball
//! cargo run --release -p ccdsim --example pinball -- pinball.ccd   # records the game
//! ccdsim verify pinball.ccd && ccdsim view pinball.ccd
//! ```

use ccdsim::record::RunWriter;
use ccdsim::Gravity;
use ccdsim::{BodySpec, Scene, Sensor, SensorChange, Simulation, Vector, Wall};

/// Table width and length, metres.
const TABLE: [f64; 2] = [0.6, 1.2];
/// Width of the plunger lane along the right side, metres.
const LANE: f64 = 0.06;
/// Ball radius, metres.
const BALL: f64 = 0.014;
/// Frames per second of the game loop.
const FPS: f64 = 60.0;
/// Balls played.
const BALLS: usize = 5;
/// Longest a ball is played, seconds.
const MAX_SECONDS: f64 = 120.0;

fn segment(a: [f64; 2], b: [f64; 2]) -> Wall<2> {
    Wall::Segment {
        a: Vector(a),
        b: Vector(b),
    }
}

/// A closed polygon of segments.
fn polygon(points: &[[f64; 2]]) -> Vec<Wall<2>> {
    (0..points.len())
        .map(|k| segment(points[k], points[(k + 1) % points.len()]))
        .collect()
}

/// A sensor of radius `r` around `c`.
fn sensor(c: [f64; 2], r: f64) -> Sensor<2> {
    Sensor {
        center: Vector(c),
        radius: r,
    }
}

/// A round bumper: a regular polygon of `sides` segments around `c`.
fn bumper(c: [f64; 2], r: f64, sides: usize) -> Vec<Wall<2>> {
    let points: Vec<[f64; 2]> = (0..sides)
        .map(|k| {
            let a = std::f64::consts::TAU * k as f64 / sides as f64;
            [c[0] + r * a.cos(), c[1] + r * a.sin()]
        })
        .collect();
    polygon(&points)
}

fn table() -> Scene<2> {
    let [w, h] = TABLE;
    let lane = w - LANE;
    let mut walls = vec![
        // The cabinet, with a drain gap at the bottom between the two slopes.
        segment([0.0, 0.25], [0.0, h - 0.1]),
        segment([0.0, h - 0.1], [0.1, h]),
        segment([0.1, h], [w - 0.1, h]),
        segment([w - 0.1, h], [w, h - 0.1]),
        segment([w, h - 0.1], [w, 0.0]),
        segment([w, 0.0], [lane, 0.0]),
        // The plunger lane's inner wall, open at the top.
        segment([lane, 0.0], [lane, h - 0.25]),
        // Slopes down to the drain.
        segment([0.0, 0.25], [0.24, 0.08]),
        segment([lane, 0.25], [0.34, 0.08]),
        // A deflector that sends the launched ball into the playfield.
        segment([w - 0.02, h - 0.12], [w - 0.09, h - 0.02]),
    ];
    for (c, r) in [
        ([0.18, 0.85], 0.035),
        ([0.36, 0.9], 0.035),
        ([0.27, 0.72], 0.035),
    ] {
        walls.extend(bumper(c, r, 12));
    }
    // Triangular slingshots above the slopes.
    walls.extend(polygon(&[[0.06, 0.38], [0.06, 0.26], [0.14, 0.27]]));
    walls.extend(polygon(&[
        [lane - 0.06, 0.38],
        [lane - 0.14, 0.27],
        [lane - 0.06, 0.26],
    ]));
    let mut scene = Scene {
        bodies: vec![BodySpec::new(Vector(PLUNGER), Vector([0.0, LAUNCH]), BALL)],
        walls,
        sensors: vec![
            // Targets: the three lanes at the top, and the centre spinner.
            sensor([0.15, 1.05], 0.02),
            sensor([0.27, 1.05], 0.02),
            sensor([0.39, 1.05], 0.02),
            sensor([0.27, 0.5], 0.03),
            // The drain: a wide region below the gap between the slopes, which a ball falling
            // out of the table meets whichever way it goes.
            sensor([0.29, -1.0], 1.0),
            // The bottom of the plunger lane: a ball that rolls back into the lane is
            // launched again.
            sensor([PLUNGER[0], 0.03], 0.01),
        ],
        ..Scene::default()
    };
    // 7° of tilt: g·sin 7° down the table.
    scene.settings.gravity = Gravity::new(&[0.0, -9.81 * 7f64.to_radians().sin()]);
    scene.settings.restitution = 0.8;
    scene.settings.tc = Some(1e-3);
    scene
}

/// Where a ball waits in the plunger lane, and the speed it is launched at (m/s).
const PLUNGER: [f64; 2] = [TABLE[0] - LANE / 2.0, 0.05];
const LAUNCH: f64 = 1.9;
/// Points per target, by sensor index (the drain and the plunger score nothing).
const POINTS: [u64; 6] = [100, 100, 100, 50, 0, 0];
const DRAIN: usize = 4;
const RELAUNCH: usize = 5;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    play(std::env::args().nth(1).as_deref())
}

/// Plays the game, recording it to the run file `out` if given (`tests/suite/examples.rs` runs it
/// too).
pub fn play(out: Option<&str>) -> Result<(), Box<dyn std::error::Error>> {
    let scene = table();
    let mut sim = Simulation::new(&scene, "cells")?;
    let mut run = out
        .as_ref()
        .map(|path| RunWriter::record_steered(&mut sim, path.as_ref(), &scene))
        .transpose()?;
    let (mut score, mut played, mut kicks) = (0u64, 1usize, 0usize);
    let mut ball_started = sim.time();
    while played <= BALLS && sim.time() < MAX_SECONDS * BALLS as f64 {
        let frame = sim.advance(1.0 / FPS);
        if let Some(run) = &mut run {
            for record in &frame {
                run.write_event(record)?;
            }
        }
        let (mut drained, mut fell_back) = (false, false);
        for e in sim.take_sensor_events() {
            if e.change != SensorChange::Enter {
                continue;
            }
            score += POINTS[e.sensor];
            drained |= e.sensor == DRAIN;
            fell_back |= e.sensor == RELAUNCH;
        }
        if fell_back && !drained && sim.world().velocity_at(0, sim.time())[1] <= 0.0 {
            sim.set_velocity(0, Vector([0.0, LAUNCH]))?;
            kicks += 1;
        }
        // A ball that has not drained in MAX_SECONDS is stuck somewhere: it is served again.
        if drained || sim.time() - ball_started > MAX_SECONDS {
            println!(
                "ball {played}: {} after {:.1} s, score {score}",
                if drained {
                    "drained".to_string()
                } else {
                    format!("stuck at {:?}, served again", sim.position(0).0)
                },
                sim.time() - ball_started
            );
            played += 1;
            ball_started = sim.time();
            if played <= BALLS {
                // The next ball: back to the plunger, launched with a little less or more
                // force each time so that no two balls play alike.
                sim.set_position(0, Vector(PLUNGER))?;
                let launch = LAUNCH * (1.0 + 0.02 * (played as f64 - 3.0));
                sim.set_velocity(0, Vector([0.0, launch]))?;
                kicks += 1;
            }
        }
        if let Some(run) = &mut run {
            for record in sim.take_edits() {
                run.write_event(&record)?;
            }
        }
    }
    println!(
        "{BALLS} balls in {:.1} s of play: score {score}, {} bounces, {kicks} launches and \
         relaunches, largest overlap {:.1e}",
        sim.time(),
        sim.stats().wall_collisions,
        sim.stats().max_overlap
    );
    if let (Some(run), Some(path)) = (run, &out) {
        run.finish(sim.time())?;
        println!("recorded to {path}");
    }
    Ok(())
}
