//! Playing a run file back: the state at any time or after any event, event windows and the
//! finder's boxes, all served from the keyframe index plus short replays from the file.

use crate::error::ViewerError;
use crate::extent::Extent;
use crate::keyframes::{KeyframeIndex, KeyframeOptions};
use crate::states::BodyStates;
use ccdsim::finder::DebugBox;
use ccdsim::record::{open_run, record_len, AnyRunReader, RunReader, RunRecord, Tail};
use ccdsim::{make_finder, BodySpec, Collision, FinderOptions, Scene, Vector, World};
use std::fs::File;
use std::io::BufReader;
use std::path::Path;

/// The state of every body at one instant of a run.
#[derive(Clone, Debug, PartialEq)]
pub struct Snapshot<const D: usize> {
    /// The instant, seconds.
    pub time: f64,
    /// Events applied: every event at or before `time` (or the first `applied` events when
    /// asked by event count).
    pub applied: u64,
    /// The bodies' stored states after those events.
    pub states: BodyStates<D>,
    /// The last applied event, if any.
    pub last: Option<Collision<D>>,
}

/// A `D`-dimensional run file opened for playback.
pub struct Playback<const D: usize> {
    reader: RunReader<BufReader<File>, D>,
    scene: Scene<D>,
    index: KeyframeIndex<D>,
}

/// A run of either dimension opened for playback.
pub enum AnyPlayback {
    /// A 2D run.
    D2(Playback<2>),
    /// A 3D run.
    D3(Playback<3>),
}

impl AnyPlayback {
    /// Opens the run at `path` and builds its keyframe index in one pass over the file.
    pub fn open(path: &Path, options: &KeyframeOptions) -> Result<Self, ViewerError> {
        let (_, len) = open_file(path)?;
        Ok(match open_run(path)? {
            AnyRunReader::D2(r) => AnyPlayback::D2(Playback::from_reader(r, len, options)?),
            AnyRunReader::D3(r) => AnyPlayback::D3(Playback::from_reader(r, len, options)?),
        })
    }

    /// The run's dimension, 2 or 3.
    #[must_use]
    pub fn dim(&self) -> usize {
        match self {
            AnyPlayback::D2(_) => 2,
            AnyPlayback::D3(_) => 3,
        }
    }
}

impl<const D: usize> Playback<D> {
    /// Opens a `D`-dimensional run at `path` and builds its keyframe index; see
    /// [`AnyPlayback::open`] for either dimension.
    pub fn open(path: &Path, options: &KeyframeOptions) -> Result<Self, ViewerError> {
        let (file, len) = open_file(path)?;
        let reader = RunReader::new(
            BufReader::with_capacity(1 << 16, file),
            path.display().to_string(),
        )?;
        Self::from_reader(reader, len, options)
    }

    /// Builds the keyframe index of the run `reader` is positioned at the first record of;
    /// `file_len` (bytes) sizes the keyframe interval to the budget.
    pub fn from_reader(
        mut reader: RunReader<BufReader<File>, D>,
        file_len: u64,
        options: &KeyframeOptions,
    ) -> Result<Self, ViewerError> {
        let records = file_len.saturating_sub(reader.data_start()) / record_len(D) as u64;
        let n = reader.scene().bodies.len();
        let per_body = BodyStates::<D>::bytes_per_body_of(reader.scene());
        let interval = options.interval_for(records, n, per_body);
        let index = KeyframeIndex::build(&mut reader, interval, options.budget_bytes)?;
        Ok(Playback {
            scene: reader.scene().clone(),
            reader,
            index,
        })
    }

    /// The scene the run started from.
    #[must_use]
    pub fn scene(&self) -> &Scene<D> {
        &self.scene
    }

    /// The run's bounds and largest speed.
    #[must_use]
    pub fn extent(&self) -> &Extent<D> {
        &self.index.extent
    }

    /// The run file's name.
    #[must_use]
    pub fn path(&self) -> &str {
        self.reader.path()
    }

    /// Number of events in the run.
    #[must_use]
    pub fn events(&self) -> u64 {
        self.index.events
    }

    /// Simulated time the run starts at, seconds.
    #[must_use]
    pub fn start_time(&self) -> f64 {
        self.scene.start_time
    }

    /// Simulated time the run ends at: its end record's time, or the last event's when the
    /// file has no end record, seconds.
    #[must_use]
    pub fn end_time(&self) -> f64 {
        self.index
            .end_time
            .unwrap_or(self.index.last_event_time)
            .max(self.scene.start_time)
    }

    /// True when the file ends with an end record.
    #[must_use]
    pub fn complete(&self) -> bool {
        self.index.tail == Tail::Complete
    }

