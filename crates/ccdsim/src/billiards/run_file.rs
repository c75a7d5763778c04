//! Run files of pool shots: the pool scene, then the strike and every event with the states of
//! the balls it changed, written as the shot is played.
//!
//! # Format (version 16, little-endian)
//!
//! The preamble of every run file ([`crate::record`]): magic `CCDSIMRF`, format version 16
//! (`u32`), dimension 2 (`u32`), header length `h` (`u64`), then the pool scene as JSON (the
//! pool scene format, [`PoolScene`]), then records of [`POOL_RECORD_LEN`] = 135 bytes:
//!
//! | bytes | content |
//! |---|---|
//! | 1 | tag: 1 two balls meet, 2 a ball meets a straight cushion, 3 end of run, 6 a jaw, 7 a pocket, 8 a state change, 9 the cue's strike |
//! | 4 | `a` (`u32`): the ball (the lower-numbered of two) |
//! | 4 | `b` (`u32`): the other ball, the cushion, jaw or pocket (indices into the table's lists), the state that ends (a state change), 0 otherwise |
//! | 8 | `t` (`f64`), seconds |
//! | 56 | ball `a` after the record: position (2), velocity (2), angular velocity (3), `f64`s |
//! | 56 | ball `b` after a meeting of two balls, zeros otherwise |
//! | 1 | ball `a`'s motion state after the record (0 stationary, 1 spinning, 2 sliding, 3 rolling) |
//! | 1 | ball `b`'s, 0 unless two balls meet |
//! | 4 | FNV-1a checksum (`u32`) of the record's other bytes |
//!
//! A pocketed ball's state is its pocket's centre, at rest. The end record's `t` is the time
//! the shot stopped at. As for every run file, a run killed at any moment leaves a file that
//! reads back to its last complete record, and the reader refuses damaged records and trailing
//! data with errors that name the record.

use std::fs::File;
use std::io::{BufReader, BufWriter, Read, Write};
use std::path::Path;

use super::pool_scene::PoolScene;
use super::shot::Shot;
use super::shot_event::{ShotEvent, ShotEventKind};
use super::table::{PocketTableSpecs, Table};
use crate::geom::Vector;
use crate::motion::{ClothBall, ClothState};
use crate::record::{
    fnv1a, more_follows, read_frame, read_header, Frame, RecordError, Tail, MAGIC, PREAMBLE_LEN,
    VERSION_POOL,
};

/// Bytes in one record of a pool run file.
pub const POOL_RECORD_LEN: usize = 1 + 4 + 4 + 8 + 2 * 7 * 8 + 2 + 4;

const TAG_BALLS: u8 = 1;
const TAG_CUSHION: u8 = 2;
const TAG_END: u8 = 3;
const TAG_JAW: u8 = 6;
const TAG_POCKET: u8 = 7;
const TAG_TRANSITION: u8 = 8;
const TAG_STRIKE: u8 = 9;

/// A ball's state right after a record: where it is and how it moves, and its motion state.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BallAfter {
    /// Position (m), velocity (m/s) and angular velocity (rad/s).
    pub ball: ClothBall,
    /// Its motion state from then on.
    pub state: ClothState,
}

/// One record of a pool run file.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum PoolRecord {
    /// The cue strikes `ball` at `time` (seconds); it leaves as `after`.
    Strike {
        /// Time, seconds.
        time: f64,
        /// The ball struck.
        ball: usize,
        /// The ball as it leaves the cue.
        after: BallAfter,
    },
    /// An event of the shot, and the state after it of the ball it names (of both balls, `a`
    /// then `b`, when two meet).
    Event {
        /// The event.
        event: ShotEvent,
        /// Ball `a` (the event's only ball, or the lower-numbered of two) after it.
        after: BallAfter,
        /// Ball `b` after a meeting of two balls.
        after_b: Option<BallAfter>,
    },
    /// The shot stopped at this time, seconds: every ball at rest or pocketed, or the shot cut
    /// short (see `ccdsim::billiards::ShotError`).
    End(f64),
}

