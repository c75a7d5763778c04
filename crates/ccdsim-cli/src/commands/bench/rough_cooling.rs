//! `ccdsim bench rough-cooling`: homogeneous cooling gases of rough spheres against the
//! Huthmann–Zippelius theory, over a grid of normal and tangential restitutions: a table, a
//! JSON report, the samples as CSV and a plot of `T_rot/T_tr` against collisions per body.

use super::{parse_list, write_file};
use crate::number::sig;
use crate::progress::Progress;
use anyhow::{anyhow, Result};
use ccdsim_bench::{default_settle, rough_cooling, CoolingConfig, CoolingReport};
use plotters::prelude::*;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

/// Arguments of `ccdsim bench rough-cooling`.
#[derive(clap::Args)]
pub struct Args {
    /// Number of spheres (radius ½, unit density, kT = kT_rot = 1 at the start).
    #[arg(long, default_value_t = 10_000)]
    n: usize,
    /// Volume fraction. Dilute, so that the gas stays homogeneous (no clusters, no
    /// vortices) for the many collisions weakly rough spheres need to settle.
    #[arg(long, default_value_t = 0.01)]
    packing: f64,
    /// Normal restitutions, comma-separated. (`std::vec::Vec`: clap reads a plain `Vec` as
    /// a repeated option, not one parsed list.)
    #[arg(long, default_value = "0.7,0.9,0.99", value_parser = parse_list::<f64>)]
    restitution: std::vec::Vec<f64>,
    /// Tangential restitutions, comma-separated.
    #[arg(long, default_value = "-0.5,0,0.5,1", value_parser = parse_list::<f64>, allow_hyphen_values = true)]
    tangential_restitution: std::vec::Vec<f64>,
    /// Moment-of-inertia factor q (2/5: solid spheres).
    #[arg(long, default_value_t = 0.4)]
    inertia: f64,
    /// Collisions per body run before measuring (default: eight relaxation times of the
    /// ratio T_rot/T_tr by the theory, at least 10).
    #[arg(long)]
    settle: Option<f64>,
    /// Collisions per body measured after settling.
    #[arg(long, default_value_t = 20.0)]
    collisions_per_body: f64,
    /// The TC model's time, seconds.
    #[arg(long, default_value_t = 1e-4)]
    tc: f64,
    /// Seed.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Directory for rough_cooling.json, rough_cooling.csv and rough_cooling.svg.
    #[arg(long, default_value = "target/ccdsim-bench")]
    out: PathBuf,
    /// No progress bar.
    #[arg(long, short)]
    quiet: bool,
}

/// Runs the command.
pub fn run(args: Args) -> Result<ExitCode> {
    let cases: Vec<(f64, f64)> = args
        .restitution
        .iter()
        .flat_map(|&e| args.tangential_restitution.iter().map(move |&b| (e, b)))
        .collect();
    let per_body = |e: f64, beta: f64| {
        args.settle
            .unwrap_or_else(|| default_settle(e, beta, args.inertia))
            + args.collisions_per_body
    };
    let runs: Vec<u64> = cases
        .iter()
        .map(|&(e, b)| (per_body(e, b) * args.n as f64 / 2.0).ceil() as u64)
        .collect();
    let mut progress = Progress::new(runs.iter().sum(), "rough cooling", args.quiet);
    let mut reports = Vec::new();
    let mut done = 0;
    for (k, &(e, beta)) in cases.iter().enumerate() {
        let cfg = CoolingConfig {
            n: args.n,
            packing: args.packing,
            restitution: e,
            tangential_restitution: beta,
            inertia: args.inertia,
            tc: args.tc,
            settle: args.settle,
            collisions_per_body: args.collisions_per_body,
            seed: args.seed,
            ..CoolingConfig::default()
        };
        let report = rough_cooling(&cfg, |d, _| progress.set(done + d)).map_err(|e| anyhow!(e))?;
        done += runs[k];
        reports.push(report);
    }
    progress.finish();
    write_file(
        &args.out,
        "rough_cooling.json",
        &(serde_json::to_string_pretty(&reports)? + "\n"),
    )?;
    let mut csv =
        String::from("e,beta,collisions_per_body,time,temperature,rotational_temperature\n");
    for r in &reports {
        for s in &r.samples {
            csv += &format!(
                "{},{},{},{},{},{}\n",
                r.restitution,
                r.tangential_restitution,
                s.collisions_per_body,
                s.time,
                s.temperature,
                s.rotational_temperature
            );
        }
    }
    write_file(&args.out, "rough_cooling.csv", &csv)?;
    let plot = args.out.join("rough_cooling.svg");
    plot_ratios(&plot, &reports)?;
    print_table(&reports)?;
    outln!(
        "wrote {0}/rough_cooling.json, {0}/rough_cooling.csv and {1}",
        args.out.display(),
        plot.display()
    )?;
    Ok(ExitCode::SUCCESS)
}

