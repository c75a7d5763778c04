//! Adversarial pool shots: balls on a lattice of one diameter (touching each other and the
//! rails), on half a diameter (some overlap and are refused), mirrored about the table's long
//! axis, in blocks of touching balls (square or racked), or anywhere; struck slowly or hard,
//! with and without spin and elevation; meeting with and without friction. Every shot must
//! end, give the oracle's events bit for bit with every finder (the run files recorded with
//! the default finder and with each finder, the oracle first, are the same, byte for byte)
//! and pass `verify`.
//! `CCDSIM_POOL_CASES` sets how many shots (64 by default).

use ccdsim::billiards::{
    record_shot, record_struck, PoolBall, PoolBallBall, PoolFinder, PoolRecord, PoolRunReader,
    PoolRunWriter, PoolScene, PoolSetup, PoolShot,
};
use ccdsim::verify::PoolVerifier;
use proptest::prelude::*;
use proptest::strategy::ValueTree;
use std::sync::atomic::{AtomicU64, Ordering};

const R: f64 = 0.028575;
const WIDTH: f64 = 0.9906;
const LENGTH: f64 = 1.9812;

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

/// Shots played (scenes the table accepted), and their events.
static PLAYED: AtomicU64 = AtomicU64::new(0);
static EVENTS: AtomicU64 = AtomicU64::new(0);

/// Plays `scene` both ways and verifies it; `Ok(false)` when the scene is refused.
fn check(scene: &PoolScene) -> Result<bool, String> {
    if scene.shot().is_err() {
        return Ok(false);
    }
    PLAYED.fetch_add(1, Ordering::Relaxed);
    let mut kept = Vec::new();
    let w = PoolRunWriter::new(&mut kept, "kept".into(), scene).map_err(|e| e.to_string())?;
    let (_, played) = record_shot(scene, w, 200_000).map_err(|e| e.to_string())?;
    let events = played.map_err(|e| format!("the shot did not end: {e}"))?;
    EVENTS.fetch_add(events as u64, Ordering::Relaxed);
    for finder in PoolFinder::ALL {
        let mut other = Vec::new();
        let w = PoolRunWriter::new(&mut other, "other".into(), scene).map_err(|e| e.to_string())?;
        let mut shot = scene.shot().map_err(|e| e.to_string())?;
        shot.set_finder(finder);
        let (_, again) =
            record_struck(shot, scene.struck_ball(), w, 200_000).map_err(|e| e.to_string())?;
        again.map_err(|e| format!("the shot did not end with the {finder} finder: {e}"))?;
        if kept != other {
            return Err(format!(
                "the default finder's run file differs from the {finder} finder's"
            ));
        }
    }
    let mut reader = PoolRunReader::new(&kept[..], "kept".into()).map_err(|e| e.to_string())?;
    let mut v = PoolVerifier::new(scene)?;
    let mut end = 0.0;
    while let Some(rec) = reader.next_record().map_err(|e| e.to_string())? {
        v.check(&rec).map_err(|e| format!("verify: {e}"))?;
        end = rec.time();
        if let PoolRecord::End(_) = rec {
            break;
        }
    }
    let report = v.finish(end).map_err(|e| format!("verify: {e}"))?;
    if !report.still {
        return Err("balls still move at the end".into());
    }
    Ok(true)
}

fn cases() -> u32 {
    std::env::var("CCDSIM_POOL_CASES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(64)
}

proptest! {
    #![proptest_config(ProptestConfig { cases: cases(), ..ProptestConfig::default() })]

    #[test]
    fn adversarial_shots_match_the_oracle_and_verify(
        p in placement(),
        s in strike(),
        frictional in any::<bool>(),
    ) {
        let scene = scene(&p, &s, frictional);
        if let Err(why) = check(&scene) {
            prop_assert!(false, "{why}\n{}", scene.to_json());
        }
        if std::env::var_os("CCDSIM_POOL_STATS").is_some() {
            eprintln!("played {} events {}", PLAYED.load(Ordering::Relaxed), EVENTS.load(Ordering::Relaxed));
        }
    }
}

/// Most drawn shots are accepted and play events: the fuzzing above is not all refusals.
#[test]
fn most_adversarial_shots_are_played() {
    let mut runner = proptest::test_runner::TestRunner::deterministic();
    let strategy = (placement(), strike(), any::<bool>());
    let (mut accepted, mut events) = (0, 0);
    for _ in 0..64 {
        let (p, s, frictional) = strategy.new_tree(&mut runner).unwrap().current();
        let scene = scene(&p, &s, frictional);
        if let Ok(mut shot) = scene.shot() {
            accepted += 1;
            events += shot.run(200_000).unwrap();
        }
    }
    assert!(accepted >= 32, "{accepted} of 64 accepted");
    assert!(
        events >= 8 * accepted,
        "{events} events in {accepted} shots"
    );
}
