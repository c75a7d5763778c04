//! Inputs that used to be taken silently or handled wrongly (issue 20): the default finder,
//! times before the scene's start, and scripts that assumed `./target`.

mod common;

use common::{ccdsim, run_ok};
use std::path::Path;
use std::process::Command;

/// The workspace's root directory.
fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .and_then(Path::parent)
        .unwrap()
}

#[test]
fn run_defaults_to_the_fast_finder() {
    let out = run_ok(ccdsim().args(["run", "--until", "1", "--json"]));
    let summary: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(summary["finder"], "cells", "{summary}");
}

#[test]
fn until_before_the_start_time_is_refused() {
    for until in ["-1", "--until=-1"] {
        let mut cmd = ccdsim();
        cmd.arg("run");
        if until.starts_with("--") {
            cmd.arg(until);
        } else {
            cmd.args(["--until", until]);
        }
        let out = cmd.output().unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{err}");
        assert!(err.contains("before the scene's start time"), "{err}");
        assert!(out.stdout.is_empty());
    }
}

#[test]
fn scripts_find_binaries_in_a_moved_target_directory() {
    let moved = std::env::temp_dir().join(format!("ccdsim-moved-target-{}", std::process::id()));
    let e2e = root().join("crates/ccdsim-viewer/e2e/run.sh");
    let out = run_ok(
        Command::new("bash")
            .arg(&e2e)
            .arg("--which-bin")
            .env("CARGO_TARGET_DIR", &moved),
    );
    let bin = String::from_utf8(out.stdout).unwrap();
    assert_eq!(
        Path::new(bin.trim()),
        moved.join("debug/ccdsim"),
        "the browser tests must run the binary cargo built, wherever the target directory is"
    );
    let out = run_ok(
        Command::new("bash")
            .arg(root().join("scripts/target-dir"))
            .env("CARGO_TARGET_DIR", &moved),
    );
    assert_eq!(
        Path::new(String::from_utf8(out.stdout).unwrap().trim()),
        moved
    );
}
