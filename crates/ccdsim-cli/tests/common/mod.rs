//! Scaffolding shared by the CLI's integration tests: the built binary, scratch paths, and
//! running a command that must succeed.

#![allow(dead_code)] // each test binary uses its own subset

use std::path::PathBuf;
use std::process::{Command, Output};

/// The `ccdsim` binary built for these tests.
pub fn ccdsim() -> Command {
    Command::new(env!("CARGO_BIN_EXE_ccdsim"))
}

/// A fresh, empty scratch directory for one test: `group` names the test file, `name` the
/// test, and the process id keeps concurrent test runs apart.
pub fn scratch_dir(group: &str, name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("ccdsim-{group}-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// A path for file `name` in the scratch directory that `group`'s tests share.
pub fn scratch_file(group: &str, name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("ccdsim-{group}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
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
