//! `ccdsim bench gas`: hard discs or spheres in a periodic box, run for a fixed number of
//! collisions: collisions per second, peak memory per body, and the compressibility factor Z
//! and collision rate against the Henderson (2D) and Carnahan–Starling (3D) equations of state.

use super::write_file;
use crate::commands::finder_args::FinderArgs;
use crate::number::{num, sig};
use crate::progress::Progress;
use anyhow::{anyhow, Result};
use ccdsim_bench::{gas_bench, GasBenchConfig, GasBenchReport};
use serde::Serialize;
use std::path::PathBuf;
use std::process::ExitCode;

/// Arguments of `ccdsim bench gas`.
#[derive(clap::Args)]
pub struct Args {
    /// Dimension, 2 or 3.
    #[arg(long, default_value_t = 2, value_parser = clap::value_parser!(u8).range(2..=3))]
    dim: u8,
    /// Number of bodies (diameter 1, unit density, kT = 1).
    #[arg(long, default_value_t = 10_000)]
    n: usize,
    /// Packing fraction, in (0, 1).
    #[arg(long, default_value_t = 0.5)]
    packing: f64,
    /// Collisions timed and measured.
    #[arg(long, default_value_t = 10_000_000)]
    collisions: u64,
    /// Collisions run first to melt the lattice start (default: 20 per body).
    #[arg(long)]
    equilibrate: Option<u64>,
    /// Blocks for the statistical errors (block averaging).
    #[arg(long, default_value_t = 20)]
    blocks: usize,
    /// Finder.
    #[arg(long, default_value = "cells")]
    finder: String,
    /// Seed of the Maxwell velocities.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Print one JSON object instead of the table.
    #[arg(long)]
    json: bool,
    /// Directory for gas.json.
    #[arg(long, default_value = "target/ccdsim-bench")]
    out: PathBuf,
    /// No progress bar.
    #[arg(long, short)]
    quiet: bool,
    #[command(flatten)]
    finder_options: FinderArgs,
}

/// The report with the process's peak memory.
#[derive(Serialize)]
struct Output {
    #[serde(flatten)]
    report: GasBenchReport,
    /// Peak resident set size of the whole process (VmHWM), bytes; Linux only.
    peak_rss_bytes: Option<u64>,
    /// `peak_rss_bytes / n`.
    bytes_per_body: Option<f64>,
}

/// CPU time of this process, seconds (Linux: the first field of /proc/self/schedstat).
fn cpu_seconds() -> f64 {
    std::fs::read_to_string("/proc/self/schedstat")
        .ok()
        .and_then(|s| s.split_whitespace().next()?.parse::<f64>().ok())
        .map_or(f64::NAN, |ns| ns * 1e-9)
}

/// Peak resident set size, bytes (Linux: VmHWM in /proc/self/status).
fn peak_rss() -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    let kb: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kb * 1024)
}

/// Runs the command.
pub fn run(args: Args) -> Result<ExitCode> {
    let cfg = GasBenchConfig {
        n: args.n,
        packing: args.packing,
        collisions: args.collisions,
        equilibrate: args.equilibrate,
        blocks: args.blocks,
        finder: args.finder.clone(),
        finder_options: args.finder_options.options()?,
        seed: args.seed,
    };
    let total = cfg.equilibrate.unwrap_or(20 * cfg.n as u64) + cfg.collisions;
    let mut progress = Progress::new(total, "gas bench", args.quiet);
    let clock: Option<&dyn Fn() -> f64> = if cpu_seconds().is_finite() {
        Some(&cpu_seconds)
    } else {
        None
    };
    let report = match args.dim {
        2 => gas_bench::<2>(&cfg, clock, |done, _| progress.set(done)),
        _ => gas_bench::<3>(&cfg, clock, |done, _| progress.set(done)),
    }
    .map_err(|e| anyhow!(e))?;
    progress.finish();
    let peak = peak_rss();
    let out = Output {
        bytes_per_body: peak.map(|b| b as f64 / cfg.n as f64),
        peak_rss_bytes: peak,
        report,
    };
    let json = serde_json::to_string_pretty(&out)? + "\n";
    write_file(&args.out, "gas.json", &json)?;
    if args.json {
        outln!("{}", serde_json::to_string(&out)?)?;
    } else {
        print_table(&out)?;
        outln!("wrote {}/gas.json", args.out.display())?;
    }
    Ok(ExitCode::SUCCESS)
}

fn print_table(o: &Output) -> std::io::Result<()> {
    let r = &o.report;
    let eos = if r.dim == 2 {
        "Henderson"
    } else {
        "Carnahan-Starling"
    };
    outln!(
        "gas: {}D, n = {}, packing {}, finder {}, periodic box, lattice start, kT = {}",
        r.dim,
        r.n,
        num(r.packing),
        r.finder,
        num(r.temperature)
    )?;
    outln!(
        "{} collisions after {} to equilibrate; {} s wall, {} s CPU; {} simulated s",
        r.collisions,
        r.equilibrated,
        sig(r.seconds, 4),
        r.cpu_seconds.map_or("?".to_string(), |c| sig(c, 4)),
        num(r.sim_time)
    )?;
    outln!(
        "collisions/s        {} (wall), {} (CPU)",
        sig(r.collisions_per_second, 5),
        r.collisions_per_cpu_second
            .map_or("?".to_string(), |c| sig(c, 5))
    )?;
    match (o.peak_rss_bytes, o.bytes_per_body) {
        (Some(p), Some(b)) => outln!(
            "peak memory         {:.1} MiB = {:.1} bytes/body (finder {} bytes/body)",
            p as f64 / (1 << 20) as f64,
            b,
            r.finder_bytes
                .map_or("?".to_string(), |f| format!("{:.1}", f as f64 / r.n as f64))
        )?,
        _ => outln!("peak memory         unknown on this system")?,
    }
    let dev = |x: f64, e: f64| 100.0 * (x / e - 1.0);
    outln!(
        "Z                   {:.5} ± {:.5}   {eos} {:.5} ({:+.2} %)",
        r.compressibility,
        r.compressibility_error,
        r.compressibility_eos,
        dev(r.compressibility, r.compressibility_eos)
    )?;
    outln!(
        "collision rate      {:.5} ± {:.5}   {eos} (Enskog) {:.5} ({:+.2} %)",
        r.collision_rate,
        r.collision_rate_error,
        r.collision_rate_eos,
        dev(r.collision_rate, r.collision_rate_eos)
    )?;
    if !r.finder_counters.is_empty() && r.collisions > 0 {
        let per: Vec<String> = r
            .finder_counters
            .iter()
            .map(|(name, count)| format!("{name} {:.3}", *count as f64 / r.collisions as f64))
            .collect();
        outln!("finder work         per collision: {}", per.join(", "))?;
    }
    Ok(())
}
