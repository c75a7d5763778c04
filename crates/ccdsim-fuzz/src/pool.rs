//! Pool shots for the fuzzer: balls on a lattice of one diameter (touching each other and the
//! rails), on half a diameter (some overlap and are refused), mirrored about the table's long
//! axis, in blocks of touching balls (square or racked) with the cue ball aimed at them, or
//! anywhere; struck slowly or hard, with and without spin and elevation; meeting with and
//! without friction. A pool case holds a pool scene where a scene case holds a scene
//! (`ccdsim gen table` writes the same JSON); [`check_pool`] plays it with every finder
//! ([`PoolFinder`]), compares the run files with the oracle's byte for byte and replays the
//! oracle's through `verify`. Every shot must end.

use crate::case::{Case, Schedule};
use crate::verdict::{Checked, Failure};
use ccdsim::billiards::{
    record_struck, PoolBall, PoolBallBall, PoolFinder, PoolRecord, PoolRunReader, PoolRunWriter,
    PoolScene, PoolSetup, PoolShot,
};
use ccdsim::verify::PoolVerifier;
use proptest::prelude::*;

/// Most events a fuzzed shot may take: every shot must end well within it.
const MAX_EVENTS: u64 = 200_000;

const R: f64 = 0.028575;
const WIDTH: f64 = 0.9906;
const LENGTH: f64 = 1.9812;

/// Where the balls stand.
#[derive(Clone, Debug)]
enum Placement {
    /// Cells of one diameter from the rails: neighbours touch, the outer ones touch a rail.
    Lattice(Vec<(u8, u8)>),
    /// Cells of half a diameter: many overlap (refused), the rest touch or nearly.
    HalfLattice(Vec<(u8, u8)>),
    /// Pairs mirrored about the long axis.
    Mirrored(Vec<(f64, f64)>),
    /// Anywhere.
    Free(Vec<(f64, f64)>),
    /// The cue ball anywhere, and a block of `w × h` touching balls (rows shifted by a
    /// radius, as in a rack, when `racked`) whose corner cell is `at`.
    Block {
        cue: (f64, f64),
        at: (u8, u8),
        w: u8,
        h: u8,
        racked: bool,
    },
}

fn placement() -> impl Strategy<Value = Placement> {
    let cells = |i: u8, j: u8| prop::collection::vec((0..i, 0..j), 1..9);
    prop_oneof![
        cells(17, 35).prop_map(Placement::Lattice),
        cells(34, 69).prop_map(Placement::HalfLattice),
        prop::collection::vec((R..WIDTH / 2.0, R..LENGTH - R), 1..5).prop_map(Placement::Mirrored),
        prop::collection::vec((R..WIDTH - R, R..LENGTH - R), 1..9).prop_map(Placement::Free),
        (
            (R..WIDTH - R, R..LENGTH - R),
            (0u8..14, 0u8..32),
            1u8..4,
            1u8..4,
            any::<bool>()
        )
            .prop_map(|(cue, at, w, h, racked)| Placement::Block {
                cue,
                at,
                w,
                h,
                racked
            }),
    ]
}

fn positions(p: &Placement) -> Vec<[f64; 2]> {
    match p {
        Placement::Lattice(c) => c
            .iter()
            .map(|&(i, j)| [R + 2.0 * R * f64::from(i), R + 2.0 * R * f64::from(j)])
            .collect(),
        Placement::HalfLattice(c) => c
            .iter()
            .map(|&(i, j)| [R + R * f64::from(i), R + R * f64::from(j)])
            .collect(),
        Placement::Mirrored(c) => c
            .iter()
            .flat_map(|&(x, y)| [[x, y], [WIDTH - x, y]])
            .collect(),
        Placement::Free(c) => c.iter().map(|&(x, y)| [x, y]).collect(),
        Placement::Block {
            cue,
            at,
            w,
            h,
            racked,
        } => {
            let mut out = vec![[cue.0, cue.1]];
            let row = if *racked { 3f64.sqrt() * R } else { 2.0 * R };
            for j in 0..*h {
                let shift = if *racked && j % 2 == 1 { R } else { 0.0 };
                for i in 0..*w {
                    out.push([
                        R + 2.0 * R * f64::from(at.0 + i) + shift,
                        R + 2.0 * R * f64::from(at.1) + row * f64::from(j),
                    ]);
                }
            }
            out
        }
    }
}

/// How the cue ball is struck.
#[derive(Clone, Debug)]
struct Strike {
    speed: f64,
    phi: f64,
    theta: f64,
    a: f64,
    b: f64,
}

fn strike() -> impl Strategy<Value = Strike> {
    let speed = prop_oneof![
        prop::sample::select(vec![0.05, 0.3, 1.0, 3.0, 8.0]),
        0.01f64..6.0
    ];
    let phi = prop_oneof![(0u8..8).prop_map(|k| 45.0 * f64::from(k)), 0.0f64..360.0];
    let offset = prop::sample::select(vec![0.0, 0.3, -0.3, 0.5, -0.5]);
    (
        speed,
        phi,
        prop::sample::select(vec![0.0, 5.0, 30.0]),
        offset.clone(),
        offset,
    )
        .prop_map(|(speed, phi, theta, a, b)| Strike {
            speed,
            phi,
            theta,
            a,
            b,
        })
}

