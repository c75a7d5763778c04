//! Export of a pool shot's run file to JSON Lines: a header line with the scene, then one line
//! per record with pooltool's names for the event and its agents and the state of each ball it
//! changed.
//!
//! ```json
//! {"version":16,"pool":{"balls":[…],"shot":{…}}}
//! {"t":0.0,"type":"strike","agents":["cue"],"balls":[{"name":"cue","pos":[…],"vel":[…],"spin":[…],"state":"sliding"}]}
//! {"t":0.07,"type":"ball_linear_cushion","agents":["cue","3"],"balls":[…]}
//! {"t":7.67,"type":"end"}
//! ```

use std::io::{Read, Write};

use serde::Serialize;

use super::pool_scene::PoolSetup;
use super::run_file::{BallAfter, PoolRecord, PoolRunReader};
use crate::record::{ExportError, VERSION_POOL};

#[derive(Serialize)]
struct Header<'a> {
    version: u32,
    pool: &'a PoolSetup,
}

#[derive(Serialize)]
struct Line<'a> {
    t: f64,
    #[serde(rename = "type")]
    kind: String,
    #[serde(skip_serializing_if = "Vec::is_empty")]
    agents: Vec<String>,
    #[serde(skip_serializing_if = "Vec::is_empty")]
    balls: Vec<BallOut<'a>>,
}

#[derive(Serialize)]
struct BallOut<'a> {
    name: &'a str,
    pos: [f64; 2],
    vel: [f64; 2],
    spin: [f64; 3],
    state: &'static str,
}

/// Writes the pool shot `reader` reads as JSON Lines to `out` (see the module docs).
///
/// # Errors
/// A record that cannot be read, or output that cannot be written.
pub fn export_pool_jsonl<R: Read, W: Write>(
    reader: &mut PoolRunReader<R>,
    out: &mut W,
) -> Result<(), ExportError> {
    let header = Header {
        version: VERSION_POOL,
        pool: &reader.scene().pool,
    };
    writeln!(
        out,
        "{}",
        serde_json::to_string(&header).map_err(std::io::Error::other)?
    )?;
    let names = reader.scene().names();
    let ball = |i: usize, a: &BallAfter| BallOut {
        name: &names[i],
        pos: a.ball.pos.0,
        vel: a.ball.vel.0,
        spin: a.ball.spin.0,
        state: a.state.name(),
    };
    while let Some(rec) = reader.next_record()? {
        let line = match rec {
            PoolRecord::Strike {
                time,
                ball: i,
                after,
            } => Line {
                t: time,
                kind: "strike".into(),
                agents: vec![names[i].clone()],
                balls: vec![ball(i, &after)],
            },
            PoolRecord::Event {
                event,
                after,
                after_b,
            } => {
                let (kind, agents) = event.kind.names(reader.table(), &names);
                let (a, b) = match event.kind {
                    super::ShotEventKind::Balls { a, b } => (a, Some(b)),
                    super::ShotEventKind::Transition { ball, .. }
                    | super::ShotEventKind::Cushion { ball, .. }
                    | super::ShotEventKind::Jaw { ball, .. }
                    | super::ShotEventKind::Pocket { ball, .. } => (ball, None),
                };
                let mut balls = vec![ball(a, &after)];
                if let (Some(b), Some(after_b)) = (b, after_b) {
                    balls.push(ball(b, &after_b));
                }
                Line {
                    t: event.time,
                    kind,
                    agents,
                    balls,
                }
            }
            PoolRecord::End(time) => Line {
                t: time,
                kind: "end".into(),
                agents: Vec::new(),
                balls: Vec::new(),
            },
        };
        writeln!(
            out,
            "{}",
            serde_json::to_string(&line).map_err(std::io::Error::other)?
        )?;
    }
    Ok(())
}