impl PoolRecord {
    /// The record of `ball`'s strike, from the shot just struck.
    #[must_use]
    pub fn strike(shot: &Shot, ball: usize) -> PoolRecord {
        PoolRecord::Strike {
            time: shot.time(),
            ball,
            after: after(shot, ball),
        }
    }

    /// The record of `event`, from the shot that has just played it.
    #[must_use]
    pub fn event(shot: &Shot, event: &ShotEvent) -> PoolRecord {
        let (a, b) = match event.kind {
            ShotEventKind::Balls { a, b } => (a, Some(b)),
            ShotEventKind::Transition { ball, .. }
            | ShotEventKind::Cushion { ball, .. }
            | ShotEventKind::Jaw { ball, .. }
            | ShotEventKind::Pocket { ball, .. } => (ball, None),
        };
        PoolRecord::Event {
            event: *event,
            after: after(shot, a),
            after_b: b.map(|b| after(shot, b)),
        }
    }

    /// The record's time, seconds.
    #[must_use]
    pub fn time(&self) -> f64 {
        match *self {
            PoolRecord::Strike { time, .. } | PoolRecord::End(time) => time,
            PoolRecord::Event { event, .. } => event.time,
        }
    }
}

fn after(shot: &Shot, i: usize) -> BallAfter {
    let b = &shot.balls()[i];
    BallAfter {
        ball: b.ball,
        state: b.state,
    }
}

fn state_code(s: ClothState) -> u8 {
    match s {
        ClothState::Stationary => 0,
        ClothState::Spinning => 1,
        ClothState::Sliding => 2,
        ClothState::Rolling => 3,
    }
}

fn state_of_code(c: u32) -> Option<ClothState> {
    Some(match c {
        0 => ClothState::Stationary,
        1 => ClothState::Spinning,
        2 => ClothState::Sliding,
        3 => ClothState::Rolling,
        _ => return None,
    })
}

/// Appends the records of a pool shot to a run file, buffered. The header is flushed at
/// creation, so a shot killed at any moment leaves a file that reads back to its last
/// complete record.
pub struct PoolRunWriter<W: Write> {
    out: BufWriter<W>,
    path: String,
    buf: Vec<u8>,
}

impl PoolRunWriter<File> {
    /// Creates (or truncates) `path` and writes the header holding `scene`.
    ///
    /// # Errors
    /// [`RecordError::Io`] when the file cannot be written.
    pub fn create(path: &Path, scene: &PoolScene) -> Result<Self, RecordError> {
        let name = path.display().to_string();
        let file = File::create(path).map_err(|source| RecordError::Io {
            path: name.clone(),
            source,
        })?;
        Self::new(file, name, scene)
    }
}

impl<W: Write> PoolRunWriter<W> {
    /// Writes the header holding `scene` to `out`; `name` is used in error messages.
    ///
    /// # Errors
    /// [`RecordError::Io`] when `out` fails.
    pub fn new(out: W, name: String, scene: &PoolScene) -> Result<Self, RecordError> {
        let mut out = BufWriter::with_capacity(1 << 14, out);
        let json = scene.to_json();
        let mut head = Vec::with_capacity(PREAMBLE_LEN + json.len());
        head.extend_from_slice(&MAGIC);
        head.extend_from_slice(&VERSION_POOL.to_le_bytes());
        head.extend_from_slice(&2u32.to_le_bytes());
        head.extend_from_slice(&(json.len() as u64).to_le_bytes());
        head.extend_from_slice(json.as_bytes());
        let io = |source| RecordError::Io {
            path: name.clone(),
            source,
        };
        out.write_all(&head).map_err(io)?;
        out.flush().map_err(io)?;
        Ok(PoolRunWriter {
            out,
            path: name,
            buf: Vec::with_capacity(POOL_RECORD_LEN),
        })
    }

