//! The thesis's Table 5.1 as a benchmark: the §5.2 scene at n = 8 … 2048 for 5 simulated
//! seconds, every finder, several seeds, mean collisions and mean running times.

use super::budget::{CellStatus, Planner};
use ccdsim::finder::{make_finder, FinderOptions};
use ccdsim::generate::{thesis, ThesisConfig, THESIS_DURATION, THESIS_TABLE_5_1};
use ccdsim::sim::Simulation;
use ccdsim::FINDER_NAMES;
use serde::Serialize;
use std::fmt::Write as _;
use std::time::Instant;

/// What to run.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ThesisBenchConfig {
    /// Numbers of bodies, increasing.
    pub sizes: Vec<usize>,
    /// Runs (seeds `first_seed`, `first_seed + 1`, …) per size and finder.
    pub runs: u32,
    /// Seed of the first run.
    pub first_seed: u64,
    /// Finder names, as [`make_finder`] knows them.
    pub finders: Vec<String>,
    /// Time budget of each finder over all its cells, seconds: a cell predicted not to fit in
    /// what is left is skipped, a run that uses it up is abandoned, and either way the finder's
    /// larger sizes are skipped (see [`Planner`]).
    pub budget_seconds: f64,
    /// Simulated time per run, seconds (thesis: 5).
    pub duration: f64,
    /// Dimension, 2 (the thesis's) or 3.
    pub dim: usize,
}

impl Default for ThesisBenchConfig {
    fn default() -> Self {
        ThesisBenchConfig {
            sizes: THESIS_TABLE_5_1.iter().map(|r| r.0).collect(),
            runs: 3,
            first_seed: 1,
            finders: FINDER_NAMES.iter().map(|s| (*s).to_string()).collect(),
            budget_seconds: 120.0,
            duration: THESIS_DURATION,
            dim: 2,
        }
    }
}

/// One finder at one size.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ThesisCell {
    /// Finder name.
    pub finder: String,
    /// Number of bodies.
    pub n: usize,
    /// Whether the cell ran.
    pub status: CellStatus,
    /// Runs completed.
    pub runs: u32,
    /// Mean events (body–body plus body–wall collisions) per run.
    pub mean_collisions: f64,
    /// Mean body–body collisions per run.
    pub mean_body_collisions: f64,
    /// Mean body–wall collisions per run.
    pub mean_wall_collisions: f64,
    /// Mean wall-clock seconds per run (finder set-up plus simulation; not scene generation).
    pub mean_seconds: f64,
    /// Median wall-clock seconds per run.
    pub median_seconds: f64,
    /// Largest peak of the finder's own memory over the runs, bytes, for finders that track it.
    pub peak_memory_bytes: Option<usize>,
}

/// Everything a thesis benchmark measured.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ThesisBenchReport {
    /// What was asked for.
    pub config: ThesisBenchConfig,
    /// One cell per (size, finder), sizes outer, in the config's order.
    pub cells: Vec<ThesisCell>,
    /// Total wall-clock seconds of the benchmark.
    pub total_seconds: f64,
}

/// Counts of one run.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ThesisRun {
    /// Body–body collisions.
    pub body_collisions: u64,
    /// Body–wall collisions.
    pub wall_collisions: u64,
    /// Wall-clock seconds (finder set-up plus simulation).
    pub seconds: f64,
    /// Peak bytes of the finder's own structures, when it tracks them.
    pub peak_memory_bytes: Option<usize>,
}

/// Runs the thesis scene with `n` bodies and `seed` for `duration` simulated seconds with the
/// named finder. Gives up, returning `Ok(None)`, once `deadline_seconds` of wall-clock time have
/// passed.
pub fn run_thesis_once(
    dim: usize,
    n: usize,
    seed: u64,
    finder: &str,
    duration: f64,
    deadline_seconds: f64,
) -> Result<Option<ThesisRun>, String> {
    match dim {
        2 => run_once::<2>(n, seed, finder, duration, deadline_seconds),
        3 => run_once::<3>(n, seed, finder, duration, deadline_seconds),
        _ => Err(format!("dimension {dim} is not 2 or 3")),
    }
}

fn run_once<const D: usize>(
    n: usize,
    seed: u64,
    finder: &str,
    duration: f64,
    deadline_seconds: f64,
) -> Result<Option<ThesisRun>, String> {
    let scene = thesis::<D>(&ThesisConfig::new(n, seed)).map_err(|e| e.to_string())?;
    let finder = make_finder::<D>(finder, &FinderOptions::default()).map_err(|e| e.to_string())?;
    let started = Instant::now();
    let mut sim = Simulation::with_finder(&scene, finder).map_err(|e| e.to_string())?;
    let mut events: u64 = 0;
    while let Some(e) = sim.peek_event() {
        if e.time > duration {
            break;
        }
        sim.step_event();
        events += 1;
        if events % 1024 == 0 && started.elapsed().as_secs_f64() > deadline_seconds {
            return Ok(None);
        }
    }
    let seconds = started.elapsed().as_secs_f64();
    let stats = *sim.stats();
    let (f, _) = sim.finder_mut();
    Ok(Some(ThesisRun {
        body_collisions: stats.body_collisions,
        wall_collisions: stats.wall_collisions,
        seconds,
        peak_memory_bytes: f.memory().map(|m| m.peak_bytes),
    }))
}

