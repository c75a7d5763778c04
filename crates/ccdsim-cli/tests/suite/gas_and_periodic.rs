//! `ccdsim bench gas`, `gen gas --periodic --lattice --temperature` and the observables of
//! `run --json`, end to end.

use crate::common;

use common::{ccdsim, run_ok};
use std::process::Output;

fn tmp(name: &str) -> common::ScratchFile {
    common::scratch_file("gas", name)
}

fn json(out: &Output) -> serde_json::Value {
    serde_json::from_slice(&out.stdout).unwrap()
}

#[test]
fn bench_gas_reports_speed_memory_and_the_equation_of_state() {
    let dir = tmp("bench");
    let out = run_ok(ccdsim().args([
        "bench",
        "gas",
        "--n",
        "400",
        "--packing",
        "0.3",
        "--collisions",
        "60000",
        "--json",
        "-q",
        "--out",
        dir.to_str().unwrap(),
    ]));
    let v = json(&out);
    assert_eq!(v["collisions"], 60000);
    assert_eq!(v["dim"], 2);
    assert!(v["collisions_per_second"].as_f64().unwrap() > 0.0);
    let z = v["compressibility"].as_f64().unwrap();
    let eos = v["compressibility_eos"].as_f64().unwrap();
    assert!((z / eos - 1.0).abs() < 0.05, "Z = {z}, EOS {eos}");
    assert!(v["compressibility_error"].as_f64().unwrap() > 0.0);
    if cfg!(target_os = "linux") {
        assert!(v["bytes_per_body"].as_f64().unwrap() > 0.0);
    }
    assert!(dir.join("gas.json").exists());
    let out = run_ok(ccdsim().args([
        "bench",
        "gas",
        "--dim",
        "3",
        "--n",
        "256",
        "--packing",
        "0.3",
        "--collisions",
        "20000",
        "-q",
        "--out",
        dir.to_str().unwrap(),
    ]));
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.contains("Carnahan-Starling"), "{text}");
    assert!(text.contains("collisions/s"), "{text}");
}

#[test]
fn periodic_lattice_gas_runs_identically_with_every_finder() {
    let scene = tmp("periodic.json");
    let gen = run_ok(ccdsim().args([
        "gen",
        "gas",
        "--n",
        "300",
        "--packing",
        "0.5",
        "--periodic",
        "--lattice",
        "--temperature",
        "1",
    ]));
    std::fs::write(&scene, &gen.stdout).unwrap();
    let text = String::from_utf8_lossy(&gen.stdout);
    assert!(text.contains("\"periodic\""), "{text}");
    let mut files = Vec::new();
    for finder in ["cells", "all-pairs", "bvh", "sedgewick"] {
        let rec = tmp(&format!("periodic-{finder}.ccd"));
        let out = run_ok(ccdsim().args([
            "run",
            scene.to_str().unwrap(),
            "--finder",
            finder,
            "--events",
            "3000",
            "--record",
            rec.to_str().unwrap(),
            "--json",
            "-q",
        ]));
        let v = json(&out);
        assert_eq!(v["events"], 3000);
        assert!((v["temperature"].as_f64().unwrap() - 1.0).abs() < 1e-9);
        assert!(v["collision_rate"].as_f64().unwrap() > 0.0);
        assert!(v["pressure"].as_f64().unwrap() > 0.0);
        assert!(v["compressibility"].as_f64().unwrap() > 1.0);
        if finder == "cells" {
            // Internal work is reported apart from events: 3000 events, and the grid's
            // crossings and rescans counted on their own.
            let counters = v["finder_counters"].as_object().unwrap();
            assert!(counters["crossings"].as_u64().unwrap() > 0, "{counters:?}");
            assert!(
                counters["recomputes"].as_u64().unwrap() >= 3000,
                "{counters:?}"
            );
        }
        files.push(std::fs::read(&rec).unwrap());
        run_ok(ccdsim().args(["verify", rec.to_str().unwrap()]));
    }
    for (k, file) in files.iter().enumerate().skip(1) {
        assert!(*file == files[0], "run file {k} differs from cells'");
    }
}

