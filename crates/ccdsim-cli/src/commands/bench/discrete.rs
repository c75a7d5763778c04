//! `ccdsim bench discrete`: Table 5.2 of the thesis, the exact simulation against a
//! discrete-time stepper at several time steps.

use super::{parse_list, write_file, SceneRuns};
use crate::progress::Progress;
use anyhow::{anyhow, Result};
use ccdsim::FINDER_NAMES;
use ccdsim_bench::{run_discrete_bench, DiscreteBenchConfig};
use std::process::ExitCode;

/// Arguments of `ccdsim bench discrete`.
#[derive(clap::Args)]
pub struct Args {
    /// Number of bodies.
    #[arg(long, default_value_t = 1024)]
    n: usize,
    /// Time steps of the discrete stepper, seconds, comma-separated.
    #[arg(long, default_value = "0.001,0.005,0.01,0.03,0.1,1", value_parser = parse_list::<f64>)]
    dt: std::vec::Vec<f64>,
    /// The exact finder of the first row (default: bvh when built in, else sedgewick).
    #[arg(long)]
    finder: Option<String>,
    #[command(flatten)]
    runs: SceneRuns,
}

/// Runs the command.
pub fn run(args: Args) -> Result<ExitCode> {
    let finder = args.finder.unwrap_or_else(|| {
        if FINDER_NAMES.contains(&"bvh") {
            "bvh".into()
        } else {
            "sedgewick".into()
        }
    });
    let cfg = DiscreteBenchConfig {
        n: args.n,
        dts: args.dt,
        runs: args.runs.runs()?,
        first_seed: args.runs.seed,
        finder,
        duration: args.runs.duration,
        dim: args.runs.dim(),
    };
    let total = u64::from(cfg.runs) * (1 + cfg.dts.len() as u64);
    let mut progress = Progress::new(total, "discrete bench", args.runs.quiet);
    let report = run_discrete_bench(&cfg, |done, _| progress.set(done)).map_err(|e| anyhow!(e))?;
    progress.finish();
    outln!(
        "Thesis §5.2 scene, {}D, n = {}, {} simulated s per run, mean of {} run(s)",
        cfg.dim,
        cfg.n,
        cfg.duration,
        cfg.runs
    )?;
    out!("{}", report.table())?;
    outln!("total {:.1} s", report.total_seconds)?;
    write_file(&args.runs.out, "discrete.csv", &report.csv())?;
    write_file(
        &args.runs.out,
        "discrete.json",
        &(serde_json::to_string_pretty(&report)? + "\n"),
    )?;
    outln!("wrote {}/discrete.{{csv,json}}", args.runs.out.display())?;
    Ok(ExitCode::SUCCESS)
}
