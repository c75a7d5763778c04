//! A pool scene file: the balls on pooltool's default table and the shot to play, as JSON.
//!
//! ```json
//! {"pool": {"balls": [{"name": "cue", "pos": [0.842, 0.456]},
//!                     {"name": "1", "pos": [0.495, 1.526]}],
//!           "shot": {"ball": "cue", "speed": 8.0, "phi": 108.0}}}
//! ```
//!
//! `shot` also takes `theta` (cue elevation, degrees), `a` and `b` (tip offsets in ball radii),
//! all zero by default. Units are metres, m/s and degrees, as [`CueStrike`]'s. Balls meet
//! without friction and elastically unless `pool` has `"ball_ball": {"restitution": e_b,
//! "friction": u_b}`, the frictional model ([`BallBallModel::FrictionalInelastic`]; `e_b` is
//! 0.95 by default, and without `friction` the coefficient follows Alciatore's curve).

use serde::{Deserialize, Serialize};
use thiserror::Error;

use super::params::{BallBallModel, BallFriction, BallParams};
use super::rack::Game;
use super::shot::{Shot, ShotError};
use super::table::{PocketTableSpecs, Table};
use crate::geom::Vector;
use crate::motion::CueStrike;

/// A ball of a pool scene: its name and where it stands (metres).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PoolBall {
    /// The ball's name ("cue", "1", …).
    pub name: String,
    /// Position on the table, metres.
    pub pos: [f64; 2],
}

/// The shot of a pool scene: which ball the cue strikes, and how.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PoolShot {
    /// The name of the ball struck.
    pub ball: String,
    /// Cue speed, m/s.
    pub speed: f64,
    /// Direction, degrees counter-clockwise from `+x`.
    pub phi: f64,
    /// Cue elevation, degrees.
    #[serde(default)]
    pub theta: f64,
    /// Side offset of the tip, ball radii.
    #[serde(default)]
    pub a: f64,
    /// Vertical offset of the tip, ball radii.
    #[serde(default)]
    pub b: f64,
}

/// The frictional ball–ball model of a pool scene ([`BallBallModel::FrictionalInelastic`]).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PoolBallBall {
    /// Coefficient of restitution between two balls, `e_b` in [0, 1] (0.95).
    #[serde(default = "PoolBallBall::default_restitution")]
    pub restitution: f64,
    /// Coefficient of friction between two balls' surfaces, `u_b` ≥ 0; without it,
    /// Alciatore's curve ([`BallFriction::ALCIATORE`]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub friction: Option<f64>,
}

impl PoolBallBall {
    fn default_restitution() -> f64 {
        0.95
    }

    /// The model, or why the numbers cannot be one ([`PoolSceneError::Format`]).
    ///
    /// # Errors
    /// A restitution outside [0, 1] or a friction that is not a number ≥ 0.
    pub fn model(&self) -> Result<BallBallModel, PoolSceneError> {
        if !(0.0..=1.0).contains(&self.restitution) {
            return Err(PoolSceneError::Format(format!(
                "pool.ball_ball.restitution: {} is not in [0, 1]",
                self.restitution
            )));
        }
        let friction = match self.friction {
            None => BallFriction::ALCIATORE,
            Some(u) if u.is_finite() && u >= 0.0 => BallFriction::Constant(u),
            Some(u) => {
                return Err(PoolSceneError::Format(format!(
                    "pool.ball_ball.friction: {u} is not a number ≥ 0"
                )))
            }
        };
        Ok(BallBallModel::FrictionalInelastic {
            restitution: self.restitution,
            friction,
        })
    }
}

/// What a pool scene holds.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PoolSetup {
    /// The balls, in order.
    pub balls: Vec<PoolBall>,
    /// The shot.
    pub shot: PoolShot,
    /// The frictional ball–ball model; without it, balls meet without friction, elastically.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ball_ball: Option<PoolBallBall>,
}

/// A pool scene file: `{"pool": {...}}`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PoolScene {
    /// The balls and the shot.
    pub pool: PoolSetup,
}

