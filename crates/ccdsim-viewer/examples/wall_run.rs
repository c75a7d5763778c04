//! Records a run with moving walls (a steered run file, format version 10) and prints what it
//! did as JSON, for the browser tests (`e2e/walls.test.mjs`):
//!
//! ```sh
//! cargo run -p ccdsim-viewer --example wall_run -- walls.ccd
//! ccdsim view walls.ccd
//! ```
//!
//! The run is the one the Rust tests check playback against (`tests/common/walls.rs`): a dozen
//! balls in an 8 m box beside a paddle (a segment) the program swings left and right every
//! frame of 0.05 s and below a piston (a line) it brings down and back up. The JSON lists every
//! motion each moving wall had (`pieces`: time, offset from its scene geometry then, velocity),
//! from which its place at any time follows.

#[path = "../tests/common/walls.rs"]
mod walls;

use std::path::Path;

fn main() {
    let Some(out) = std::env::args().nth(1) else {
        eprintln!("usage: wall_run OUT.ccd");
        std::process::exit(2);
    };
    let run = walls::record_wall_run(Path::new(&out));
    let pieces: Vec<Vec<_>> = run
        .pieces
        .iter()
        .map(|ps| {
            ps.iter()
                .map(|m| {
                    serde_json::json!({
                        "time": m.time, "offset": m.offset.0, "velocity": m.velocity.0,
                    })
                })
                .collect()
        })
        .collect();
    let report = serde_json::json!({
        "events": run.events,
        "end": run.end,
        "walls": run.scene.walls,
        "moving_walls": run.scene.moving_walls,
        "moving_wall_hits": run.moving_wall_hits,
        "pieces": pieces,
    });
    println!("{report}");
}
