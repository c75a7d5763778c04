//! The cloth motion laws and the cue strike against pooltool 0.3.3: every ball of
//! `tests/data/pooltool-cloth.json` (written by `scripts/pooltool-reference` from pooltool's
//! own `evolve_ball_motion`, `get_slide_time`, `get_roll_time`, `get_spin_time` and
//! `cue_strike`) evolved by ccdsim to the same times, and every shot launched, must agree to
//! 10⁻⁹ relative (pooltool rotates into the ball's frame and back, ccdsim does not: the
//! difference is rounding).

use ccdsim::motion::cloth::settle;
use ccdsim::motion::{ClothBall, ClothParams, ClothState, CueStrike};
use ccdsim::Vector;
use serde_json::Value;

use crate::reference_json::{num, vec_of};

const REFERENCE: &str = include_str!("../data/pooltool-cloth.json");

fn state_of(name: &Value) -> ClothState {
    match name.as_str().expect("a state") {
        "stationary" => ClothState::Stationary,
        "spinning" => ClothState::Spinning,
        "sliding" => ClothState::Sliding,
        "rolling" => ClothState::Rolling,
        s => panic!("unknown state {s}"),
    }
}

/// `|a − b| ≤ 10⁻⁹·scale`, with `scale` the size of the quantity (a speed, a spin, a length).
fn near(a: f64, b: f64, scale: f64) -> bool {
    (a - b).abs() <= 1e-9 * scale.max(1e-3)
}

fn params(reference: &Value) -> ClothParams {
    let p = &reference["params"];
    ClothParams {
        radius: num(&p["radius"]),
        sliding_friction: num(&p["sliding_friction"]),
        rolling_friction: num(&p["rolling_friction"]),
        spinning_friction: num(&p["spinning_friction"]),
        gravity: num(&p["gravity"]),
    }
}

#[test]
fn the_default_parameters_are_pooltools() {
    let reference: Value = serde_json::from_str(REFERENCE).unwrap();
    let p = params(&reference);
    let d = ClothParams::default();
    assert_eq!(p.radius, d.radius);
    assert_eq!(p.sliding_friction, d.sliding_friction);
    assert_eq!(p.rolling_friction, d.rolling_friction);
    assert!(near(
        p.spinning_friction,
        d.spinning_friction,
        d.spinning_friction
    ));
    assert_eq!(p.gravity, d.gravity);
}

#[test]
fn balls_evolve_as_in_pooltool_through_every_transition() {
    let reference: Value = serde_json::from_str(REFERENCE).unwrap();
    let p = params(&reference);
    let cases = reference["evolve"].as_array().unwrap();
    assert!(cases.len() >= 100, "{} cases", cases.len());
    let mut states_seen = std::collections::HashSet::new();
    for (k, case) in cases.iter().enumerate() {
        let ball = ClothBall {
            pos: vec_of(&case["pos"]),
            vel: vec_of(&case["vel"]),
            spin: vec_of(&case["spin"]),
        };
        let state = state_of(&case["state"]);
        let t = num(&case["t"]);
        // The state's own duration, as pooltool's transition cache computes it.
        let times = &case["times"];
        let want_span = match state {
            ClothState::Sliding => Some(num(&times["slide"])),
            ClothState::Rolling => Some(num(&times["roll"])),
            ClothState::Spinning => Some(num(&times["spin"])),
            ClothState::Stationary => None,
        };
        let span = p.transition(&ball, state).map(|(s, _)| s);
        assert_eq!(span.is_some(), want_span.is_some(), "case {k}");
        if let (Some(s), Some(w)) = (span, want_span) {
            assert!(near(s, w, w), "case {k}: lasts {s} s, pooltool {w} s");
        }
        let (got, got_state) = p.advance(&ball, state, t);
        let after = &case["after"];
        let want_state = state_of(&after["state"]);
        states_seen.insert((state, want_state));
        assert_eq!(got_state, want_state, "case {k} at t = {t}");
        // pooltool leaves a spinning or stationary ball's rounding residues in place until its
        // transition event resolves them; ccdsim settles them at the transition.
        let want = settle(
            ClothBall {
                pos: vec_of(&after["pos"]),
                vel: vec_of(&after["vel"]),
                spin: vec_of(&after["spin"]),
            },
            want_state,
        );
        let speed = ball.vel.norm().max(p.radius * ball.spin.norm());
        let spin = ball.spin.norm().max(ball.vel.norm() / p.radius);
        for d in 0..2 {
            assert!(
                near(got.pos[d], want.pos[d], 1.0),
                "case {k}: position {:?}, pooltool {:?}",
                got.pos,
                want.pos
            );
            assert!(
                near(got.vel[d], want.vel[d], speed),
                "case {k}: velocity {:?}, pooltool {:?}",
                got.vel,
                want.vel
            );
        }
        for d in 0..3 {
            assert!(
                near(got.spin[d], want.spin[d], spin),
                "case {k}: spin {:?}, pooltool {:?}",
                got.spin,
                want.spin
            );
        }
    }
    // The grid reaches every transition.
    for pair in [
        (ClothState::Sliding, ClothState::Sliding),
        (ClothState::Sliding, ClothState::Rolling),
        (ClothState::Sliding, ClothState::Stationary),
        (ClothState::Rolling, ClothState::Spinning),
        (ClothState::Spinning, ClothState::Stationary),
    ] {
        assert!(states_seen.contains(&pair), "no case goes {pair:?}");
    }
}

#[test]
fn the_cue_strike_launches_as_in_pooltool() {
    let reference: Value = serde_json::from_str(REFERENCE).unwrap();
    let p = params(&reference);
    let m = num(&reference["params"]["mass"]);
    let strikes = reference["strikes"].as_array().unwrap();
    assert!(!strikes.is_empty());
    for (k, s) in strikes.iter().enumerate() {
        let strike = CueStrike {
            speed: num(&s["V0"]),
            phi: num(&s["phi"]),
            theta: num(&s["theta"]),
            a: num(&s["a"]),
            b: num(&s["b"]),
        };
        let (v, w) = strike
            .launch(m, p.radius, num(&s["cue_mass"]), true)
            .expect("a ball the tip hits");
        let want_v: Vector<3> = vec_of(&s["vel"]);
        let want_w: Vector<3> = vec_of(&s["spin"]);
        assert_eq!(
            want_v[2], 0.0,
            "strike {k}: pooltool's ball leaves along the table"
        );
        let speed = want_v.norm();
        let spin = want_w.norm().max(speed / p.radius);
        for d in 0..2 {
            assert!(
                near(v[d], want_v[d], speed),
                "strike {k}: {v:?} vs {want_v:?}"
            );
        }
        for d in 0..3 {
            assert!(
                near(w[d], want_w[d], spin),
                "strike {k}: {w:?} vs {want_w:?}"
            );
        }
    }
}
