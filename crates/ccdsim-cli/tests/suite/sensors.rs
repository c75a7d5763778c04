//! A Galton board through the command line: `gen pegs --bins`, `run --sensor-log`.

use crate::common;

use common::{ccdsim, run_ok, scratch_dir};

#[test]
fn a_galton_board_counts_its_bins_and_logs_every_sensor_event() {
    let dir = scratch_dir("sensors", "galton");
    let scene = dir.join("galton.json");
    run_ok(
        ccdsim()
            .args(["gen", "pegs", "--rows", "4", "--balls", "32", "--bins", "4"])
            .args(["--restitution", "0.5", "--out"])
            .arg(&scene),
    );
    let log = dir.join("bins.jsonl");
    let out = run_ok(
        ccdsim()
            .arg("run")
            .arg(&scene)
            .args(["--until", "8", "--json", "--quiet", "--sensor-log"])
            .arg(&log),
    );
    let summary: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let sensors = summary["sensors"].as_array().unwrap();
    assert_eq!(sensors.len(), 4);
    // Balls on the floor lie in exactly one bin each (those that came to rest on top of
    // others stand above the bins): most of the 32, never more.
    let inside: u64 = sensors.iter().map(|s| s["inside"].as_u64().unwrap()).sum();
    assert!((24..=32).contains(&inside), "{sensors:?}");
    // The log holds every enter and leave the counts add up, in time order.
    let text = std::fs::read_to_string(&log).unwrap();
    let lines: Vec<serde_json::Value> = text
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    let count = |k: usize, change: &str| {
        lines
            .iter()
            .filter(|e| e["sensor"] == k && e["change"] == change)
            .count() as u64
    };
    for (k, s) in sensors.iter().enumerate() {
        assert_eq!(count(k, "enter"), s["enters"].as_u64().unwrap());
        assert_eq!(count(k, "leave"), s["leaves"].as_u64().unwrap());
    }
    let times: Vec<f64> = lines.iter().map(|e| e["t"].as_f64().unwrap()).collect();
    assert!(times.windows(2).all(|w| w[0] <= w[1]));
    // The readable summary names the bins.
    let out = run_ok(
        ccdsim()
            .arg("run")
            .arg(&scene)
            .args(["--until", "2", "--quiet"]),
    );
    let text = String::from_utf8(out.stdout).unwrap();
    assert!(text.contains("sensor 3: "), "{text}");
}

#[test]
fn a_sensor_log_without_sensors_is_refused_before_any_file_is_written() {
    let dir = scratch_dir("sensors", "refused");
    let record = dir.join("run.ccd");
    let out = ccdsim()
        .args(["run", "--until", "1", "--quiet", "--sensor-log"])
        .arg(dir.join("log.jsonl"))
        .arg("--record")
        .arg(&record)
        .output()
        .unwrap();
    assert!(!out.status.success());
    let err = String::from_utf8(out.stderr).unwrap();
    assert!(err.contains("no sensors"), "{err}");
    assert!(!record.exists() && !dir.join("log.jsonl").exists());
}
