//! Records a run that adds and removes bodies (a steered run file, format version 9) and
//! prints what it did as JSON, for the browser tests (`e2e/slots.test.mjs`):
//!
//! ```sh
//! cargo run -p ccdsim-viewer --example slot_run -- slots.ccd
//! ccdsim view slots.ccd
//! ```
//!
//! The run is the one the Rust tests check playback against (`tests/common/slots.rs`): a
//! dozen balls under gravity in an 8 m box, a body added every third frame of 0.05 s (every
//! fourth kinematic, every fifth with an id of its own) and one removed every fourth frame.

#[path = "../tests/common/slots.rs"]
mod slots;

use std::path::Path;

fn main() {
    let Some(out) = std::env::args().nth(1) else {
        eprintln!("usage: slot_run OUT.ccd");
        std::process::exit(2);
    };
    let run = slots::record_slot_run(Path::new(&out), &slots::PLAN);
    let adds: Vec<_> = run
        .adds
        .iter()
        .map(|a| {
            serde_json::json!({
                "slot": a.slot, "time": a.time, "radius": a.radius,
                "kinematic": a.kinematic, "id": a.id,
            })
        })
        .collect();
    let removals: Vec<_> = run
        .removals
        .iter()
        .map(|r| serde_json::json!({ "slot": r.slot, "time": r.time, "pos": r.pos.0 }))
        .collect();
    let report = serde_json::json!({
        "events": run.events,
        "end": run.end,
        "scene_bodies": run.scene.bodies.len(),
        "adds": adds,
        "removals": removals,
    });
    println!("{report}");
}
