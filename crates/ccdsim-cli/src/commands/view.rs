//! `ccdsim view`: serve a run file to the browser viewer on 127.0.0.1.

use super::finder_args::FinderArgs;
use anyhow::Result;
use ccdsim_viewer::{serve, ServeOptions, ViewerError};
use std::io::Write;
use std::path::PathBuf;
use std::process::ExitCode;

/// Port tried when none is given; any free port is used when it is taken.
const DEFAULT_PORT: u16 = 7979;

/// Arguments of `ccdsim view`.
#[derive(clap::Args)]
pub struct Args {
    /// The run file (written by `ccdsim run --record`).
    run: PathBuf,
    /// Port on 127.0.0.1 (0: any free port) [default: 7979, or any free port if taken].
    #[arg(long)]
    port: Option<u16>,
    /// Finder whose boxes the page draws.
    #[arg(long, default_value = "bvh")]
    finder: String,
    #[command(flatten)]
    finder_options: FinderArgs,
}

/// Runs the command: prints the page's URL on standard output, then serves until killed.
pub fn run(args: Args) -> Result<ExitCode> {
    let options = ServeOptions {
        finder: args.finder.clone(),
        finder_options: args.finder_options.options()?,
        ..ServeOptions::default()
    };
    // A file that cannot be opened gets its one-line error before any word of progress.
    std::fs::File::open(&args.run).map_err(|e| anyhow::anyhow!("{}: {e}", args.run.display()))?;
    eprintln!("indexing {} …", args.run.display());
    let server = match args.port {
        Some(p) => serve(&args.run, p, &options)?,
        None => match serve(&args.run, DEFAULT_PORT, &options) {
            Err(ViewerError::Bind { .. }) => serve(&args.run, 0, &options)?,
            other => other?,
        },
    };
    let mut out = std::io::stdout().lock();
    writeln!(out, "{}", server.url())?;
    out.flush()?;
    eprintln!(
        "serving {} on 127.0.0.1 only; open the URL above in a browser (Ctrl-C stops)",
        args.run.display()
    );
    server.run();
    Ok(ExitCode::SUCCESS)
}
