//! A Rapier-style comparison: the same 2D scenes simulated by ccdsim (exact, event-driven)
//! and by Rapier (`rapier2d`, CCD on every ball), frame by frame at 60 Hz. For each: the
//! largest penetration at frame ends, the drift of kinetic plus potential energy, the balls
//! found outside the walled box (tunnelling) and the wall-clock cost per frame.
//!
//! Run: `cargo run --release --manifest-path bench/rapier-compare/Cargo.toml`

mod engines;
mod metrics;
mod report;
mod scenes;

use engines::{CcdOn, Ccdsim, Engine, Rapier};
use metrics::{mechanical_energy, median_p99, outside_box, penetration, Penetration, State};
use report::Outcome;
use scenes::Setup;
use std::time::Instant;

/// Frame length, seconds (60 Hz).
pub const DT: f64 = 1.0 / 60.0;
/// Frames simulated: 10 s.
pub const FRAMES: usize = 600;
/// Gravity, m/s² (downwards).
pub const GRAVITY: f64 = 9.81;
/// Balls of scenes (a) and (b).
pub const N_BALLS: usize = 200;
/// Their radius, metres.
pub const BALL_RADIUS: f64 = 0.05;
/// Side of their square box, metres.
pub const BOX_SIZE: f64 = 4.0;
/// Their speeds are uniform in `[0, MAX_SPEED]`, m/s.
pub const MAX_SPEED: f64 = 5.0;
/// Balls of scene (b) that are bullets instead.
pub const BULLETS: usize = 10;
/// The bullets' speed, m/s.
pub const BULLET_SPEED: f64 = 200.0;
/// Smallest clearance between balls, and from the walls, at the start, metres.
pub const PLACEMENT_GAP: f64 = 0.005;
/// Seed of the random placement.
pub const SEED: u64 = 20_261_125;
/// Thickness of Rapier's box walls (cuboids outside the box), metres.
pub const WALL_THICKNESS: f64 = 1.0;
/// ccdsim's finder (all give the same events; `cells` is the fast one).
pub const CCDSIM_FINDER: &str = "cells";
/// Where the report goes, under `bench/results/`: the machine's folder.
pub const MACHINE_DIR: &str = "amd-epyc-2vcpu";
/// The command named in the report unless `RAPIER_COMPARE_COMMAND` says otherwise.
pub const DEFAULT_COMMAND: &str =
    "CARGO_TARGET_DIR=/work/target-rapier cargo run --release --manifest-path bench/rapier-compare/Cargo.toml";

/// Runs `FRAMES` frames, measuring after each one.
fn run(setup: &Setup, engine: &mut dyn Engine, name: &'static str) -> Outcome {
    let radii = setup.radii();
    let masses = engine.masses();
    let gravity = setup.gravity();
    let mut state = State::default();
    engine.state(&mut state);
    let e0 = mechanical_energy(&masses, gravity, &state);
    let mut worst = Penetration::default();
    let mut outside = vec![false; radii.len()];
    let mut frame_us = Vec::with_capacity(FRAMES);
    let (mut drift_end, mut drift_max) = (0.0, 0.0_f64);
    for _ in 0..FRAMES {
        let start = Instant::now();
        engine.step();
        frame_us.push(start.elapsed().as_secs_f64() * 1e6);
        engine.state(&mut state);
        let p = penetration(setup, &radii, &state.pos);
        worst.pair = worst.pair.max(p.pair);
        worst.wall = worst.wall.max(p.wall);
        for (flag, &x) in outside.iter_mut().zip(&state.pos) {
            *flag |= outside_box(setup, x);
        }
        drift_end = (mechanical_energy(&masses, gravity, &state) - e0) / e0.abs();
        drift_max = drift_max.max(drift_end.abs());
    }
    Outcome {
        scene: setup.name,
        engine: name,
        penetration: worst,
        drift_end,
        drift_max,
        balls_outside: outside.iter().filter(|&&o| o).count(),
        frame_us: median_p99(&frame_us),
        total_s: frame_us.iter().sum::<f64>() * 1e-6,
        notes: engine.notes(),
    }
}