/// Why a pool scene cannot be read or set up.
#[derive(Debug, Error)]
pub enum PoolSceneError {
    /// Not JSON, or not a pool scene's fields (the path says where).
    #[error("{0}")]
    Format(String),
    /// Two balls share a name.
    #[error("two balls are named {0:?}")]
    DuplicateName(String),
    /// The shot names a ball that is not there.
    #[error("the shot strikes {0:?}, which is not one of the balls")]
    NoSuchBall(String),
    /// The balls or the strike are refused by the table (the message names the balls).
    #[error("{1}")]
    Shot(ShotError, String),
}

impl PoolScene {
    /// Whether a JSON document is a pool scene (a top-level object with a `pool` key), so
    /// that a reader can tell it from a ccdsim scene before parsing it.
    #[must_use]
    pub fn is_pool_json(json: &str) -> bool {
        serde_json::from_str::<serde_json::Value>(json)
            .is_ok_and(|v| v.as_object().is_some_and(|o| o.contains_key("pool")))
    }

    /// Parses a pool scene.
    ///
    /// # Errors
    /// [`PoolSceneError::Format`] with the path of the bad field.
    pub fn from_json(json: &str) -> Result<PoolScene, PoolSceneError> {
        let de = &mut serde_json::Deserializer::from_str(json);
        serde_path_to_error::deserialize(de).map_err(|e| {
            let path = e.path().to_string();
            PoolSceneError::Format(format!("{path}: {}", e.into_inner()))
        })
    }

    /// The scene as pretty-printed JSON.
    #[must_use]
    pub fn to_json(&self) -> String {
        serde_json::to_string_pretty(self).expect("a pool scene serialises") + "\n"
    }

    /// `game`'s rack on pooltool's default table (seeded: [`super::rack`]) with the break:
    /// the cue ball struck at 8 m/s straight at the first object ball, without friction
    /// between the balls.
    #[must_use]
    pub fn racked(game: Game, seed: u64) -> PoolScene {
        let table = Table::pool(&PocketTableSpecs::default());
        let balls = super::rack(game, &table, BallParams::default().radius(), seed);
        let d = balls[1].1 - balls[0].1;
        PoolScene {
            pool: PoolSetup {
                balls: balls
                    .iter()
                    .map(|(name, p)| PoolBall {
                        name: name.clone(),
                        pos: p.0,
                    })
                    .collect(),
                shot: PoolShot {
                    ball: balls[0].0.clone(),
                    speed: 8.0,
                    phi: d[1].atan2(d[0]).to_degrees().rem_euclid(360.0),
                    theta: 0.0,
                    a: 0.0,
                    b: 0.0,
                },
                ball_ball: None,
            },
        }
    }

    /// The index of the ball the shot strikes (the first ball when no ball has its name: the
    /// scene's [`PoolScene::shot`] refuses such a scene).
    #[must_use]
    pub fn struck_ball(&self) -> usize {
        self.pool
            .balls
            .iter()
            .position(|b| b.name == self.pool.shot.ball)
            .unwrap_or(0)
    }

    /// The balls' names, in order.
    #[must_use]
    pub fn names(&self) -> Vec<String> {
        self.pool.balls.iter().map(|b| b.name.clone()).collect()
    }

