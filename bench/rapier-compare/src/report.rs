//! The Markdown report: a header naming the command, date, versions and machine, and the
//! table.

use crate::metrics::Penetration;
use std::process::Command;
use std::time::{SystemTime, UNIX_EPOCH};

/// What one engine did on one scene.
pub struct Outcome {
    /// The scene's table name.
    pub scene: &'static str,
    /// `ccdsim` or `Rapier`.
    pub engine: &'static str,
    /// Largest penetrations over all frame ends.
    pub penetration: Penetration,
    /// `(E(T) − E(0)) / E(0)`, kinetic plus potential.
    pub drift_end: f64,
    /// Largest `|E(t) − E(0)| / |E(0)|` over frame ends.
    pub drift_max: f64,
    /// Balls whose centre was outside the box at some frame end.
    pub balls_outside: usize,
    /// Wall-clock microseconds per frame: median and 99th percentile.
    pub frame_us: (f64, f64),
    /// Wall-clock seconds of all the frames' steps together.
    pub total_s: f64,
    /// The engine's own notes.
    pub notes: String,
}

/// `YYYY-MM-DD HH:MM UTC` for now.
fn utc_now() -> String {
    let secs = SystemTime::now()
        .duration_since(UNIX_EPOCH)
        .map_or(0, |d| d.as_secs());
    let (days, rem) = ((secs / 86_400) as i64, secs % 86_400);
    // Civil date from days since 1970-01-01 (H. Hinnant's algorithm).
    let z = days + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z - era * 146_097;
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let day = doy - (153 * mp + 2) / 5 + 1;
    let month = if mp < 10 { mp + 3 } else { mp - 9 };
    let year = yoe + era * 400 + i64::from(month <= 2);
    format!(
        "{year:04}-{month:02}-{day:02} {:02}:{:02} UTC",
        rem / 3600,
        rem % 3600 / 60
    )
}

fn cpu_model() -> String {
    std::fs::read_to_string("/proc/cpuinfo")
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with("model name"))
                .and_then(|l| l.split_once(':'))
                .map(|(_, m)| m.trim().to_string())
        })
        .unwrap_or_else(|| "unknown".into())
}

fn load_average() -> String {
    std::fs::read_to_string("/proc/loadavg")
        .map(|s| s.split_whitespace().take(3).collect::<Vec<_>>().join(" "))
        .unwrap_or_else(|_| "unknown".into())
}

/// The commit of the working tree that holds this program, and whether it has changes.
fn ccdsim_commit() -> String {
    let dir = env!("CARGO_MANIFEST_DIR");
    let git = |args: &[&str]| {
        Command::new("git")
            .arg("-C")
            .arg(dir)
            .args(args)
            .output()
            .ok()
            .filter(|o| o.status.success())
            .map(|o| String::from_utf8_lossy(&o.stdout).trim().to_string())
    };
    match git(&["rev-parse", "--short", "HEAD"]) {
        Some(commit) => {
            let dirty = git(&["status", "--porcelain", "--", "../../crates"])
                .is_some_and(|s| !s.is_empty());
            if dirty {
                format!("{commit} (crates/ has uncommitted changes)")
            } else {
                commit
            }
        }
        None => "unknown".into(),
    }
}

/// The header lines: command, date, versions, machine.
pub fn header(command: &str) -> String {
    let nproc = std::thread::available_parallelism().map_or(0, |n| n.get());
    format!(
        "- command: `{command}`\n\
         - date: {}\n\
         - rapier2d {} (f32, default features); ccdsim at {}; {}\n\
         - machine: `nproc` = {nproc}, CPU \"{}\", load average at start {}\n",
        utc_now(),
        env!("RAPIER2D_VERSION"),
        ccdsim_commit(),
        env!("RUSTC_VERSION"),
        cpu_model(),
        load_average(),
    )
}

fn sci(x: f64) -> String {
    if x == 0.0 {
        "0".into()
    } else {
        format!("{x:.2e}")
    }
}

fn signed(x: f64) -> String {
    if x == 0.0 {
        "0".into()
    } else {
        format!("{x:+.2e}")
    }
}

/// The results as a Markdown table.
pub fn table(outcomes: &[Outcome]) -> String {
    let mut s = String::from(
        "| scene | engine | max ball–ball penetration / r | max ball–wall penetration / r \
         | energy drift at T | max \\|drift\\| | balls outside the box | median µs/frame \
         | p99 µs/frame | total s | notes |\n\
         |---|---|---:|---:|---:|---:|---:|---:|---:|---:|---|\n",
    );
    for o in outcomes {
        s.push_str(&format!(
            "| {} | {} | {} | {} | {} | {} | {} | {:.0} | {:.0} | {:.3} | {} |\n",
            o.scene,
            o.engine,
            sci(o.penetration.pair),
            sci(o.penetration.wall),
            signed(o.drift_end),
            sci(o.drift_max),
            o.balls_outside,
            o.frame_us.0,
            o.frame_us.1,
            o.total_s,
            o.notes,
        ));
    }
    s
}
