//! Playing a pool shot's run file (format version 16) back: the table, the events with
//! pooltool's names, and the balls sampled at a fixed rate with a marker fixed in each ball
//! that turns with its angular velocity, for the pool page (`assets/pool.js`).
//!
//! Positions and angular velocities come from the records through the cloth's motion laws
//! ([`ccdsim::motion::ClothParams::evolve`]); the marker's orientation is the angular
//! velocity integrated in steps of at most a millisecond (each a rotation about the axis of
//! the angular velocity at its middle), which is for the eye only.

use crate::error::ViewerError;
use ccdsim::billiards::{open_pool_run, BallAfter, PoolRecord, PoolScene, Table};
use ccdsim::motion::ClothParams;
use ccdsim::record::Tail;
use ccdsim::Vector;
use serde_json::{json, Value};
use std::path::Path;

/// Frames per second of the sampled shot.
pub const POOL_FRAME_RATE: f64 = 120.0;
/// Integration steps of the markers per frame.
const MARKER_STEPS: usize = 8;
/// Most frames sampled (a shot longer than this many frames is sampled more coarsely).
const MAX_FRAMES: usize = 20_000;

/// A pool shot's run file read for playback.
pub struct PoolPlayback {
    path: String,
    scene: PoolScene,
    table: Table,
    cloth: ClothParams,
    records: Vec<PoolRecord>,
    end: f64,
    tail: Tail,
}

impl PoolPlayback {
    /// Reads the run file at `path` whole (a shot has at most a few thousand records).
    ///
    /// # Errors
    /// The file cannot be read or is not a pool shot's run file.
    pub fn open(path: &Path) -> Result<PoolPlayback, ViewerError> {
        let mut reader = open_pool_run(path)?;
        let mut records = Vec::new();
        while let Some(rec) = reader.next_record()? {
            records.push(rec);
        }
        let end = records.last().map_or(0.0, PoolRecord::time);
        let shot = reader.scene().shot().map_err(|e| ViewerError::BadRun {
            path: reader.path().to_string(),
            why: e.to_string(),
        })?;
        Ok(PoolPlayback {
            path: reader.path().to_string(),
            scene: reader.scene().clone(),
            table: reader.table().clone(),
            cloth: shot.params().cloth,
            records,
            end,
            tail: reader.tail(),
        })
    }

    /// The shot's duration, seconds (its last record's time).
    #[must_use]
    pub fn end(&self) -> f64 {
        self.end
    }

    /// The records, in order.
    #[must_use]
    pub fn records(&self) -> &[PoolRecord] {
        &self.records
    }

    /// The table.
    #[must_use]
    pub fn table(&self) -> &Table {
        &self.table
    }

    /// The balls' radius, metres.
    #[must_use]
    pub fn radius(&self) -> f64 {
        self.cloth.radius
    }

    /// The balls' names (`cue`, `1`, …), in the scene's order.
    #[must_use]
    pub fn names(&self) -> Vec<String> {
        self.scene.names()
    }

    /// Where each ball is at time `t` (seconds from the strike), or `None` for a ball that
    /// dropped into a pocket at or before `t`.
    #[must_use]
    pub fn balls_at(&self, t: f64) -> Vec<Option<[f64; 2]>> {
        let mut balls = self.start_states();
        let mut pocketed = vec![false; balls.len()];
        for rec in self.records.iter().take_while(|r| r.time() <= t) {
            apply_record(rec, &mut balls);
            if let PoolRecord::Event { event, .. } = rec {
                if let ccdsim::billiards::ShotEventKind::Pocket { ball, .. } = event.kind {
                    pocketed[ball] = true;
                }
            }
        }
        balls
            .iter()
            .zip(pocketed)
            .map(|((b, since), gone)| {
                let at = self.cloth.evolve(&b.ball, b.state, t - since);
                (!gone).then_some([at.pos[0], at.pos[1]])
            })
            .collect()
    }

    /// Every ball at rest where the scene places it, as of time 0.
    fn start_states(&self) -> Vec<(BallAfter, f64)> {
        self.scene
            .pool
            .balls
            .iter()
            .map(|b| {
                (
                    BallAfter {
                        ball: ccdsim::motion::ClothBall {
                            pos: Vector(b.pos),
                            vel: Vector::ZERO,
                            spin: Vector::ZERO,
                        },
                        state: ccdsim::motion::ClothState::Stationary,
                    },
                    0.0,
                )
            })
            .collect()
    }

