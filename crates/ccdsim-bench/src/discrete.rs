//! The thesis's Table 5.2 as a benchmark: the §5.2 scene at n = 1024, simulated exactly by a
//! finder and by the discrete-time stepper at several time steps, with the stepper's misses.

use super::thesis::fmt_seconds;
use ccdsim::discrete::DiscreteStepper;
use ccdsim::finder::{make_finder, FinderOptions};
use ccdsim::generate::{thesis, ThesisConfig, THESIS_DURATION, THESIS_TABLE_5_2};
use ccdsim::scene::Scene;
use ccdsim::sim::Simulation;
use serde::Serialize;
use std::fmt::Write as _;
use std::time::Instant;

/// What to run.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct DiscreteBenchConfig {
    /// Number of bodies (thesis: 1024).
    pub n: usize,
    /// Time steps of the discrete stepper, seconds.
    pub dts: Vec<f64>,
    /// Runs (seeds `first_seed`, …) per row.
    pub runs: u32,
    /// Seed of the first run.
    pub first_seed: u64,
    /// The exact finder of the first row.
    pub finder: String,
    /// Simulated time per run, seconds (thesis: 5).
    pub duration: f64,
    /// Dimension, 2 (the thesis's) or 3.
    pub dim: usize,
}

impl Default for DiscreteBenchConfig {
    fn default() -> Self {
        DiscreteBenchConfig {
            n: 1024,
            dts: THESIS_TABLE_5_2.iter().filter_map(|r| r.0).collect(),
            runs: 3,
            first_seed: 1,
            finder: "sedgewick".into(),
            duration: THESIS_DURATION,
            dim: 2,
        }
    }
}

/// One row: the exact simulation (`dt` is `None`) or the stepper at one time step.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct DiscreteRow {
    /// `continuous (<finder>)` or `discrete (dt = …)`.
    pub algorithm: String,
    /// The stepper's time step, seconds; `None` for the exact simulation.
    pub dt: Option<f64>,
    /// Mean wall-clock seconds per run (the stepper without miss counting).
    pub mean_seconds: f64,
    /// Median wall-clock seconds per run.
    pub median_seconds: f64,
    /// Mean collisions resolved per run: events (exact) or detected contacts (stepper).
    pub mean_collisions: f64,
    /// Mean missed pairs per run, body–body plus body–wall (0 for the exact simulation).
    pub mean_misses: f64,
    /// Mean missed body–body pairs per run.
    pub mean_body_misses: f64,
    /// Mean missed body–wall pairs per run.
    pub mean_wall_misses: f64,
    /// The thesis's running time for this row, seconds, if it has the row.
    pub thesis_seconds: Option<f64>,
    /// The thesis's mean misses for this row, if it has the row.
    pub thesis_misses: Option<f64>,
}

/// Everything a discrete benchmark measured.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct DiscreteBenchReport {
    /// What was asked for.
    pub config: DiscreteBenchConfig,
    /// The exact row first, then one per time step in the config's order.
    pub rows: Vec<DiscreteRow>,
    /// Total wall-clock seconds of the benchmark.
    pub total_seconds: f64,
}

/// Runs the benchmark, calling `progress(done, total)` after every run.
pub fn run_discrete_bench(
    cfg: &DiscreteBenchConfig,
    progress: impl FnMut(u64, u64),
) -> Result<DiscreteBenchReport, String> {
    if cfg.dts.iter().any(|&dt| !(dt > 0.0 && dt.is_finite())) {
        return Err("time steps must be positive and finite".into());
    }
    match cfg.dim {
        2 => run::<2>(cfg, progress),
        3 => run::<3>(cfg, progress),
        d => Err(format!("dimension {d} is not 2 or 3")),
    }
}

