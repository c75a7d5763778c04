//! Time budgets for benchmark tables: each finder gets a total budget; each cell's cost is
//! predicted from the sizes already measured, and what would not fit is skipped.

use serde::Serialize;

/// Whether a benchmark cell ran.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(tag = "status", rename_all = "snake_case")]
pub enum CellStatus {
    /// Every run completed.
    Done,
    /// Not run: predicted to exceed what was left of the finder's budget, or a smaller size of
    /// the same finder already was skipped (`predicted_seconds` is then `None`).
    Skipped {
        /// The finder's total budget, seconds.
        budget_seconds: f64,
        /// What was left of it, seconds.
        left_seconds: f64,
        /// The predicted cost of the cell, seconds.
        predicted_seconds: Option<f64>,
    },
    /// Started, then abandoned when it used up the rest of the budget.
    Overran {
        /// The finder's total budget, seconds.
        budget_seconds: f64,
    },
}

impl CellStatus {
    /// A short label for tables: `done`, or `skipped (120 s budget)`.
    #[must_use]
    pub fn short(&self) -> String {
        match self {
            CellStatus::Done => "done".into(),
            CellStatus::Skipped { budget_seconds, .. } | CellStatus::Overran { budget_seconds } => {
                format!("skipped ({budget_seconds} s budget)")
            }
        }
    }
}

/// Growth exponent assumed while fewer than two sizes have been measured long enough to tell.
const DEFAULT_EXPONENT: f64 = 3.0;
/// Measurements shorter than this (per run) are too noisy to fit an exponent on.
const MIN_FIT_SECONDS: f64 = 0.02;

/// Decides, for one finder, which sizes fit in its total time budget.
///
/// The cost of a cell is predicted as `runs · t · (n / n_last)^k` from the last measured per-run
/// time `t` at `n_last`, where `k` is the growth exponent between the last two sizes measured
/// long enough to fit (clamped to [1, 4]) or 3 before there are two. A cell runs when its
/// prediction fits in what is left of the budget, and its runs are abandoned when they use it
/// up; once a cell is skipped or abandoned, every larger size is skipped: the finder has reached
/// its limit. So a finder never spends much more than its budget.
#[derive(Clone, Debug)]
pub struct Planner {
    budget: f64,
    spent: f64,
    measured: Vec<(usize, f64)>,
    stopped: bool,
}

impl Planner {
    /// A planner with a total budget in seconds.
    #[must_use]
    pub fn new(budget_seconds: f64) -> Self {
        Planner {
            budget: budget_seconds,
            spent: 0.0,
            measured: Vec::new(),
            stopped: false,
        }
    }

    /// Seconds left of the budget.
    #[must_use]
    pub fn left(&self) -> f64 {
        (self.budget - self.spent).max(0.0)
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
        let (budget_seconds, left_seconds) = (self.budget, self.left());
        let skipped = |predicted_seconds| CellStatus::Skipped {
            budget_seconds,
            left_seconds,
            predicted_seconds,
        };
        if self.stopped {
            return Some(skipped(None));
        }
        let predicted = self.predict(n).map(|t| t * f64::from(runs));
        if predicted.is_some_and(|p| p > self.left()) || self.left() <= 0.0 {
            self.stopped = true;
            return Some(skipped(predicted));
        }
        None
    }

    /// Records a completed cell: its mean per-run seconds and its total seconds.
    pub fn record(&mut self, n: usize, per_run_seconds: f64, cell_seconds: f64) {
        self.measured.push((n, per_run_seconds));
        self.spent += cell_seconds;
    }

    /// Records that a cell was abandoned after `cell_seconds`; returns its status.
    pub fn overran(&mut self, cell_seconds: f64) -> CellStatus {
        self.spent += cell_seconds;
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
        p.record(8, 0.001, 0.003);
        // One (short) measurement: cubic growth assumed.
        assert!((p.predict(16).unwrap() - 0.008).abs() < 1e-12);
        p.record(16, 0.1, 0.3);
        p.record(32, 0.4, 1.2);
        // Exponent 2 between 16 and 32.
        assert!((p.predict(64).unwrap() - 1.6).abs() < 1e-9);
        assert_eq!(p.refuse(64, 3), None);
        p.record(64, 1.6, 4.8);
        assert!((p.left() - (10.0 - 6.303)).abs() < 1e-9);
        // 6.4 s per run × 3 runs > 3.7 s left.
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
        assert_eq!(p.refuse(256, 1).unwrap().short(), "skipped (10 s budget)");
    }

    #[test]
    fn exponent_is_clamped_and_overruns_stop() {
        let mut p = Planner::new(1.0);
        p.record(10, 0.05, 0.05);
        p.record(20, 100.0, 100.0);
        assert!((p.predict(40).unwrap() - 1600.0).abs() < 1e-9);
        assert_eq!(p.left(), 0.0);
        assert!(p.refuse(40, 1).is_some());
        let mut q = Planner::new(1.0);
        q.record(10, 0.5, 0.5);
        q.record(20, 0.1, 0.1);
        assert!((q.predict(40).unwrap() - 0.2).abs() < 1e-12);
        assert!(q.refuse(40, 1).is_none());
        assert!(matches!(q.overran(0.4), CellStatus::Overran { .. }));
        assert!(q.refuse(80, 1).is_some());
    }
}
