//! `ccdsim run --frames DT --trajectory F`: frames at fixed times, clear refusals, no partial
//! output. (The Python suite reads the files back with ASE and the gsd package.)

use crate::common;

use common::{ccdsim, run_ok, scratch_dir};

#[test]
fn frames_are_written_at_every_sample_time() {
    let dir = scratch_dir("trajectory", "frames");
    let xyz = dir.join("break.xyz");
    let out = run_ok(
        ccdsim()
            .args(["run", "--until", "2", "--frames", "0.25", "--json"])
            .arg("--trajectory")
            .arg(&xyz),
    );
    let summary: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(summary["frames"], 9, "{summary}");
    let text = std::fs::read_to_string(&xyz).unwrap();
    let times: Vec<&str> = text
        .lines()
        .filter_map(|l| l.split("Time=").nth(1))
        .map(|t| t.split(' ').next().unwrap())
        .collect();
    assert_eq!(
        times,
        ["0.0", "0.25", "0.5", "0.75", "1.0", "1.25", "1.5", "1.75", "2.0"]
    );
    // The billiard break: 16 balls per frame, walls' bounding box, not periodic.
    assert_eq!(text.lines().count(), 9 * 18);
    assert!(text.lines().nth(1).unwrap().ends_with("pbc=\"F F F\""));
    let gsd = dir.join("break.gsd");
    run_ok(
        ccdsim()
            .args(["run", "--until", "2", "--frames", "0.25"])
            .arg("--trajectory")
            .arg(&gsd),
    );
    assert_eq!(
        &std::fs::read(&gsd).unwrap()[..8],
        &[0xdf, 0x65, 0xdf, 0x65, 0xdf, 0x65, 0xdf, 0x65]
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn bad_requests_are_refused_without_output() {
    let dir = scratch_dir("trajectory", "bad");
    let record = dir.join("run.ccd");
    for (args, message) in [
        (vec!["--frames", "0", "--trajectory", "t.xyz"], "positive"),
        (vec!["--frames", "-1", "--trajectory", "t.xyz"], "positive"),
        (
            vec!["--frames", "0.1", "--trajectory", "t.pdb"],
            "trajectory format",
        ),
        (
            vec!["--frames", "0.1", "--trajectory", "no/such/dir/t.xyz"],
            "t.xyz",
        ),
        (vec!["--frames", "0.1"], "--trajectory"),
        (vec!["--trajectory", "t.xyz"], "--frames"),
    ] {
        let args: Vec<String> = args
            .iter()
            .map(|a| {
                if a.contains("t.") {
                    dir.join(a).display().to_string()
                } else {
                    a.to_string()
                }
            })
            .collect();
        let out = ccdsim()
            .args(["run", "--until", "1", "--record"])
            .arg(&record)
            .args(&args)
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert!(err.contains(message), "{args:?}: {err}");
        assert!(!record.exists(), "{args:?} left a run file");
        assert!(
            std::fs::read_dir(&dir).unwrap().next().is_none(),
            "{args:?} left a file"
        );
    }
    std::fs::remove_dir_all(&dir).unwrap();
}
