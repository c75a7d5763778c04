//! `ccdsim gen thesis` and `ccdsim bench` end to end, on sizes small enough for a test.

use crate::common;

use common::{ccdsim, run_ok};

/// An output directory that does not exist yet: the commands must create it.
fn tmp_dir(name: &str) -> common::ScratchFile {
    common::scratch_file(&format!("bench-cli-{name}"), "out")
}

#[test]
fn gen_thesis_writes_a_valid_scene_of_either_dimension() {
    let out = run_ok(ccdsim().args(["gen", "thesis", "--n", "50", "--seed", "3"]));
    let scene = ccdsim::AnyScene::from_json(&String::from_utf8(out.stdout).unwrap()).unwrap();
    let ccdsim::AnyScene::D2(s) = scene else {
        panic!("expected a 2D scene")
    };
    assert_eq!((s.bodies.len(), s.walls.len()), (50, 4));
    s.validate().unwrap();
    let out = run_ok(ccdsim().args(["gen", "thesis", "--n", "20", "--dim", "3"]));
    let scene = ccdsim::AnyScene::from_json(&String::from_utf8(out.stdout).unwrap()).unwrap();
    let ccdsim::AnyScene::D3(s) = scene else {
        panic!("expected a 3D scene")
    };
    assert_eq!((s.bodies.len(), s.walls.len()), (20, 6));
}

#[test]
fn bench_thesis_prints_the_table_and_writes_csv_json_and_plots() {
    let dir = tmp_dir("thesis");
    let out = run_ok(
        ccdsim()
            .args([
                "bench", "thesis", "--sizes", "8,16,32", "--runs", "2", "--quiet",
            ])
            .args(["--finders", "all-pairs,sedgewick", "--out"])
            .arg(&dir),
    );
    let text = String::from_utf8(out.stdout).unwrap();
    assert!(
        text.contains("all-pairs s") && text.contains("sedgewick s"),
        "{text}"
    );
    assert!(
        text.contains("213.2"),
        "the thesis's counts are shown: {text}"
    );
    let csv = std::fs::read_to_string(dir.join("thesis.csv")).unwrap();
    assert_eq!(csv.lines().count(), 1 + 3 * 2);
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("thesis.json")).unwrap()).unwrap();
    assert_eq!(json["cells"].as_array().unwrap().len(), 6);
    let png = std::fs::read(dir.join("thesis.png")).unwrap();
    assert_eq!(&png[..4], b"\x89PNG");
    let svg = std::fs::read_to_string(dir.join("thesis.svg")).unwrap();
    assert!(svg.contains("<svg") && svg.contains("sedgewick"));
}

#[test]
fn bench_discrete_lists_the_exact_row_first() {
    let dir = tmp_dir("discrete");
    let out = run_ok(
        ccdsim()
            .args([
                "bench", "discrete", "--n", "64", "--dt", "0.01,0.5", "--runs", "1",
            ])
            .args([
                "--duration",
                "1",
                "--finder",
                "sedgewick",
                "--quiet",
                "--out",
            ])
            .arg(&dir),
    );
    let text = String::from_utf8(out.stdout).unwrap();
    let rows: Vec<&str> = text
        .lines()
        .filter(|l| l.starts_with("continuous") || l.starts_with("discrete"))
        .collect();
    assert_eq!(rows.len(), 3, "{text}");
    assert!(rows[0].starts_with("continuous (sedgewick)"), "{text}");
    assert!(rows[1].starts_with("discrete (dt = 0.01)"), "{text}");
    assert!(rows[2].starts_with("discrete (dt = 0.5)"), "{text}");
    let csv = std::fs::read_to_string(dir.join("discrete.csv")).unwrap();
    assert_eq!(csv.lines().count(), 4);
}

#[test]
fn bench_refuses_bad_arguments() {
    for args in [
        vec!["bench", "thesis", "--finders", "nope", "--sizes", "8"],
        vec!["bench", "thesis", "--sizes", "16,8"],
        vec!["bench", "discrete", "--dt", "0"],
    ] {
        let out = ccdsim().args(&args).arg("--quiet").output().unwrap();
        assert_eq!(out.status.code(), Some(2), "{args:?}");
        assert_eq!(String::from_utf8(out.stderr).unwrap().lines().count(), 1);
    }
}

