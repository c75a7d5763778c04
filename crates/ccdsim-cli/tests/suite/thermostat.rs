//! A thermostatted scene through the command line: run, record, verify, export.

use crate::common;

use common::{ccdsim, run_ok, scratch_dir};

#[test]
fn a_thermostatted_run_records_verifies_and_exports_its_resets() {
    let dir = scratch_dir("thermostat", "run");
    let scene = dir.join("gas.json");
    run_ok(
        ccdsim()
            .args([
                "gen",
                "gas",
                "--n",
                "100",
                "--packing",
                "0.3",
                "--periodic",
                "--seed",
                "2",
                "--out",
            ])
            .arg(&scene),
    );
    let mut json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&scene).unwrap()).unwrap();
    json["settings"]["thermostat"] =
        serde_json::json!({"temperature": 1.5, "rate": 0.5, "seed": 4});
    std::fs::write(&scene, json.to_string()).unwrap();

    let record = dir.join("gas.ccd");
    let out = run_ok(
        ccdsim()
            .arg("run")
            .arg(&scene)
            .args(["--until", "10", "--json", "--record"])
            .arg(&record),
    );
    let summary: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let resets = summary["resets"].as_u64().unwrap();
    assert!(resets > 300, "{summary}");
    assert_eq!(
        summary["events"].as_u64().unwrap(),
        summary["body_collisions"].as_u64().unwrap() + resets
    );
    let out = run_ok(ccdsim().arg("verify").arg(&record));
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        text.contains(&format!("{resets} thermostat resets")),
        "{text}"
    );
    let out = run_ok(
        ccdsim()
            .arg("export")
            .arg(&record)
            .args(["--format", "jsonl"]),
    );
    let text = String::from_utf8_lossy(&out.stdout);
    assert_eq!(
        text.lines()
            .filter(|l| l.contains("\"kind\":\"reset\""))
            .count() as u64,
        resets
    );

    // A bad thermostat is refused like any bad field.
    json["settings"]["thermostat"]["rate"] = serde_json::json!(0.0);
    std::fs::write(&scene, json.to_string()).unwrap();
    let out = ccdsim().arg("run").arg(&scene).output().unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("settings.thermostat.rate"));
    std::fs::remove_dir_all(&dir).unwrap();
}