    /// Appends one record.
    ///
    /// # Errors
    /// [`RecordError::Io`] when the file cannot be written.
    pub fn write(&mut self, record: &PoolRecord) -> Result<(), RecordError> {
        let none = BallAfter {
            ball: ClothBall {
                pos: Vector::ZERO,
                vel: Vector::ZERO,
                spin: Vector::ZERO,
            },
            state: ClothState::Stationary,
        };
        let (tag, a, b, t, first, second) = match *record {
            PoolRecord::Strike { time, ball, after } => (TAG_STRIKE, ball, 0, time, after, none),
            PoolRecord::End(time) => (TAG_END, 0, 0, time, none, none),
            PoolRecord::Event {
                event,
                after,
                after_b,
            } => {
                let (tag, a, b) = match event.kind {
                    ShotEventKind::Balls { a, b } => (TAG_BALLS, a, b),
                    ShotEventKind::Cushion { ball, cushion } => (TAG_CUSHION, ball, cushion),
                    ShotEventKind::Jaw { ball, jaw } => (TAG_JAW, ball, jaw),
                    ShotEventKind::Pocket { ball, pocket } => (TAG_POCKET, ball, pocket),
                    ShotEventKind::Transition { ball, from, .. } => {
                        (TAG_TRANSITION, ball, usize::from(state_code(from)))
                    }
                };
                (tag, a, b, event.time, after, after_b.unwrap_or(none))
            }
        };
        let index = |i: usize| {
            u32::try_from(i).map_err(|_| RecordError::Io {
                path: self.path.clone(),
                source: std::io::Error::other(format!("index {i} does not fit a record")),
            })
        };
        let (a, b) = (index(a)?, index(b)?);
        self.buf.clear();
        self.buf.push(tag);
        self.buf.extend_from_slice(&a.to_le_bytes());
        self.buf.extend_from_slice(&b.to_le_bytes());
        self.buf.extend_from_slice(&t.to_le_bytes());
        for s in [first, second] {
            let c = &s.ball;
            for x in c.pos.0.iter().chain(&c.vel.0).chain(&c.spin.0) {
                self.buf.extend_from_slice(&x.to_le_bytes());
            }
        }
        self.buf.push(state_code(first.state));
        self.buf.push(state_code(second.state));
        let sum = fnv1a(&self.buf);
        self.buf.extend_from_slice(&sum.to_le_bytes());
        debug_assert_eq!(self.buf.len(), POOL_RECORD_LEN);
        self.out
            .write_all(&self.buf)
            .map_err(|source| RecordError::Io {
                path: self.path.clone(),
                source,
            })
    }

    /// Writes the end record (the shot stopped at `time`), flushes and returns the inner
    /// writer.
    ///
    /// # Errors
    /// [`RecordError::Io`] when the file cannot be written.
    pub fn finish(mut self, time: f64) -> Result<W, RecordError> {
        self.write(&PoolRecord::End(time))?;
        let path = self.path.clone();
        self.out.into_inner().map_err(|e| RecordError::Io {
            path,
            source: e.into_error(),
        })
    }
}

/// Plays `scene`'s shot to the end (at most `max_events` events), writing its run file to
/// `out` as it goes; returns the shot as it ended and how the play ended. The file ends with
/// an end record either way.
///
/// # Errors
/// The scene cannot be set up (as a `RecordError::Header`), or the file cannot be written.
pub fn record_shot<W: Write>(
    scene: &PoolScene,
    out: PoolRunWriter<W>,
    max_events: usize,
) -> Result<(Shot, Result<usize, super::ShotError>), RecordError> {
    let shot = scene.shot().map_err(|e| RecordError::Header {
        path: out.path.clone(),
        why: e.to_string(),
    })?;
    record_struck(shot, scene.struck_ball(), out, max_events)
}

/// [`record_shot`] for a shot already set up and struck (ball `struck`) from the scene `out`
/// was created with: to play it with another finder ([`Shot::set_finder`]).
///
/// # Errors
/// The file cannot be written.
pub fn record_struck<W: Write>(
    mut shot: Shot,
    struck: usize,
    mut out: PoolRunWriter<W>,
    max_events: usize,
) -> Result<(Shot, Result<usize, super::ShotError>), RecordError> {
    out.write(&PoolRecord::strike(&shot, struck))?;
    let mut failed = None;
    let played = shot.run_with(max_events, |s, e| {
        if failed.is_none() {
            failed = out.write(&PoolRecord::event(s, e)).err();
        }
    });
    if let Some(e) = failed {
        return Err(e);
    }
    out.finish(shot.time())?;
    Ok((shot, played))
}