/// Runs the benchmark, calling `progress(done, total)` after every run (skipped runs count as
/// done). Fails on an unknown finder, a bad size, or when two finders disagree on a run's
/// collision count (they are exact, so they must not).
pub fn run_thesis_bench(
    cfg: &ThesisBenchConfig,
    mut progress: impl FnMut(u64, u64),
) -> Result<ThesisBenchReport, String> {
    for f in &cfg.finders {
        make_finder::<2>(f, &FinderOptions::default()).map_err(|e| e.to_string())?;
    }
    if cfg.sizes.windows(2).any(|w| w[0] >= w[1]) {
        return Err("sizes must increase".into());
    }
    let started = Instant::now();
    let total = (cfg.sizes.len() * cfg.finders.len()) as u64 * u64::from(cfg.runs);
    let mut done = 0;
    let mut planners: Vec<Planner> = cfg
        .finders
        .iter()
        .map(|_| Planner::new(cfg.budget_seconds))
        .collect();
    let mut cells = Vec::new();
    // Reference counts per seed at the current size, to check that finders agree.
    for &n in &cfg.sizes {
        let mut reference: Vec<Option<(u64, u64)>> = vec![None; cfg.runs as usize];
        for (fi, finder) in cfg.finders.iter().enumerate() {
            let planner = &mut planners[fi];
            let mut cell = ThesisCell {
                finder: finder.clone(),
                n,
                status: CellStatus::Done,
                runs: 0,
                mean_collisions: 0.0,
                mean_body_collisions: 0.0,
                mean_wall_collisions: 0.0,
                mean_seconds: 0.0,
                median_seconds: 0.0,
                peak_memory_bytes: None,
            };
            if let Some(status) = planner.refuse(n, cfg.runs) {
                cell.status = status;
                done += u64::from(cfg.runs);
                progress(done, total);
                cells.push(cell);
                continue;
            }
            let cell_started = Instant::now();
            let mut times = Vec::new();
            let (mut body, mut wall) = (0u64, 0u64);
            for r in 0..cfg.runs {
                let left = planner.left() - cell_started.elapsed().as_secs_f64();
                let seed = cfg.first_seed + u64::from(r);
                let Some(run) = run_thesis_once(cfg.dim, n, seed, finder, cfg.duration, left)?
                else {
                    cell.status = planner.overran(cell_started.elapsed().as_secs_f64());
                    break;
                };
                let counts = (run.body_collisions, run.wall_collisions);
                match reference[r as usize] {
                    Some(c) if c != counts => {
                        return Err(format!(
                            "finder {finder} counted {counts:?} collisions at n = {n}, seed \
                             {seed}; another finder counted {c:?}"
                        ))
                    }
                    _ => reference[r as usize] = Some(counts),
                }
                body += run.body_collisions;
                wall += run.wall_collisions;
                times.push(run.seconds);
                cell.peak_memory_bytes = match (cell.peak_memory_bytes, run.peak_memory_bytes) {
                    (Some(a), Some(b)) => Some(a.max(b)),
                    (a, b) => a.or(b),
                };
                done += 1;
                progress(done, total);
            }
            if cell.status == CellStatus::Done {
                let k = times.len() as f64;
                cell.runs = times.len() as u32;
                cell.mean_body_collisions = body as f64 / k;
                cell.mean_wall_collisions = wall as f64 / k;
                cell.mean_collisions = (body + wall) as f64 / k;
                cell.mean_seconds = times.iter().sum::<f64>() / k;
                cell.median_seconds = median(&mut times);
                planner.record(n, cell.mean_seconds, cell_started.elapsed().as_secs_f64());
            } else {
                cell.peak_memory_bytes = None;
                done += u64::from(cfg.runs) - times.len() as u64;
                progress(done, total);
            }
            cells.push(cell);
        }
    }
    Ok(ThesisBenchReport {
        config: cfg.clone(),
        cells,
        total_seconds: started.elapsed().as_secs_f64(),
    })
}

fn median(xs: &mut [f64]) -> f64 {
    xs.sort_by(f64::total_cmp);
    let m = xs.len() / 2;
    if xs.len() % 2 == 1 {
        xs[m]
    } else {
        0.5 * (xs[m - 1] + xs[m])
    }
}

