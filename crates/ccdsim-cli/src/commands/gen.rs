//! `ccdsim gen`: write a generated scene as JSON.

use anyhow::{Context, Result};
use ccdsim::generate::{gas, rack, GasConfig, RackConfig};
use ccdsim::AnyScene;
use std::path::PathBuf;
use std::process::ExitCode;

/// Arguments of `ccdsim gen`.
#[derive(clap::Args)]
pub struct Args {
    #[command(subcommand)]
    kind: Kind,
    /// Write the scene here instead of to standard output.
    #[arg(long, global = true)]
    out: Option<PathBuf>,
}

#[derive(clap::Subcommand)]
enum Kind {
    /// Random non-overlapping bodies in a walled box.
    Gas(GasArgs),
    /// A 15-ball billiard rack with the cue ball shot into it (2D).
    Rack(RackArgs),
}

#[derive(clap::Args)]
struct GasArgs {
    /// Number of bodies.
    #[arg(long, default_value_t = 1000)]
    n: usize,
    /// Fraction of the box covered by bodies, in (0, 1).
    #[arg(long, default_value_t = 0.2)]
    packing: f64,
    /// Smallest radius, metres.
    #[arg(long, default_value_t = 0.5)]
    radius_min: f64,
    /// Largest radius, metres.
    #[arg(long, default_value_t = 0.5)]
    radius_max: f64,
    /// Smallest speed, m/s.
    #[arg(long, default_value_t = 0.0)]
    speed_min: f64,
    /// Largest speed, m/s.
    #[arg(long, default_value_t = 1.0)]
    speed_max: f64,
    /// Random seed.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Dimension, 2 or 3.
    #[arg(long, default_value_t = 2, value_parser = clap::value_parser!(u8).range(2..=3))]
    dim: u8,
}

#[derive(clap::Args)]
struct RackArgs {
    /// Cue ball speed, m/s.
    #[arg(long, default_value_t = RackConfig::default().speed)]
    speed: f64,
    /// Sideways offset of the cue ball's aim, metres (0 = dead centre).
    #[arg(long, default_value_t = RackConfig::default().offset)]
    offset: f64,
}

/// Runs the command.
pub fn run(args: Args) -> Result<ExitCode> {
    let scene: AnyScene = match args.kind {
        Kind::Gas(g) => {
            let cfg = GasConfig {
                n: g.n,
                packing: g.packing,
                radius_min: g.radius_min,
                radius_max: g.radius_max,
                speed_min: g.speed_min,
                speed_max: g.speed_max,
                seed: g.seed,
            };
            if g.dim == 2 {
                gas::<2>(&cfg)?.into()
            } else {
                gas::<3>(&cfg)?.into()
            }
        }
        Kind::Rack(r) => {
            let scene = rack(&RackConfig {
                speed: r.speed,
                offset: r.offset,
                ..RackConfig::default()
            });
            scene.validate().context("rack")?;
            scene.into()
        }
    };
    let json = scene.to_json();
    match args.out {
        Some(path) => std::fs::write(&path, json + "\n")
            .with_context(|| format!("writing {}", path.display()))?,
        None => println!("{json}"),
    }
    Ok(ExitCode::SUCCESS)
}