/// Reads the records of a pool shot's run file in order.
pub struct PoolRunReader<R: Read> {
    input: R,
    path: String,
    scene: PoolScene,
    table: Table,
    balls: usize,
    index: u64,
    data_start: u64,
    last_time: f64,
    tail: Tail,
    buf: [u8; POOL_RECORD_LEN],
}

/// Opens the run file of a pool shot and reads its header.
///
/// # Errors
/// The file cannot be read, is not a run file, is not a pool shot's (a scene's run file is
/// read by [`crate::record::open_run`]), or its header is not a valid pool scene.
pub fn open_pool_run(path: &Path) -> Result<PoolRunReader<BufReader<File>>, RecordError> {
    let name = path.display().to_string();
    let io = |source| RecordError::Io {
        path: name.clone(),
        source,
    };
    let file = File::open(path).map_err(io)?;
    let size = file.metadata().map_err(io)?.len();
    PoolRunReader::read(BufReader::new(file), name, Some(size))
}

impl<R: Read> PoolRunReader<R> {
    /// Reads the header of a pool run from `input`; `name` is used in errors.
    ///
    /// # Errors
    /// As [`open_pool_run`].
    pub fn new(input: R, name: String) -> Result<Self, RecordError> {
        Self::read(input, name, None)
    }

    fn read(mut input: R, name: String, size: Option<u64>) -> Result<Self, RecordError> {
        let (version, dim, json) = read_header(&mut input, &name, size)?;
        let header = |why: String| RecordError::Header {
            path: name.clone(),
            why,
        };
        if version != VERSION_POOL {
            return Err(header(format!(
                "format version {version} is a scene's run file, not a pool shot's \
                 (read it with ccdsim::record::open_run)"
            )));
        }
        if dim != 2 {
            return Err(header(format!("a pool shot is 2D, the file says {dim}D")));
        }
        let scene = PoolScene::from_json(&json).map_err(|e| header(e.to_string()))?;
        // The scene must set up (names, positions, strike) for its records to mean anything.
        scene.shot().map_err(|e| header(e.to_string()))?;
        Ok(PoolRunReader {
            balls: scene.pool.balls.len(),
            input,
            scene,
            table: Table::pool(&PocketTableSpecs::default()),
            index: 0,
            data_start: (PREAMBLE_LEN + json.len()) as u64,
            last_time: 0.0,
            tail: Tail::Unread,
            buf: [0; POOL_RECORD_LEN],
            path: name,
        })
    }

    /// The pool scene the shot started from.
    #[must_use]
    pub fn scene(&self) -> &PoolScene {
        &self.scene
    }

    /// The table the shot is played on.
    #[must_use]
    pub fn table(&self) -> &Table {
        &self.table
    }

    /// The file name given at opening.
    #[must_use]
    pub fn path(&self) -> &str {
        &self.path
    }

    /// How the file ended; [`Tail::Unread`] until [`PoolRunReader::next_record`] returned
    /// `None`.
    #[must_use]
    pub fn tail(&self) -> Tail {
        self.tail
    }

    /// Records read so far.
    #[must_use]
    pub fn records_read(&self) -> u64 {
        self.index
    }

    /// The next record; `Ok(None)` at the end of the file (see [`PoolRunReader::tail`]).
    ///
    /// # Errors
    /// A damaged record followed by more data, a record that breaks the format (an unknown
    /// tag, an index out of range, a number that is not finite, a time before the one
    /// before), or bytes after the end record. A damaged last record is a truncated tail.
    pub fn next_record(&mut self) -> Result<Option<PoolRecord>, RecordError> {
        if self.tail != Tail::Unread {
            return Ok(None);
        }
        match read_frame(&mut self.input, &mut self.buf, &self.path)? {
            Frame::Whole => {}
            Frame::End(tail) => {
                self.tail = tail;
                return Ok(None);
            }
            Frame::Damaged => return Err(self.corrupt("checksum mismatch".into())),
        }
        let rec = self.decode().map_err(|why| self.corrupt(why))?;
        let t = rec.time();
        if t < self.last_time {
            return Err(self.corrupt(format!(
                "time {t} is before the record before it ({})",
                self.last_time
            )));
        }
        self.last_time = t;
        self.index += 1;
        if let PoolRecord::End(_) = rec {
            if self.more_follows()? {
                return Err(RecordError::TrailingData {
                    path: self.path.clone(),
                    offset: self.data_start + self.index * POOL_RECORD_LEN as u64,
                });
            }
            self.tail = Tail::Complete;
        }
        Ok(Some(rec))
    }

