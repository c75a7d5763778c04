//! The billiards engine against pooltool 0.3.3: pooltool's default table, and 100 simple
//! shots on it (`tests/data/pooltool-shots.json`, written by `scripts/pooltool-reference`
//! from pooltool's own `simulate`: 50 with the cue ball alone, 50 onto one object ball).
//! ccdsim plays each shot, checking at every event that its kept predictions give the
//! oracle's next event bit for bit, and must give pooltool's events in pooltool's order and
//! the same pocketed balls, each event within 10⁻⁶ s of pooltool's time. pooltool moves
//! touching balls 10⁻⁹ m apart before resolving a collision, and a slow ball meeting a
//! cushion at a grazing angle turns that nudge into microseconds; the reference holds each
//! shot played again with a nudge a hundred times smaller. An event further than 10⁻⁶ s from
//! pooltool's time passes only if it is within 10⁻⁶ s of that second run and nearer to it:
//! pooltool's time moves towards ccdsim's as the nudge goes to zero, so ccdsim's is the
//! exact one.

use ccdsim::billiards::{BallParams, PocketTableSpecs, Shot, Table};
use ccdsim::motion::CueStrike;
use ccdsim::Vector;
use serde_json::Value;

use crate::reference_json::{num, vec_of};

const REFERENCE: &str = include_str!("../data/pooltool-shots.json");

fn point(v: &Value) -> Vector<2> {
    vec_of(v)
}

fn close(a: Vector<2>, b: Vector<2>) -> bool {
    (a - b).norm() < 1e-12
}

#[test]
fn the_pool_table_is_pooltools_default_table() {
    let reference: Value = serde_json::from_str(REFERENCE).unwrap();
    let t = &reference["table"];
    let ours = Table::pool(&PocketTableSpecs::default());
    assert_eq!(ours.width, num(&t["width"]));
    assert_eq!(ours.length, num(&t["length"]));
    let linear = t["linear"].as_array().unwrap();
    assert_eq!(linear.len(), ours.cushions.len());
    for c in linear {
        let id = c["id"].as_str().unwrap();
        let mine = ours.cushions.iter().find(|m| m.id == id).expect(id);
        let (p1, p2) = (point(&c["p1"]), point(&c["p2"]));
        let same = (close(mine.p1, p1) && close(mine.p2, p2))
            || (close(mine.p1, p2) && close(mine.p2, p1));
        assert!(same, "cushion {id}: {mine:?} vs {c}");
        assert!((mine.height - num(&c["height"])).abs() < 1e-15);
    }
    let circular = t["circular"].as_array().unwrap();
    assert_eq!(circular.len(), ours.jaws.len());
    for c in circular {
        let id = c["id"].as_str().unwrap();
        let mine = ours.jaws.iter().find(|m| m.id == id).expect(id);
        assert!(close(mine.center, point(&c["center"])), "jaw {id}");
        assert!((mine.radius - num(&c["radius"])).abs() < 1e-15, "jaw {id}");
    }
    let pockets = t["pockets"].as_array().unwrap();
    assert_eq!(pockets.len(), ours.pockets.len());
    for p in pockets {
        let id = p["id"].as_str().unwrap();
        let mine = ours.pockets.iter().find(|m| m.id == id).expect(id);
        assert!(close(mine.center, point(&p["center"])), "pocket {id}");
        assert!(
            (mine.radius - num(&p["radius"])).abs() < 1e-15,
            "pocket {id}"
        );
    }
}

/// Plays a shot of the reference, checking the kept predictions against the oracle at
/// every event.
fn play(shot_ref: &Value) -> (Shot, Vec<String>) {
    let balls = shot_ref["balls"].as_object().unwrap();
    // The cue ball first, then the object balls in the reference's order.
    let mut names: Vec<String> = vec!["cue".into()];
    names.extend(balls.keys().filter(|k| *k != "cue").cloned());
    let positions: Vec<Vector<2>> = names.iter().map(|n| point(&balls[n])).collect();
    let table = Table::pool(&PocketTableSpecs::default());
    let mut shot = Shot::new(table, BallParams::default(), &positions).unwrap();
    let s = &shot_ref["strike"];
    let strike = CueStrike {
        speed: num(&s["V0"]),
        phi: num(&s["phi"]),
        theta: num(&s["theta"]),
        a: num(&s["a"]),
        b: num(&s["b"]),
    };
    shot.strike(0, &strike).unwrap();
    for _ in 0..100_000 {
        let naive = shot.next_event_naive();
        assert_eq!(
            shot.next_event(),
            naive,
            "kept predictions differ from the oracle"
        );
        if shot.step().is_none() {
            break;
        }
    }
    assert!(shot.is_still());
    (shot, names)
}

#[test]
fn one_hundred_shots_give_pooltools_events() {
    let reference: Value = serde_json::from_str(REFERENCE).unwrap();
    let mut failures = Vec::new();
    let mut compared = 0;
    let mut explained = Vec::new();
    let mut worst = 0.0f64;
    for (k, s) in reference["shots"].as_array().unwrap().iter().enumerate() {
        let (shot, names) = play(s);
        let theirs = s["events"].as_array().unwrap();
        let ours = shot.events();
        let n = theirs.len().max(ours.len());
        for i in 0..n {
            let (Some(mine), Some(their)) = (ours.get(i), theirs.get(i)) else {
                failures.push(format!(
                    "shot {k}: {} events in ccdsim, {} in pooltool",
                    ours.len(),
                    theirs.len()
                ));
                break;
            };
            let (kind, agents) = mine.kind.names(shot.table(), &names);
            let their_agents: Vec<String> = their["agents"]
                .as_array()
                .unwrap()
                .iter()
                .map(|a| a.as_str().unwrap().to_owned())
                .collect();
            let dt = (mine.time - num(&their["time"])).abs();
            let fine = num(&s["fine_gap_events"][i]["time"]);
            let dt_fine = (mine.time - fine).abs();
            let nudged = dt > 1e-6 && dt_fine <= 1e-6 && dt_fine < dt;
            if kind != their["type"].as_str().unwrap()
                || agents != their_agents
                || (dt > 1e-6 && !nudged)
            {
                failures.push(format!(
                    "shot {k} event {i}: ccdsim {kind} {agents:?} at {}, pooltool {} {:?} at {} \
                     ({fine} with the finer nudge)",
                    mine.time, their["type"], their_agents, their["time"]
                ));
                break;
            }
            if nudged {
                explained.push(format!("shot {k} event {i}: {dt:.1e} s, {dt_fine:.1e} s"));
            } else {
                worst = worst.max(dt);
            }
            compared += 1;
        }
        for (i, name) in names.iter().enumerate() {
            let pocketed = shot.balls()[i].pocket.is_some();
            let their = s["final"][name.as_str()]["state"].as_str().unwrap() == "pocketed";
            if pocketed != their {
                failures.push(format!(
                    "shot {k}: ball {name} pocketed {pocketed} vs {their}"
                ));
            }
        }
    }
    assert!(
        failures.is_empty(),
        "{} of the shots differ ({compared} events agreed):\n{}",
        failures.len(),
        failures.join("\n")
    );
    assert!(compared > 1000, "{compared}");
    // The nudge explains a few late, slow events, not the shots at large.
    assert!(explained.len() <= 20, "{explained:?}");
    eprintln!(
        "{compared} events as pooltool's; largest difference {worst:.1e} s; {} further off \
         by pooltool's nudge (difference from pooltool, from pooltool with the finer nudge): {}",
        explained.len(),
        explained.join("; ")
    );
}
