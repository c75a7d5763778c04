//! The `ccdsim` command: run, generate, verify and export exact collision simulations.

#[macro_use]
mod out;

mod commands;
mod huge_pages;
mod number;
mod progress;

use clap::{Parser, Subcommand};
use std::process::ExitCode;

/// Large blocks get transparent huge pages (see [`huge_pages`]).
#[global_allocator]
static ALLOCATOR: huge_pages::HugePageAlloc = huge_pages::HugePageAlloc;

/// Exact event-driven collision simulation of circles (2D) and spheres (3D).
#[derive(Parser)]
#[command(name = "ccdsim", version, about, long_about = None)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Run a scene (or the built-in billiard break) and print a summary.
    Run(commands::run::Args),
    /// Generate a scene and write it as JSON.
    Gen(commands::gen::Args),
    /// Compress a random gas into a jammed packing (growing radii, Lubachevsky–Stillinger).
    Pack(commands::pack::Args),
    /// Replay a run file and check the numerical rules.
    Verify(commands::verify::Args),
    /// Convert a run file to another format.
    Export(commands::export::Args),
    /// Run a benchmark workload and print its table (writes CSV, JSON and plots).
    Bench(commands::bench::Args),
    /// Play a run file in the browser (served on 127.0.0.1).
    View(commands::view::Args),
    /// Draw a run file to a PNG frame or an animated GIF.
    Render(commands::render::Args),
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Run(a) => commands::run::run(a),
        Command::Gen(a) => commands::gen::run(a),
        Command::Pack(a) => commands::pack::run(a),
        Command::Verify(a) => commands::verify::run(a),
        Command::Export(a) => commands::export::run(a),
        Command::Bench(a) => commands::bench::run(a),
        Command::View(a) => commands::view::run(a),
        Command::Render(a) => commands::render::run(a),
    };
    match result {
        Ok(code) => code,
        Err(e) if is_broken_pipe(&e) => ExitCode::SUCCESS,
        Err(e) => {
            // One line: the culprit is named by the library's error messages.
            eprintln!("error: {}", one_line(&e));
            ExitCode::from(2)
        }
    }
}

/// The error and its causes on one line, `context: cause: cause's cause`, each said once:
/// some error types write their source's message into their own (the run-file reader's
/// `"{path}: {source}"`) and also return it as `source()`, which `{:#}` would print twice.
fn one_line(e: &anyhow::Error) -> String {
    let mut line = String::new();
    for cause in e.chain() {
        let text = cause.to_string();
        if text.is_empty() || line.contains(&text) {
            continue;
        }
        if !line.is_empty() {
            line.push_str(": ");
        }
        line.push_str(&text);
    }
    line
}

/// A reader that stopped reading (`ccdsim export run.ccd | head`) is not an error.
fn is_broken_pipe(e: &anyhow::Error) -> bool {
    e.chain().any(|c| {
        c.downcast_ref::<std::io::Error>()
            .is_some_and(|io| io.kind() == std::io::ErrorKind::BrokenPipe)
    })
}