#[test]
fn open_scene_has_no_pressure() {
    let scene = tmp("two.json");
    std::fs::write(
        &scene,
        r#"{"dim": 2, "bodies": [{"pos": [0, 0], "vel": [1, 0], "radius": 0.5}, {"pos": [3, 0], "vel": [-1, 0], "radius": 0.5}]}"#,
    )
    .unwrap();
    let v = json(&run_ok(ccdsim().args([
        "run",
        scene.to_str().unwrap(),
        "--finder",
        "cells",
        "--until",
        "5",
        "--json",
        "-q",
    ])));
    assert_eq!(v["body_collisions"], 1);
    assert!(v["pressure"].is_null() && v["compressibility"].is_null());
    assert!(v["temperature"].as_f64().unwrap() > 0.0);
}

/// A sheared box end to end: `gen gas --shear-rate` starts the gas in the flow, `run --json`
/// reports the shear stress and viscosity (a positive rate gives positive ones), the run file
/// verifies, `bvh` gives the same run, and a shear without a periodic box is refused by name.
#[test]
fn a_sheared_box_reports_its_viscosity_and_verifies() {
    let scene = tmp("sheared.json");
    let record = tmp("sheared.ccd");
    run_ok(
        ccdsim()
            .args([
                "gen",
                "gas",
                "--dim",
                "3",
                "--n",
                "500",
                "--packing",
                "0.15",
            ])
            .args([
                "--periodic",
                "--temperature",
                "1",
                "--shear-rate",
                "0.3",
                "--out",
                scene.to_str().unwrap(),
            ]),
    );
    let written: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&scene).unwrap()).unwrap();
    assert_eq!(written["settings"]["shear_rate"], 0.3);
    let out = run_ok(ccdsim().args([
        "run",
        scene.to_str().unwrap(),
        "--events",
        "20000",
        "--record",
        record.to_str().unwrap(),
        "--json",
        "-q",
    ]));
    let v = json(&out);
    let stress = v["shear_stress"].as_f64().unwrap();
    let eta = v["viscosity"].as_f64().unwrap();
    assert!(
        stress > 0.0 && (eta - stress / 0.3).abs() < 1e-12 * eta,
        "{v}"
    );
    // The profile follows the imposed flow 0.3 (y − L/2) within the noise of 500 spheres.
    let l = written["periodic"][1].as_f64().unwrap();
    let profile = v["velocity_profile"].as_array().unwrap();
    assert_eq!(profile.len(), 10);
    for slab in profile {
        let (y, vx) = (slab[0].as_f64().unwrap(), slab[1].as_f64().unwrap());
        assert!((vx - 0.3 * (y - l / 2.0)).abs() < 0.5, "{slab} in {v}");
    }
    assert!(
        v["temperature"].as_f64().unwrap() < 2.0,
        "peculiar, not lab: {v}"
    );
    let out = run_ok(ccdsim().args(["verify", record.to_str().unwrap()]));
    assert!(
        String::from_utf8_lossy(&out.stdout).contains("OK"),
        "{out:?}"
    );
    // Every finder gives the same run.
    let bvh = run_ok(ccdsim().args([
        "run",
        scene.to_str().unwrap(),
        "--events",
        "20000",
        "--finder",
        "bvh",
        "--json",
        "-q",
    ]));
    assert_eq!(json(&bvh)["viscosity"], v["viscosity"]);
    let out = ccdsim()
        .args(["gen", "gas", "--n", "50", "--shear-rate", "1"])
        .output()
        .unwrap();
    assert!(!out.status.success());
    assert!(
        String::from_utf8_lossy(&out.stderr).contains("settings.shear_rate"),
        "{out:?}"
    );
}
