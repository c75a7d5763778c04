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
        .args(["--record", "x.ccd"])
        .output()
        .unwrap();
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("--record is not available"));
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
