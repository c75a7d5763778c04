//! Records a run where balls come to rest on planes and slide along them (`settings.rest_speed`,
//! a steered run file of format version 11) and prints what it did as JSON, for the browser
//! tests (`e2e/resting.test.mjs`):
//!
//! ```sh
//! cargo run -p ccdsim-viewer --example rest_run -- resting.ccd
//! ccdsim view resting.ccd
//! ```
//!
//! The run is the one the Rust tests check playback against (`tests/common/resting.rs`): a
//! ball dropped on a floor with restitution 0.5 comes to rest and slides along it, another
//! let go on a 30° incline slides down it and bounces on along the floor, and the first is
//! kicked up at t = 3 s and comes to rest again. The JSON gives the times each first came to
//! rest and, every frame of 0.05 s, each ball's position, velocity and support (the wall it
//! rests on, or `null`) as the simulation had them.

#[path = "../tests/common/resting.rs"]
mod resting;

use std::path::Path;

fn main() {
    let Some(out) = std::env::args().nth(1) else {
        eprintln!("usage: rest_run OUT.ccd");
        std::process::exit(2);
    };
    let run = resting::record_rest_run(Path::new(&out));
    let frames: Vec<_> = run
        .checkpoints
        .iter()
        .map(|cp| {
            let bodies: Vec<_> = cp
                .bodies
                .iter()
                .map(|b| {
                    serde_json::json!({
                        "pos": b.pos.0, "vel": b.vel.0, "support": b.support,
                    })
                })
                .collect();
            serde_json::json!({ "time": cp.time, "applied": cp.applied, "bodies": bodies })
        })
        .collect();
    let report = serde_json::json!({
        "events": run.events,
        "end": run.end,
        "radius": resting::RADIUS,
        "walls": run.scene.walls,
        "floor_rest": run.floor_rest,
        "incline_rest": run.incline_rest,
        "kick_time": run.checkpoints[resting::KICK_AT].time,
        "frames": frames,
    });
    println!("{report}");
}