    fn decode(&self) -> Result<PoolRecord, String> {
        let b = &self.buf;
        let u32_at = |at: usize| u32::from_le_bytes(b[at..at + 4].try_into().expect("4"));
        let f64_at = |at: usize| f64::from_le_bytes(b[at..at + 8].try_into().expect("8"));
        let (tag, ia, ib, time) = (b[0], u32_at(1), u32_at(5), f64_at(9));
        if !time.is_finite() {
            return Err(format!("time is {time}"));
        }
        let slot = |k: usize| -> Result<BallAfter, String> {
            let at = 17 + 56 * k;
            let x: Vec<f64> = (0..7).map(|i| f64_at(at + 8 * i)).collect();
            if let Some(bad) = x.iter().find(|v| !v.is_finite()) {
                return Err(format!("ball slot {k} holds {bad}"));
            }
            let code = b[129 + k];
            let state = state_of_code(u32::from(code))
                .ok_or_else(|| format!("ball slot {k}: unknown motion state {code}"))?;
            Ok(BallAfter {
                ball: ClothBall {
                    pos: Vector([x[0], x[1]]),
                    vel: Vector([x[2], x[3]]),
                    spin: Vector([x[4], x[5], x[6]]),
                },
                state,
            })
        };
        let ball = |i: u32| -> Result<usize, String> {
            let i = i as usize;
            (i < self.balls)
                .then_some(i)
                .ok_or_else(|| format!("ball {i} of {}", self.balls))
        };
        let within = |i: u32, len: usize, what: &str| -> Result<usize, String> {
            let i = i as usize;
            (i < len)
                .then_some(i)
                .ok_or_else(|| format!("{what} {i} of {len}"))
        };
        let event = |kind: ShotEventKind, after_b: Option<BallAfter>| -> Result<_, String> {
            Ok(PoolRecord::Event {
                event: ShotEvent { time, kind },
                after: slot(0)?,
                after_b,
            })
        };
        let t = &self.table;
        match tag {
            TAG_END => Ok(PoolRecord::End(time)),
            TAG_STRIKE => Ok(PoolRecord::Strike {
                time,
                ball: ball(ia)?,
                after: slot(0)?,
            }),
            TAG_BALLS => {
                let (a, bb) = (ball(ia)?, ball(ib)?);
                if a >= bb {
                    return Err(format!("balls {a} and {bb} are not in order"));
                }
                event(ShotEventKind::Balls { a, b: bb }, Some(slot(1)?))
            }
            TAG_CUSHION => event(
                ShotEventKind::Cushion {
                    ball: ball(ia)?,
                    cushion: within(ib, t.cushions.len(), "cushion")?,
                },
                None,
            ),
            TAG_JAW => event(
                ShotEventKind::Jaw {
                    ball: ball(ia)?,
                    jaw: within(ib, t.jaws.len(), "jaw")?,
                },
                None,
            ),
            TAG_POCKET => event(
                ShotEventKind::Pocket {
                    ball: ball(ia)?,
                    pocket: within(ib, t.pockets.len(), "pocket")?,
                },
                None,
            ),
            TAG_TRANSITION => {
                let from = state_of_code(ib).ok_or_else(|| format!("unknown motion state {ib}"))?;
                let to = slot(0)?.state;
                if from == to {
                    return Err(format!("a state change from {from:?} to itself"));
                }
                event(
                    ShotEventKind::Transition {
                        ball: ball(ia)?,
                        from,
                        to,
                    },
                    None,
                )
            }
            other => Err(format!("unknown tag {other}")),
        }
    }

