//! Inputs that used to be taken silently or handled wrongly (issue 20): the default finder,
//! times before the scene's start, and scripts that assumed `./target`.

use crate::common;

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

/// Records the built-in break for one second and returns the run file's bytes.
fn recorded_break(dir: &Path) -> Vec<u8> {
    let run = dir.join("break.ccd");
    run_ok(
        ccdsim()
            .args(["run", "--until", "1", "--quiet", "--record"])
            .arg(&run),
    );
    std::fs::read(&run).unwrap()
}

/// Runs `verify` and `export` on `bytes` written to a file, returning each one's exit code
/// and standard error.
fn verify_and_export(dir: &Path, name: &str, bytes: &[u8]) -> [(Option<i32>, String); 2] {
    let path = dir.join(name);
    std::fs::write(&path, bytes).unwrap();
    let out_file = dir.join(format!("{name}.jsonl"));
    let _ = std::fs::remove_file(&out_file);
    let verify = ccdsim().arg("verify").arg(&path).output().unwrap();
    let export = ccdsim()
        .arg("export")
        .arg(&path)
        .arg("--out")
        .arg(&out_file)
        .output()
        .unwrap();
    if !export.status.success() {
        assert!(!out_file.exists(), "{name}: a failed export leaves no file");
    }
    [verify, export].map(|o| {
        (
            o.status.code(),
            String::from_utf8_lossy(&o.stderr).into_owned(),
        )
    })
}

#[test]
fn a_corrupt_header_length_is_an_error_not_an_allocation_failure() {
    let dir = common::scratch_dir("hard-inputs", "header-length");
    let mut bytes = recorded_break(&dir);
    bytes[16..24].copy_from_slice(&(1u64 << 36).to_le_bytes());
    for (code, err) in verify_and_export(&dir, "long-header.ccd", &bytes) {
        // An abort would end the process by a signal, with no exit code.
        assert_eq!(code, Some(2), "{err}");
        assert!(err.contains("header length 68719476736"), "{err}");
        assert_eq!(err.trim_end().lines().count(), 1, "{err}");
    }
}

#[test]
fn export_reports_a_truncated_run_file_as_verify_does() {
    let dir = common::scratch_dir("hard-inputs", "truncated");
    let mut bytes = recorded_break(&dir);
    bytes.truncate(bytes.len() - 30);
    for (code, err) in verify_and_export(&dir, "cut.ccd", &bytes) {
        assert_eq!(code, Some(0), "{err}");
        assert!(
            err.contains("warning") && err.contains("incomplete record"),
            "{err}"
        );
    }
}

#[test]
fn bytes_after_the_end_record_are_refused() {
    let dir = common::scratch_dir("hard-inputs", "trailing");
    let mut bytes = recorded_break(&dir);
    let end = bytes.len();
    bytes.extend_from_slice(b"appended");
    for (code, err) in verify_and_export(&dir, "trailing.ccd", &bytes) {
        assert_ne!(code, Some(0), "{err}");
        assert!(
            err.contains(&format!(
                "trailing data after the end record, at byte {end}"
            )),
            "{err}"
        );
    }
}

/// A missing file is named once with its cause said once, not "…(os error 2): …(os error 2)".
#[test]
fn a_missing_file_says_its_cause_once() {
    let dir = common::scratch_dir("hard_inputs", "missing_file");
    for (cmd, file) in [
        ("verify", "missing.ccd"),
        ("export", "missing.ccd"),
        ("run", "missing.json"),
        ("view", "missing.ccd"),
        ("render", "missing.ccd"),
    ] {
        let path = dir.join(file);
        let mut c = ccdsim();
        c.arg(cmd).arg(&path);
        if cmd == "render" {
            c.args(["--at", "0", "--out"]).arg(dir.join("f.png"));
        }
        let out = c.output().unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{cmd}: {err}");
        assert_eq!(err.trim_end().lines().count(), 1, "{cmd}: {err}");
        assert!(err.contains(file), "{cmd}: the file is named: {err}");
        assert_eq!(err.matches("os error 2").count(), 1, "{cmd}: {err}");
    }
}

/// A packing denser than random placement reaches is refused at once (it used to try 10⁸
/// placements first, minutes of silence), with the way out named; lattices go further.
#[test]
fn gen_refuses_unreachable_packings_at_once() {
    let dir = common::scratch_dir("hard_inputs", "unreachable_packing");
    let out_file = dir.join("gas.json");
    for (dim, packing, hint) in [
        ("2", "0.95", "--lattice"),
        ("2", "0.6", "--lattice"),
        ("3", "0.5", "--lattice"),
    ] {
        let start = std::time::Instant::now();
        let out = ccdsim()
            .args([
                "gen",
                "gas",
                "--n",
                "100000",
                "--dim",
                dim,
                "--packing",
                packing,
            ])
            .arg("--out")
            .arg(&out_file)
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{err}");
        assert!(err.contains("packing") && err.contains(hint), "{err}");
        assert_eq!(err.trim_end().lines().count(), 1, "{err}");
        assert!(out.stdout.is_empty() && !out_file.exists());
        assert!(
            start.elapsed() < std::time::Duration::from_secs(10),
            "{dim}D {packing}"
        );
    }
    // Beyond the densest lattice packing too.
    let out = ccdsim()
        .args([
            "gen",
            "gas",
            "--n",
            "1000",
            "--packing",
            "0.95",
            "--lattice",
        ])
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(err.contains("0.9068"), "{err}");
    run_ok(ccdsim().args([
        "gen",
        "gas",
        "--n",
        "1000",
        "--packing",
        "0.85",
        "--lattice",
    ]));
}
