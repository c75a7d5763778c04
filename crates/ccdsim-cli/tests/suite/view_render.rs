//! `ccdsim view` and `ccdsim render` as a user runs them: thin commands over ccdsim-viewer.

use crate::common;
use std::io::{BufRead, BufReader, Read, Write};

use common::{ccdsim, run_ok};
use std::path::{Path, PathBuf};
use std::process::Stdio;

fn tmp(name: &str) -> common::ScratchDir {
    common::scratch_dir("cli-view", name)
}

/// Records the built-in billiard break for `until` seconds.
fn record_break(dir: &Path, until: &str) -> PathBuf {
    let run = dir.join("break.ccd");
    run_ok(
        ccdsim()
            .args(["run", "--until", until, "--quiet", "--record"])
            .arg(&run),
    );
    run
}

/// Runs `ccdsim render RUN ARGS --out PNG` and requires the usage status, one line on
/// standard error naming `culprit`, and no file.
fn refused(run: &Path, args: &[&str], png: &Path, culprit: &str) {
    let out = ccdsim()
        .arg("render")
        .arg(run)
        .args(args)
        .arg("--out")
        .arg(png)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2), "{args:?}");
    let err = String::from_utf8(out.stderr).unwrap();
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(err.contains(culprit), "{err}");
    assert!(!png.exists());
}

#[test]
fn render_writes_a_png_and_a_gif() {
    let dir = tmp("render");
    let run = record_break(&dir, "3");
    let png = dir.join("frame.png");
    run_ok(
        ccdsim()
            .arg("render")
            .arg(&run)
            .args(["--at", "0.5", "--width", "320", "--out"])
            .arg(&png),
    );
    let bytes = std::fs::read(&png).unwrap();
    assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n");
    let be = |k: usize| u32::from_be_bytes(bytes[k..k + 4].try_into().unwrap());
    // IHDR: a 320 px wide frame of the 2:1 table.
    assert_eq!((be(16), be(20)), (320, 168));
    let gif = dir.join("break.gif");
    let out = ccdsim()
        .arg("render")
        .arg(&run)
        .arg("--gif")
        .arg(&gif)
        .args([
            "--fps", "10", "--speed", "2", "--from", "0", "--to", "1", "--width", "200",
        ])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let said = String::from_utf8(out.stdout).unwrap();
    assert!(said.contains("(6 frames, 200×"), "{said}");
    assert_eq!(&std::fs::read(&gif).unwrap()[..6], b"GIF89a");
}

#[test]
fn render_draws_a_pool_shot_and_refuses_what_it_cannot_draw() {
    let dir = tmp("render-pool");
    let scene = dir.join("nine.json");
    let run = dir.join("nine.ccd");
    for args in [
        vec!["gen".into(), "table".into(), "--out".into(), scene.clone()],
        vec!["run".into(), scene.clone(), "--record".into(), run.clone()],
    ] {
        run_ok(ccdsim().args(&args));
    }
    let png = dir.join("nine.png");
    run_ok(
        ccdsim()
            .arg("render")
            .arg(&run)
            .args(["--at", "0.5", "--width", "400", "--out"])
            .arg(&png),
    );
    let bytes = std::fs::read(&png).unwrap();
    assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n");
    let be = |k: usize| u32::from_be_bytes(bytes[k..k + 4].try_into().unwrap());
    // The table's long side across: wider than high.
    assert_eq!(be(16), 400);
    assert!(be(20) < 300, "{}", be(20));
    let gif = dir.join("nine.gif");
    let out = run_ok(
        ccdsim()
            .arg("render")
            .arg(&run)
            .arg("--gif")
            .arg(&gif)
            .args(["--fps", "10", "--to", "1", "--width", "200"]),
    );
    let said = String::from_utf8(out.stdout).unwrap();
    assert!(said.contains("(11 frames, 200×"), "{said}");
    assert_eq!(&std::fs::read(&gif).unwrap()[..6], b"GIF89a");
    std::fs::remove_file(&png).unwrap();
    for (args, culprit) in [
        (vec!["--at", "0.5", "--boxes"], "finder boxes"),
        (vec!["--at", "0.5", "--colour", "speed"], "own colours"),
        (vec!["--at", "1000"], "outside the shot"),
    ] {
        refused(&run, &args, &png, culprit);
    }
}

#[test]
fn render_refuses_bad_options_with_one_line_and_no_file() {
    let dir = tmp("render-bad");
    let run = record_break(&dir, "1");
    let png = dir.join("frame.png");
    for (args, culprit) in [
        (vec!["--at", "0.5", "--width", "2"], "width"),
        (
            vec!["--at", "0.5", "--boxes", "--finder", "nope"],
            "unknown finder `nope`",
        ),
        (vec!["--at", "0.5", "--colour", "pink"], "--colour"),
        // Past the end, or before the start, of the recorded run (the run covers 0 … 1 s).
        (vec!["--at", "5"], "outside the run"),
        (vec!["--at", "-1"], "outside the run"),
    ] {
        refused(&run, &args, &png, culprit);
    }
    let out = ccdsim()
        .arg("render")
        .arg(dir.join("missing.ccd"))
        .args(["--at", "0"])
        .arg("--out")
        .arg(&png)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8(out.stderr)
        .unwrap()
        .contains("missing.ccd"));
}

#[test]
fn view_prints_its_url_and_serves_the_run() {
    let dir = tmp("view");
    let run = record_break(&dir, "2");
    let mut child = ccdsim()
        .arg("view")
        .arg(&run)
        .args(["--port", "0"])
        .stdout(Stdio::piped())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    let mut line = String::new();
    BufReader::new(child.stdout.take().unwrap())
        .read_line(&mut line)
        .unwrap();
    let url = line.trim_end();
    let port: u16 = url
        .strip_prefix("http://127.0.0.1:")
        .and_then(|r| r.strip_suffix('/'))
        .unwrap_or_else(|| panic!("not a loopback URL: {url}"))
        .parse()
        .unwrap();
    let mut s = std::net::TcpStream::connect(("127.0.0.1", port)).unwrap();
    write!(s, "GET /api/meta HTTP/1.0\r\n\r\n").unwrap();
    let mut answer = String::new();
    s.read_to_string(&mut answer).unwrap();
    child.kill().unwrap();
    child.wait().unwrap();
    assert!(
        answer.starts_with("HTTP/1.1 200") || answer.starts_with("HTTP/1.0 200"),
        "{answer}"
    );
    assert!(answer.contains("\"bodies\":16"), "{answer}");
}

#[test]
fn view_refuses_a_file_that_is_not_a_run() {
    let dir = tmp("view-bad");
    let bogus = dir.join("scene.json");
    std::fs::write(&bogus, "{}").unwrap();
    let out = ccdsim()
        .arg("view")
        .arg(&bogus)
        .args(["--port", "0"])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8(out.stderr).unwrap();
    assert!(err.contains("not a ccdsim run file"), "{err}");
    assert!(out.stdout.is_empty(), "no URL printed");
}
