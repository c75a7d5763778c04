//! `ccdsim-fuzz`: the differential fuzzer, run for as long as one likes.
//!
//! ```sh
//! cargo run --release -p ccdsim-fuzz -- --minutes 30            # 30 minutes, both cores
//! cargo run --release -p ccdsim-fuzz -- --cases 100000 --seed 7
//! cargo run --release -p ccdsim-fuzz -- replay crates/ccdsim-fuzz/regressions/*.json
//! ```
//!
//! Failing cases are shrunk and written to `--out` (by default the regression directory that
//! the tests replay); the exit status is 1 when any case failed, 3 on a hang.

use anyhow::{Context, Result};
use ccdsim_fuzz::campaign::{self, Progress, Settings};
use ccdsim_fuzz::{check_case, Case};
use clap::{Parser, Subcommand};
use std::io::IsTerminal;
use std::path::PathBuf;
use std::sync::atomic::Ordering;
use std::sync::Arc;
use std::time::Duration;

#[derive(Parser)]
#[command(
    about = "Differential fuzzer: adversarial scenes through every finder against the all-pairs oracle"
)]
struct Cli {
    #[command(subcommand)]
    command: Option<Command>,
    /// Minutes to run (default 1, unless --cases is given).
    #[arg(long)]
    minutes: Option<f64>,
    /// Stop after this many cases.
    #[arg(long)]
    cases: Option<u64>,
    /// Campaign seed.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Threads (default: the machine's cores).
    #[arg(long)]
    threads: Option<usize>,
    /// Bodies per scene, at most.
    #[arg(long, default_value_t = 24)]
    max_bodies: usize,
    /// One batch of 64 cases in this many is of pool shots, every finder against the oracle
    /// (0: none; 1: pool shots only).
    #[arg(long, default_value_t = 8)]
    pool_every: u64,
    /// Where failing cases are written.
    #[arg(long, default_value = concat!(env!("CARGO_MANIFEST_DIR"), "/regressions"))]
    out: PathBuf,
    /// Compare the finders only: do not replay the oracle's runs through `verify`.
    #[arg(long)]
    no_verify: bool,
    /// Print the report as JSON.
    #[arg(long)]
    json: bool,
}

#[derive(Subcommand)]
enum Command {
    /// Checks case files (regressions) and says which fail.
    Replay {
        /// Case files.
        files: Vec<PathBuf>,
    },
}

fn main() -> Result<()> {
    let cli = Cli::parse();
    if let Some(Command::Replay { files }) = &cli.command {
        return replay(files);
    }
    let minutes = cli.minutes.unwrap_or(if cli.cases.is_some() {
        f64::INFINITY
    } else {
        1.0
    });
    anyhow::ensure!(minutes > 0.0, "--minutes must be positive");
    let settings = Settings {
        seed: cli.seed,
        duration: Duration::from_secs_f64((minutes * 60.0).min(1e9)),
        max_cases: cli.cases,
        max_bodies: cli.max_bodies,
        pool_every: cli.pool_every,
        verify: !cli.no_verify,
        threads: cli
            .threads
            .unwrap_or_else(|| std::thread::available_parallelism().map_or(1, |n| n.get())),
        hang_limit: Duration::from_secs(120),
        memory_limit: 6 << 30,
        out_dir: cli.out.clone(),
    };
    let progress = Arc::new(Progress::default());
    let bar = std::io::stderr().is_terminal().then(|| {
        let bar = indicatif::ProgressBar::new_spinner();
        bar.enable_steady_tick(Duration::from_millis(250));
        bar
    });
    let report = std::thread::scope(|scope| {
        let worker = scope.spawn(|| campaign::run(&settings, &progress));
        while !worker.is_finished() {
            if let Some(bar) = &bar {
                bar.set_message(format!(
                    "{} cases, {} failing",
                    progress.tried.load(Ordering::Relaxed),
                    progress.failures.load(Ordering::Relaxed)
                ));
            }
            std::thread::sleep(Duration::from_millis(250));
        }
        worker.join().expect("the campaign")
    });
    if let Some(bar) = bar {
        bar.finish_and_clear();
    }
    let mut written = Vec::new();
    for (k, found) in report.found.iter().enumerate() {
        std::fs::create_dir_all(&cli.out)
            .with_context(|| format!("cannot create {}", cli.out.display()))?;
        let path = cli.out.join(format!("found-{}-{k}.json", cli.seed));
        std::fs::write(&path, found.case.to_json_pretty())
            .with_context(|| format!("cannot write {}", path.display()))?;
        written.push(path);
    }
    if cli.json {
        let found: Vec<_> = report
            .found
            .iter()
            .zip(&written)
            .map(|(f, p)| {
                serde_json::json!({
                    "reason": f.reason, "after": f.after, "origin": f.origin,
                    "file": p.display().to_string(),
                })
            })
            .collect();
        println!(
            "{}",
            serde_json::json!({
                "cases": report.tried, "valid": report.valid, "events": report.events,
                "finder_runs": report.runs, "seconds": report.elapsed.as_secs_f64(),
                "cases_per_minute": report.per_minute(), "coverage": report.coverage,
                "failures": found,
            })
        );
    } else {
        println!(
            "{} cases in {:.1} s ({:.0} per minute), {} valid scenes, {} oracle events, {} finder runs compared",
            report.tried,
            report.elapsed.as_secs_f64(),
            report.per_minute(),
            report.valid,
            report.events,
            report.runs
        );
        println!("valid cases per feature:\n{}", report.coverage_table());
        for (f, p) in report.found.iter().zip(&written) {
            println!(
                "FAILED after {} cases ({}): {}\n  shrunk case written to {}",
                f.after,
                f.origin,
                f.reason,
                p.display()
            );
        }
        if report.found.is_empty() {
            println!("no failure");
        }
    }
    if !report.found.is_empty() {
        std::process::exit(1);
    }
    Ok(())
}

fn replay(files: &[PathBuf]) -> Result<()> {
    let mut failed = 0;
    for path in files {
        let text = std::fs::read_to_string(path)
            .with_context(|| format!("cannot read {}", path.display()))?;
        let case =
            Case::from_json(&text).with_context(|| format!("{}: not a case", path.display()))?;
        match check_case(&case) {
            Ok(Some(c)) => println!("{}: ok ({} events)", path.display(), c.events),
            Ok(None) => println!("{}: scene refused by the validator", path.display()),
            Err(f) => {
                failed += 1;
                println!("{}: FAILED: {f}", path.display());
            }
        }
    }
    if failed > 0 {
        std::process::exit(1);
    }
    Ok(())
}