    /// Everything the pool page draws, as JSON: `file`, `names`, `radius` (m), `table`
    /// (`width`, `length`, `cushions` `[x1, y1, x2, y2]`, `jaws` and `pockets` `[x, y, r]`,
    /// metres), `end` (s), `events` (`t`, `type`, `agents`, pooltool's names; the strike is
    /// `"strike"`), `pocketed` (each ball's pocketing time or null), `warning` (a file that
    /// did not end cleanly), and the frames: `dt` (s), `count`, then per frame and ball
    /// `pos` (`x`, `y`), `marker` (a unit vector fixed in the ball, `x`, `y`, `z` with `z`
    /// up) and `state` (0 stationary, 1 spinning, 2 sliding, 3 rolling), flattened frame by
    /// frame.
    #[must_use]
    pub fn page_json(&self) -> Value {
        let names = self.scene.names();
        let n = names.len();
        let t = &self.table;
        let r = self.cloth.radius;
        let events: Vec<Value> = self
            .records
            .iter()
            .filter_map(|rec| match rec {
                PoolRecord::Strike { time, ball, .. } => Some(json!({
                    "t": time, "type": "strike", "agents": [names[*ball]],
                })),
                PoolRecord::Event { event, .. } => {
                    let (kind, agents) = event.kind.names(t, &names);
                    Some(json!({ "t": event.time, "type": kind, "agents": agents }))
                }
                PoolRecord::End(_) => None,
            })
            .collect();
        let mut pocketed: Vec<Option<f64>> = vec![None; n];
        for rec in &self.records {
            if let PoolRecord::Event { event, .. } = rec {
                if let ccdsim::billiards::ShotEventKind::Pocket { ball, .. } = event.kind {
                    pocketed[ball] = Some(event.time);
                }
            }
        }
        let frames = self.frames();
        json!({
            "file": self.path,
            "names": names,
            "radius": r,
            "table": {
                "width": t.width,
                "length": t.length,
                "cushions": t.cushions.iter().map(|c| [c.p1[0], c.p1[1], c.p2[0], c.p2[1]]).collect::<Vec<_>>(),
                "jaws": t.jaws.iter().map(|j| [j.center[0], j.center[1], j.radius]).collect::<Vec<_>>(),
                "pockets": t.pockets.iter().map(|p| [p.center[0], p.center[1], p.radius]).collect::<Vec<_>>(),
            },
            "end": self.end,
            "events": events,
            "pocketed": pocketed,
            "warning": self.tail.warning(),
            "dt": frames.dt,
            "count": frames.count,
            "pos": frames.pos,
            "marker": frames.marker,
            "state": frames.state,
        })
    }

    /// The shot sampled every `dt` seconds from 0 to its end (see [`PoolPlayback::page_json`]).
    fn frames(&self) -> Frames {
        let n = self.scene.pool.balls.len();
        let mut dt = 1.0 / POOL_FRAME_RATE;
        if self.end / dt > MAX_FRAMES as f64 {
            dt = self.end / MAX_FRAMES as f64;
        }
        let count = (self.end / dt).ceil() as usize + 1;
        let mut balls = self.start_states();
        // Each ball's marker starts straight up, tipped a little so that a spin about the
        // vertical shows too.
        let tip = 0.35f64;
        let mut markers = vec![Vector([tip.sin(), 0.0, tip.cos()]); n];
        let mut next = 0;
        let mut out = Frames {
            dt,
            count,
            pos: Vec::with_capacity(count * n * 2),
            marker: Vec::with_capacity(count * n * 3),
            state: Vec::with_capacity(count * n),
        };
        let apply = |upto: f64, next: &mut usize, balls: &mut [(BallAfter, f64)]| {
            while let Some(rec) = self.records.get(*next) {
                if rec.time() > upto {
                    break;
                }
                apply_record(rec, balls);
                *next += 1;
            }
        };
        let round = |x: f64, k: f64| (x * k).round() / k;
        for f in 0..count {
            let t = (f as f64 * dt).min(self.end);
            if f > 0 {
                let t0 = ((f - 1) as f64 * dt).min(self.end);
                let h = (t - t0) / MARKER_STEPS as f64;
                for s in 0..MARKER_STEPS {
                    let ts = t0 + h * s as f64;
                    apply(ts, &mut next, &mut balls);
                    for (i, m) in markers.iter_mut().enumerate() {
                        let (b, since) = &balls[i];
                        let w = self
                            .cloth
                            .evolve(&b.ball, b.state, ts + 0.5 * h - since)
                            .spin;
                        *m = rotate(*m, w, h);
                    }
                }
            }
            apply(t, &mut next, &mut balls);
            for (i, (b, since)) in balls.iter().enumerate() {
                let at = self.cloth.evolve(&b.ball, b.state, t - since);
                out.pos.push(round(at.pos[0], 1e7));
                out.pos.push(round(at.pos[1], 1e7));
                out.marker
                    .extend(markers[i].0.iter().map(|&c| round(c, 1e4)));
                out.state.push(match b.state {
                    ccdsim::motion::ClothState::Stationary => 0,
                    ccdsim::motion::ClothState::Spinning => 1,
                    ccdsim::motion::ClothState::Sliding => 2,
                    ccdsim::motion::ClothState::Rolling => 3,
                });
            }
        }
        out
    }
}

