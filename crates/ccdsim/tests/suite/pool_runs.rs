//! Run files of pool shots (format version 16) and their verification: every shot recorded
//! reads back event for event, is the file the oracle's search writes, byte for byte, and
//! passes `verify`'s pool checks; a record dropped, moved or changed fails them.

use ccdsim::billiards::{
    rack_at, record_shot, record_struck, BallParams, Game, PocketTableSpecs, PoolBall,
    PoolBallBall, PoolFinder, PoolRecord, PoolRunReader, PoolRunWriter, PoolScene, PoolSetup,
    PoolShot, ShotEventKind, Table,
};
use ccdsim::record::Tail;
use ccdsim::verify::{PoolReport, PoolVerifier, Violation};
use serde_json::Value;

use crate::reference_json::num;

const REFERENCE: &str = include_str!("../data/pooltool-shots.json");

/// The 100 reference shots (cue ball alone, cue ball onto one ball) as pool scenes.
fn reference_scenes() -> Vec<PoolScene> {
    let reference: Value = serde_json::from_str(REFERENCE).unwrap();
    reference["shots"]
        .as_array()
        .unwrap()
        .iter()
        .map(|s| {
            let balls = s["balls"].as_object().unwrap();
            let mut names: Vec<String> = vec!["cue".into()];
            names.extend(balls.keys().filter(|k| *k != "cue").cloned());
            let st = &s["strike"];
            PoolScene {
                pool: PoolSetup {
                    balls: names
                        .iter()
                        .map(|n| PoolBall {
                            name: n.clone(),
                            pos: [num(&balls[n][0]), num(&balls[n][1])],
                        })
                        .collect(),
                    shot: PoolShot {
                        ball: "cue".into(),
                        speed: num(&st["V0"]),
                        phi: num(&st["phi"]),
                        theta: num(&st["theta"]),
                        a: num(&st["a"]),
                        b: num(&st["b"]),
                    },
                    ball_ball: None,
                },
            }
        })
        .collect()
}

/// Breaks of both games, with and without friction between the balls, and pooltool #154's
/// break (the rack's apex at 75 % of the length, the cue ball at 25 %, 3.26 m/s), whose balls
/// press together.
fn break_scenes() -> Vec<PoolScene> {
    let mut out = Vec::new();
    let table = Table::pool(&PocketTableSpecs::default());
    for seed in 0..4 {
        let balls = rack_at(
            Game::EightBall,
            &table,
            BallParams::default().radius(),
            seed,
            [0.5, 0.75],
            [0.5, 0.25],
        );
        let mut s = PoolScene::racked(Game::EightBall, 1);
        for (b, (name, p)) in s.pool.balls.iter_mut().zip(&balls) {
            (b.name, b.pos) = (name.clone(), p.0);
        }
        (s.pool.shot.speed, s.pool.shot.phi) = (3.262213, 81.83468);
        out.push(s);
    }
    for game in [Game::NineBall, Game::EightBall] {
        for seed in 1..=4 {
            let mut s = PoolScene::racked(game, seed);
            out.push(s.clone());
            s.pool.ball_ball = Some(PoolBallBall {
                restitution: 0.95,
                friction: None,
            });
            s.pool.shot.speed = 5.0;
            out.push(s);
        }
    }
    out
}

/// The shot recorded, read back: its records, and how many events and pressings it had.
/// Recorded again with every finder (the oracle first), the file is the same, byte for byte.
fn recorded(scene: &PoolScene) -> (Vec<PoolRecord>, usize, usize) {
    let mut bytes = Vec::new();
    let w = PoolRunWriter::new(&mut bytes, "mem".into(), scene).unwrap();
    let (shot, _) = record_shot(scene, w, 100_000).unwrap();
    for finder in PoolFinder::ALL {
        let mut other = Vec::new();
        let w = PoolRunWriter::new(&mut other, "mem".into(), scene).unwrap();
        let mut again = scene.shot().unwrap();
        again.set_finder(finder);
        let (_, played) = record_struck(again, scene.struck_ball(), w, 100_000).unwrap();
        played.unwrap();
        assert!(other == bytes, "the {finder} finder's file differs");
    }
    let mut r = PoolRunReader::new(&bytes[..], "mem".into()).unwrap();
    let mut recs = Vec::new();
    while let Some(rec) = r.next_record().unwrap() {
        recs.push(rec);
    }
    assert_eq!(r.tail(), Tail::Complete);
    (recs, shot.events().len(), shot.pressings().0)
}

fn verify(scene: &PoolScene, recs: &[PoolRecord]) -> Result<PoolReport, Violation> {
    let mut v = PoolVerifier::new(scene).unwrap();
    let mut end = 0.0;
    for rec in recs {
        v.check(rec)?;
        end = rec.time();
    }
    v.finish(end)
}

