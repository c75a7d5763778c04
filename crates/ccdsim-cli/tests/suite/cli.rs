//! The `ccdsim` binary end to end: bad input, summaries, run files, interruption.

use crate::common;

use common::{ccdsim, run_ok};
use std::path::Path;
use std::process::Stdio;

fn tmp(name: &str) -> common::ScratchFile {
    common::scratch_file("cli", name)
}

const GOOD_BODY: &str = r#"{"pos": [1, 1], "vel": [1, 0], "radius": 0.5}"#;
const TABLE: &str = r#"[{"a": [0,0], "b": [4,0]}, {"a": [4,0], "b": [4,2]}, {"a": [4,2], "b": [0,2]}, {"a": [0,2], "b": [0,0]}]"#;

/// Runs a bad scene and checks: exit status 2, one line on stderr containing `culprit`, no
/// run file left behind, nothing on stdout.
fn refuse(name: &str, scene: &str, culprit: &str) {
    let path = tmp(&format!("{name}.json"));
    std::fs::write(&path, scene).unwrap();
    let rec = tmp(&format!("{name}.ccd"));
    let _ = std::fs::remove_file(&rec);
    let out = ccdsim()
        .arg("run")
        .arg(&path)
        .arg("--record")
        .arg(&rec)
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{name}: {err}");
    assert_eq!(
        err.trim_end().lines().count(),
        1,
        "{name}: one line expected: {err}"
    );
    assert!(err.contains(culprit), "{name}: `{culprit}` not in: {err}");
    assert!(out.stdout.is_empty(), "{name}: no output expected");
    assert!(!rec.exists(), "{name}: no run file may be left");
}

#[test]
fn malformed_json_names_line_and_column() {
    refuse(
        "malformed",
        "{\"dim\": 2,\n \"bodies\": [,]}",
        "line 2, column",
    );
}

#[test]
fn non_finite_numbers_name_the_field() {
    let s = format!(
        r#"{{"dim": 2, "bodies": [{GOOD_BODY}, {{"pos": [3, 1], "vel": [1e999, 0], "radius": 0.5}}]}}"#
    );
    refuse("infinite", &s, "bodies[1].vel");
}

#[test]
fn non_positive_radius_and_mass() {
    let s = r#"{"dim": 2, "bodies": [{"pos": [1, 1], "vel": [0, 0], "radius": 0}]}"#;
    refuse("radius", s, "bodies[0].radius");
    let s = r#"{"dim": 2, "bodies": [{"pos": [1, 1], "vel": [0, 0], "radius": 1, "mass": -2}]}"#;
    refuse("mass", s, "bodies[0].mass");
}

#[test]
fn overlapping_bodies_are_named() {
    let s = format!(
        r#"{{"dim": 2, "bodies": [{GOOD_BODY}, {{"pos": [1.5, 1.2], "vel": [0, 0], "radius": 0.5}}]}}"#
    );
    refuse("overlap", &s, "body 0 and body 1 overlap");
}

#[test]
fn bodies_outside_the_table_or_across_a_wall() {
    let s = format!(
        r#"{{"dim": 2, "walls": {TABLE}, "bodies": [{GOOD_BODY}, {{"pos": [7, 1], "vel": [0, 0], "radius": 0.5}}]}}"#
    );
    refuse("outside", &s, "body 1 is outside the table");
    let s = format!(
        r#"{{"dim": 2, "walls": {TABLE}, "bodies": [{{"pos": [3.8, 1], "vel": [0, 0], "radius": 0.5}}]}}"#
    );
    refuse("crossing", &s, "body 0 crosses wall 1");
}

#[test]
fn degenerate_walls() {
    let s =
        format!(r#"{{"dim": 2, "walls": [{{"a": [5,5], "b": [5,5]}}], "bodies": [{GOOD_BODY}]}}"#);
    refuse("segment", &s, "walls[0]");
    let s = r#"{"dim": 3, "walls": [{"point": [0,0,0], "normal": [0,0,0]}], "bodies": []}"#;
    refuse("plane", s, "walls[0]");
}

#[test]
fn duplicate_ids() {
    let s = r#"{"dim": 2, "bodies": [{"id": 4, "pos": [1, 1], "vel": [0, 0], "radius": 0.5},
                                     {"id": 4, "pos": [3, 1], "vel": [0, 0], "radius": 0.5}]}"#;
    refuse("ids", s, "duplicate id 4");
}

