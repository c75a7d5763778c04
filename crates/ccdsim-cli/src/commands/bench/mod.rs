//! `ccdsim bench`: scene-based benchmarks that print tables and write CSV, JSON and plots.
//! One file per workload.

mod discrete;
mod gas;
mod plot;
mod thesis;

use anyhow::{Context, Result};
use std::path::Path;
use std::process::ExitCode;

/// Arguments of `ccdsim bench`.
#[derive(clap::Args)]
pub struct Args {
    #[command(subcommand)]
    workload: Workload,
}

#[derive(clap::Subcommand)]
enum Workload {
    /// The thesis's Table 5.1 and Figure 5.1: running time against n for every finder on the
    /// §5.2 scene.
    Thesis(thesis::Args),
    /// The thesis's Table 5.2: the exact simulation against a discrete-time stepper, with the
    /// collisions the stepper misses.
    Discrete(discrete::Args),
    /// Hard discs or spheres in a periodic box: collisions per second, peak memory per body,
    /// and the equation of state (Z, collision rate) against Henderson / Carnahan–Starling.
    Gas(gas::Args),
}

/// Runs the command.
pub fn run(args: Args) -> Result<ExitCode> {
    match args.workload {
        Workload::Thesis(a) => thesis::run(a),
        Workload::Discrete(a) => discrete::run(a),
        Workload::Gas(a) => gas::run(a),
    }
}

/// Writes `text` to `dir/name`, creating `dir`.
fn write_file(dir: &Path, name: &str, text: &str) -> Result<()> {
    std::fs::create_dir_all(dir).with_context(|| format!("creating {}", dir.display()))?;
    let path = dir.join(name);
    std::fs::write(&path, text).with_context(|| format!("writing {}", path.display()))
}

/// Parses a comma-separated list.
fn parse_list<T: std::str::FromStr>(s: &str) -> Result<Vec<T>, String>
where
    T::Err: std::fmt::Display,
{
    s.split(',')
        .map(|x| x.trim().parse::<T>().map_err(|e| format!("`{x}`: {e}")))
        .collect()
}