impl ThesisBenchReport {
    /// The cell of `finder` at `n`.
    #[must_use]
    pub fn cell(&self, finder: &str, n: usize) -> Option<&ThesisCell> {
        self.cells.iter().find(|c| c.finder == finder && c.n == n)
    }

    /// Mean collisions at `n` from any finder that ran it (they all agree).
    #[must_use]
    pub fn collisions(&self, n: usize) -> Option<&ThesisCell> {
        self.cells
            .iter()
            .find(|c| c.n == n && c.status == CellStatus::Done)
    }

    /// The largest size each finder completed, in the config's finder order.
    #[must_use]
    pub fn largest_sizes(&self) -> Vec<(String, Option<usize>)> {
        self.config
            .finders
            .iter()
            .map(|f| {
                let n = self
                    .cells
                    .iter()
                    .filter(|c| &c.finder == f && c.status == CellStatus::Done)
                    .map(|c| c.n)
                    .max();
                (f.clone(), n)
            })
            .collect()
    }

    /// A table like the thesis's Table 5.1: n, mean collisions (ours and the thesis's), then per
    /// finder the mean seconds and the speed-up over all-pairs (`×ap`), the finders' peak memory
    /// where tracked, and the thesis's two timings.
    #[must_use]
    pub fn table(&self) -> String {
        let mut s = String::new();
        let _ = write!(s, "{:>6} {:>11} {:>11}", "n", "collisions", "thesis");
        for f in &self.config.finders {
            let _ = write!(s, " | {:>14} {:>7}", format!("{f} s"), "×ap");
        }
        let _ = writeln!(s, " | {:>14} {:>12}", "thesis ap s", "thesis bvh s");
        for &n in &self.config.sizes {
            let ours = self
                .collisions(n)
                .map_or("—".to_string(), |c| format!("{:.1}", c.mean_collisions));
            let theirs = thesis_row(n);
            let _ = write!(
                s,
                "{n:>6} {ours:>11} {:>11}",
                theirs.map_or("—".into(), |r| format!("{:.1}", r.1))
            );
            let all_pairs = self
                .cell("all-pairs", n)
                .filter(|c| c.status == CellStatus::Done)
                .map(|c| c.mean_seconds);
            for f in &self.config.finders {
                let cell = self.cell(f, n).expect("every cell is recorded");
                match &cell.status {
                    CellStatus::Done => {
                        let ratio = all_pairs
                            .map_or("—".into(), |ap| format!("{:.1}", ap / cell.mean_seconds));
                        let _ = write!(s, " | {:>14} {ratio:>7}", fmt_seconds(cell.mean_seconds));
                    }
                    other => {
                        let _ = write!(s, " | {:>22}", other.short());
                    }
                }
            }
            let _ = writeln!(
                s,
                " | {:>14} {:>12}",
                theirs.map_or("—".into(), |r| fmt_seconds(r.2)),
                theirs.map_or("—".into(), |r| fmt_seconds(r.3))
            );
        }
        let memory: Vec<&ThesisCell> = self
            .cells
            .iter()
            .filter(|c| c.peak_memory_bytes.is_some())
            .collect();
        if !memory.is_empty() {
            let _ = writeln!(s, "\npeak finder memory (MB):");
            for c in memory {
                let _ = writeln!(
                    s,
                    "  {:>10} n = {:>6}: {:>10.3}",
                    c.finder,
                    c.n,
                    c.peak_memory_bytes.unwrap_or(0) as f64 / 1e6
                );
            }
        }
        s
    }

    /// One CSV line per cell with a header: `finder,n,status,runs,mean_collisions,
    /// mean_body_collisions,mean_wall_collisions,mean_seconds,median_seconds,peak_memory_bytes,
    /// thesis_collisions,thesis_all_pairs_seconds,thesis_bvh_seconds`.
    #[must_use]
    pub fn csv(&self) -> String {
        let mut s = String::from(
            "finder,n,status,runs,mean_collisions,mean_body_collisions,mean_wall_collisions,\
             mean_seconds,median_seconds,peak_memory_bytes,thesis_collisions,\
             thesis_all_pairs_seconds,thesis_bvh_seconds\n",
        );
        for c in &self.cells {
            let t = thesis_row(c.n);
            let opt = |x: Option<f64>| x.map_or(String::new(), |v| v.to_string());
            let done = c.status == CellStatus::Done;
            let _ = writeln!(
                s,
                "{},{},{},{},{},{},{},{},{},{},{},{},{}",
                c.finder,
                c.n,
                c.status.short().replace(',', ";"),
                c.runs,
                opt(done.then_some(c.mean_collisions)),
                opt(done.then_some(c.mean_body_collisions)),
                opt(done.then_some(c.mean_wall_collisions)),
                opt(done.then_some(c.mean_seconds)),
                opt(done.then_some(c.median_seconds)),
                c.peak_memory_bytes.map_or(String::new(), |b| b.to_string()),
                opt(t.map(|r| r.1)),
                opt(t.map(|r| r.2)),
                opt(t.map(|r| r.3)),
            );
        }
        s
    }
}

