//! The keyframe index: every body's state every `K` events, built in one streaming pass.
//!
//! A run file can be larger than memory, so the viewer never holds its events. It holds the
//! full state after every `K`-th event instead (in a run where bodies rest on walls, with the
//! wall each body rests on); the state after any event `k` is then the
//! keyframe at or before `k` plus at most `K − 1` records replayed from the file (records are
//! fixed-size, so record `k` is at a known offset). `K` is chosen so that all keyframes fit a
//! memory budget; a run that adds bodies, and so outgrows the estimate made from its scene,
//! doubles `K` (dropping every other keyframe) whenever its keyframes would not fit.

use crate::error::ViewerError;
use crate::extent::{Extent, ExtentBuilder};
use crate::states::{edit_code, BodyStates};
use ccdsim::record::{RunReader, RunRecord, Tail};
use ccdsim::EventKind;
use std::io::Read;

/// How densely to keyframe.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct KeyframeOptions {
    /// Upper bound on the memory all keyframes take together, bytes (estimated from the file
    /// length before the pass).
    pub budget_bytes: usize,
    /// Smallest interval `K` between keyframes, events (> 0).
    pub min_interval: u64,
}

impl Default for KeyframeOptions {
    fn default() -> Self {
        KeyframeOptions {
            budget_bytes: 256 << 20,
            min_interval: 1024,
        }
    }
}

impl KeyframeOptions {
    /// The interval `K` for a run of about `events` events and `bodies` bodies in `D`
    /// dimensions: the budget's, but at least `min_interval`.
    #[must_use]
    pub fn interval<const D: usize>(&self, events: u64, bodies: usize) -> u64 {
        self.interval_for(events, bodies, BodyStates::<D>::bytes_per_body())
    }

    /// The interval `K` for a run of about `events` events and `bodies` bodies of
    /// `bytes_per_body` bytes each in a keyframe (see [`BodyStates::bytes_per_body_of`]): the
    /// budget's, but at least `min_interval`.
    #[must_use]
    pub fn interval_for(&self, events: u64, bodies: usize, bytes_per_body: usize) -> u64 {
        let per_frame = (bytes_per_body.max(1) * bodies.max(1)) as u128;
        let frames_fitting = (self.budget_bytes as u128 / per_frame).max(1);
        let k = (u128::from(events)).div_ceil(frames_fitting);
        (k as u64).max(self.min_interval.max(1))
    }
}

/// One keyframe: the state after the first `applied` events.
#[derive(Clone, Debug, PartialEq)]
pub struct Keyframe<const D: usize> {
    /// Events applied.
    pub applied: u64,
    /// Time of the last applied event (the run's start time for the first keyframe), seconds.
    pub time: f64,
    /// Every body's state.
    pub states: BodyStates<D>,
}

impl<const D: usize> Keyframe<D> {
    /// Heap bytes this keyframe adds to the one before it, `before` (the slot table counts
    /// only when it is not the one `before` shares).
    fn bytes_after(&self, before: Option<&Keyframe<D>>) -> usize {
        let s = &self.states;
        if before.is_some_and(|b| b.states.shares_slot_table(s)) {
            s.heap_bytes() - s.slot_table_bytes()
        } else {
            s.heap_bytes()
        }
    }
}

/// Keyframes of a whole run, and what the pass learnt about it.
#[derive(Clone, Debug)]
pub struct KeyframeIndex<const D: usize> {
    /// Events between keyframes.
    pub interval: u64,
    /// `keyframes[j]` holds the state after `j · interval` events; `keyframes[0]` is the start.
    pub keyframes: Vec<Keyframe<D>>,
    /// Events in the file (the end record excluded).
    pub events: u64,
    /// Time of the last event, or the start time when there is none, seconds.
    pub last_event_time: f64,
    /// Time the run stopped at, when the file ends with an end record, seconds.
    pub end_time: Option<f64>,
    /// How the file ended.
    pub tail: Tail,
    /// The space the run uses and its top speed.
    pub extent: Extent<D>,
    /// The largest number of body slots over the run: the scene's bodies, or more when
    /// bodies were added past them (see [`BodyStates`]).
    pub slots: usize,
    /// True when the run adds or removes bodies.
    pub slot_edits: bool,
}