    /// The shot set up on pooltool's default table with its default balls, struck and ready
    /// to run.
    ///
    /// # Errors
    /// Duplicate names, a shot at a ball that is not there, balls off the table or
    /// overlapping, a tip that misses.
    pub fn shot(&self) -> Result<Shot, PoolSceneError> {
        let names = self.names();
        for (i, n) in names.iter().enumerate() {
            if names[..i].contains(n) {
                return Err(PoolSceneError::DuplicateName(n.clone()));
            }
        }
        let s = &self.pool.shot;
        let cue = names
            .iter()
            .position(|n| *n == s.ball)
            .ok_or_else(|| PoolSceneError::NoSuchBall(s.ball.clone()))?;
        let positions: Vec<Vector<2>> = self.pool.balls.iter().map(|b| Vector(b.pos)).collect();
        let table = Table::pool(&PocketTableSpecs::default());
        let named = |e: ShotError| {
            let text = e.describe(&names);
            PoolSceneError::Shot(e, text)
        };
        let params = BallParams {
            ball_ball: match &self.pool.ball_ball {
                None => BallBallModel::FrictionlessElastic,
                Some(b) => b.model()?,
            },
            ..BallParams::default()
        };
        let mut shot = Shot::new(table, params, &positions).map_err(named)?;
        shot.strike(
            cue,
            &CueStrike {
                speed: s.speed,
                phi: s.phi,
                theta: s.theta,
                a: s.a,
                b: s.b,
            },
        )
        .map_err(named)?;
        Ok(shot)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_pool_scene_reads_back_and_plays() {
        let json = r#"{"pool": {"balls": [{"name": "cue", "pos": [0.5, 0.5]},
                                          {"name": "1", "pos": [0.5, 1.2]}],
                                "shot": {"ball": "cue", "speed": 2.0, "phi": 90.0}}}"#;
        assert!(PoolScene::is_pool_json(json));
        assert!(!PoolScene::is_pool_json(r#"{"dim": 2, "bodies": []}"#));
        let scene = PoolScene::from_json(json).unwrap();
        assert_eq!(PoolScene::from_json(&scene.to_json()).unwrap(), scene);
        let mut shot = scene.shot().unwrap();
        shot.run(100_000).unwrap();
        assert!(shot.events().len() > 3);
    }

    #[test]
    fn bad_pool_scenes_say_what_is_wrong() {
        let err = PoolScene::from_json(r#"{"pool": {"balls": [], "shot": {"ball": "cue"}}}"#)
            .unwrap_err();
        assert!(err.to_string().contains("pool.shot"), "{err}");
        let twice = r#"{"pool": {"balls": [{"name": "cue", "pos": [0.5, 0.5]},
                                           {"name": "cue", "pos": [0.5, 1.0]}],
                                 "shot": {"ball": "cue", "speed": 1, "phi": 0}}}"#;
        let e = PoolScene::from_json(twice).unwrap().shot().unwrap_err();
        assert!(matches!(e, PoolSceneError::DuplicateName(_)));
        let missing = r#"{"pool": {"balls": [{"name": "cue", "pos": [0.5, 0.5]}],
                                   "shot": {"ball": "white", "speed": 1, "phi": 0}}}"#;
        let e = PoolScene::from_json(missing).unwrap().shot().unwrap_err();
        assert!(e.to_string().contains("white"), "{e}");
        for (field, says) in [
            (r#"{"restitution": 1.5}"#, "restitution"),
            (r#"{"friction": -0.1}"#, "friction"),
            (r#"{"friction": 0.1, "spin": 2}"#, "unknown field"),
        ] {
            let json = format!(
                r#"{{"pool": {{"balls": [{{"name": "cue", "pos": [0.5, 0.5]}}],
                             "shot": {{"ball": "cue", "speed": 1, "phi": 0}},
                             "ball_ball": {field}}}}}"#
            );
            let e = PoolScene::from_json(&json).and_then(|s| s.shot().map(|_| ()));
            let e = e.expect_err(field).to_string();
            assert!(e.contains(says) && e.contains("ball_ball"), "{field}: {e}");
        }
    }

    #[test]
    fn a_frictional_scene_plays_with_its_model_and_reads_back() {
        let json = r#"{"pool": {"balls": [{"name": "cue", "pos": [0.5, 0.5]},
                                          {"name": "1", "pos": [0.5, 1.0]}],
                                "shot": {"ball": "cue", "speed": 2, "phi": 88},
                                "ball_ball": {"friction": 0.06}}}"#;
        let scene = PoolScene::from_json(json).unwrap();
        let b = scene.pool.ball_ball.as_ref().unwrap();
        assert_eq!((b.restitution, b.friction), (0.95, Some(0.06)));
        assert_eq!(PoolScene::from_json(&scene.to_json()).unwrap(), scene);
        let shot = scene.shot().unwrap();
        assert_eq!(
            shot.params().ball_ball,
            BallBallModel::FrictionalInelastic {
                restitution: 0.95,
                friction: BallFriction::Constant(0.06)
            }
        );
        // The same cut without friction sends the object ball elsewhere.
        let mut plain = scene.clone();
        plain.pool.ball_ball = None;
        let end = |s: &PoolScene| {
            let mut shot = s.shot().unwrap();
            shot.run(10_000).unwrap();
            shot.balls()[1].ball.pos
        };
        let (a, b) = (end(&scene), end(&plain));
        assert!((a - b).norm() > 1e-3, "{a:?} {b:?}");
    }
}