/// The thesis's Table 5.1 row for `n`, if it has one.
#[must_use]
pub fn thesis_row(n: usize) -> Option<(usize, f64, f64, f64)> {
    THESIS_TABLE_5_1.iter().copied().find(|r| r.0 == n)
}

/// Seconds in plain decimal notation with four significant digits (at least one decimal).
#[must_use]
pub fn fmt_seconds(s: f64) -> String {
    if !(s.is_finite() && s > 0.0) {
        return format!("{s}");
    }
    let decimals = (3 - s.log10().floor() as i32).max(1) as usize;
    format!("{s:.decimals$}")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn small_bench_runs_every_finder_and_agrees() {
        let cfg = ThesisBenchConfig {
            sizes: vec![8, 16, 32],
            runs: 2,
            finders: vec!["all-pairs".into(), "sedgewick".into()],
            ..ThesisBenchConfig::default()
        };
        let mut calls = Vec::new();
        let report = run_thesis_bench(&cfg, |d, t| calls.push((d, t))).unwrap();
        assert_eq!(calls.last(), Some(&(12, 12)));
        assert_eq!(report.cells.len(), 6);
        for n in [8, 16, 32] {
            let a = report.cell("all-pairs", n).unwrap();
            let b = report.cell("sedgewick", n).unwrap();
            assert_eq!(a.status, CellStatus::Done);
            assert_eq!(a.mean_collisions, b.mean_collisions);
            assert!(a.mean_collisions > 0.0);
            assert!(b.peak_memory_bytes.is_some() && a.peak_memory_bytes.is_none());
        }
        let table = report.table();
        assert!(table.contains("sedgewick s") && table.contains("52.3"));
        assert_eq!(report.csv().lines().count(), 7);
        assert_eq!(
            report.largest_sizes(),
            vec![
                ("all-pairs".into(), Some(32)),
                ("sedgewick".into(), Some(32))
            ]
        );
    }

    #[test]
    fn an_exhausted_budget_skips_the_rest() {
        let cfg = ThesisBenchConfig {
            sizes: vec![8, 64, 128],
            runs: 1,
            finders: vec!["all-pairs".into()],
            budget_seconds: 0.0,
            ..ThesisBenchConfig::default()
        };
        let report = run_thesis_bench(&cfg, |_, _| {}).unwrap();
        // With no time at all, nothing runs.
        assert!(report
            .cells
            .iter()
            .all(|c| matches!(c.status, CellStatus::Skipped { .. })));
        assert!(report.table().contains("skipped (0 s budget)"));
        assert_eq!(report.largest_sizes(), vec![("all-pairs".into(), None)]);
    }

    #[test]
    fn a_small_budget_stops_at_the_predicted_limit() {
        let cfg = ThesisBenchConfig {
            sizes: vec![8, 16, 2048, 4096],
            runs: 1,
            finders: vec!["all-pairs".into()],
            budget_seconds: 5.0,
            ..ThesisBenchConfig::default()
        };
        let report = run_thesis_bench(&cfg, |_, _| {}).unwrap();
        // n = 8 and 16 take about a millisecond, far below the budget however loaded the
        // machine; all-pairs at 2048 takes hours, which the cubic extrapolation from n = 16
        // (×2^21) foresees.
        assert_eq!(report.largest_sizes(), vec![("all-pairs".into(), Some(16))]);
        assert!(matches!(
            report.cells[2].status,
            CellStatus::Skipped {
                predicted_seconds: Some(_),
                ..
            }
        ));
        assert!(matches!(
            report.cells[3].status,
            CellStatus::Skipped {
                predicted_seconds: None,
                ..
            }
        ));
    }

    #[test]
    fn seconds_have_four_significant_digits() {
        assert_eq!(fmt_seconds(0.000049), "0.00004900");
        assert_eq!(fmt_seconds(0.3747), "0.3747");
        assert_eq!(fmt_seconds(46.33965052), "46.34");
        assert_eq!(fmt_seconds(13085.64345), "13085.6");
    }

    #[test]
    fn unknown_finders_are_refused() {
        let cfg = ThesisBenchConfig {
            finders: vec!["nope".into()],
            ..ThesisBenchConfig::default()
        };
        assert!(run_thesis_bench(&cfg, |_, _| {}).is_err());
    }
}
