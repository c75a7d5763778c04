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
}

impl Progress {
    /// A progress reporter; silent when `quiet` or when stderr is not a terminal.
    pub fn new(total: u64, message: &'static str, quiet: bool) -> Self {
        Progress {
            bar: None,
            enabled: !quiet && std::io::stderr().is_terminal(),
            started: Instant::now(),
            total,
            message,
        }
    }

    /// Reports that `done` of `total` is done.
    pub fn set(&mut self, done: u64) {
        if !self.enabled {
            return;
        }
        if self.bar.is_none() && self.started.elapsed() > Duration::from_secs(1) {
            let bar = ProgressBar::with_draw_target(Some(self.total), ProgressDrawTarget::stderr());
            bar.set_style(
                ProgressStyle::with_template(
                    "{msg} [{elapsed_precise}] {wide_bar} {percent}% (eta {eta})",
                )
                .expect("valid template"),
            );
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