#[test]
fn wrong_dimension() {
    let s = r#"{"dim": 3, "bodies": [{"pos": [1, 1], "vel": [0, 0, 0], "radius": 0.5}]}"#;
    refuse("dim-mismatch", s, "bodies[0].pos");
    refuse("dim-bad", r#"{"dim": 4, "bodies": []}"#, "dim");
    refuse("dim-missing", r#"{"bodies": []}"#, "dim");
}

#[test]
fn unknown_fields_and_finders() {
    let s = r#"{"dim": 2, "bodies": [{"pos": [1, 1], "vel": [0, 0], "radius": 0.5, "colour": 3}]}"#;
    refuse("unknown-field", s, "colour");
    let path = tmp("finder.json");
    std::fs::write(&path, format!(r#"{{"dim": 2, "bodies": [{GOOD_BODY}]}}"#)).unwrap();
    let rec = tmp("finder.ccd");
    let out = ccdsim()
        .arg("run")
        .arg(&path)
        .args(["--finder", "nope", "--record"])
        .arg(&rec)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("unknown finder `nope`"));
    assert!(!rec.exists());
}

#[test]
fn bad_finder_options_are_named_by_their_flag() {
    for (flag, value, why) in [
        ("--bvh-grow", "0.5", "greater than 1"),
        ("--bvh-shrink", "2", "outside (0, 1]"),
        ("--bvh-initial-dt", "0", "greater than 0"),
        ("--cells-skin", "2", "neither 0 nor in [0.001, 1]"),
    ] {
        let rec = tmp(&format!("option{flag}.ccd"));
        let out = ccdsim()
            .args(["run", "--finder", "bvh", flag, value, "--record"])
            .arg(&rec)
            .output()
            .unwrap();
        assert_eq!(out.status.code(), Some(2), "{flag}");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.contains(&format!("{flag}: {value}")), "{err}");
        assert!(err.contains(why), "{err}");
        assert_eq!(err.trim().lines().count(), 1, "{err}");
        assert!(!rec.exists());
    }
}

#[test]
fn builtin_break_prints_a_readable_summary() {
    let out = run_ok(ccdsim().arg("run").arg("--quiet"));
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.contains("billiard break"), "{text}");
    assert!(text.contains("events"), "{text}");
}

#[test]
fn json_summary_has_the_interface_fields() {
    let out = run_ok(ccdsim().args(["run", "--json", "--until", "3", "--finder", "all-pairs"]));
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    for key in [
        "events",
        "body_collisions",
        "wall_collisions",
        "sim_time",
        "wall_seconds",
        "kinetic_energy_start",
        "kinetic_energy_end",
        "max_overlap",
        "finder",
    ] {
        assert!(v.get(key).is_some(), "missing {key} in {v}");
    }
    assert_eq!(v["sim_time"], 3.0);
    assert_eq!(v["finder"], "all-pairs");
    assert!(v["finder_counters"].as_object().unwrap().is_empty());
    assert_eq!(
        v["events"].as_u64().unwrap(),
        v["body_collisions"].as_u64().unwrap() + v["wall_collisions"].as_u64().unwrap()
    );
}

#[test]
fn gen_run_verify_export_round_trip() {
    for dim in ["2", "3"] {
        let scene = tmp(&format!("gas{dim}.json"));
        run_ok(
            ccdsim()
                .args([
                    "gen",
                    "gas",
                    "--n",
                    "50",
                    "--packing",
                    "0.2",
                    "--seed",
                    "5",
                    "--dim",
                    dim,
                    "--out",
                ])
                .arg(&scene),
        );
        let rec = tmp(&format!("gas{dim}.ccd"));
        let out = run_ok(
            ccdsim()
                .arg("run")
                .arg(&scene)
                .args(["--events", "500", "--json", "--record"])
                .arg(&rec),
        );
        let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
        assert_eq!(v["events"], 500);
        let out = run_ok(ccdsim().arg("verify").arg(&rec));
        assert!(String::from_utf8_lossy(&out.stdout).starts_with("OK"));
        let out = run_ok(ccdsim().arg("export").arg(&rec).args(["--format", "jsonl"]));
        let text = String::from_utf8_lossy(&out.stdout);
        let lines: Vec<&str> = text.lines().collect();
        assert_eq!(lines.len(), 501);
        let header: serde_json::Value = serde_json::from_str(lines[0]).unwrap();
        assert_eq!(header["dim"].as_u64().unwrap().to_string(), dim);
        assert_eq!(header["bodies"].as_array().unwrap().len(), 50);
        for key in ["version", "walls", "start_time"] {
            assert!(header.get(key).is_some(), "header lacks {key}");
        }
        for line in &lines[1..] {
            let e: serde_json::Value = serde_json::from_str(line).unwrap();
            let n = if e["kind"] == "body" { 2 } else { 1 };
            assert_eq!(e["pos"].as_array().unwrap().len(), n);
            assert_eq!(e["vel"].as_array().unwrap().len(), n);
            assert!(e["t"].is_f64() && e["a"].is_u64() && e["b"].is_u64());
        }
    }
}

#[test]
fn gen_rack_is_a_valid_scene() {
    let out = run_ok(ccdsim().args(["gen", "rack"]));
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["dim"], 2);
    assert_eq!(v["bodies"].as_array().unwrap().len(), 16);
}

