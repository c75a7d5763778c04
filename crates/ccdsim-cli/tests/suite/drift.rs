//! `run` and `verify` print one relative energy drift, the library's
//! (`ccdsim::observables::EnergyBalance`), for the same run: elastic or not, under gravity or
//! not.

use crate::common;

use common::{ccdsim, run_ok};

/// The number after "relative drift " in `text` (exactly one such).
fn drift_in(text: &str) -> String {
    let parts: Vec<&str> = text.split("relative drift ").collect();
    assert_eq!(parts.len(), 2, "one relative drift expected in: {text}");
    parts[1]
        .split(|c: char| c == ')' || c.is_whitespace() || c == ';')
        .next()
        .unwrap()
        .to_string()
}

/// Runs `scene` until `until` (summary and `--json`), records it, verifies the record, and
/// returns the drift as both print it and as `--json` gives it.
fn drifts(dir: &std::path::Path, name: &str, until: &str) -> (String, String, f64) {
    let scene = dir.join(format!("{name}.json"));
    let run = dir.join(format!("{name}.ccd"));
    let summary = run_ok(
        ccdsim()
            .arg("run")
            .arg(&scene)
            .args(["--quiet", "--until", until, "--record"])
            .arg(&run),
    );
    let json = run_ok(
        ccdsim()
            .arg("run")
            .arg(&scene)
            .args(["--json", "--until", until]),
    );
    let v: serde_json::Value = serde_json::from_slice(&json.stdout).unwrap();
    let verified = run_ok(ccdsim().arg("verify").arg(&run).arg("--quiet"));
    (
        drift_in(&String::from_utf8_lossy(&summary.stdout)),
        drift_in(&String::from_utf8_lossy(&verified.stdout)),
        v["energy_drift"].as_f64().unwrap(),
    )
}

#[test]
fn run_and_verify_print_the_same_drift_for_inelastic_runs() {
    let dir = common::scratch_dir("drift", "inelastic");
    // An inelastic gas without gravity: the drift is the fraction of kinetic energy lost.
    let gas = run_ok(ccdsim().args(["gen", "gas", "--n", "60", "--packing", "0.2"]));
    let mut scene: serde_json::Value = serde_json::from_slice(&gas.stdout).unwrap();
    scene["settings"] = serde_json::json!({"restitution": 0.8});
    std::fs::write(dir.join("gas.json"), scene.to_string()).unwrap();
    let (run, verify, json) = drifts(&dir, "gas", "5");
    assert_eq!(run, verify);
    assert!(json < -0.05, "energy is lost: {json}");
    let printed: f64 = run.parse().unwrap();
    assert!(
        (printed - json).abs() <= 0.01 * json.abs(),
        "{printed} vs {json}"
    );
    // A peg board under gravity, restitution 0.5: kinetic energy grows as the balls fall,
    // the total shrinks; one drift, of the total, in both.
    run_ok(
        ccdsim()
            .args([
                "gen",
                "pegs",
                "--restitution",
                "0.5",
                "--balls",
                "12",
                "--out",
            ])
            .arg(dir.join("pegs.json")),
    );
    let (run, verify, json) = drifts(&dir, "pegs", "3");
    assert_eq!(run, verify);
    assert!(json < 0.0, "energy is lost: {json}");
}