fn run<const D: usize>(
    cfg: &DiscreteBenchConfig,
    mut progress: impl FnMut(u64, u64),
) -> Result<DiscreteBenchReport, String> {
    make_finder::<D>(&cfg.finder, &FinderOptions::default()).map_err(|e| e.to_string())?;
    let started = Instant::now();
    let scenes: Vec<Scene<D>> = (0..cfg.runs)
        .map(|r| thesis::<D>(&ThesisConfig::new(cfg.n, cfg.first_seed + u64::from(r))))
        .collect::<Result<_, _>>()
        .map_err(|e| e.to_string())?;
    let total = u64::from(cfg.runs) * (1 + cfg.dts.len() as u64);
    let mut done = 0;
    let mut rows = Vec::new();

    let (mut times, mut collisions) = (Vec::new(), 0u64);
    for scene in &scenes {
        let finder =
            make_finder::<D>(&cfg.finder, &FinderOptions::default()).map_err(|e| e.to_string())?;
        let t0 = Instant::now();
        let mut sim = Simulation::with_finder(scene, finder).map_err(|e| e.to_string())?;
        collisions += sim.run_until(cfg.duration);
        times.push(t0.elapsed().as_secs_f64());
        done += 1;
        progress(done, total);
    }
    let k = f64::from(cfg.runs.max(1));
    let exact = THESIS_TABLE_5_2.iter().find(|r| r.0.is_none());
    rows.push(DiscreteRow {
        algorithm: format!("continuous ({})", cfg.finder),
        dt: None,
        mean_seconds: times.iter().sum::<f64>() / k,
        median_seconds: median(&mut times),
        mean_collisions: collisions as f64 / k,
        mean_misses: 0.0,
        mean_body_misses: 0.0,
        mean_wall_misses: 0.0,
        thesis_seconds: exact.map(|r| r.1),
        thesis_misses: exact.map(|r| r.2),
    });

    for &dt in &cfg.dts {
        let mut times = Vec::new();
        let (mut contacts, mut body_misses, mut wall_misses) = (0u64, 0u64, 0u64);
        for scene in &scenes {
            // Timed without miss counting, as a game would run it ...
            let t0 = Instant::now();
            let mut plain = DiscreteStepper::new(scene).map_err(|e| e.to_string())?;
            plain.run_until(cfg.duration, dt);
            times.push(t0.elapsed().as_secs_f64());
            // ... then again, same trajectory, counting what it misses.
            let mut counted = DiscreteStepper::new(scene).map_err(|e| e.to_string())?;
            counted.set_count_misses(true);
            counted.run_until(cfg.duration, dt);
            let s = counted.stats();
            contacts += s.body_contacts + s.wall_contacts;
            body_misses += s.body_misses;
            wall_misses += s.wall_misses;
            done += 1;
            progress(done, total);
        }
        let theirs = THESIS_TABLE_5_2.iter().find(|r| r.0 == Some(dt));
        rows.push(DiscreteRow {
            algorithm: format!("discrete (dt = {dt})"),
            dt: Some(dt),
            mean_seconds: times.iter().sum::<f64>() / k,
            median_seconds: median(&mut times),
            mean_collisions: contacts as f64 / k,
            mean_misses: (body_misses + wall_misses) as f64 / k,
            mean_body_misses: body_misses as f64 / k,
            mean_wall_misses: wall_misses as f64 / k,
            thesis_seconds: theirs.map(|r| r.1),
            thesis_misses: theirs.map(|r| r.2),
        });
    }
    Ok(DiscreteBenchReport {
        config: cfg.clone(),
        rows,
        total_seconds: started.elapsed().as_secs_f64(),
    })
}

fn median(xs: &mut [f64]) -> f64 {
    if xs.is_empty() {
        return f64::NAN;
    }
    xs.sort_by(f64::total_cmp);
    let m = xs.len() / 2;
    if xs.len() % 2 == 1 {
        xs[m]
    } else {
        0.5 * (xs[m - 1] + xs[m])
    }
}

impl DiscreteBenchReport {
    /// A table like the thesis's Table 5.2, with its numbers beside ours.
    #[must_use]
    pub fn table(&self) -> String {
        let mut s = String::new();
        let _ = writeln!(
            s,
            "{:<28} {:>12} {:>11} {:>11} {:>11} {:>12} | {:>12} {:>12}",
            "algorithm",
            "seconds",
            "misses",
            "body miss",
            "wall miss",
            "collisions",
            "thesis s",
            "thesis miss"
        );
        for r in &self.rows {
            let _ = writeln!(
                s,
                "{:<28} {:>12} {:>11.2} {:>11.2} {:>11.2} {:>12.1} | {:>12} {:>12}",
                r.algorithm,
                fmt_seconds(r.mean_seconds),
                r.mean_misses,
                r.mean_body_misses,
                r.mean_wall_misses,
                r.mean_collisions,
                r.thesis_seconds.map_or("—".into(), fmt_seconds),
                r.thesis_misses.map_or("—".into(), |m| format!("{m:.2}")),
            );
        }
        s
    }

    /// One CSV line per row with a header.
    #[must_use]
    pub fn csv(&self) -> String {
        let mut s = String::from(
            "algorithm,dt,mean_seconds,median_seconds,mean_collisions,mean_misses,\
             mean_body_misses,mean_wall_misses,thesis_seconds,thesis_misses\n",
        );
        let opt = |x: Option<f64>| x.map_or(String::new(), |v| v.to_string());
        for r in &self.rows {
            let _ = writeln!(
                s,
                "{},{},{},{},{},{},{},{},{},{}",
                r.algorithm,
                opt(r.dt),
                r.mean_seconds,
                r.median_seconds,
                r.mean_collisions,
                r.mean_misses,
                r.mean_body_misses,
                r.mean_wall_misses,
                opt(r.thesis_seconds),
                opt(r.thesis_misses)
            );
        }
        s
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn small_discrete_bench() {
        let cfg = DiscreteBenchConfig {
            n: 64,
            dts: vec![0.001, 0.1, 1.0],
            runs: 2,
            duration: 2.0,
            ..DiscreteBenchConfig::default()
        };
        let mut last = (0, 0);
        let report = run_discrete_bench(&cfg, |d, t| last = (d, t)).unwrap();
        assert_eq!(last, (8, 8));
        assert_eq!(report.rows.len(), 4);
        assert_eq!(report.rows[0].dt, None);
        assert_eq!(report.rows[0].mean_misses, 0.0);
        assert!(report.rows[0].mean_collisions > 100.0);
        assert!(report.rows[3].mean_misses > report.rows[1].mean_misses);
        assert_eq!(report.rows[1].thesis_misses, Some(0.17));
        assert!(report.table().starts_with("algorithm"));
        assert_eq!(report.csv().lines().count(), 5);
        assert!(run_discrete_bench(
            &DiscreteBenchConfig {
                dts: vec![0.0],
                ..cfg
            },
            |_, _| {}
        )
        .is_err());
    }
}