/// The states `rec` leaves its balls in, each with the time it starts from.
fn apply_record(rec: &PoolRecord, balls: &mut [(BallAfter, f64)]) {
    match *rec {
        PoolRecord::Strike { time, ball, after } => balls[ball] = (after, time),
        PoolRecord::Event {
            event,
            after,
            after_b,
        } => {
            use ccdsim::billiards::ShotEventKind as K;
            let (a, b) = match event.kind {
                K::Balls { a, b } => (a, Some(b)),
                K::Transition { ball, .. }
                | K::Cushion { ball, .. }
                | K::Jaw { ball, .. }
                | K::Pocket { ball, .. } => (ball, None),
            };
            balls[a] = (after, event.time);
            if let (Some(b), Some(after_b)) = (b, after_b) {
                balls[b] = (after_b, event.time);
            }
        }
        PoolRecord::End(_) => {}
    }
}

struct Frames {
    dt: f64,
    count: usize,
    pos: Vec<f64>,
    marker: Vec<f64>,
    state: Vec<u8>,
}

/// `m` turned for `h` seconds at angular velocity `w` (rad/s): Rodrigues' rotation about
/// `w`'s axis by `|w|·h`, renormalised against drift.
fn rotate(m: Vector<3>, w: Vector<3>, h: f64) -> Vector<3> {
    let speed = w.norm();
    if speed == 0.0 || h == 0.0 {
        return m;
    }
    let k = w * (1.0 / speed);
    let (s, c) = (speed * h).sin_cos();
    let kxm = Vector([
        k[1] * m[2] - k[2] * m[1],
        k[2] * m[0] - k[0] * m[2],
        k[0] * m[1] - k[1] * m[0],
    ]);
    let r = m * c + kxm * s + k * (k.dot(m) * (1.0 - c));
    r * (1.0 / r.norm())
}

#[cfg(test)]
mod tests {
    use super::*;
    use ccdsim::billiards::{record_shot, Game, PoolRunWriter};

    #[test]
    fn a_rolling_ball_turns_its_marker_about_the_axis_across_its_path() {
        // Rolling along +y: ω = ẑ×v/R points along −x, and the top of the ball moves
        // forward, along +y.
        let m = rotate(Vector([0.0, 0.0, 1.0]), Vector([-10.0, 0.0, 0.0]), 1e-3);
        assert!(m[1] > 0.0 && m[2] > 0.0, "{m:?}");
        let quarter = (0..100).fold(Vector([0.0, 0.0, 1.0]), |m, _| {
            rotate(m, Vector([-std::f64::consts::FRAC_PI_2, 0.0, 0.0]), 0.01)
        });
        assert!(
            (quarter - Vector([0.0, 1.0, 0.0])).norm() < 1e-12,
            "{quarter:?}"
        );
    }

    #[test]
    fn a_break_plays_back_frame_by_frame() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("break.ccd");
        let scene = PoolScene::racked(Game::NineBall, 1);
        let (shot, _) = record_shot(
            &scene,
            PoolRunWriter::create(&path, &scene).unwrap(),
            10_000,
        )
        .unwrap();
        let p = PoolPlayback::open(&path).unwrap();
        assert_eq!(p.end(), shot.time());
        let v = p.page_json();
        let n = shot.balls().len();
        let count = v["count"].as_u64().unwrap() as usize;
        assert_eq!(v["pos"].as_array().unwrap().len(), count * n * 2);
        assert_eq!(
            v["events"].as_array().unwrap().len(),
            shot.events().len() + 1
        );
        // The last frame is where the shot left the balls.
        let pos = v["pos"].as_array().unwrap();
        for (i, b) in shot.balls().iter().enumerate() {
            let at = (count - 1) * n * 2 + 2 * i;
            let x = pos[at].as_f64().unwrap();
            assert!((x - b.ball.pos[0]).abs() < 1e-6, "ball {i}");
        }
        assert_eq!(v["table"]["pockets"].as_array().unwrap().len(), 6);
    }
}