    /// The largest number of body slots over the run (the scene's bodies, or more when the
    /// run adds bodies past them).
    #[must_use]
    pub fn slots(&self) -> usize {
        self.index.slots
    }

    /// True when the run adds or removes bodies.
    #[must_use]
    pub fn has_slot_edits(&self) -> bool {
        self.index.slot_edits
    }

    /// True when bodies may rest on walls in the run (its scene has `settings.rest_speed`;
    /// run files of format version 11, or 12 when they rest on segments too): each body's
    /// support is kept, and the API's answers carry it (see [`crate::wire`]).
    #[must_use]
    pub fn has_rests(&self) -> bool {
        self.scene.settings.rest_speed.is_some()
    }

    /// The keyframe index.
    #[must_use]
    pub fn index(&self) -> &KeyframeIndex<D> {
        &self.index
    }

    /// Reads event `k` (0-based) from the file.
    pub fn event(&mut self, k: u64) -> Result<Collision<D>, ViewerError> {
        self.events_window(k, 1)?.pop().ok_or_else(|| {
            ViewerError::param(
                "event",
                format!("no event {k} (the run has {})", self.index.events),
            )
        })
    }

    /// Up to `count` events from event `from` on.
    pub fn events_window(
        &mut self,
        from: u64,
        count: u64,
    ) -> Result<Vec<Collision<D>>, ViewerError> {
        let count = count.min(self.index.events.saturating_sub(from));
        let mut out = Vec::with_capacity(count as usize);
        if count == 0 {
            return Ok(out);
        }
        self.reader.seek_record(from)?;
        while (out.len() as u64) < count {
            match self.reader.next_record()? {
                Some(RunRecord::Event(c)) => out.push(c),
                Some(RunRecord::End(_)) | None => break,
            }
        }
        Ok(out)
    }

    /// Starts a replay at keyframe `kf`: its state and its last event.
    fn start_from(&mut self, kf_applied: u64) -> Result<Snapshot<D>, ViewerError> {
        let kf = self.index.at_or_before_event(kf_applied).clone();
        let last = if kf.applied > 0 {
            Some(self.event(kf.applied - 1)?)
        } else {
            None
        };
        self.reader.seek_record(kf.applied)?;
        Ok(Snapshot {
            time: kf.time,
            applied: kf.applied,
            states: kf.states,
            last,
        })
    }

    /// Applies events while `keep(event time)` holds; leaves the reader past them.
    fn replay_while(
        &mut self,
        snap: &mut Snapshot<D>,
        limit: u64,
        keep: impl Fn(f64) -> bool,
    ) -> Result<(), ViewerError> {
        while snap.applied < limit {
            match self.reader.next_record()? {
                Some(RunRecord::Event(c)) if keep(c.event.time) => {
                    snap.states.apply(&c);
                    snap.applied += 1;
                    snap.last = Some(c);
                }
                _ => break,
            }
        }
        Ok(())
    }

    /// The state at time `t`: every event at or before `t` applied. Costs one keyframe copy
    /// and at most one keyframe interval of replayed records.
    pub fn snapshot_at(&mut self, t: f64) -> Result<Snapshot<D>, ViewerError> {
        if t.is_nan() {
            return Err(ViewerError::param("t", "is NaN"));
        }
        let applied = self.index.at_or_before_time(t).applied;
        let mut snap = self.start_from(applied)?;
        self.replay_while(&mut snap, self.index.events, |et| et <= t)?;
        snap.time = t;
        Ok(snap)
    }

    /// The state right after the first `k` events (clamped to the run's length), at the time
    /// of event `k − 1` (the start time for `k = 0`).
    pub fn snapshot_after(&mut self, k: u64) -> Result<Snapshot<D>, ViewerError> {
        let k = k.min(self.index.events);
        let mut snap = self.start_from(k)?;
        self.replay_while(&mut snap, k, |_| true)?;
        snap.time = snap.last.map_or(self.scene.start_time, |c| c.event.time);
        Ok(snap)
    }

    /// Time of the first event strictly after `t`, if any.
    pub fn next_event_time(&mut self, t: f64) -> Result<Option<f64>, ViewerError> {
        let from = self.index.at_or_before_time(t).applied;
        self.reader.seek_record(from)?;
        while let Some(rec) = self.reader.next_record()? {
            match rec {
                RunRecord::Event(c) if c.event.time > t => return Ok(Some(c.event.time)),
                RunRecord::Event(_) => {}
                RunRecord::End(_) => break,
            }
        }
        Ok(None)
    }

    /// Time of the last event strictly before `t`, if any.
    pub fn prev_event_time(&mut self, t: f64) -> Result<Option<f64>, ViewerError> {
        let kf = self.index.before_time(t).applied;
        let mut found = None;
        self.reader.seek_record(kf.saturating_sub(1))?;
        while let Some(rec) = self.reader.next_record()? {
            match rec {
                RunRecord::Event(c) if c.event.time < t => found = Some(c.event.time),
                _ => break,
            }
        }
        Ok(found)
    }

