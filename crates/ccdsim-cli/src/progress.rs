//! A progress bar that appears only on long work, on a terminal, unless `--quiet`.

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::io::IsTerminal;
use std::time::{Duration, Instant};

/// Shows progress from 0 to `total` once the work has taken more than a second.
pub struct Progress {
    bar: Option<ProgressBar>,
    enabled: bool,
    started: Instant,
    total: u64,
    message: &'static str,
    /// Whether the bar shows an estimated time to completion (see [`Progress::without_eta`]).
    eta: bool,
}

/// The bar with an ETA: for work done at a steady rate (events, bytes, benchmark runs).
const WITH_ETA: &str = "{msg} [{elapsed_precise}] {wide_bar} {percent}% (eta {eta})";
/// The bar without: the rate of simulated time (or of pressure decades) changes as a run goes
/// on, so an ETA extrapolated from it would be wrong (a peg board's balls pile up, collide
/// ever more often, and simulated time slows: 17 s shown for a run that took minutes).
const WITHOUT_ETA: &str = "{msg} [{elapsed_precise}] {wide_bar} {percent}%";

impl Progress {
    /// A progress reporter; silent when `quiet` or when stderr is not a terminal.
    pub fn new(total: u64, message: &'static str, quiet: bool) -> Self {
        Progress {
            bar: None,
            enabled: !quiet && std::io::stderr().is_terminal(),
            started: Instant::now(),
            total,
            message,
            eta: true,
        }
    }

    /// A progress reporter without an estimated time to completion, for progress measured in
    /// something whose rate changes as the work goes on (simulated time, pressure decades).
    pub fn without_eta(total: u64, message: &'static str, quiet: bool) -> Self {
        Progress {
            eta: false,
            ..Self::new(total, message, quiet)
        }
    }

    /// The bar's indicatif template.
    fn template(&self) -> &'static str {
        if self.eta {
            WITH_ETA
        } else {
            WITHOUT_ETA
        }
    }

    /// Reports that `done` of `total` is done.
    pub fn set(&mut self, done: u64) {
        if !self.enabled {
            return;
        }
        if self.bar.is_none() && self.started.elapsed() > Duration::from_secs(1) {
            let bar = ProgressBar::with_draw_target(Some(self.total), ProgressDrawTarget::stderr());
            bar.set_style(ProgressStyle::with_template(self.template()).expect("valid template"));
            bar.set_message(self.message);
            self.bar = Some(bar);
        }
        if let Some(bar) = &self.bar {
            bar.set_position(done.min(self.total));
        }
    }

    /// Removes the bar.
    pub fn finish(self) {
        if let Some(bar) = self.bar {
            bar.finish_and_clear();
        }
    }
}

#[cfg(test)]
mod tests {
    use super::{Progress, WITHOUT_ETA};
    use indicatif::ProgressStyle;

    #[test]
    fn steady_work_shows_an_eta_and_changing_rates_do_not() {
        assert!(Progress::new(10, "events", true)
            .template()
            .contains("{eta}"));
        let t = Progress::without_eta(10, "simulated time", true).template();
        assert!(!t.contains("eta"), "{t}");
        for t in [t, Progress::new(1, "", true).template(), WITHOUT_ETA] {
            assert!(ProgressStyle::with_template(t).is_ok(), "{t}");
        }
    }
}