#[test]
fn verify_fails_on_a_tampered_run() {
    let rec = tmp("tampered.ccd");
    run_ok(
        ccdsim()
            .args(["run", "--events", "100", "--quiet", "--record"])
            .arg(&rec),
    );
    // Rewrite one event's velocity (and its checksum) so that momentum is not conserved.
    let mut bytes = std::fs::read(&rec).unwrap();
    let start = data_start(&bytes);
    let len = 21 + 32 * 2;
    let body_event = (0..100)
        .map(|k| start + k * len)
        .find(|&off| bytes[off] == 1)
        .unwrap();
    let vel_at = body_event + 17 + 16;
    bytes[vel_at..vel_at + 8].copy_from_slice(&123.0f64.to_le_bytes());
    let sum = fnv1a(&bytes[body_event..body_event + len - 4]);
    bytes[body_event + len - 4..body_event + len].copy_from_slice(&sum.to_le_bytes());
    std::fs::write(&rec, bytes).unwrap();
    let out = ccdsim().arg("verify").arg(&rec).output().unwrap();
    assert_eq!(out.status.code(), Some(1));
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        text.starts_with("FAIL") && text.contains("momentum"),
        "{text}"
    );
}

fn data_start(bytes: &[u8]) -> usize {
    24 + u64::from_le_bytes(bytes[16..24].try_into().unwrap()) as usize
}

fn fnv1a(bytes: &[u8]) -> u32 {
    bytes.iter().fold(0x811c_9dc5u32, |h, &b| {
        (h ^ u32::from(b)).wrapping_mul(0x0100_0193)
    })
}

#[test]
fn killed_run_leaves_a_readable_file() {
    let scene = tmp("kill.json");
    run_ok(
        ccdsim()
            .args(["gen", "gas", "--n", "400", "--packing", "0.3", "--out"])
            .arg(&scene),
    );
    let rec = tmp("kill.ccd");
    let mut child = ccdsim()
        .arg("run")
        .arg(&scene)
        .args(["--events", "100000000", "--quiet", "--record"])
        .arg(&rec)
        .stdout(Stdio::null())
        .spawn()
        .unwrap();
    // Wait until a few buffer flushes have happened, then kill -9 mid-write.
    let deadline = std::time::Instant::now() + std::time::Duration::from_secs(120);
    while size(&rec) < 300_000 && std::time::Instant::now() < deadline {
        std::thread::sleep(std::time::Duration::from_millis(20));
    }
    child.kill().unwrap();
    child.wait().unwrap();
    assert!(size(&rec) > 0);
    let out = ccdsim().arg("verify").arg(&rec).output().unwrap();
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{text} {}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(text.starts_with("OK"), "{text}");
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("no end record") || err.contains("incomplete record"),
        "{err}"
    );
}

fn size(p: &Path) -> u64 {
    std::fs::metadata(p).map(|m| m.len()).unwrap_or(0)
}

