//! `ccdsim pack`: compression to a jammed packing, end to end.

use crate::common;

use common::{ccdsim, run_ok};

/// Standard output of a command that must succeed.
fn stdout(cmd: &mut std::process::Command) -> String {
    String::from_utf8(run_ok(cmd).stdout).unwrap()
}

#[test]
fn packs_a_bidisperse_2d_mixture_and_writes_scene_and_xyz() {
    let prefix = common::scratch_file("pack", "bi2d");
    let out = stdout(
        ccdsim()
            .args([
                "pack",
                "--dim",
                "2",
                "--n",
                "200",
                "--bidisperse",
                "1.4",
                "--periodic",
            ])
            .args([
                "--rate",
                "0.02",
                "--until-pressure",
                "1e8",
                "--seed",
                "3",
                "--json",
            ])
            .arg("--out")
            .arg(&prefix),
    );
    let s: serde_json::Value = serde_json::from_str(out.trim()).unwrap();
    assert_eq!(s["stop"], "pressure");
    assert_eq!(s["bodies"], 200);
    assert!(s["reduced_pressure"].as_f64().unwrap() >= 1e8);
    let phi = s["packing_fraction"].as_f64().unwrap();
    assert!((0.8..0.87).contains(&phi), "{phi}");
    assert!(s["mean_contacts"].as_f64().unwrap() > 3.5, "{s}");
    // The scene reads back and runs; the XYZ frame holds every body with its radius.
    let scene = std::path::PathBuf::from(s["scene"].as_str().unwrap());
    let summary = stdout(
        ccdsim()
            .arg("run")
            .arg(&scene)
            .args(["--events", "2000", "--json"]),
    );
    let run: serde_json::Value = serde_json::from_str(summary.trim()).unwrap();
    assert_eq!(run["events"], 2000);
    assert!(run["max_overlap"].as_f64().unwrap() < 1e-9);
    let xyz = std::fs::read_to_string(s["xyz"].as_str().unwrap()).unwrap();
    let mut lines = xyz.lines();
    assert_eq!(lines.next(), Some("200"));
    assert!(lines.next().unwrap().contains("radius"));
    assert_eq!(lines.count(), 200);
}

#[test]
fn a_growing_scene_runs_records_and_verifies() {
    let prefix = common::scratch_file("pack", "grow");
    let scene = prefix.with_extension("json");
    let text = stdout(ccdsim().args([
        "gen",
        "gas",
        "--n",
        "300",
        "--packing",
        "0.3",
        "--periodic",
        "--temperature",
        "1",
    ]));
    let text = text.replacen(
        "\"settings\":{",
        "\"settings\":{\"growth\":{\"rate\":0.05},",
        1,
    );
    assert!(text.contains("growth"), "{text}");
    std::fs::write(&scene, text).unwrap();
    let rec = prefix.with_extension("ccd");
    run_ok(
        ccdsim()
            .arg("run")
            .arg(&scene)
            .args(["--until", "5", "--quiet", "--record"])
            .arg(&rec),
    );
    let out = stdout(ccdsim().arg("verify").arg(&rec));
    assert!(out.starts_with("OK"), "{out}");
}

#[test]
fn bad_pack_settings_are_refused() {
    for (args, culprit) in [
        (vec!["--rate", "0"], "growth rate"),
        (vec!["--until-pressure", "0.5"], "pressure"),
        (vec!["--bidisperse", "0.5"], "bidisperse"),
        (vec!["--polydisperse", "2"], "polydisperse"),
        (vec!["--n", "0"], "--n"),
        (vec!["--isostatic", "--overlap", "0.5"], "overlap"),
        (vec!["--overlap", "1e-6"], "--isostatic"),
    ] {
        let out = ccdsim()
            .args(["pack", "--dim", "2", "--n", "20", "--periodic"])
            .args(&args)
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert!(err.contains(culprit), "{args:?}: {err}");
    }
}

#[test]
fn an_isostatic_packing_is_rigid_and_says_so() {
    let prefix = common::scratch_file("pack", "iso3d");
    let args = [
        "pack",
        "--dim",
        "3",
        "--n",
        "200",
        "--periodic",
        "--rate",
        "0.05",
    ];
    let out = stdout(
        ccdsim()
            .args(args)
            .args(["--isostatic", "--json", "--out"])
            .arg(&prefix),
    );
    let s: serde_json::Value = serde_json::from_str(out.trim()).unwrap();
    assert_eq!(s["rigid"], true, "{s}");
    let held = s["held_contacts"].as_u64().unwrap();
    assert!(held >= s["isostatic_contacts"].as_u64().unwrap(), "{s}");
    assert!(s["mean_contacts"].as_f64().unwrap() >= 5.95, "{s}");
    assert!(s["finish"]["mean_overlap"].as_f64().unwrap() <= 1e-6, "{s}");
    // Compression stopped at 10^4 before the finish.
    assert!(s["reduced_pressure"].as_f64().unwrap() < 1e5, "{s}");
    // Compression alone, even to 10^12, freezes before the contacts can hold the packing,
    // and the summary says so.
    let plain = stdout(ccdsim().args(args).arg("--out").arg(&prefix));
    assert!(plain.contains("NOT RIGID"), "{plain}");
}