#[test]
fn rough_gases_run_verify_and_cool_as_the_bench_reports() {
    let dir = tmp_dir("rough");
    std::fs::create_dir_all(&dir).unwrap();
    let scene = dir.join("rough.json");
    run_ok(
        ccdsim()
            .args(["gen", "gas", "--dim", "3", "--n", "200", "--packing", "0.1"])
            .args(["--periodic", "--temperature", "1", "--restitution", "0.9"])
            .args(["--tangential-restitution", "0.5", "--tc", "1e-4", "--out"])
            .arg(&scene),
    );
    let record = dir.join("rough.ccd");
    let out = run_ok(
        ccdsim()
            .arg("run")
            .arg(&scene)
            .args(["--events", "5000", "--json", "--quiet", "--record"])
            .arg(&record),
    );
    let summary: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let rotational = summary["rotational_temperature"].as_f64().unwrap();
    assert!(rotational > 0.0 && summary["energy_drift"].as_f64().unwrap() < 0.0);
    let out = run_ok(ccdsim().arg("verify").arg(&record));
    assert!(String::from_utf8(out.stdout).unwrap().starts_with("OK"));
    // The cooling check, small: its table, samples and plot.
    let out = run_ok(
        ccdsim()
            .args([
                "bench",
                "rough-cooling",
                "--n",
                "300",
                "--restitution",
                "0.9",
            ])
            .args(["--tangential-restitution=-1,1", "--settle", "3"])
            .args(["--collisions-per-body", "3", "--quiet", "--out"])
            .arg(&dir),
    );
    let text = String::from_utf8(out.stdout).unwrap();
    assert!(
        text.contains("| 0.9 | 1 |") && text.contains("| 0.9 | -1 |"),
        "{text}"
    );
    let csv = std::fs::read_to_string(dir.join("rough_cooling.csv")).unwrap();
    assert!(csv.starts_with("e,beta,collisions_per_body,time,temperature,rotational_temperature"));
    let svg = std::fs::read_to_string(dir.join("rough_cooling.svg")).unwrap();
    assert!(svg.contains("<svg") && svg.contains("e = 0.9"));
}

#[test]
fn bench_pool_break_plays_a_rack_and_a_layout_beside_pooltools_events() {
    // ccdsim's own 9-ball rack: every ball ends still, and the report adds up.
    let out = run_ok(ccdsim().args(["bench", "pool-break", "--runs", "3", "--json"]));
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let events = v["events"].as_u64().unwrap();
    assert!(events > 20, "{v}");
    assert_eq!(v["event_list"].as_array().unwrap().len() as u64, events);
    assert!(v["breaks_per_second"].as_f64().unwrap() > 0.0);
    assert!(
        v["ball_ball"].as_u64().unwrap() >= 9,
        "the break reaches every ball: {v}"
    );
    assert_eq!(v["finder"], "cells");
    // Another finder plays the same events.
    let out = run_ok(ccdsim().args([
        "bench",
        "pool-break",
        "--runs",
        "1",
        "--json",
        "--finder",
        "sedgewick",
    ]));
    let w: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(
        (&w["finder"], &w["event_list"]),
        (&"sedgewick".into(), &v["event_list"])
    );

    // A layout with pooltool's events: one of the reference shots of the library's tests
    // (the cue ball onto one object ball), with a made-up pooltool time.
    let reference: serde_json::Value = serde_json::from_str(include_str!(
        "../../../ccdsim/tests/data/pooltool-shots.json"
    ))
    .unwrap();
    let shot = &reference["shots"][50];
    let layout = serde_json::json!({
        "balls": shot["balls"],
        "strike": shot["strike"],
        "pooltool": {"median_seconds": 0.1, "events": shot["events"]},
    });
    let file = common::scratch_file("bench-cli-pool", "layout.json");
    std::fs::write(&file, layout.to_string()).unwrap();
    let out = run_ok(
        ccdsim()
            .args(["bench", "pool-break", "--runs", "2", "--layout"])
            .arg(&file),
    );
    let text = String::from_utf8(out.stdout).unwrap();
    let n = shot["events"].as_array().unwrap().len();
    assert!(
        text.contains(&format!(
            "the same {n} events as pooltool, in the same order"
        )),
        "{text}"
    );
    assert!(
        text.contains("pooltool: median 100.0 ms per break"),
        "{text}"
    );

    // A layout whose balls overlap is refused with the reason.
    std::fs::write(
        &file,
        r#"{"balls": {"cue": [0.5, 0.5], "1": [0.51, 0.5]}, "strike": {"V0": 1, "phi": 0, "theta": 0, "a": 0, "b": 0}}"#,
    )
    .unwrap();
    let out = ccdsim()
        .args(["bench", "pool-break", "--layout"])
        .arg(&file)
        .output()
        .unwrap();
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("overlap"));
}
