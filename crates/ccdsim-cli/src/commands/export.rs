//! `ccdsim export`: convert a run file to JSON Lines.

use anyhow::{Context, Result};
use ccdsim::billiards::{export_pool_jsonl, open_pool_run};
use ccdsim::record::{export_jsonl, open_run, run_file_version, AnyRunReader, VERSION_POOL};
use std::io::{BufWriter, Write};
use std::path::PathBuf;
use std::process::ExitCode;

/// Output formats.
#[derive(clap::ValueEnum, Clone, Copy)]
enum Format {
    /// A header object, then one object per event (see docs/run-files.md).
    Jsonl,
}

/// Arguments of `ccdsim export`.
#[derive(clap::Args)]
pub struct Args {
    /// The run file.
    file: PathBuf,
    /// Output format.
    #[arg(long, value_enum, default_value = "jsonl")]
    format: Format,
    /// Write here instead of to standard output.
    #[arg(long)]
    out: Option<PathBuf>,
}

/// Runs the command. A failed export leaves no partial output file.
pub fn run(args: Args) -> Result<ExitCode> {
    let result = export(&args);
    if let (Err(_), Some(path)) = (&result, &args.out) {
        let _ = std::fs::remove_file(path);
    }
    result
}

fn export(args: &Args) -> Result<ExitCode> {
    let Format::Jsonl = args.format;
    let pool = run_file_version(&args.file)? == VERSION_POOL;
    let mut reader = if pool {
        Err(open_pool_run(&args.file)?)
    } else {
        Ok(open_run(&args.file)?)
    };
    let mut out: Box<dyn Write> = match &args.out {
        Some(p) => {
            Box::new(std::fs::File::create(p).with_context(|| format!("creating {}", p.display()))?)
        }
        None => Box::new(std::io::stdout().lock()),
    };
    let mut out = BufWriter::new(&mut out);
    let tail = match &mut reader {
        Err(r) => {
            export_pool_jsonl(r, &mut out)?;
            r.tail()
        }
        Ok(AnyRunReader::D2(r)) => {
            export_jsonl(r, &mut out)?;
            r.tail()
        }
        Ok(AnyRunReader::D3(r)) => {
            export_jsonl(r, &mut out)?;
            r.tail()
        }
    };
    out.flush()?;
    // Like verify: a file cut short still exports what it holds, and says so.
    if let Some(warning) = tail.warning() {
        eprintln!("warning: {}: {warning}", args.file.display());
    }
    Ok(ExitCode::SUCCESS)
}