    /// The run's world rebuilt to `snap`, with the clock at the snapshot's time.
    ///
    /// Until a body is added or removed, this is the scene's world with every body's stored
    /// state as the simulation had it, resting bodies on their walls (its moving walls move as
    /// the scene started them, not as the run steered them: no finder sees moving walls). A
    /// body turning about a segment's end point ([`BodyStates::turn`]) is put where its turn
    /// has it at the snapshot's time, with its velocity then, and falls from there: the
    /// library offers no way to start a turn in a world it did not simulate (its own world
    /// shows finders such a body parked where its turn started).
    /// After that (the snapshot's states have slot edits), the world holds the snapshot's
    /// bodies only, vacant slots left out (so its indices are not the run's slots), each with
    /// its stored state, radius and kinematic flag, and the scene's settings; it has no walls
    /// or sensors (so no body rests on a wall in it: a resting body falls under `g` there),
    /// its bodies collide with nothing (group and mask 0, so that bodies that pass through
    /// each other in the run may overlap) and their ids and masses are the defaults. That is what a finder's boxes need (every
    /// body present, where it is), not a world to simulate on; the simulation's own world
    /// also holds its vacant and reserved slots, at rest and out of every collision.
    pub fn world_at(&self, snap: &Snapshot<D>) -> Result<World<D>, ViewerError> {
        let s = &snap.states;
        if !s.has_slot_edits() {
            let mut world = World::from_scene(&self.scene)?;
            for i in 0..s.len() {
                world.set_motion(i, world_motion(s, i, snap.time));
                if let Some(w) = s.support(i) {
                    // A wall bodies rest on: the keyframe pass checked it.
                    world.set_support(i, Some(w));
                }
            }
            world.set_time(snap.time);
            return Ok(world);
        }
        let present: Vec<usize> = (0..s.len()).filter(|&i| !s.is_vacant(i)).collect();
        // Built at the origin (which validates: they may overlap), then given their states.
        let scene = Scene {
            bodies: present
                .iter()
                .map(|&i| BodySpec {
                    kinematic: s.is_kinematic(i),
                    group: Some(0),
                    mask: Some(0),
                    ..BodySpec::new(Vector::ZERO, Vector::ZERO, s.radius(i))
                })
                .collect(),
            walls: Vec::new(),
            sensors: Vec::new(),
            moving_walls: Vec::new(),
            arrivals: Vec::new(),
            histogram: None,
            periodic: None,
            start_time: snap.time,
            settings: self.scene.settings,
        };
        let mut world = World::from_scene(&scene)?;
        for (k, &i) in present.iter().enumerate() {
            world.set_motion(k, world_motion(s, i, snap.time));
        }
        world.set_time(snap.time);
        Ok(world)
    }

    /// The boxes of the finder called `finder` (e.g. `bvh`) built on the world at `snap`, as
    /// the library computes them (swept leaf boxes and inner nodes with their depths).
    pub fn finder_boxes(
        &self,
        snap: &Snapshot<D>,
        finder: &str,
        options: &FinderOptions,
    ) -> Result<Vec<DebugBox<D>>, ViewerError> {
        let world = self.world_at(snap)?;
        let mut f = make_finder::<D>(finder, options)?;
        f.init(&world)?;
        Ok(f.debug_boxes(&world))
    }
}

/// Body `i`'s motion in a world rebuilt at time `t` (see [`Playback::world_at`]): its stored
/// state, or for a turning body its state on its turn at `t`.
fn world_motion<const D: usize>(s: &BodyStates<D>, i: usize, t: f64) -> ccdsim::Motion<D> {
    match s.turn(i) {
        Some(_) => ccdsim::Motion {
            pos: s.position_at(i, t),
            vel: s.velocity_at(i, t),
            time: t,
        },
        None => s.motion(i),
    }
}

