//! An air-hockey table driven frame by frame: two kinematic paddles (infinite mass, moved
//! only by the velocity the game gives them every frame) chase a puck on a table of four
//! walls. Every hit is found exactly, between frames too; each frame prints nothing, the
//! end prints a summary.
//!
//! ```sh
//! cargo run --release -p ccdsim --example air_hockey
//! cargo run --release -p ccdsim --example air_hockey -- hockey.ccd   # records the game
//! ccdsim verify hockey.ccd && ccdsim view hockey.ccd
//! ```
//!
//! With a file name the game is recorded as a steered run file: the collisions and, between
//! them, every velocity the game gave its paddles (edit records), so that `verify` and the
//! viewer replay it exactly.

use ccdsim::generate::box_walls;
use ccdsim::record::RunWriter;
use ccdsim::{BodySpec, Scene, Simulation, Vector};

/// Table length and width, metres.
const TABLE: [f64; 2] = [2.0, 1.0];
/// Frames per second of the game loop.
const FPS: f64 = 60.0;
/// Seconds played.
const SECONDS: f64 = 30.0;
/// Fastest a paddle moves, metres per second.
const PADDLE_SPEED: f64 = 1.5;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    play(std::env::args().nth(1).as_deref())
}

/// Plays the game, recording it to the run file `out` if given (`tests/suite/examples.rs` runs it
/// too).
pub fn play(out: Option<&str>) -> Result<(), Box<dyn std::error::Error>> {
    let paddle = |x: f64| BodySpec {
        kinematic: true,
        ..BodySpec::new(Vector([x, 0.5]), Vector([0.0, 0.0]), 0.05)
    };
    let puck = BodySpec {
        mass: Some(0.02),
        ..BodySpec::new(Vector([1.0, 0.5]), Vector([1.7, 1.1]), 0.03)
    };
    let mut scene = Scene::<2> {
        bodies: vec![paddle(0.15), paddle(1.85), puck],
        walls: box_walls(Vector(TABLE)),
        ..Scene::default()
    };
    // Cushions and paddles take a tenth of the puck's normal speed; paddles also give it
    // their own velocity, so the game stays lively without running away.
    scene.settings.restitution = 0.9;
    let mut sim = Simulation::new(&scene, "cells")?;
    let mut run = out
        .as_ref()
        .map(|path| RunWriter::record_steered(&mut sim, path.as_ref(), &scene))
        .transpose()?;
    let (mut hits, mut cushions) = (0, 0);
    for _ in 0..(SECONDS * FPS) as usize {
        // Each paddle tracks the puck's height on its own goal line, at a capped speed, and
        // stays on the table (kinematic bodies meet no wall: the game keeps them in).
        let puck_y = sim.position(2)[1];
        for i in 0..2 {
            let y = sim.position(i)[1];
            let want = (puck_y - y) * FPS;
            let vy = want.clamp(-PADDLE_SPEED, PADDLE_SPEED);
            let vy = if (y <= 0.1 && vy < 0.0) || (y >= TABLE[1] - 0.1 && vy > 0.0) {
                0.0
            } else {
                vy
            };
            sim.set_velocity(i, Vector([0.0, vy]))?;
        }
        let edits = sim.take_edits();
        let frame = sim.advance(1.0 / FPS);
        for c in &frame {
            match c.event.kind {
                ccdsim::EventKind::Body => hits += 1,
                _ => cushions += 1,
            }
        }
        if let Some(run) = &mut run {
            for record in edits.iter().chain(&frame) {
                run.write_event(record)?;
            }
        }
    }
    if let (Some(run), Some(path)) = (run, &out) {
        run.finish(sim.time())?;
        println!("recorded to {path}");
    }
    let v = sim.world().velocity_at(2, sim.time());
    println!(
        "{SECONDS} s at {FPS} Hz: {hits} paddle hits, {cushions} cushion bounces, puck at {:.3?} \
         moving {:.3} m/s, largest overlap {:.1e}",
        sim.position(2).0,
        v.norm(),
        sim.stats().max_overlap
    );
    Ok(())
}