/// Checks the shared energy function against ccdsim's own bookkeeping.
fn check_energy(sim: &Ccdsim, gravity: [f64; 2]) {
    let mut state = State::default();
    sim.state(&mut state);
    let shared = mechanical_energy(&sim.masses(), gravity, &state);
    let own = sim.own_energy();
    assert!(
        (shared - own).abs() <= 1e-9 * own.abs(),
        "shared energy {shared} differs from ccdsim's {own}"
    );
}

fn main() -> std::io::Result<()> {
    let command =
        std::env::var("RAPIER_COMPARE_COMMAND").unwrap_or_else(|_| DEFAULT_COMMAND.to_string());
    let header = report::header(&command);
    let setups = scenes::all();
    let mut outcomes = Vec::new();
    for setup in &setups {
        eprintln!("{}: ccdsim …", setup.name);
        let mut sim = Ccdsim::new(setup);
        outcomes.push(run(setup, &mut sim, "ccdsim"));
        check_energy(&sim, setup.gravity());
        eprintln!("{}: Rapier …", setup.name);
        let mut rapier = Rapier::new(setup, CcdOn::AllBalls);
        outcomes.push(run(setup, &mut rapier, "Rapier"));
        if setup.bullets > 0 {
            eprintln!("{}: Rapier, CCD on the bullets only …", setup.name);
            let mut rapier = Rapier::new(setup, CcdOn::BulletsOnly);
            outcomes.push(run(setup, &mut rapier, "Rapier, CCD on bullets only"));
        }
    }
    let mut md = format!(
        "# ccdsim against Rapier: penetration, energy, tunnelling, cost per frame\n\n{header}\n"
    );
    md.push_str(&format!(
        "Each engine simulates {:.0} s in {FRAMES} frames of 1/60 s, gravity (0, −{GRAVITY}) m/s², \
         every collision elastic. Scenes:\n\n",
        FRAMES as f64 * DT
    ));
    for s in &setups {
        md.push_str(&format!("- {}: {}\n", s.name, s.description));
    }
    md.push_str(&format!(
        "\nccdsim: `Simulation::advance(1/60)` per frame, finder `{CCDSIM_FINDER}`. Rapier: \
         `PhysicsPipeline::step` per frame, `IntegrationParameters::default()` but `dt`, \
         `ccd_enabled(true)` on every ball, restitution 1 with `CoefficientCombineRule::Max`, \
         friction 0, density 1 (the same masses as ccdsim); the box is four fixed cuboids \
         {WALL_THICKNESS} m thick whose inner faces are the box's sides, the pegs are segment \
         colliders. Both start from the same numbers (the initial state is rounded to `f32`, \
         Rapier's precision). Rapier documents that a CCD body (\"bullet\") sweeps every \
         other body except other bullets, so with CCD on every ball its ball–ball contacts rest \
         on speculative contacts alone; the extra row of scene (b) gives CCD to the bullets \
         only, so that they sweep the slow balls.\n\n\
         Measured after every frame, by the same functions for both engines: penetration \
         `(r_i + r_j − |x_i − x_j|) / r` over ball pairs and `(r − distance) / r` against the \
         box's sides and the pegs (balls inside the box); energy `Σ ½ m v² − m g·x` (zero at the \
         box's floor), drift relative to its start; a ball is outside the box when its centre \
         is. Cost: wall-clock time of the step call alone (`advance`, `step`), median and 99th \
         percentile over the {FRAMES} frames, in this one process run.\n\n"
    ));
    md.push_str(&report::table(&outcomes));
    print!("{md}");
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../results")
        .join(MACHINE_DIR)
        .join("rapier");
    std::fs::create_dir_all(&dir)?;
    let dir = dir.canonicalize()?;
    let path = dir.join("comparison.md");
    std::fs::write(&path, &md)?;
    eprintln!("wrote {}", path.display());
    Ok(())
}
