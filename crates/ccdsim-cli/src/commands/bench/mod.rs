//! `ccdsim bench`: scene-based benchmarks that print tables and write CSV, JSON and plots.
//! One file per workload.

mod discrete;
mod gas;
mod plot;
mod pool_break;
mod rough_cooling;
mod shear;
mod thesis;

use anyhow::{anyhow, Context, Result};
use std::path::{Path, PathBuf};
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
    /// Homogeneous cooling gases of rough spheres: the ratio of rotational to translational
    /// temperature and Haff's law against the Huthmann–Zippelius theory.
    RoughCooling(rough_cooling::Args),
    /// Hard spheres in simple shear (Lees–Edwards): the viscosity against Enskog's,
    /// extrapolated to zero rate, and granular gases' heat balance.
    Shear(shear::Args),
    /// A racked pool table broken again and again: the median time per break and breaks
    /// per second (beside pooltool's, with a layout from scripts/pool-break-compare).
    PoolBreak(pool_break::Args),
}

/// Runs the command.
pub fn run(args: Args) -> Result<ExitCode> {
    match args.workload {
        Workload::Thesis(a) => thesis::run(a),
        Workload::Discrete(a) => discrete::run(a),
        Workload::Gas(a) => gas::run(a),
        Workload::RoughCooling(a) => rough_cooling::run(a),
        Workload::Shear(a) => shear::run(a),
        Workload::PoolBreak(a) => pool_break::run(a),
    }
}

/// The options of the benchmarks on the thesis's §5.2 scene (`thesis`, `discrete`): which
/// runs, how long each, and where the results go.
#[derive(clap::Args)]
struct SceneRuns {
    /// Runs (seeds) per table cell; times and counts are averaged.
    #[arg(long, default_value_t = 3)]
    runs: u32,
    /// Seed of the first run.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Simulated seconds per run.
    #[arg(long, default_value_t = 5.0)]
    duration: f64,
    /// Dimension, 2 (the thesis's) or 3.
    #[arg(long, default_value_t = 2, value_parser = clap::value_parser!(u8).range(2..=3))]
    dim: u8,
    /// Directory for the result files (CSV, JSON and, for `thesis`, the plots).
    #[arg(long, default_value = "target/ccdsim-bench")]
    out: PathBuf,
    /// No progress bar.
    #[arg(long, short)]
    quiet: bool,
}

impl SceneRuns {
    /// The number of runs, refused when zero.
    fn runs(&self) -> Result<u32> {
        if self.runs == 0 {
            return Err(anyhow!("--runs must be at least 1"));
        }
        Ok(self.runs)
    }

    /// The dimension as a `usize`.
    fn dim(&self) -> usize {
        usize::from(self.dim)
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