fn print_table(reports: &[CoolingReport]) -> std::io::Result<()> {
    outln!(
        "| e | β | settle | T_rot/T_tr | theory | decay per collision | theory | Haff R² | energy change | collisions | seconds |"
    )?;
    outln!("|---|---|---|---|---|---|---|---|---|---|---|")?;
    for r in reports {
        outln!(
            "| {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} |",
            r.restitution,
            r.tangential_restitution,
            sig(r.settle, 3),
            sig(r.ratio, 4),
            sig(r.ratio_theory, 4),
            sig(r.decay, 4),
            sig(r.decay_theory, 4),
            format!("{:.6}", r.haff_r2),
            sig(r.energy_change, 3),
            r.collisions,
            sig(r.seconds, 3)
        )?;
    }
    Ok(())
}

const COLOURS: [RGBColor; 4] = [
    RGBColor(0xd6, 0x27, 0x28),
    RGBColor(0x1f, 0x77, 0xb4),
    RGBColor(0x2c, 0xa0, 0x2c),
    RGBColor(0x94, 0x67, 0xbd),
];

/// `T_rot/T_tr` against collisions per body, each run's theory as a dashed line; one panel
/// per normal restitution.
fn plot_ratios(path: &Path, reports: &[CoolingReport]) -> Result<()> {
    let root = SVGBackend::new(path, (1200, 450)).into_drawing_area();
    let fail = |e: &dyn std::fmt::Display| anyhow!("drawing {}: {e}", path.display());
    root.fill(&WHITE).map_err(|e| fail(&e))?;
    let mut restitutions: Vec<f64> = reports.iter().map(|r| r.restitution).collect();
    restitutions.dedup();
    let panels = root.split_evenly((1, restitutions.len().max(1)));
    let tau = reports
        .iter()
        .flat_map(|r| r.samples.last())
        .map(|s| s.collisions_per_body)
        .fold(1.0, f64::max);
    let top = reports
        .iter()
        .flat_map(|r| {
            r.samples
                .iter()
                .map(|s| s.rotational_temperature / s.temperature)
        })
        .chain(reports.iter().map(|r| r.ratio_theory))
        .filter(|x| x.is_finite())
        .fold(1.0, f64::max)
        * 1.1;
    for (panel, e) in panels.iter().zip(&restitutions) {
        let mut chart = ChartBuilder::on(panel)
            .caption(format!("e = {e}"), ("sans-serif", 22))
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(50)
            .build_cartesian_2d(0.0..tau, 0.0..top)
            .map_err(|e| fail(&e))?;
        chart
            .configure_mesh()
            .x_desc("collisions per sphere")
            .y_desc("T_rot / T_tr")
            .draw()
            .map_err(|e| fail(&e))?;
        for (k, r) in reports.iter().filter(|r| r.restitution == *e).enumerate() {
            let colour = COLOURS[k % COLOURS.len()];
            chart
                .draw_series(LineSeries::new(
                    r.samples.iter().map(|s| {
                        (
                            s.collisions_per_body,
                            s.rotational_temperature / s.temperature,
                        )
                    }),
                    colour.stroke_width(2),
                ))
                .map_err(|e| fail(&e))?
                .label(format!("β = {}", r.tangential_restitution))
                .legend(move |(x, y)| PathElement::new([(x, y), (x + 18, y)], colour));
            if r.ratio_theory.is_finite() {
                chart
                    .draw_series(DashedLineSeries::new(
                        [(0.0, r.ratio_theory), (tau, r.ratio_theory)],
                        6,
                        4,
                        colour.stroke_width(1),
                    ))
                    .map_err(|e| fail(&e))?;
            }
        }
        chart
            .configure_series_labels()
            .background_style(WHITE.mix(0.8))
            .border_style(BLACK)
            .draw()
            .map_err(|e| fail(&e))?;
    }
    root.present().map_err(|e| fail(&e))?;
    Ok(())
}
