//! A Galton board with a sink: balls fall through rows of pegs under gravity into bins along
//! the floor, sensors that report the instant a ball enters one; the sink takes each ball
//! that lands out of the game (`remove_body`), counts it in its bin's column, and a new ball
//! is dropped in from above the pegs (`add_body`, which fills the slot the landed ball left:
//! every other ball keeps its index). Collisions and landings are exact; a new ball refused
//! where it would overlap another is tried elsewhere; the end prints the histogram. (Pegs and
//! side walls this far apart scatter the balls widely: the edges fill as well as the middle.)
//!
//! ```sh
//! cargo run --release -p ccdsim --example galton
//! cargo run --release -p ccdsim --example galton -- galton.ccd   # records it
//! ccdsim verify galton.ccd && ccdsim view galton.ccd
//! ```
//!
//! With a file name the run is recorded as a steered run file, the balls taken out and
//! dropped in as edit records, so that `verify` and the viewer replay it exactly.

use ccdsim::generate::{pegs, PegsConfig};
use ccdsim::record::RunWriter;
use ccdsim::{BodySpec, SensorChange, Simulation, Vector};

/// Bins along the floor.
const BINS: usize = 12;
/// Seconds played.
const SECONDS: f64 = 120.0;
/// Frames per second of the loop that empties the sink.
const FPS: f64 = 30.0;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    play(std::env::args().nth(1).as_deref())
}

/// Plays the game, recording it to the run file `out` if given (`tests/suite/examples.rs` runs it
/// too).
pub fn play(out: Option<&str>) -> Result<(), Box<dyn std::error::Error>> {
    let mut scene = pegs(&PegsConfig {
        rows: 10,
        balls: 32,
        bins: BINS,
        restitution: 0.6,
        ..PegsConfig::default()
    })?;
    // The generator tilts every peg the same way (so that no ball rests on a flat top),
    // which would push balls left: here every other peg leans the other way.
    for (k, wall) in scene.walls.iter_mut().skip(4).enumerate() {
        if let ccdsim::Wall::Segment { a, b } = wall {
            if k % 2 == 1 {
                std::mem::swap(&mut a[1], &mut b[1]);
            }
        }
    }
    let top = scene
        .bodies
        .iter()
        .map(|b| b.pos[1])
        .fold(f64::NEG_INFINITY, f64::max);
    let radius = scene.bodies[0].radius;
    let mut sim = Simulation::new(&scene, "cells")?;
    let mut run = out
        .as_ref()
        .map(|path| RunWriter::record_steered(&mut sim, path.as_ref(), &scene))
        .transpose()?;
    let mut counts = [0u64; BINS];
    // A small deterministic generator for the respawn spots.
    let mut seed = 0x2545_f491_4f6c_dd1du64;
    let mut next = || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        (seed >> 11) as f64 / (1u64 << 53) as f64
    };
    let frames = (SECONDS * FPS) as usize;
    for _ in 0..frames {
        let frame = sim.advance(1.0 / FPS);
        if let Some(run) = &mut run {
            for record in &frame {
                run.write_event(record)?;
            }
        }
        for e in sim.take_sensor_events() {
            if e.change != SensorChange::Enter
                || sim
                    .sensors()
                    .is_some_and(|s| !s.is_inside(e.body, e.sensor))
            {
                continue;
            }
            counts[e.sensor] += 1;
            sim.remove_body(e.body)?;
            // A new ball, falling from above the middle of the board: try spots until one is
            // free of other balls.
            for _ in 0..100 {
                let pos = Vector([4.0 + 4.0 * next(), top]);
                let vel = Vector([0.2 * (next() - 0.5), 0.0]);
                if sim.add_body(BodySpec::new(pos, vel, radius)).is_ok() {
                    break;
                }
            }
        }
        if let Some(run) = &mut run {
            for record in sim.take_edits() {
                run.write_event(&record)?;
            }
        }
    }
    if let (Some(run), Some(path)) = (run, &out) {
        run.finish(sim.time())?;
        println!("recorded to {path}");
    }
    let total: u64 = counts.iter().sum();
    println!(
        "{total} balls landed in {SECONDS} s ({} collisions, {} of them with pegs and walls):",
        sim.stats().events,
        sim.stats().wall_collisions
    );
    let most = counts.iter().copied().max().unwrap_or(1).max(1);
    for (k, &c) in counts.iter().enumerate() {
        let bar = "#".repeat((60 * c / most) as usize);
        println!("bin {k:2} {c:6} {bar}");
    }
    Ok(())
}