#[test]
fn every_example_scene_runs_and_verifies() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples");
    let mut seen = 0;
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_some_and(|e| e == "json") {
            let rec = tmp(&format!(
                "example-{}.ccd",
                path.file_stem().unwrap().to_string_lossy()
            ));
            run_ok(
                ccdsim()
                    .arg("run")
                    .arg(&path)
                    .args(["--until", "5", "--quiet", "--record"])
                    .arg(&rec),
            );
            run_ok(ccdsim().arg("verify").arg(&rec));
            seen += 1;
        }
    }
    assert!(seen >= 3, "examples/ should hold the documented scenes");
}

/// The exactness contract end to end: every finder writes the same bytes as the oracle.
#[test]
fn every_finder_records_byte_identical_run_files() {
    let gas2 = tmp("same-gas2.json");
    run_ok(
        ccdsim()
            .args([
                "gen",
                "gas",
                "--n",
                "300",
                "--packing",
                "0.3",
                "--radius-min",
                "0.3",
                "--seed",
                "8",
                "--out",
            ])
            .arg(&gas2),
    );
    let gas3 = tmp("same-gas3.json");
    run_ok(
        ccdsim()
            .args([
                "gen",
                "gas",
                "--n",
                "200",
                "--packing",
                "0.25",
                "--dim",
                "3",
                "--seed",
                "9",
                "--out",
            ])
            .arg(&gas3),
    );
    for (name, scene) in [
        ("gas2", Some(&gas2)),
        ("gas3", Some(&gas3)),
        ("break", None),
    ] {
        let mut reference: Option<Vec<u8>> = None;
        for finder in ccdsim::FINDER_NAMES {
            let rec = tmp(&format!("same-{name}-{finder}.ccd"));
            let mut cmd = ccdsim();
            cmd.arg("run");
            if let Some(s) = scene {
                cmd.arg(s);
            }
            run_ok(
                cmd.args([
                    "--events", "3000", "--quiet", "--finder", finder, "--record",
                ])
                .arg(&rec),
            );
            let bytes = std::fs::read(&rec).unwrap();
            match &reference {
                None => reference = Some(bytes),
                Some(r) => assert!(r == &bytes, "{finder} differs from all-pairs on {name}"),
            }
        }
    }
}

#[test]
fn gravity_scenes_from_gen_run_and_verify_alike_with_every_finder() {
    let scene = tmp("pegs.json");
    run_ok(
        ccdsim()
            .args(["gen", "pegs", "--balls", "20", "--rows", "4", "--out"])
            .arg(&scene),
    );
    let mut files = Vec::new();
    for finder in ["all-pairs", "bvh", "sedgewick", "cells"] {
        let rec = tmp(&format!("pegs-{finder}.ccd"));
        let out = run_ok(
            ccdsim()
                .arg("run")
                .arg(&scene)
                .args(["--until", "8", "--json", "--finder", finder, "--record"])
                .arg(&rec),
        );
        let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
        assert!(v["events"].as_u64().unwrap() > 100, "{v}");
        assert!(v["halt"].is_null(), "{v}");
        assert!(v["energy_drift"].as_f64().unwrap().abs() < 1e-9, "{v}");
        assert!(v["potential_energy_start"].as_f64().unwrap() > 0.0, "{v}");
        run_ok(ccdsim().arg("verify").arg(&rec));
        files.push(std::fs::read(&rec).unwrap());
    }
    assert!(files.windows(2).all(|w| w[0] == w[1]), "run files differ");
    // --gravity on any generated scene, validated against it.
    let out = run_ok(ccdsim().args(["gen", "gas", "--n", "10", "--gravity", "0,-9.81"]));
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["settings"]["gravity"], serde_json::json!([0.0, -9.81]));
    for (args, culprit) in [
        (
            &["gen", "gas", "--n", "10", "--gravity", "0,-1,0"][..],
            "has 3 components, the scene is 2D",
        ),
        (
            &["gen", "gas", "--n", "10", "--periodic", "--gravity", "0,-1"][..],
            "periodic box",
        ),
        (
            &["gen", "gas", "--n", "10", "--gravity", "1"][..],
            "one per dimension",
        ),
    ] {
        let out = ccdsim().args(args).output().unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(!out.status.success(), "{args:?}");
        assert!(err.contains(culprit), "{args:?}: {err}");
    }
}

