//! `ccdsim._ccdsim.pool_shot` and `pool_rack`: a pool shot played to the end, and the racks
//! (see the library's `billiards` module).

use ccdsim::billiards::{
    rack, record_struck, BallParams, Game, PocketTableSpecs, PoolBall, PoolBallBall, PoolFinder,
    PoolRunWriter, PoolScene, PoolSceneError, PoolSetup, PoolShot, Shot, Table,
};
use pyo3::exceptions::{PyOSError, PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// The names and positions of `game`'s rack ("nine-ball" or "eight-ball") on pooltool's
/// default table, seeded: a list of `(name, x, y)`, the cue ball first.
#[pyfunction]
#[pyo3(signature = (game="nine-ball", seed=1))]
pub fn pool_rack(game: &str, seed: u64) -> PyResult<Vec<(String, f64, f64)>> {
    let game = match game {
        "nine-ball" => Game::NineBall,
        "eight-ball" => Game::EightBall,
        g => {
            return Err(PyValueError::new_err(format!(
                "game must be \"nine-ball\" or \"eight-ball\", not {g:?}"
            )))
        }
    };
    let table = Table::pool(&PocketTableSpecs::default());
    Ok(rack(game, &table, BallParams::default().radius(), seed)
        .into_iter()
        .map(|(name, p)| (name, p[0], p[1]))
        .collect())
}

/// Plays one shot on pooltool's default table with its default balls: `balls` is a list of
/// `(name, x, y)` (metres), ball `cue` is struck (`speed` m/s towards `phi` degrees, cue
/// elevation `theta` degrees, tip offsets `a` and `b` in ball radii), and the shot runs until
/// every ball rests or is pocketed (at most `max_events` events). Returns a dict: `events`
/// (a list of `(time, type, agents)` with pooltool's type names), `positions` (name → (x, y)
/// at the end), `pocketed` (name → pocket id, in the order they dropped), `time` (when the
/// last ball stopped, s), `pressings` and `pressing_energy` (balls pressed together and
/// parted, and the joules that added). `ball_ball`, `(restitution, friction or None)`, makes
/// balls meet by the frictional model (see `ccdsim::billiards::ball_impact`); without it they
/// meet without friction, elastically. With `record`, the shot's run file is written there
/// (format version 16: `ccdsim verify`, `view` and `export` read it). `finder` names how each
/// event is found (`all-pairs`, `sedgewick`, `cells`, `bvh`: the same events, bit for bit).
/// Runs without the GIL.
#[pyfunction]
#[pyo3(signature = (balls, speed, phi, theta=0.0, a=0.0, b=0.0, cue="cue", max_events=1_000_000, ball_ball=None, record=None, finder="cells"))]
#[allow(clippy::too_many_arguments)]
pub fn pool_shot<'py>(
    py: Python<'py>,
    balls: Vec<(String, f64, f64)>,
    speed: f64,
    phi: f64,
    theta: f64,
    a: f64,
    b: f64,
    cue: &str,
    max_events: usize,
    ball_ball: Option<(f64, Option<f64>)>,
    record: Option<std::path::PathBuf>,
    finder: &str,
) -> PyResult<Bound<'py, PyDict>> {
    let finder: PoolFinder = finder.parse().map_err(PyValueError::new_err)?;
    let names: Vec<String> = balls.iter().map(|(n, _, _)| n.clone()).collect();
    if !names.iter().any(|n| n == cue) {
        return Err(PyValueError::new_err(format!("no ball named {cue:?}")));
    }
    let scene = PoolScene {
        pool: PoolSetup {
            balls: balls
                .iter()
                .map(|(name, x, y)| PoolBall {
                    name: name.clone(),
                    pos: [*x, *y],
                })
                .collect(),
            shot: PoolShot {
                ball: cue.to_string(),
                speed,
                phi,
                theta,
                a,
                b,
            },
            ball_ball: ball_ball.map(|(restitution, friction)| PoolBallBall {
                restitution,
                friction,
            }),
        },
    };
    let refused = |e: PoolSceneError| PyValueError::new_err(e.to_string());
    let writer = match &record {
        Some(path) => {
            scene.shot().map_err(refused)?;
            Some(
                PoolRunWriter::create(path, &scene)
                    .map_err(|e| PyOSError::new_err(e.to_string()))?,
            )
        }
        None => None,
    };
    let mut shot = scene.shot().map_err(refused)?;
    shot.set_finder(finder);
    let shot = py
        .detach(move || -> Result<Shot, String> {
            match writer {
                Some(w) => {
                    let (shot, played) = record_struck(shot, scene.struck_ball(), w, max_events)
                        .map_err(|e| e.to_string())?;
                    played.map(|_| shot).map_err(|e| e.describe(&scene.names()))
                }
                None => {
                    let mut shot = shot;
                    shot.run(max_events)
                        .map(|_| shot)
                        .map_err(|e| e.describe(&scene.names()))
                }
            }
        })
        .map_err(PyRuntimeError::new_err)?;
    let out = PyDict::new(py);
    let events: Vec<(f64, String, Vec<String>)> = shot
        .events()
        .iter()
        .map(|e| {
            let (kind, agents) = e.kind.names(shot.table(), &names);
            (e.time, kind, agents)
        })
        .collect();
    out.set_item("events", events)?;
    let end = PyDict::new(py);
    for (i, name) in names.iter().enumerate() {
        let p = shot.balls()[i].ball.pos;
        end.set_item(name, (p[0], p[1]))?;
    }
    out.set_item("positions", end)?;
    let pocketed = PyDict::new(py);
    for e in shot.events() {
        if let ccdsim::billiards::ShotEventKind::Pocket { ball, pocket } = e.kind {
            pocketed.set_item(&names[ball], &shot.table().pockets[pocket].id)?;
        }
    }
    out.set_item("pocketed", pocketed)?;
    out.set_item("time", shot.time())?;
    let (pressings, pressing_energy) = shot.pressings();
    out.set_item("pressings", pressings)?;
    out.set_item("pressing_energy", pressing_energy)?;
    Ok(out)
}
