//! `ccdsim gen table` and `ccdsim run` on the pool scene it writes.

use crate::common;

use common::{ccdsim, run_ok};

#[test]
fn gen_table_writes_a_break_that_run_plays_to_the_end() {
    let scene = common::scratch_file("pool", "break.json");
    run_ok(ccdsim().args(["gen", "table", "--out"]).arg(&scene));
    let v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&scene).unwrap()).unwrap();
    assert_eq!(v["pool"]["balls"].as_array().unwrap().len(), 10);
    assert_eq!(v["pool"]["shot"]["ball"], "cue");
    let out = run_ok(ccdsim().arg("run").arg(&scene).arg("--json"));
    let summary: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert!(summary["ball_ball"].as_u64().unwrap() >= 9, "{summary}");
    assert_eq!(summary["positions"].as_array().unwrap().len(), 10);
    let text = String::from_utf8(run_ok(ccdsim().arg("run").arg(&scene)).stdout).unwrap();
    assert!(text.starts_with("pool shot: 10 balls,"), "{text}");
    assert!(text.contains("pocketed:"), "{text}");

    // An eight-ball rack and a shot of one's own.
    let out = run_ok(ccdsim().args([
        "gen",
        "table",
        "--game",
        "eight-ball",
        "--shot",
        "2,90,0,0,0.3",
    ]));
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["pool"]["balls"].as_array().unwrap().len(), 16);
    assert_eq!(v["pool"]["shot"]["b"], 0.3);
    assert!(v["pool"].get("ball_ball").is_none());

    // The frictional ball-ball model: the scene says so, and the break plays differently.
    let frictional = common::scratch_file("pool", "frictional.json");
    run_ok(
        ccdsim()
            .args(["gen", "table", "--frictional", "--out"])
            .arg(&frictional),
    );
    let v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&frictional).unwrap()).unwrap();
    assert_eq!(
        v["pool"]["ball_ball"],
        serde_json::json!({"restitution": 0.95})
    );
    let out = run_ok(ccdsim().arg("run").arg(&frictional).arg("--json"));
    let other: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_ne!(other["positions"], summary["positions"]);
}

#[test]
fn pool_scenes_refuse_what_they_cannot_do_with_the_reason() {
    let scene = common::scratch_file("pool-bad", "break.json");
    run_ok(ccdsim().args(["gen", "table", "--out"]).arg(&scene));
    let out = ccdsim()
        .arg("run")
        .arg(&scene)
        .args(["--frames", "0.1", "--trajectory", "x.xyz"])
        .output()
        .unwrap();
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("--frames is not available"));
    for bad in ["1,2,3", "1,90,0,2,2"] {
        let out = ccdsim()
            .args(["gen", "table", "--shot", bad])
            .output()
            .unwrap();
        assert!(!out.status.success(), "--shot {bad}");
        assert!(String::from_utf8_lossy(&out.stderr).contains("--shot"));
    }
    // A ball off the table, in a scene written by hand.
    std::fs::write(
        &scene,
        r#"{"pool": {"balls": [{"name": "cue", "pos": [5, 0.5]}], "shot": {"ball": "cue", "speed": 1, "phi": 0}}}"#,
    )
    .unwrap();
    let out = ccdsim().arg("run").arg(&scene).output().unwrap();
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("not on the table"));
}

#[test]
fn a_recorded_shot_verifies_exports_and_fails_when_tampered_with() {
    let scene = common::scratch_file("pool-record", "break.json");
    let run = common::scratch_file("pool-record", "break.ccd");
    run_ok(ccdsim().args(["gen", "table", "--out"]).arg(&scene));
    let out = run_ok(
        ccdsim()
            .arg("run")
            .arg(&scene)
            .arg("--record")
            .arg(&run)
            .arg("--json"),
    );
    let summary: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let events = summary["events"].as_u64().unwrap();
    assert_eq!(summary["record"], run.display().to_string());
    let text = String::from_utf8(run_ok(ccdsim().arg("verify").arg(&run)).stdout).unwrap();
    assert!(
        text.starts_with("OK ") && text.contains(&format!("pool shot, {events} events")),
        "{text}"
    );
    assert!(text.contains("every ball at rest or pocketed"), "{text}");

    // JSON Lines: the header, the strike, every event, the end.
    let lines = String::from_utf8(run_ok(ccdsim().arg("export").arg(&run)).stdout).unwrap();
    let lines: Vec<serde_json::Value> = lines
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    assert_eq!(lines.len() as u64, events + 3);
    assert_eq!(lines[0]["version"], 16);
    assert_eq!(lines[1]["type"], "strike");
    assert_eq!(lines.last().unwrap()["type"], "end");
    assert_eq!(lines[2]["type"], "ball_ball");

    // Every finder, the oracle's search (every prediction afresh) first, writes the same file,
    // byte for byte.
    for finder in ["all-pairs", "sedgewick", "cells", "bvh"] {
        let other = common::scratch_file("pool-record", &format!("{finder}.ccd"));
        run_ok(
            ccdsim()
                .arg("run")
                .arg(&scene)
                .args(["--finder", finder, "--record"])
                .arg(&other),
        );
        assert_eq!(
            std::fs::read(&other).unwrap(),
            std::fs::read(&run).unwrap(),
            "{finder}"
        );
    }
    for (flags, says) in [
        (
            &["--finder", "grid"][..],
            "all-pairs, sedgewick, cells, bvh",
        ),
        (&["--bvh-grow", "2"][..], "finder options"),
    ] {
        let out = ccdsim()
            .arg("run")
            .arg(&scene)
            .args(flags)
            .output()
            .unwrap();
        assert!(!out.status.success());
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(stderr.contains(says), "{stderr}");
    }

    // A record whose time moved (checksum made good): the physics fails, status 1.
    let bytes = std::fs::read(&run).unwrap();
    let header = u64::from_le_bytes(bytes[16..24].try_into().unwrap()) as usize;
    let at = 24 + header + 3 * ccdsim::billiards::run_file::POOL_RECORD_LEN;
    let mut moved = bytes.clone();
    let t = f64::from_le_bytes(moved[at + 9..at + 17].try_into().unwrap());
    moved[at + 9..at + 17].copy_from_slice(&(t + 1e-4).to_le_bytes());
    let end = at + ccdsim::billiards::run_file::POOL_RECORD_LEN - 4;
    let sum = fnv1a(&moved[at..end]);
    moved[end..end + 4].copy_from_slice(&sum.to_le_bytes());
    let bad = common::scratch_file("pool-record", "moved.ccd");
    std::fs::write(&bad, &moved).unwrap();
    let out = ccdsim().arg("verify").arg(&bad).output().unwrap();
    assert_eq!(out.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&out.stdout).starts_with("FAIL "));
    // A flipped byte in the middle: the reader refuses it, status 2.
    let mut flipped = bytes;
    flipped[at + 30] ^= 0x10;
    std::fs::write(&bad, &flipped).unwrap();
    let out = ccdsim().arg("verify").arg(&bad).output().unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("record 3 is corrupt"));
}

fn fnv1a(bytes: &[u8]) -> u32 {
    let mut h: u32 = 0x811c_9dc5;
    for &b in bytes {
        h ^= u32::from(b);
        h = h.wrapping_mul(0x0100_0193);
    }
    h
}
