//! Playing a run file back: the state at any time or after any event, event windows and the
//! finder's boxes, all served from the keyframe index plus short replays from the file.

use crate::error::ViewerError;
use crate::extent::Extent;
use crate::keyframes::{KeyframeIndex, KeyframeOptions};
use crate::states::BodyStates;
use ccdsim::finder::DebugBox;
use ccdsim::record::{open_run, record_len, AnyRunReader, RunReader, RunRecord, Tail};
use ccdsim::{make_finder, Collision, FinderOptions, Scene, World};
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
        let interval = options.interval::<D>(records, n);
        let index = KeyframeIndex::build(&mut reader, interval)?;
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

    /// The run's world rebuilt to `snap`: the bodies' stored states as the simulation had
    /// them, and the clock at the snapshot's time.
    pub fn world_at(&self, snap: &Snapshot<D>) -> Result<World<D>, ViewerError> {
        let mut world = World::from_scene(&self.scene)?;
        for i in 0..snap.states.len() {
            world.set_motion(i, snap.states.motion(i));
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

fn open_file(path: &Path) -> Result<(File, u64), ViewerError> {
    let io = |source| ViewerError::Io {
        what: path.display().to_string(),
        source,
    };
    let file = File::open(path).map_err(io)?;
    let len = file.metadata().map_err(io)?.len();
    Ok((file, len))
}
