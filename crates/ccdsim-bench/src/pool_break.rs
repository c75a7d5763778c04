//! The pool break: a racked table broken by the cue ball, played to the end again and again,
//! timed per break. The same break pooltool times (`bench/pooltool/break_speed.py`) can be
//! given as a layout, so the two engines play identical shots.

use std::time::Instant;

use ccdsim::billiards::{
    rack, BallParams, Game, PocketTableSpecs, PoolFinder, Shot, ShotError, ShotEventKind, Table,
};
use ccdsim::motion::CueStrike;
use ccdsim::Vector;
use serde::Serialize;

/// Where the balls stand and how the cue ball is struck.
#[derive(Clone, Debug, PartialEq)]
pub struct BreakLayout {
    /// Ball names and positions (metres); the cue ball is the one named "cue".
    pub balls: Vec<(String, Vector<2>)>,
    /// The strike.
    pub strike: CueStrike,
}

impl BreakLayout {
    /// `game`'s rack on pooltool's default table (seeded), broken at `speed` m/s straight at
    /// the apex ball, centre ball, level cue.
    #[must_use]
    pub fn racked(game: Game, seed: u64, speed: f64) -> Self {
        let table = Table::pool(&PocketTableSpecs::default());
        let balls = rack(game, &table, BallParams::default().radius(), seed);
        let (cue, apex) = (balls[0].1, balls[1].1);
        let d = apex - cue;
        let phi = d[1].atan2(d[0]).to_degrees().rem_euclid(360.0);
        BreakLayout {
            balls,
            strike: CueStrike::new(speed, phi),
        }
    }
}

/// What the break benchmark measured.
#[derive(Clone, Debug, Serialize)]
pub struct BreakReport {
    /// The finder that found the events (`cells`, …).
    pub finder: String,
    /// Breaks played.
    pub runs: usize,
    /// Median wall time of one break (set-up, strike and every event), seconds.
    pub median_seconds: f64,
    /// Fastest and slowest break, seconds.
    pub min_seconds: f64,
    /// Slowest break, seconds.
    pub max_seconds: f64,
    /// Events in one break.
    pub events: usize,
    /// Ball–ball collisions in one break.
    pub ball_ball: usize,
    /// Cushion and jaw collisions in one break.
    pub cushion: usize,
    /// Balls pocketed, by name, in the order they dropped.
    pub pocketed: Vec<String>,
    /// Ball–ball collisions of balls pressed together, parted at the contact time's speed
    /// (`ccdsim::billiards::ball_impact::part_pressed`).
    pub pressings: usize,
    /// Simulated time until every ball rests, seconds.
    pub duration: f64,
    /// Every event of one break as pooltool names it: type, agents, time (seconds).
    pub event_list: Vec<(String, Vec<String>, f64)>,
}

/// Plays `layout` `runs` times (at least once), each event found by `finder`, and reports
/// the median time per break.
///
/// # Errors
/// The layout's balls are off the table or overlap, the strike misses, or the break does not
/// end within a million events.
pub fn pool_break(
    layout: &BreakLayout,
    runs: usize,
    finder: PoolFinder,
) -> Result<BreakReport, ShotError> {
    let table = Table::pool(&PocketTableSpecs::default());
    let cue = layout
        .balls
        .iter()
        .position(|(name, _)| name == "cue")
        .ok_or(ShotError::NoSuchBall(0))?;
    let positions: Vec<Vector<2>> = layout.balls.iter().map(|(_, p)| *p).collect();
    let mut times = Vec::with_capacity(runs.max(1));
    let mut last = None;
    for _ in 0..runs.max(1) {
        let start = Instant::now();
        let mut shot = Shot::new(table.clone(), BallParams::default(), &positions)?;
        shot.set_finder(finder);
        shot.strike(cue, &layout.strike)?;
        shot.run(1_000_000)?;
        times.push(start.elapsed().as_secs_f64());
        last = Some(shot);
    }
    let shot = last.expect("at least one run");
    times.sort_by(f64::total_cmp);
    let count = |f: fn(&ShotEventKind) -> bool| shot.events().iter().filter(|e| f(&e.kind)).count();
    let pocketed = shot
        .events()
        .iter()
        .filter_map(|e| match e.kind {
            ShotEventKind::Pocket { ball, .. } => Some(layout.balls[ball].0.clone()),
            _ => None,
        })
        .collect();
    let names: Vec<String> = layout.balls.iter().map(|(n, _)| n.clone()).collect();
    let event_list = shot
        .events()
        .iter()
        .map(|e| {
            let (kind, agents) = e.kind.names(shot.table(), &names);
            (kind, agents, e.time)
        })
        .collect();
    Ok(BreakReport {
        finder: finder.name().into(),
        runs: times.len(),
        median_seconds: times[times.len() / 2],
        min_seconds: times[0],
        max_seconds: times[times.len() - 1],
        events: shot.events().len(),
        ball_ball: count(|k| matches!(k, ShotEventKind::Balls { .. })),
        cushion: count(|k| matches!(k, ShotEventKind::Cushion { .. } | ShotEventKind::Jaw { .. })),
        pocketed,
        pressings: shot.pressings().0,
        duration: shot.time(),
        event_list,
    })
}
