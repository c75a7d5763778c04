//! Time budgets for benchmark tables: predict each cell's cost from the smaller sizes already
//! measured and skip what would not fit.

use serde::Serialize;

/// Whether a benchmark cell ran.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(tag = "status", rename_all = "snake_case")]
pub enum CellStatus {
    /// Every run completed.
    Done,
    /// Not run: predicted to exceed the budget, or a smaller size of the same finder already
    /// did (`predicted_seconds` is then `None`).
    Skipped {
        /// The cell budget, seconds.
        budget_seconds: f64,
        /// The predicted cost of the cell, seconds.
        predicted_seconds: Option<f64>,
    },
    /// Started, then abandoned when it used up the budget.
    Overran {
        /// The cell budget, seconds.
        budget_seconds: f64,
    },
}

impl CellStatus {
    /// A short label for tables, e.g. `skipped (60 s budget)`.
    #[must_use]
    pub fn short(&self) -> String {
        match self {
            CellStatus::Done => "done".into(),
            CellStatus::Skipped {
                budget_seconds,
                predicted_seconds: Some(p),
            } => format!("skipped (~{p:.0} s > {budget_seconds} s)"),
            CellStatus::Skipped { budget_seconds, .. } => {
                format!("skipped ({budget_seconds} s budget)")
            }
            CellStatus::Overran { budget_seconds } => {
                format!("skipped (overran {budget_seconds} s)")
            }
        }
    }
}

/// Growth exponent assumed while fewer than two sizes have been measured long enough to tell.
const DEFAULT_EXPONENT: f64 = 3.0;
/// Measurements shorter than this (per run) are too noisy to fit an exponent on.
const MIN_FIT_SECONDS: f64 = 0.02;

/// Decides, for one finder, which sizes fit in a per-cell time budget.
///
/// The cost of a cell is predicted as `runs · t · (n / n_last)^k` from the last measured per-run
/// time `t` at `n_last`, where `k` is the growth exponent between the last two sizes measured
/// long enough to fit (clamped to [1, 4]) or 3 before there are two. Once a cell is skipped or
/// overruns, every larger size is skipped too: the finder has reached its limit.
#[derive(Clone, Debug)]
pub struct Planner {
    budget: f64,
    measured: Vec<(usize, f64)>,
    stopped: bool,
}

impl Planner {
    /// A planner with a per-cell budget in seconds.
    #[must_use]
    pub fn new(budget_seconds: f64) -> Self {
        Planner {
            budget: budget_seconds,
            measured: Vec::new(),
            stopped: false,
        }
    }

    /// Predicted per-run seconds at `n`, or `None` before any measurement.
    #[must_use]
    pub fn predict(&self, n: usize) -> Option<f64> {
        let &(n1, t1) = self.measured.last()?;
        let fit: Vec<&(usize, f64)> = self
            .measured
            .iter()
            .filter(|m| m.1 >= MIN_FIT_SECONDS)
            .collect();
        let k = match fit.as_slice() {
            [.., a, b] if b.0 > a.0 => {
                ((b.1 / a.1).ln() / (b.0 as f64 / a.0 as f64).ln()).clamp(1.0, 4.0)
            }
            _ => DEFAULT_EXPONENT,
        };
        Some(t1 * (n as f64 / n1 as f64).powf(k))
    }

    /// `Some(status)` when the cell of `n` bodies and `runs` runs must not run.
    pub fn refuse(&mut self, n: usize, runs: u32) -> Option<CellStatus> {
        if self.stopped {
            return Some(CellStatus::Skipped {
                budget_seconds: self.budget,
                predicted_seconds: None,
            });
        }
        let predicted = self.predict(n)? * f64::from(runs);
        (predicted > self.budget).then(|| {
            self.stopped = true;
            CellStatus::Skipped {
                budget_seconds: self.budget,
                predicted_seconds: Some(predicted),
            }
        })
    }

    /// Records a completed cell's mean per-run seconds.
    pub fn record(&mut self, n: usize, per_run_seconds: f64) {
        self.measured.push((n, per_run_seconds));
    }

    /// Records that a cell overran after `elapsed` seconds; returns its status.
    pub fn overran(&mut self, _elapsed: f64) -> CellStatus {
        self.stopped = true;
        CellStatus::Overran {
            budget_seconds: self.budget,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn predicts_by_the_fitted_exponent_and_stops_for_good() {
        let mut p = Planner::new(10.0);
        assert_eq!(p.refuse(8, 3), None);
        p.record(8, 0.001);
        // One (short) measurement: cubic growth assumed.
        assert!((p.predict(16).unwrap() - 0.008).abs() < 1e-12);
        p.record(16, 0.1);
        p.record(32, 0.4);
        // Exponent 2 between 16 and 32.
        assert!((p.predict(64).unwrap() - 1.6).abs() < 1e-9);
        assert_eq!(p.refuse(64, 3), None);
        p.record(64, 1.6);
        // 6.4 s per run × 3 runs > 10 s.
        assert!(matches!(
            p.refuse(128, 3),
            Some(CellStatus::Skipped { predicted_seconds: Some(x), .. }) if (x - 19.2).abs() < 1e-9
        ));
        assert!(matches!(
            p.refuse(256, 1),
            Some(CellStatus::Skipped {
                predicted_seconds: None,
                ..
            })
        ));
    }

    #[test]
    fn exponent_is_clamped() {
        let mut p = Planner::new(1.0);
        p.record(10, 0.05);
        p.record(20, 100.0);
        assert!((p.predict(40).unwrap() - 1600.0).abs() < 1e-9);
        let mut q = Planner::new(1.0);
        q.record(10, 0.5);
        q.record(20, 0.1);
        assert!((q.predict(40).unwrap() - 0.2).abs() < 1e-12);
        assert!(matches!(q.overran(2.0), CellStatus::Overran { .. }));
        assert!(q.refuse(80, 1).is_some());
    }
}
