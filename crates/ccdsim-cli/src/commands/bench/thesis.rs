//! `ccdsim bench thesis`: Table 5.1 and Figure 5.1 of the thesis, for every finder.

use super::plot::{plot_times, Series};
use super::{parse_list, write_file, SceneRuns};
use crate::progress::Progress;
use anyhow::{anyhow, Result};
use ccdsim::generate::THESIS_TABLE_5_1;
use ccdsim::FINDER_NAMES;
use ccdsim_bench::{run_thesis_bench, CellStatus, ThesisBenchConfig};
use std::process::ExitCode;

/// Arguments of `ccdsim bench thesis`.
#[derive(clap::Args)]
pub struct Args {
    /// Numbers of bodies, comma-separated, increasing.
    #[arg(long, default_value = "8,16,32,64,128,256,512,1024,2048", value_parser = parse_list::<usize>)]
    sizes: std::vec::Vec<usize>,
    /// Finders, comma-separated (default: every finder).
    #[arg(long, value_parser = parse_list::<String>)]
    finders: Option<std::vec::Vec<String>>,
    /// Time budget of each finder over all its sizes, seconds. A size predicted not to fit in
    /// what is left, or whose runs use it up, is shown as skipped, and so are the finder's
    /// larger sizes.
    #[arg(long, default_value_t = 120.0)]
    budget: f64,
    #[command(flatten)]
    runs: SceneRuns,
}

/// Runs the command.
pub fn run(args: Args) -> Result<ExitCode> {
    let cfg = ThesisBenchConfig {
        sizes: args.sizes,
        runs: args.runs.runs()?,
        first_seed: args.runs.seed,
        finders: args
            .finders
            .unwrap_or_else(|| FINDER_NAMES.iter().map(|s| (*s).to_string()).collect()),
        budget_seconds: args.budget,
        duration: args.runs.duration,
        dim: args.runs.dim(),
    };
    let total = (cfg.sizes.len() * cfg.finders.len()) as u64 * u64::from(cfg.runs);
    let mut progress = Progress::new(total, "thesis bench", args.runs.quiet);
    let report = run_thesis_bench(&cfg, |done, _| progress.set(done)).map_err(|e| anyhow!(e))?;
    progress.finish();
    outln!(
        "Thesis §5.2 scene, {}D, {} simulated s per run, mean of {} run(s) per cell, budget {} s per finder",
        cfg.dim, cfg.duration, cfg.runs, cfg.budget_seconds
    )?;
    out!("{}", report.table())?;
    outln!("largest n completed:")?;
    for (f, n) in report.largest_sizes() {
        outln!(
            "  {f:>10}: {}",
            n.map_or("none".to_string(), |n| n.to_string())
        )?;
    }
    outln!("total {:.1} s", report.total_seconds)?;

    write_file(&args.runs.out, "thesis.csv", &report.csv())?;
    write_file(
        &args.runs.out,
        "thesis.json",
        &(serde_json::to_string_pretty(&report)? + "\n"),
    )?;
    let mut series: Vec<Series> = cfg
        .finders
        .iter()
        .enumerate()
        .map(|(k, f)| Series {
            label: f.clone(),
            colour: k,
            points: report
                .cells
                .iter()
                .filter(|c| &c.finder == f && c.status == CellStatus::Done)
                .map(|c| (c.n as f64, c.mean_seconds))
                .collect(),
            thesis: false,
        })
        .collect();
    if cfg.dim == 2 && cfg.duration == 5.0 {
        for (finder, k) in [("all-pairs", 2), ("bvh", 3)] {
            let colour = cfg
                .finders
                .iter()
                .position(|f| f == finder)
                .unwrap_or(cfg.finders.len() + k);
            series.push(Series {
                label: format!("thesis {finder} (i7-2630QM)"),
                colour,
                points: THESIS_TABLE_5_1
                    .iter()
                    .filter(|r| cfg.sizes.contains(&r.0))
                    .map(|r| (r.0 as f64, if k == 2 { r.2 } else { r.3 }))
                    .collect(),
                thesis: true,
            });
        }
    }
    let title = format!(
        "Thesis scene ({}D, {} s simulated): seconds per run against n",
        cfg.dim, cfg.duration
    );
    plot_times(&args.runs.out.join("thesis.png"), &title, &series)?;
    plot_times(&args.runs.out.join("thesis.svg"), &title, &series)?;
    outln!(
        "wrote {}/thesis.{{csv,json,png,svg}}",
        args.runs.out.display()
    )?;
    Ok(ExitCode::SUCCESS)
}
