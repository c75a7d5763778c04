//! Scaffolding shared by the CLI's integration tests: the built binary, scratch paths, and
//! running a command that must succeed.

#![allow(dead_code)] // each test binary uses its own subset

mod scratch;

pub use scratch::{ScratchDir, ScratchFile};
use std::process::{Command, Output};

/// The `ccdsim` binary built for these tests.
pub fn ccdsim() -> Command {
    Command::new(env!("CARGO_BIN_EXE_ccdsim"))
}

/// A fresh, empty scratch directory for one test, removed when it is dropped: `group` names
/// the test file, `name` the test.
pub fn scratch_dir(group: &str, name: &str) -> ScratchDir {
    ScratchDir::new(&format!("{group}-{name}"))
}

/// A path for file `name` in a scratch directory of its own for `group`'s tests, removed
/// with the file when it is dropped.
pub fn scratch_file(group: &str, name: &str) -> ScratchFile {
    ScratchFile::new(group, name)
}

/// Runs `cmd` and panics with its standard error unless it succeeds.
#[track_caller]
pub fn run_ok(cmd: &mut Command) -> Output {
    let out = cmd.output().unwrap();
    assert!(
        out.status.success(),
        "failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    out
}