    fn more_follows(&mut self) -> Result<bool, RecordError> {
        more_follows(&mut self.input, &self.path)
    }

    fn corrupt(&self, why: String) -> RecordError {
        RecordError::Corrupt {
            path: self.path.clone(),
            index: self.index,
            why,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scene() -> PoolScene {
        PoolScene::from_json(
            r#"{"pool": {"balls": [{"name": "cue", "pos": [0.5, 0.5]},
                                   {"name": "1", "pos": [0.52, 1.2]}],
                         "shot": {"ball": "cue", "speed": 2.5, "phi": 88.0, "b": 0.3}}}"#,
        )
        .unwrap()
    }

    fn recorded() -> (Shot, Vec<u8>) {
        let mut bytes = Vec::new();
        let w = PoolRunWriter::new(&mut bytes, "mem".into(), &scene()).unwrap();
        let (shot, played) = record_shot(&scene(), w, 10_000).unwrap();
        played.unwrap();
        (shot, bytes)
    }

    #[test]
    fn a_shot_reads_back_record_for_record() {
        let (shot, bytes) = recorded();
        let mut r = PoolRunReader::new(&bytes[..], "mem".into()).unwrap();
        assert_eq!(r.scene(), &scene());
        let Some(PoolRecord::Strike { ball: 0, after, .. }) = r.next_record().unwrap() else {
            panic!("the strike comes first");
        };
        assert_eq!(after.state, ClothState::Sliding);
        let mut events = Vec::new();
        let mut end = None;
        while let Some(rec) = r.next_record().unwrap() {
            match rec {
                PoolRecord::Event { event, .. } => events.push(event),
                PoolRecord::End(t) => end = Some(t),
                PoolRecord::Strike { .. } => panic!("one strike"),
            }
        }
        assert_eq!(events, shot.events());
        assert_eq!(end, Some(shot.time()));
        assert_eq!(r.tail(), Tail::Complete);
        assert_eq!(
            bytes.len(),
            PREAMBLE_LEN + scene().to_json().len() + (events.len() + 2) * POOL_RECORD_LEN
        );
    }

    #[test]
    fn damaged_files_are_refused_or_cut_at_their_last_whole_record() {
        let (_, bytes) = recorded();
        let data = PREAMBLE_LEN + scene().to_json().len();
        let read_all = |b: &[u8]| -> Result<(u64, Tail), RecordError> {
            let mut r = PoolRunReader::new(b, "mem".into())?;
            while r.next_record()?.is_some() {}
            Ok((r.records_read(), r.tail()))
        };
        // A torn last record is a truncated tail.
        let (n, tail) = read_all(&bytes[..bytes.len() - 7]).unwrap();
        assert_eq!(tail, Tail::Truncated { bytes: 128 });
        assert!(n > 2);
        // A flipped byte in the middle is corruption.
        let mut bad = bytes.clone();
        bad[data + POOL_RECORD_LEN + 20] ^= 1;
        let e = read_all(&bad).unwrap_err().to_string();
        assert!(e.contains("record 1") && e.contains("checksum"), "{e}");
        // A ball index out of range, its checksum made good.
        let mut bad = bytes.clone();
        let at = data + POOL_RECORD_LEN;
        bad[at + 1..at + 5].copy_from_slice(&7u32.to_le_bytes());
        let sum = fnv1a(&bad[at..at + POOL_RECORD_LEN - 4]);
        bad[at + POOL_RECORD_LEN - 4..at + POOL_RECORD_LEN].copy_from_slice(&sum.to_le_bytes());
        let e = read_all(&bad).unwrap_err().to_string();
        assert!(e.contains("ball 7 of 2"), "{e}");
        // Bytes after the end record.
        let mut bad = bytes.clone();
        bad.push(0);
        let e = read_all(&bad).unwrap_err().to_string();
        assert!(e.contains("trailing data"), "{e}");
        // A scene's reader says what the file is.
        let e = crate::record::RunReader::<_, 2>::new(&bytes[..], "mem".into())
            .err()
            .unwrap()
            .to_string();
        assert!(e.contains("pool shot"), "{e}");
    }
}
