//! The features a case exercises, read from its scene and drive: what the fuzzer's coverage
//! table counts.

use crate::case::{Case, EditOp, Schedule};
use serde_json::Value;

/// Every feature name [`features`] can report, in the order the coverage table prints them.
pub const FEATURES: [&str; 35] = [
    "3D",
    "periodic",
    "sheared box",
    "segment walls",
    "plane walls",
    "open (no walls)",
    "gravity",
    "restitution < 1",
    "TC model",
    "resting contacts",
    "growth",
    "thermostat",
    "sensors",
    "moving walls",
    "arrivals",
    "kinematic bodies",
    "per-body restitution",
    "collision groups",
    "heavy bodies",
    "rough bodies",
    "spinning bodies",
    "bodies at rest",
    "bodies touching",
    "body on a lattice face",
    "start time ≠ 0",
    "frames",
    "velocity edits",
    "teleports",
    "bodies added",
    "bodies removed",
    "filter or wall edits",
    "velocity rescales",
    "pool shots",
    "pool: balls touching",
    "pool: frictional",
];

fn nonzero(v: &Value) -> bool {
    v.as_array()
        .is_some_and(|a| a.iter().any(|x| x.as_f64().is_some_and(|x| x != 0.0)))
}

fn components(v: &Value) -> Vec<f64> {
    v.as_array()
        .map(|a| a.iter().filter_map(Value::as_f64).collect())
        .unwrap_or_default()
}

/// The features `case` exercises (a subset of [`FEATURES`]).
#[must_use]
pub fn features(case: &Case) -> Vec<&'static str> {
    let s = &case.scene;
    if case.is_pool() {
        return pool_features(&s["pool"]);
    }
    let mut out = Vec::new();
    let mut add = |on: bool, name: &'static str| {
        if on {
            out.push(name);
        }
    };
    let settings = &s["settings"];
    let bodies = s["bodies"].as_array().cloned().unwrap_or_default();
    let walls = s["walls"].as_array().cloned().unwrap_or_default();
    add(s["dim"].as_u64() == Some(3), "3D");
    add(!s["periodic"].is_null(), "periodic");
    add(!settings["shear_rate"].is_null(), "sheared box");
    add(walls.iter().any(|w| !w["a"].is_null()), "segment walls");
    add(walls.iter().any(|w| !w["normal"].is_null()), "plane walls");
    add(
        walls.is_empty() && s["periodic"].is_null(),
        "open (no walls)",
    );
    add(!settings["gravity"].is_null(), "gravity");
    add(
        settings["restitution"].as_f64().is_some_and(|e| e < 1.0),
        "restitution < 1",
    );
    add(!settings["tc"].is_null(), "TC model");
    add(!settings["rest_speed"].is_null(), "resting contacts");
    add(!settings["growth"].is_null(), "growth");
    add(!settings["thermostat"].is_null(), "thermostat");
    add(
        s["sensors"].as_array().is_some_and(|a| !a.is_empty()),
        "sensors",
    );
    add(
        s["moving_walls"].as_array().is_some_and(|a| !a.is_empty()),
        "moving walls",
    );
    add(
        s["arrivals"].as_array().is_some_and(|a| !a.is_empty()),
        "arrivals",
    );
    add(
        bodies
            .iter()
            .any(|b| b["kinematic"].as_bool() == Some(true)),
        "kinematic bodies",
    );
    add(
        bodies.iter().any(|b| !b["restitution"].is_null()),
        "per-body restitution",
    );
    add(
        bodies.iter().any(|b| !b["group"].is_null()),
        "collision groups",
    );
    add(bodies.iter().any(|b| !b["mass"].is_null()), "heavy bodies");
    add(
        !settings["tangential_restitution"].is_null()
            || bodies
                .iter()
                .any(|b| !b["tangential_restitution"].is_null()),
        "rough bodies",
    );
    add(
        bodies.iter().any(|b| !b["spin"].is_null()),
        "spinning bodies",
    );
    add(bodies.iter().any(|b| !nonzero(&b["vel"])), "bodies at rest");
    let placed: Vec<(Vec<f64>, f64)> = bodies
        .iter()
        .map(|b| (components(&b["pos"]), b["radius"].as_f64().unwrap_or(0.0)))
        .collect();
    let touching = placed.iter().enumerate().any(|(i, (p, r))| {
        placed[..i].iter().any(|(q, s)| {
            let d2: f64 = p.iter().zip(q).map(|(a, b)| (a - b) * (a - b)).sum();
            d2 == (r + s) * (r + s)
        })
    });
    add(touching, "bodies touching");
    // Integer and half-integer coordinates are where hand-written scenes put bodies, and where
    // a grid over a box of integer sides has its faces.
    add(
        placed
            .iter()
            .any(|(p, _)| p.iter().any(|x| (2.0 * x).fract() == 0.0)),
        "body on a lattice face",
    );
    add(
        s["start_time"].as_f64().is_some_and(|t| t != 0.0),
        "start time ≠ 0",
    );
    add(matches!(case.schedule, Schedule::Frames { .. }), "frames");
    let has = |f: fn(&EditOp) -> bool| case.edits.iter().any(f);
    add(
        has(|e| matches!(e, EditOp::Velocity { .. })),
        "velocity edits",
    );
    add(has(|e| matches!(e, EditOp::Position { .. })), "teleports");
    add(has(|e| matches!(e, EditOp::Add { .. })), "bodies added");
    add(
        has(|e| matches!(e, EditOp::Remove { .. })),
        "bodies removed",
    );
    add(
        has(|e| matches!(e, EditOp::Filter { .. } | EditOp::WallVelocity { .. })),
        "filter or wall edits",
    );
    add(
        has(|e| matches!(e, EditOp::Rescale { .. })),
        "velocity rescales",
    );
    out
}

/// The features of a pool case (its scene's `pool` object).
fn pool_features(pool: &Value) -> Vec<&'static str> {
    let mut out = vec!["pool shots"];
    let at: Vec<Vec<f64>> = pool["balls"]
        .as_array()
        .map(|a| a.iter().map(|b| components(&b["pos"])).collect())
        .unwrap_or_default();
    let diameter = 2.0 * ccdsim::billiards::BallParams::default().radius();
    let touching = at.iter().enumerate().any(|(i, p)| {
        at[..i].iter().any(|q| {
            let d = p
                .iter()
                .zip(q)
                .map(|(a, b)| (a - b).powi(2))
                .sum::<f64>()
                .sqrt();
            (d - diameter).abs() <= 1e-12
        })
    });
    if touching {
        out.push("pool: balls touching");
    }
    if !pool["ball_ball"].is_null() {
        out.push("pool: frictional");
    }
    out
}