fn scene(p: &Placement, s: &Strike, frictional: bool) -> PoolScene {
    let at = positions(p);
    // At a block, the cue ball is aimed at its first ball, within 3° (`phi` picks where).
    let phi = match p {
        Placement::Block { .. } => {
            let d = [at[1][0] - at[0][0], at[1][1] - at[0][1]];
            d[1].atan2(d[0]).to_degrees() + (s.phi - 180.0) / 60.0
        }
        _ => s.phi,
    };
    let balls = at
        .into_iter()
        .enumerate()
        .map(|(i, pos)| PoolBall {
            name: if i == 0 { "cue".into() } else { i.to_string() },
            pos,
        })
        .collect();
    PoolScene {
        pool: PoolSetup {
            balls,
            shot: PoolShot {
                ball: "cue".into(),
                speed: s.speed,
                phi,
                theta: s.theta,
                a: s.a,
                b: s.b,
            },
            ball_ball: frictional.then_some(PoolBallBall {
                restitution: 0.95,
                friction: None,
            }),
        },
    }
}

/// The strategy of pool cases: a placement, a strike and a ball–ball model.
pub fn case() -> impl Strategy<Value = Case> {
    (placement(), strike(), any::<bool>()).prop_map(|(p, s, frictional)| {
        let scene = scene(&p, &s, frictional);
        Case {
            scene: serde_json::from_str(&scene.to_json()).expect("a pool scene serialises"),
            // A shot is played to its end: no schedule, no edits.
            schedule: Schedule::Events { every: 1 },
            edits: Vec::new(),
            max_events: MAX_EVENTS,
            duration: 0.0,
            note: None,
        }
    })
}

/// The shot of `scene` recorded with `finder`, and its event count if it ended within
/// `max_events` (the file then holds as much as was played, and why it stopped).
fn recorded(
    scene: &PoolScene,
    finder: PoolFinder,
    max_events: u64,
) -> Result<(Vec<u8>, Result<u64, String>), Failure> {
    let failed = |e: &dyn std::fmt::Display| Failure::Panic(format!("pool, {finder}: {e}"));
    let mut bytes = Vec::new();
    let w = PoolRunWriter::new(&mut bytes, finder.name().into(), scene).map_err(|e| failed(&e))?;
    let mut shot = scene.shot().map_err(|e| failed(&e))?;
    shot.set_finder(finder);
    let limit = usize::try_from(max_events).unwrap_or(usize::MAX);
    let (_, played) = record_struck(shot, scene.struck_ball(), w, limit).map_err(|e| failed(&e))?;
    let events = played
        .map(|n| n as u64)
        .map_err(|e| e.describe(&scene.names()));
    Ok((bytes, events))
}

/// Replays a pool run file through `verify`; every ball must be still at its end.
fn verify_pool(scene: &PoolScene, bytes: &[u8]) -> Result<(), String> {
    let mut reader = PoolRunReader::new(bytes, "oracle".into()).map_err(|e| e.to_string())?;
    let mut v = PoolVerifier::new(scene)?;
    let mut end = 0.0;
    while let Some(rec) = reader.next_record().map_err(|e| e.to_string())? {
        v.check(&rec).map_err(|e| e.to_string())?;
        end = rec.time();
        if let PoolRecord::End(_) = rec {
            break;
        }
    }
    let report = v.finish(end).map_err(|e| e.to_string())?;
    if report.still {
        Ok(())
    } else {
        Err("balls still move at the end".into())
    }
}

/// Checks a pool case: `Ok(None)` when the table refuses its balls (off the table,
/// overlapping) or its strike (a miss), else every finder's run file must be the oracle's,
/// byte for byte, and with `verify` the oracle's must verify.
pub fn check_pool(case: &Case, verify: bool) -> Result<Option<Checked>, Failure> {
    let Ok(scene) = PoolScene::from_json(&case.scene.to_string()) else {
        return Ok(None);
    };
    if scene.shot().is_err() {
        return Ok(None);
    }
    let (oracle, events) = recorded(&scene, PoolFinder::AllPairs, case.max_events)?;
    let events =
        events.map_err(|why| Failure::Verify(format!("pool: the shot did not end: {why}")))?;
    let others = &PoolFinder::ALL[1..];
    for &finder in others {
        let (got, _) = recorded(&scene, finder, case.max_events)?;
        if got != oracle {
            let at = got
                .iter()
                .zip(&oracle)
                .position(|(a, b)| a != b)
                .unwrap_or(got.len().min(oracle.len()));
            return Err(Failure::Mismatch(format!(
                "pool, {finder}: run files differ from byte {at}"
            )));
        }
    }
    if verify {
        verify_pool(&scene, &oracle).map_err(Failure::Verify)?;
    }
    Ok(Some(Checked {
        events,
        runs: others.len(),
    }))
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::strategy::ValueTree;

    /// Most drawn shots are accepted and play events: pool fuzzing is not all refusals.
    #[test]
    fn most_drawn_shots_are_played() {
        let mut runner = proptest::test_runner::TestRunner::deterministic();
        let (mut accepted, mut events) = (0, 0);
        for _ in 0..64 {
            let case = case().new_tree(&mut runner).unwrap().current();
            if let Some(checked) = check_pool(&case, true).unwrap() {
                accepted += 1;
                events += checked.events;
            }
        }
        assert!(accepted >= 32, "{accepted} of 64 accepted");
        assert!(
            events >= 8 * accepted,
            "{events} events in {accepted} shots"
        );
    }
}