#[test]
fn a_piston_heats_the_gas_by_the_work_it_does_and_verify_agrees() {
    let scene = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/piston.json");
    let rec = tmp("piston.ccd");
    let out = run_ok(
        ccdsim()
            .arg("run")
            .arg(&scene)
            .args(["--until", "20", "--json", "--record"])
            .arg(&rec),
    );
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let (k0, k1) = (
        v["kinetic_energy_start"].as_f64().unwrap(),
        v["kinetic_energy_end"].as_f64().unwrap(),
    );
    let work = v["wall_work"].as_f64().unwrap();
    assert!(work > k0, "a piston closing at 0.5 m/s heats the gas: {v}");
    assert!((k1 - k0 - work).abs() < 1e-9 * k1, "{v}");
    let out = run_ok(ccdsim().arg("verify").arg(&rec));
    let text = String::from_utf8(out.stdout).unwrap();
    assert!(
        text.starts_with("OK ") && text.contains("moving walls' work"),
        "{text}"
    );
}

#[test]
fn growing_runs_with_moving_walls_kinematic_bodies_and_own_restitution_verify() {
    // Growth with a piston and a paddle, a kinematic ball, bodies with their own restitution
    // and the TC model: recorded from the command line, `verify` accepts the run and rejects
    // it once a bounce off a moving wall is forged.
    let scene = format!(
        r#"{{"dim": 2, "walls": {walls},
        "settings": {{"growth": {{"rate": 0.05}}, "restitution": 0.95, "tc": 0.001}},
        "bodies": [
          {{"pos": [2, 2], "vel": [1, 0.5], "radius": 0.4, "restitution": 0.6}},
          {{"pos": [5, 3], "vel": [-0.5, 0.8], "radius": 0.5}},
          {{"pos": [8, 2], "vel": [-1, -0.3], "radius": 0.3, "kinematic": true}},
          {{"pos": [3, 4.5], "vel": [0.7, -0.9], "radius": 0.4, "restitution": 0.9}}
        ],
        "moving_walls": [
          {{"point": [0, 6], "normal": [0, -1], "velocity": [0, -0.2]}},
          {{"a": [0, 2.5], "b": [0, 3.5], "velocity": [0.4, 0]}}
        ]}}"#,
        walls = r#"[{"a": [0,0], "b": [10,0]}, {"a": [10,0], "b": [10,6]}, {"a": [10,6], "b": [0,6]}, {"a": [0,6], "b": [0,0]}]"#
    );
    let path = tmp("growing_combined.json");
    std::fs::write(&path, scene).unwrap();
    let rec = tmp("growing_combined.ccd");
    run_ok(
        ccdsim()
            .arg("run")
            .arg(&path)
            .args(["--until", "10", "--record"])
            .arg(&rec),
    );
    let out = run_ok(ccdsim().arg("verify").arg(&rec));
    let text = String::from_utf8(out.stdout).unwrap();
    assert!(text.starts_with("OK "), "{text}");

    // The first bounce off a moving wall (wall 4 or 5), its velocity scaled by 1.01.
    let mut bytes = std::fs::read(&rec).unwrap();
    let len = 21 + 32 * 2;
    let k = (data_start(&bytes)..bytes.len() - len + 1)
        .step_by(len)
        .find(|&at| bytes[at] & 0x3f == 2 && bytes[at + 5] >= 4)
        .expect("a moving wall is met");
    for d in 0..2 {
        let at = k + 17 + 16 + 8 * d;
        let v = f64::from_le_bytes(bytes[at..at + 8].try_into().unwrap()) * 1.01;
        bytes[at..at + 8].copy_from_slice(&v.to_le_bytes());
    }
    let sum = fnv1a(&bytes[k..k + len - 4]);
    bytes[k + len - 4..k + len].copy_from_slice(&sum.to_le_bytes());
    let forged = tmp("growing_combined_forged.ccd");
    std::fs::write(&forged, &bytes).unwrap();
    let out = ccdsim().arg("verify").arg(&forged).output().unwrap();
    let text = String::from_utf8(out.stdout).unwrap();
    assert_eq!(out.status.code(), Some(1), "{text}");
    assert!(
        text.contains("FAIL") && text.contains("growth rule"),
        "{text}"
    );
}

