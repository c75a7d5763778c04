//! `ccdsim bench shear`: hard spheres in simple shear (Lees–Edwards) against kinetic theory:
//! the viscosity of elastic spheres at several shear rates, extrapolated to zero rate, beside
//! Enskog's; and granular gases whose steady temperature balances the shear's heating against
//! their dissipation. A table, a JSON report and the velocity profiles as CSV.

use super::{parse_list, write_file};
use crate::number::sig;
use crate::progress::Progress;
use anyhow::{anyhow, Result};
use ccdsim_bench::{line_fit, shear_run, ShearConfig, ShearReport};
use std::path::PathBuf;
use std::process::ExitCode;

/// Arguments of `ccdsim bench shear`.
#[derive(clap::Args)]
pub struct Args {
    /// Number of spheres (diameter 1, unit density, kT = 1).
    #[arg(long, default_value_t = 2000)]
    n: usize,
    /// Volume fractions, comma-separated.
    #[arg(long, default_value = "0.1,0.2", value_parser = parse_list::<f64>)]
    packing: std::vec::Vec<f64>,
    /// Reduced shear rates γ̇* = γ̇ σ √(m/kT), comma-separated (elastic runs: the viscosity
    /// is extrapolated linearly to γ̇* → 0 over them).
    #[arg(long, default_value = "0.05,0.1,0.15,0.2", value_parser = parse_list::<f64>)]
    rates: std::vec::Vec<f64>,
    /// Normal restitutions, comma-separated: 1 is elastic (kept at kT = 1 by rescaling the
    /// peculiar velocities), below 1 granular (no thermostat: the steady state).
    #[arg(long, default_value = "1", value_parser = parse_list::<f64>)]
    restitution: std::vec::Vec<f64>,
    /// Collisions per body before measuring.
    #[arg(long, default_value_t = 20.0)]
    settle: f64,
    /// Collisions per body measured.
    #[arg(long, default_value_t = 400.0)]
    collisions_per_body: f64,
    /// Collisions per body between rescalings (elastic runs) and profile samples.
    #[arg(long, default_value_t = 1.0)]
    block: f64,
    /// The TC model's time (granular runs), seconds.
    #[arg(long, default_value_t = 1e-4)]
    tc: f64,
    /// Seed.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Directory for shear.json and shear_profiles.csv.
    #[arg(long, default_value = "target/ccdsim-bench")]
    out: PathBuf,
    /// No progress bar.
    #[arg(long, short)]
    quiet: bool,
}

/// A volume fraction's elastic viscosity extrapolated to zero shear rate.
#[derive(serde::Serialize)]
struct Extrapolated {
    packing: f64,
    viscosity: f64,
    enskog: f64,
    ratio: f64,
}

/// Runs the command.
pub fn run(args: Args) -> Result<ExitCode> {
    let mut cases = Vec::new();
    for &phi in &args.packing {
        for &e in &args.restitution {
            for &rate in &args.rates {
                cases.push((phi, e, rate));
            }
        }
    }
    let per_run = ((args.settle + args.collisions_per_body) * args.n as f64 / 2.0).ceil() as u64;
    let mut progress = Progress::new(per_run * cases.len() as u64, "sheared gases", args.quiet);
    let mut reports = Vec::new();
    for (k, &(packing, restitution, rate)) in cases.iter().enumerate() {
        let cfg = ShearConfig {
            n: args.n,
            packing,
            rate,
            restitution,
            tc: args.tc,
            settle: args.settle,
            collisions_per_body: args.collisions_per_body,
            block: args.block,
            seed: args.seed + k as u64,
        };
        let done = per_run * k as u64;
        let report = shear_run(&cfg, |d, _| progress.set(done + d)).map_err(|e| anyhow!(e))?;
        reports.push(report);
    }
    progress.finish();
    let extrapolated: Vec<Extrapolated> = args
        .packing
        .iter()
        .filter_map(|&phi| {
            let points: Vec<(f64, f64)> = reports
                .iter()
                .filter(|r| r.packing == phi && r.restitution >= 1.0)
                .map(|r| (r.rate, r.viscosity))
                .collect();
            let enskog = ccdsim_bench::enskog_viscosity(phi);
            let viscosity = match points.len() {
                0 => return None,
                1 => points[0].1,
                _ => line_fit(&points).intercept,
            };
            Some(Extrapolated {
                packing: phi,
                viscosity,
                enskog,
                ratio: viscosity / enskog,
            })
        })
        .collect();
    let json = serde_json::json!({ "runs": reports, "zero_rate": extrapolated });
    write_file(
        &args.out,
        "shear.json",
        &(serde_json::to_string_pretty(&json)? + "\n"),
    )?;
    let mut csv = String::from("packing,restitution,rate,y,vx,flow\n");
    for r in &reports {
        for (y, vx) in &r.profile {
            // The imposed flow at y, m/s, from the reduced rate (m = π/6).
            let flow = r.rate / (std::f64::consts::PI / 6.0).sqrt()
                * (y - r.profile.len() as f64 * (r.profile[1].0 - r.profile[0].0) / 2.0);
            csv += &format!(
                "{},{},{},{y},{vx},{flow}\n",
                r.packing, r.restitution, r.rate
            );
        }
    }
    write_file(&args.out, "shear_profiles.csv", &csv)?;
    print_tables(&reports, &extrapolated)?;
    outln!(
        "wrote {0}/shear.json and {0}/shear_profiles.csv",
        args.out.display()
    )?;
    Ok(ExitCode::SUCCESS)
}

fn print_tables(reports: &[ShearReport], zero: &[Extrapolated]) -> std::io::Result<()> {
    outln!(
        "| φ | e | γ̇* | kT | η* | ± | Enskog η* | profile slope / γ̇ | heating per sphere | dissipation per sphere | kT (Navier–Stokes) | collisions | seconds |"
    )?;
    outln!("|---|---|---|---|---|---|---|---|---|---|---|---|---|")?;
    for r in reports {
        outln!(
            "| {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} |",
            r.packing,
            r.restitution,
            r.rate,
            sig(r.temperature, 4),
            sig(r.viscosity, 4),
            sig(r.viscosity_error, 2),
            sig(r.enskog, 4),
            sig(r.profile_slope, 4),
            sig(r.heating, 4),
            sig(r.dissipation, 4),
            r.temperature_theory.map_or("—".into(), |t| sig(t, 4)),
            r.collisions,
            sig(r.seconds, 3)
        )?;
    }
    if !zero.is_empty() {
        outln!()?;
        outln!("| φ | η* at γ̇* → 0 | Enskog η* | ratio |")?;
        outln!("|---|---|---|---|")?;
        for z in zero {
            outln!(
                "| {} | {} | {} | {} |",
                z.packing,
                sig(z.viscosity, 4),
                sig(z.enskog, 4),
                sig(z.ratio, 4)
            )?;
        }
    }
    Ok(())
}