#[test]
fn every_recorded_shot_reads_back_and_verifies() {
    let (mut pocketed, mut still, mut events, mut pressed) = (0, 0, 0, 0);
    let mut worst = 0.0f64;
    for (k, scene) in reference_scenes().iter().chain(&break_scenes()).enumerate() {
        let (recs, played, pressings) = recorded(scene);
        assert_eq!(recs.len(), played + 2, "shot {k}: strike, events, end");
        let report = verify(scene, &recs)
            .unwrap_or_else(|v| panic!("shot {k}: {v}: {:?}", recs[v.index as usize]));
        assert_eq!(report.events as usize, played, "shot {k}");
        assert_eq!(report.pressings as usize, pressings, "shot {k}");
        pressed += pressings;
        assert!(report.energy_end <= report.energy_start, "shot {k}");
        worst = worst.max(report.max_overlap);
        pocketed += report.pocketed;
        still += usize::from(report.still);
        events += played;
    }
    // The shots drop balls and end at rest (a pressed pair may stop a break early).
    assert!(pocketed > 20, "{pocketed} balls pocketed");
    assert_eq!(still, 120, "every shot ends at rest");
    assert!(pressed > 50, "{pressed} pressings");
    assert!(events > 2000, "{events} events");
    assert!(worst <= 1e-12, "largest overlap {worst:e}");
}

/// The index of the first record matching `f`.
fn find(recs: &[PoolRecord], f: impl Fn(&ShotEventKind) -> bool) -> usize {
    recs.iter()
        .position(|r| matches!(r, PoolRecord::Event { event, .. } if f(&event.kind)))
        .expect("such a record")
}

#[test]
fn a_record_dropped_moved_or_changed_fails_verification() {
    let scene = PoolScene::racked(Game::NineBall, 1);
    let (recs, _, _) = recorded(&scene);
    verify(&scene, &recs).unwrap();
    let fails = |recs: &[PoolRecord], says: &str| {
        let v = verify(&scene, recs).expect_err(says);
        assert!(v.what.contains(says), "expected {says:?}: {v}");
    };
    // A collision dropped: the balls pass into each other.
    let i = find(&recs, |k| matches!(k, ShotEventKind::Balls { .. }));
    let mut r = recs.clone();
    r.remove(i);
    fails(&r, "overlap");
    // A bounce dropped: the ball passes into the cushion.
    let i = find(&recs, |k| matches!(k, ShotEventKind::Cushion { .. }));
    let mut r = recs.clone();
    r.remove(i);
    fails(&r, "cushion");
    // A state change dropped.
    let i = find(&recs, |k| matches!(k, ShotEventKind::Transition { .. }));
    let mut r = recs.clone();
    r.remove(i);
    fails(&r, "state ended");
    // A pocket dropped.
    let i = find(&recs, |k| matches!(k, ShotEventKind::Pocket { .. }));
    let mut r = recs.clone();
    r.truncate(i);
    r.push(PoolRecord::End(recs[i].time() + 1e-3));
    fails(&r, "pocket");
    // A collision a microsecond late.
    let i = find(&recs, |k| matches!(k, ShotEventKind::Balls { .. }));
    let mut r = recs.clone();
    if let PoolRecord::Event { event, .. } = &mut r[i] {
        event.time += 1e-6;
    }
    fails(&r, "");
    // A bounce that adds energy.
    let i = find(&recs, |k| matches!(k, ShotEventKind::Cushion { .. }));
    let mut r = recs.clone();
    if let PoolRecord::Event { after, .. } = &mut r[i] {
        after.ball.vel = after.ball.vel * 1.5;
    }
    fails(&r, "Han's model");
    // Balls pressed together, recorded as if the collision alone had parted them.
    let scene = &break_scenes()[0];
    let (recs, _, pressings) = recorded(scene);
    assert!(pressings > 0);
    verify(scene, &recs).unwrap();
    let mut r = recs.clone();
    let i = r
        .iter()
        .position(|rec| match rec {
            PoolRecord::Event {
                event,
                after,
                after_b: Some(after_b),
            } if matches!(event.kind, ShotEventKind::Balls { .. }) => {
                let d = after_b.ball.pos - after.ball.pos;
                (after_b.ball.vel - after.ball.vel).dot(d) < 1e-3 * d.norm()
            }
            _ => false,
        })
        .expect("a slow parting");
    if let PoolRecord::Event {
        after,
        after_b: Some(after_b),
        ..
    } = &mut r[i]
    {
        let mean = (after.ball.vel + after_b.ball.vel) * 0.5;
        let d = after_b.ball.pos - after.ball.pos;
        let n = d * (1.0 / d.norm());
        // No parting speed along the line of centres: they would press on at once.
        after.ball.vel = after.ball.vel - n * (after.ball.vel - mean).dot(n);
        after_b.ball.vel = after_b.ball.vel - n * (after_b.ball.vel - mean).dot(n);
    }
    let v = verify(scene, &r).expect_err("an unparted pressing");
    assert!(v.index as usize <= i, "{v}");
    let scene = PoolScene::racked(Game::NineBall, 1);
    let (recs, _, _) = recorded(&scene);
    let fails = |recs: &[PoolRecord], says: &str| {
        let v = verify(&scene, recs).expect_err(says);
        assert!(v.what.contains(says), "expected {says:?}: {v}");
    };
    // A strike harder than the scene's.
    let mut r = recs.clone();
    if let PoolRecord::Strike { after, .. } = &mut r[0] {
        after.ball.vel = after.ball.vel * 1.01;
    }
    fails(&r, "strike");
}