/// Numbers f64 cannot simulate are refused at the door, the field named: a segment end at
/// −1e308 once ran to "t = NaN", gravity of −9.81e200 was taken.
#[test]
fn magnitudes_beyond_f64_name_the_field() {
    let body = |extra: &str| format!(r#"{{"pos": [1, 1], "vel": [1, 0], "radius": 0.5{extra}}}"#);
    let good = body("");
    for (name, scene, culprit) in [
        (
            "far_wall",
            format!(
                r#"{{"dim": 2, "bodies": [{good}], "walls": [{{"a": [-1e308, 0], "b": [4, 0]}}]}}"#
            ),
            "walls[0].a",
        ),
        (
            "huge_gravity",
            format!(
                r#"{{"dim": 2, "settings": {{"gravity": [0, -9.81e200]}}, "bodies": [{good}], "walls": {TABLE}}}"#
            ),
            "settings.gravity",
        ),
        (
            "huge_speed",
            format!(
                r#"{{"dim": 2, "bodies": [{good}, {{"pos": [3, 1], "vel": [1e200, 0], "radius": 0.5}}]}}"#
            ),
            "bodies[1].vel",
        ),
        (
            "far_body",
            r#"{"dim": 2, "bodies": [{"pos": [1e120, 1], "vel": [0, 0], "radius": 1e110}]}"#
                .to_string(),
            "bodies[0].pos",
        ),
        (
            "tiny_radius",
            r#"{"dim": 2, "bodies": [{"pos": [0, 0], "vel": [1, 0], "radius": 1e-200}]}"#
                .to_string(),
            "bodies[0].radius",
        ),
        (
            "huge_mass",
            format!(
                r#"{{"dim": 2, "bodies": [{}]}}"#,
                body(r#", "mass": 1e200"#)
            ),
            "bodies[0].mass",
        ),
        (
            "huge_box",
            format!(r#"{{"dim": 2, "periodic": [1e200, 10], "bodies": [{good}]}}"#),
            "periodic",
        ),
    ] {
        refuse(name, &scene, culprit);
    }
}

#[test]
fn a_galton_board_from_gen_runs_records_verifies_and_draws_its_histogram() {
    let scene = tmp("galton.json");
    let out = run_ok(
        ccdsim()
            .args(["gen", "galton", "--balls", "6", "--rows", "3", "--out"])
            .arg(&scene),
    );
    let hint = String::from_utf8_lossy(&out.stderr);
    assert!(hint.contains("--until 11.25"), "{hint}");
    let mut files = Vec::new();
    for finder in ["all-pairs", "cells"] {
        let rec = tmp(&format!("galton-{finder}.ccd"));
        let out = run_ok(
            ccdsim()
                .arg("run")
                .arg(&scene)
                .args(["--until", "11.25", "--json", "--finder", finder, "--record"])
                .arg(&rec),
        );
        let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
        assert!(v["halt"].is_null(), "{v}");
        assert_eq!(v["arrivals"], 6, "{v}");
        assert!(v["arrival_energy"].as_f64().unwrap() > 0.0, "{v}");
        let counts: Vec<u64> = serde_json::from_value(v["histogram"]["counts"].clone()).unwrap();
        assert_eq!(counts.len(), 4, "{v}");
        assert_eq!(counts.iter().sum::<u64>(), 6, "{v}");
        assert_eq!(v["histogram"]["outside"], 0, "{v}");
        let out = run_ok(ccdsim().arg("verify").arg(&rec));
        assert!(
            String::from_utf8_lossy(&out.stdout).contains("6 edits adding"),
            "{}",
            String::from_utf8_lossy(&out.stdout)
        );
        files.push(std::fs::read(&rec).unwrap());
    }
    assert!(files[0] == files[1], "run files differ");
    let out = run_ok(ccdsim().arg("run").arg(&scene).args(["--until", "11.25"]));
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.contains("6 bodies arrived"), "{text}");
    assert!(
        text.contains("histogram along x: 6 bodies in 4 bins, 0 outside"),
        "{text}"
    );
    let out = ccdsim()
        .args(["gen", "galton", "--interval", "0.1"])
        .output()
        .unwrap();
    assert!(!out.status.success());
    assert!(
        String::from_utf8_lossy(&out.stderr).contains("at least 0.25 s"),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}
