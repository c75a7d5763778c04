//! `ccdsim verify`: replay a run file and check the numerical rules.

use crate::number::{num, sig};
use crate::progress::Progress;
use anyhow::Result;
use ccdsim::billiards::{open_pool_run, PoolRecord};
use ccdsim::observables::EnergyBalance;
use ccdsim::record::{
    open_run, run_file_version, AnyRunReader, RunReader, RunRecord, VERSION_POOL,
};
use ccdsim::verify::{PoolVerifier, Verifier};
use std::io::Read;
use std::path::PathBuf;
use std::process::ExitCode;

/// Arguments of `ccdsim verify`.
#[derive(clap::Args)]
pub struct Args {
    /// The run file.
    file: PathBuf,
    /// No progress bar.
    #[arg(long, short)]
    quiet: bool,
}

/// Runs the command: exit status 0 when the run keeps every rule, 1 at the first violation.
pub fn run(args: Args) -> Result<ExitCode> {
    if run_file_version(&args.file)? == VERSION_POOL {
        return check_pool(&args.file);
    }
    let size = std::fs::metadata(&args.file).map(|m| m.len()).unwrap_or(0);
    match open_run(&args.file)? {
        AnyRunReader::D2(r) => check(r, size, args.quiet),
        AnyRunReader::D3(r) => check(r, size, args.quiet),
    }
}

fn check<R: Read, const D: usize>(
    mut reader: RunReader<R, D>,
    size: u64,
    quiet: bool,
) -> Result<ExitCode> {
    let mut verifier = Verifier::new(reader.scene());
    let mut end = reader.scene().start_time;
    let mut progress = Progress::new(size, "verifying", quiet);
    let rec_len = ccdsim::record::record_len(D) as u64;
    while let Some(rec) = reader.next_record()? {
        match rec {
            RunRecord::Event(c) => {
                end = c.event.time;
                if let Err(v) = verifier.check(&c) {
                    progress.finish();
                    outln!("FAIL {}: {v}", reader.path())?;
                    return Ok(ExitCode::from(1));
                }
                if reader.records_read() % 4096 == 0 {
                    progress.set(reader.data_start() + reader.records_read() * rec_len);
                }
            }
            RunRecord::End(t) => end = t,
        }
    }
    progress.finish();
    match verifier.finish(end) {
        Ok(report) => {
            if let Some(warning) = reader.tail().warning() {
                eprintln!("warning: {warning}");
            }
            // The one relative drift, the library's (`EnergyBalance`, what `run` prints): a
            // steered run's edits add energy of their own, and moving walls do work; the drift
            // is the other collisions'.
            let drift = EnergyBalance {
                kinetic_start: report.kinetic_energy_start,
                kinetic_end: report.kinetic_energy_end,
                potential_start: report.potential_energy_start,
                potential_end: report.potential_energy_end,
                work: report.edit_energy + report.wall_work,
                rotational_start: report.rotational_energy_start,
                rotational_end: report.rotational_energy_end,
            }
            .relative_drift();
            let mut resets = if report.resets > 0 {
                format!(", {} thermostat resets", report.resets)
            } else {
                String::new()
            };
            if report.edits > 0 {
                resets += &format!(
                    ", {} edits adding {} J",
                    report.edits,
                    num(report.edit_energy)
                );
            }
            if report.wall_work != 0.0 {
                resets += &format!(", moving walls' work {} J", num(report.wall_work));
            }
            outln!(
                "OK {}: {} events ({} body-body, {} body-wall{resets}) up to t = {}; largest overlap {}; relative drift {}",
                reader.path(),
                report.events,
                report.body_collisions,
                report.wall_collisions,
                sig(end, 10),
                sig(report.max_overlap, 3),
                sig(drift, 3)
            )?;
            Ok(ExitCode::SUCCESS)
        }
        Err(v) => {
            outln!("FAIL {}: {v}", reader.path())?;
            Ok(ExitCode::from(1))
        }
    }
}

/// Verifies a pool shot's run file (format version 16; see `ccdsim::verify::PoolVerifier`).
fn check_pool(path: &std::path::Path) -> Result<ExitCode> {
    let mut reader = open_pool_run(path)?;
    let mut verifier = PoolVerifier::new(reader.scene()).map_err(anyhow::Error::msg)?;
    let mut end = 0.0;
    while let Some(rec) = reader.next_record()? {
        end = rec.time();
        if let Err(v) = verifier.check(&rec) {
            outln!("FAIL {}: {v}", reader.path())?;
            return Ok(ExitCode::from(1));
        }
        if let PoolRecord::End(_) = rec {
            break;
        }
    }
    match verifier.finish(end) {
        Ok(r) => {
            if let Some(warning) = reader.tail().warning() {
                eprintln!("warning: {warning}");
            }
            let ending = if r.still {
                "every ball at rest or pocketed"
            } else {
                "balls still moving (the shot stopped short)"
            };
            let pressed = if r.pressings > 0 {
                format!(
                    "; {} pressed pairs parted, adding {} J",
                    r.pressings,
                    sig(r.pressing_energy, 3)
                )
            } else {
                String::new()
            };
            outln!(
                "OK {}: pool shot, {} events ({} ball-ball, {} cushion, {} pocketed, {} state changes) up to t = {}, {ending}; largest overlap {}; energy {} J after the strike, {} J at the end{pressed}",
                reader.path(),
                r.events,
                r.ball_ball,
                r.cushion,
                r.pocketed,
                r.transitions,
                sig(end, 10),
                sig(r.max_overlap, 3),
                sig(r.energy_start, 6),
                sig(r.energy_end, 6)
            )?;
            Ok(ExitCode::SUCCESS)
        }
        Err(v) => {
            outln!("FAIL {}: {v}", reader.path())?;
            Ok(ExitCode::from(1))
        }
    }
}
