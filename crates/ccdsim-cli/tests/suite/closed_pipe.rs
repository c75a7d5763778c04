//! A reader that stops reading (`ccdsim run --json | head -c 100`) ends the command quietly,
//! as Unix tools do: no panic, no message, no failure status.

use crate::common;

use common::{ccdsim, run_ok};
use std::process::{Command, Stdio};

/// Runs `cmd` with its standard output a pipe whose reading end is closed at once, so that
/// everything the command prints meets a closed pipe; checks that it exits 0 and says nothing.
#[track_caller]
fn quiet_on_closed_pipe(label: &str, cmd: &mut Command) {
    let mut child = cmd
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    drop(child.stdout.take());
    let out = child.wait_with_output().unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!err.contains("panicked"), "{label}: {err}");
    assert!(err.is_empty(), "{label}: nothing on stderr expected: {err}");
    assert_eq!(out.status.code(), Some(0), "{label}: {err}");
}

#[test]
fn every_command_writing_to_stdout_exits_quietly_when_the_reader_is_gone() {
    let dir = common::scratch_dir("closed_pipe", "all");
    let scene = dir.join("gas.json");
    let run = dir.join("gas.ccd");
    run_ok(
        ccdsim()
            .args(["gen", "gas", "--n", "50", "--out"])
            .arg(&scene),
    );
    run_ok(
        ccdsim()
            .arg("run")
            .arg(&scene)
            .args(["--until", "2", "--record"])
            .arg(&run),
    );
    quiet_on_closed_pipe("run --json", ccdsim().args(["run", "--json", "--quiet"]));
    quiet_on_closed_pipe("run", ccdsim().args(["run", "--quiet"]));
    quiet_on_closed_pipe("gen", ccdsim().args(["gen", "gas", "--n", "2000"]));
    quiet_on_closed_pipe("export", ccdsim().arg("export").arg(&run));
    quiet_on_closed_pipe("verify", ccdsim().arg("verify").arg(&run).arg("--quiet"));
    quiet_on_closed_pipe(
        "pack",
        ccdsim()
            .args([
                "pack",
                "--dim",
                "2",
                "--n",
                "20",
                "--until-pressure",
                "100",
                "--out",
            ])
            .arg(dir.join("packed")),
    );
}