impl<const D: usize> KeyframeIndex<D> {
    /// Reads every record of `reader` from the first one on, keyframing every `interval`
    /// events, or every `2^j · interval` when the keyframes after the first would take more
    /// than `budget_bytes` (a run whose added bodies outgrow its scene). Refuses events that
    /// go back in time, and records naming slots that hold no body (see
    /// [`BodyStates::check`]) or an added body without its id record right after it.
    pub fn build<R: Read>(
        reader: &mut RunReader<R, D>,
        interval: u64,
        budget_bytes: usize,
    ) -> Result<Self, ViewerError> {
        let scene = reader.scene().clone();
        let mut interval = interval.max(1);
        let mut states = BodyStates::from_scene(&scene);
        let mut keyframes = vec![Keyframe {
            applied: 0,
            time: scene.start_time,
            states: states.clone(),
        }];
        // Bytes of the keyframes after the first (the interval was sized for those).
        let mut bytes = 0usize;
        let (mut events, mut last, mut end_time) = (0u64, scene.start_time, None);
        let mut extent = ExtentBuilder::new(&scene);
        // The added body whose id record must come next, and when it was added.
        let mut pending_add: Option<(u32, f64)> = None;
        while let Some(rec) = reader.next_record()? {
            match rec {
                RunRecord::Event(c) => {
                    let t = c.event.time;
                    let bad = |why: String| ViewerError::BadRun {
                        path: reader.path().to_string(),
                        why: format!("event {events} (t = {t}) {why}"),
                    };
                    if t < last {
                        return Err(bad(format!(
                            "is earlier than the one before it (t = {last})"
                        )));
                    }
                    let is_id = c.event.kind == EventKind::Edit && c.event.b == edit_code::ADD_ID;
                    match pending_add.take() {
                        Some((a, at)) if !(is_id && c.event.a == a && t == at) => {
                            return Err(bad(format!(
                                "follows the added body {a} instead of its id record"
                            )))
                        }
                        None if is_id => {
                            return Err(bad("is an id record without its added body".into()))
                        }
                        _ => {}
                    }
                    states.check(&c).map_err(bad)?;
                    if c.event.kind == EventKind::Edit && c.event.b == edit_code::ADD {
                        pending_add = Some((c.event.a, t));
                    }
                    // The extent reads the states the collision ends (their arcs under gravity).
                    extent.add(&c, &states);
                    states.apply(&c);
                    events += 1;
                    last = t;
                    if events % interval == 0 {
                        let kf = Keyframe {
                            applied: events,
                            time: t,
                            states: states.clone(),
                        };
                        bytes += kf.bytes_after(keyframes.last());
                        keyframes.push(kf);
                        while bytes > budget_bytes && keyframes.len() > 2 {
                            interval *= 2;
                            keyframes.retain(|k| k.applied % interval == 0);
                            bytes = (1..keyframes.len())
                                .map(|j| keyframes[j].bytes_after(Some(&keyframes[j - 1])))
                                .sum();
                        }
                    }
                }
                RunRecord::End(t) => end_time = Some(t),
            }
        }
        // A file cut between an added body and its id record plays up to the cut: the body is
        // there, its id unknown (`u64::MAX`).
        let extent = extent.finish(&states, end_time.unwrap_or(last), &scene.walls);
        Ok(KeyframeIndex {
            interval,
            keyframes,
            events,
            last_event_time: last,
            end_time,
            tail: reader.tail(),
            extent,
            slots: states.len(),
            slot_edits: states.has_slot_edits(),
        })
    }

    /// The last keyframe whose time is at most `t` (or the first one).
    #[must_use]
    pub fn at_or_before_time(&self, t: f64) -> &Keyframe<D> {
        let j = self.keyframes.partition_point(|k| k.time <= t);
        &self.keyframes[j.saturating_sub(1)]
    }

    /// The last keyframe whose time is strictly before `t` (or the first one).
    #[must_use]
    pub fn before_time(&self, t: f64) -> &Keyframe<D> {
        let j = self.keyframes.partition_point(|k| k.time < t);
        &self.keyframes[j.saturating_sub(1)]
    }

    /// The last keyframe with at most `k` events applied.
    #[must_use]
    pub fn at_or_before_event(&self, k: u64) -> &Keyframe<D> {
        let j = (k / self.interval) as usize;
        &self.keyframes[j.min(self.keyframes.len() - 1)]
    }

    /// Heap bytes the keyframes hold (a slot table shared by consecutive keyframes counted
    /// once).
    #[must_use]
    pub fn heap_bytes(&self) -> usize {
        let k = &self.keyframes;
        (0..k.len())
            .map(|j| k[j].bytes_after(j.checked_sub(1).map(|i| &k[i])))
            .sum()
    }
}
