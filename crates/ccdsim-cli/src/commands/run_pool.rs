//! `ccdsim run` on a pool scene (`ccdsim gen table`): the shot played until every ball rests
//! or is pocketed, and what happened.

use std::path::Path;

use anyhow::{bail, Result};
use ccdsim::billiards::{record_struck, PoolFinder, PoolRunWriter, PoolScene, ShotEventKind};
use serde::Serialize;

/// The `--json` summary of a pool shot; field names are an interface: extend, never rename.
#[derive(Serialize)]
struct PoolSummary {
    /// Events played.
    events: usize,
    /// Ball–ball collisions.
    ball_ball: usize,
    /// Cushion and jaw collisions.
    cushion: usize,
    /// When the last ball stopped, seconds.
    time: f64,
    /// Balls pocketed, in order: `[ball, pocket]`.
    pocketed: Vec<[String; 2]>,
    /// Each ball's final position (a pocketed ball at its pocket's centre), metres.
    positions: Vec<(String, [f64; 2])>,
    /// Collisions of balls pressed together by their decelerations, parted at the speed the
    /// contact time asks for (docs/model.md, "Balls pressed together").
    pressings: usize,
    /// The kinetic energy those partings added, joules.
    pressing_energy: f64,
    /// The run file written (`--record`).
    #[serde(skip_serializing_if = "Option::is_none")]
    record: Option<String>,
}

/// The options of `ccdsim run` a pool scene has no use for yet, by flag name, when given.
pub struct Unsupported<'a>(pub Vec<&'a str>);

/// Most events a shot may take.
const MAX_EVENTS: usize = 1_000_000;

/// Plays the pool scene `json` and prints its summary, each event found by `finder` (every
/// finder gives the same events, bit for bit). With `record`, writes its run file there as it
/// goes (kept, with its end record, when the shot stops short).
pub fn run(
    json: &str,
    unsupported: &Unsupported<'_>,
    finder: PoolFinder,
    record: Option<&Path>,
    as_json: bool,
) -> Result<()> {
    if let Some(flag) = unsupported.0.first() {
        bail!("{flag} is not available for pool scenes (trajectories, sensors, time limits and finder options are for ccdsim scenes; a pool shot plays to its end, found by --finder all-pairs, sedgewick, cells or bvh)");
    }
    let scene = PoolScene::from_json(json)?;
    let names = scene.names();
    let mut shot = scene.shot()?;
    shot.set_finder(finder);
    let (shot, played) = match record {
        Some(path) => {
            let out = PoolRunWriter::create(path, &scene)?;
            record_struck(shot, scene.struck_ball(), out, MAX_EVENTS)?
        }
        None => {
            let played = shot.run(MAX_EVENTS);
            (shot, played)
        }
    };
    if let Err(e) = played {
        bail!(
            "the shot could not be played to the end (docs/model.md, Pool): {}{}",
            e.describe(&names),
            record.map_or(String::new(), |p| format!(
                "; {} holds the shot up to there",
                p.display()
            ))
        );
    }
    let count = |f: fn(&ShotEventKind) -> bool| shot.events().iter().filter(|e| f(&e.kind)).count();
    let summary = PoolSummary {
        events: shot.events().len(),
        ball_ball: count(|k| matches!(k, ShotEventKind::Balls { .. })),
        cushion: count(|k| matches!(k, ShotEventKind::Cushion { .. } | ShotEventKind::Jaw { .. })),
        time: shot.time(),
        pocketed: shot
            .events()
            .iter()
            .filter_map(|e| match e.kind {
                ShotEventKind::Pocket { ball, pocket } => {
                    Some([names[ball].clone(), shot.table().pockets[pocket].id.clone()])
                }
                _ => None,
            })
            .collect(),
        positions: names
            .iter()
            .enumerate()
            .map(|(i, n)| (n.clone(), shot.balls()[i].ball.pos.0))
            .collect(),
        pressings: shot.pressings().0,
        pressing_energy: shot.pressings().1,
        record: record.map(|p| p.display().to_string()),
    };
    if as_json {
        outln!("{}", serde_json::to_string(&summary)?)?;
        return Ok(());
    }
    outln!(
        "pool shot: {} balls, {} events ({} ball-ball, {} cushion), every ball still at {:.3} s",
        names.len(),
        summary.events,
        summary.ball_ball,
        summary.cushion,
        summary.time
    )?;
    if summary.pocketed.is_empty() {
        outln!("pocketed: none")?;
    } else {
        let list: Vec<String> = summary
            .pocketed
            .iter()
            .map(|[b, p]| format!("{b} ({p})"))
            .collect();
        outln!("pocketed: {}", list.join(", "))?;
    }
    if summary.pressings > 0 {
        outln!(
            "balls pressed together: {} collisions parted at the contact time's speed, adding {:.3e} J",
            summary.pressings,
            summary.pressing_energy
        )?;
    }
    if let Some(path) = &summary.record {
        outln!("run file written to {path}")?;
    }
    Ok(())
}
