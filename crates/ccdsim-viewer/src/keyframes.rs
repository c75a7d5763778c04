//! The keyframe index: every body's state every `K` events, built in one streaming pass.
//!
//! A run file can be larger than memory, so the viewer never holds its events. It holds the
//! full state after every `K`-th event instead; the state after any event `k` is then the
//! keyframe at or before `k` plus at most `K − 1` records replayed from the file (records are
//! fixed-size, so record `k` is at a known offset). `K` is chosen so that all keyframes fit a
//! memory budget.

use crate::error::ViewerError;
use crate::extent::{Extent, ExtentBuilder};
use crate::states::BodyStates;
use ccdsim::record::{RunReader, RunRecord, Tail};
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
        let per_frame = (BodyStates::<D>::bytes_per_body() * bodies.max(1)) as u128;
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
}

impl<const D: usize> KeyframeIndex<D> {
    /// Reads every record of `reader` from the first one on, keyframing every `interval`
    /// events. Refuses events that go back in time.
    pub fn build<R: Read>(
        reader: &mut RunReader<R, D>,
        interval: u64,
    ) -> Result<Self, ViewerError> {
        let scene = reader.scene().clone();
        let mut states = BodyStates::from_scene(&scene);
        let mut keyframes = vec![Keyframe {
            applied: 0,
            time: scene.start_time,
            states: states.clone(),
        }];
        let (mut events, mut last, mut end_time) = (0u64, scene.start_time, None);
        let mut extent = ExtentBuilder::new(&scene);
        while let Some(rec) = reader.next_record()? {
            match rec {
                RunRecord::Event(c) => {
                    let t = c.event.time;
                    if t < last {
                        return Err(ViewerError::BadRun {
                            path: reader.path().to_string(),
                            why: format!("event {events} at t = {t} is earlier than the one before it (t = {last})"),
                        });
                    }
                    // The extent reads the states the collision ends (their arcs under gravity).
                    extent.add(&c, &states);
                    states.apply(&c);
                    events += 1;
                    last = t;
                    if events % interval == 0 {
                        keyframes.push(Keyframe {
                            applied: events,
                            time: t,
                            states: states.clone(),
                        });
                    }
                }
                RunRecord::End(t) => end_time = Some(t),
            }
        }
        let extent = extent.finish(&states, end_time.unwrap_or(last), &scene.walls);
        Ok(KeyframeIndex {
            interval,
            keyframes,
            events,
            last_event_time: last,
            end_time,
            tail: reader.tail(),
            extent,
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

    /// Heap bytes the keyframes hold.
    #[must_use]
    pub fn heap_bytes(&self) -> usize {
        self.keyframes.iter().map(|k| k.states.heap_bytes()).sum()
    }
}