fn open_file(path: &Path) -> Result<(File, u64), ViewerError> {
    let io = |source| ViewerError::Io {
        what: path.display().to_string(),
        source,
    };
    let file = File::open(path).map_err(io)?;
    let len = file.metadata().map_err(io)?.len();
    Ok((file, len))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::wire::{encode_snapshot, meta_json, STATE_HEADER};
    use ccdsim::generate::{gas, GasConfig};
    use ccdsim::record::RunWriter;
    use ccdsim::Gravity;
    use ccdsim::Simulation;
    use std::path::PathBuf;

    /// A run file's path in a fresh directory, removed when the returned guard is dropped.
    fn temp_file(name: &str) -> (tempfile::TempDir, PathBuf) {
        let dir = tempfile::Builder::new()
            .prefix(&format!("ccdsim-viewer-unit-{name}-"))
            .tempdir()
            .unwrap();
        let path = dir.path().join("run.ccdrun");
        (dir, path)
    }

    fn record<const D: usize>(scene: &Scene<D>, until: f64, path: &Path) -> u64 {
        let mut sim = Simulation::new(scene, "all-pairs").unwrap();
        let mut w = RunWriter::create(path, scene).unwrap();
        let n = sim.run_until_with(until, |c| w.write_event(c).unwrap());
        w.finish(until).unwrap();
        n
    }

    /// Small keyframe intervals, so that snapshots replay from several keyframes.
    const DENSE: KeyframeOptions = KeyframeOptions {
        budget_bytes: 1 << 20,
        min_interval: 16,
    };

    #[test]
    fn gravity_runs_play_back_on_parabolas() {
        let mut scene = gas::<2>(&GasConfig {
            n: 30,
            packing: 0.2,
            seed: 4,
            ..GasConfig::default()
        })
        .unwrap();
        scene.settings.gravity = Gravity::new(&[0.5, -9.81]);
        let (_dir, path) = temp_file("gravity");
        let events = record(&scene, 3.0, &path);
        assert!(events > 100, "{events}");
        let mut p = Playback::<2>::open(&path, &DENSE).unwrap();
        assert!(p.index().keyframes.len() > 3);
        assert_eq!(
            meta_json(&p, "cells")["gravity"],
            serde_json::json!([0.5, -9.81])
        );
        // Between events, the snapshot's bodies are where the simulation has them.
        let mut sim = Simulation::new(&scene, "all-pairs").unwrap();
        for k in 1..=20 {
            let t = 0.1371 * f64::from(k);
            sim.run_until(t);
            let snap = p.snapshot_at(t).unwrap();
            let wire = encode_snapshot(&snap);
            let floats: Vec<f32> = wire[8 * STATE_HEADER..]
                .chunks_exact(4)
                .map(|c| f32::from_le_bytes(c.try_into().unwrap()))
                .collect();
            for i in 0..snap.states.len() {
                let (want_p, want_v) = (sim.position(i), sim.world().velocity_at(i, t));
                let (got_p, got_v) = (snap.states.position_at(i, t), snap.states.velocity_at(i, t));
                assert!((got_p - want_p).norm() < 1e-12, "t = {t}, body {i}");
                assert!((got_v - want_v).norm() < 1e-12, "t = {t}, body {i}");
                // The page is sent the velocity at the snapshot's time.
                let n = snap.states.len();
                for d in 0..2 {
                    let sent = f64::from(floats[2 * n + 2 * i + d]);
                    assert!((sent - want_v[d]).abs() < 1e-5 * (1.0 + want_v.norm()));
                }
            }
        }
    }

    #[test]
    fn the_extent_holds_the_tops_of_the_arcs() {
        // Two balls thrown up in an open world, no walls and no collision: the bounds must
        // reach the tops of their arcs, which neither the start nor the end shows.
        let mut scene = Scene::<2> {
            bodies: vec![
                BodySpec::new(Vector([0.0, 0.0]), Vector([1.0, 10.0]), 0.5),
                BodySpec::new(Vector([5.0, 0.0]), Vector([-1.0, 5.0]), 0.5),
            ],
            ..Scene::default()
        };
        scene.settings.gravity = Gravity::new(&[0.0, -10.0]);
        let (_dir, path) = temp_file("arcs");
        assert_eq!(record(&scene, 2.0, &path), 0);
        let p = Playback::<2>::open(&path, &DENSE).unwrap();
        let e = *p.extent();
        // Ball 0 peaks at y = 5 at t = 1 (top of the ball 5.5) and is back at 0 at t = 2.
        assert!((e.bounds.max[1] - 5.5).abs() < 1e-12, "{e:?}");
        // Ball 1 ends lowest: y = 5·2 − 5·2² = −10.
        assert!((e.bounds.min[1] + 10.5).abs() < 1e-12, "{e:?}");
        // Speeds grow as they fall: ball 1 ends at √(1 + 15²).
        assert!((e.max_speed - 226f64.sqrt()).abs() < 1e-12, "{e:?}");
        let states = crate::states::BodyStates::from_scene(&scene);
        for k in 0..=200 {
            let t = 0.01 * f64::from(k);
            for i in 0..2 {
                let q = states.position_at(i, t);
                for d in 0..2 {
                    assert!(q[d] - 0.5 >= e.bounds.min[d] - 1e-12);
                    assert!(q[d] + 0.5 <= e.bounds.max[d] + 1e-12);
                }
            }
        }
    }
}
