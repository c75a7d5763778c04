//! Writing run files with buffering, as the run goes.

use super::{
    fnv1a, record_len, version_for, RecordError, MAGIC, PIVOT_A, PIVOT_B, REST_A, REST_B, TAG_BODY,
    TAG_EDIT, TAG_END, TAG_RESET, TAG_WALL, VERSION_SLOTS,
};
use crate::event::EventKind;
use crate::scene::Scene;
use crate::sim::Collision;
use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::Path;

/// Appends records to a run file. The header is flushed at creation, so a run killed at any
/// moment leaves a file that reads back to its last complete record.
pub struct RunWriter<W: Write, const D: usize> {
    out: BufWriter<W>,
    path: String,
    buf: Vec<u8>,
    records: u64,
    /// Whether edit records may be written (format version 8).
    steered: bool,
}

impl<const D: usize> RunWriter<File, D> {
    /// Creates (or truncates) `path` and writes the header holding `scene`.
    pub fn create(path: &Path, scene: &Scene<D>) -> Result<Self, RecordError> {
        let name = path.display().to_string();
        let file = File::create(path).map_err(|source| RecordError::Io {
            path: name.clone(),
            source,
        })?;
        Self::new(file, name, scene)
    }

    /// Creates the run file `path` of a run a program steers: [`RunWriter::new_steered`].
    pub fn create_steered(path: &Path, scene: &Scene<D>) -> Result<Self, RecordError> {
        let name = path.display().to_string();
        let file = File::create(path).map_err(|source| RecordError::Io {
            path: name.clone(),
            source,
        })?;
        Self::new_steered(file, name, scene)
    }

    /// Starts recording `sim`, a run of `scene` a program steers, to the file `path`: turns
    /// on its edit journal ([`crate::Simulation::record_edits`]) and creates the steered run
    /// file ([`RunWriter::create_steered`]). Write each frame's
    /// [`take_edits`](crate::Simulation::take_edits) and collisions to it, in order.
    pub fn record_steered(
        sim: &mut crate::Simulation<D>,
        path: &Path,
        scene: &Scene<D>,
    ) -> Result<Self, RecordError> {
        let run = Self::create_steered(path, scene)?;
        sim.record_edits(true);
        Ok(run)
    }
}

impl<W: Write, const D: usize> RunWriter<W, D> {
    /// Writes the header holding `scene` to `out`; `name` is used in error messages.
    pub fn new(out: W, name: String, scene: &Scene<D>) -> Result<Self, RecordError> {
        Self::open(out, name, scene, false)
    }

    /// A writer for a run a program steers: like [`RunWriter::new`], but the file is format
    /// version 9 (10 with moving walls) and takes edit records ([`crate::EventKind::Edit`], from
    /// [`crate::Simulation::take_edits`]) between the collisions.
    pub fn new_steered(out: W, name: String, scene: &Scene<D>) -> Result<Self, RecordError> {
        Self::open(out, name, scene, true)
    }

    /// A scene's arrivals ([`crate::scene::arrival`]) are recorded as the additions they are: the
    /// file of a scene with arrivals is steered, and its header holds the scene without them.
    fn open(out: W, name: String, scene: &Scene<D>, steered: bool) -> Result<Self, RecordError> {
        let without_arrivals;
        let (scene, steered) = if scene.arrivals.is_empty() {
            (scene, steered)
        } else {
            without_arrivals = Scene {
                arrivals: Vec::new(),
                ..scene.clone()
            };
            (&without_arrivals, true)
        };
        let version = if steered {
            version_for(scene).max(VERSION_SLOTS)
        } else {
            version_for(scene)
        };
        let mut out = BufWriter::with_capacity(1 << 16, out);
        let json = scene.to_json();
        let io = |source| RecordError::Io {
            path: name.clone(),
            source,
        };
        let mut head = Vec::with_capacity(24 + json.len());
        head.extend_from_slice(&MAGIC);
        head.extend_from_slice(&version.to_le_bytes());
        head.extend_from_slice(&(D as u32).to_le_bytes());
        head.extend_from_slice(&(json.len() as u64).to_le_bytes());
        head.extend_from_slice(json.as_bytes());
        out.write_all(&head).map_err(io)?;
        out.flush().map_err(io)?;
        Ok(RunWriter {
            out,
            path: name,
            buf: Vec::with_capacity(record_len(D)),
            records: 0,
            steered,
        })
    }

    /// Records written so far (events and end).
    #[must_use]
    pub fn records(&self) -> u64 {
        self.records
    }

    fn put(
        &mut self,
        tag: u8,
        a: u32,
        b: u32,
        t: f64,
        vecs: [&[f64]; 4],
    ) -> Result<(), RecordError> {
        self.buf.clear();
        self.buf.push(tag);
        self.buf.extend_from_slice(&a.to_le_bytes());
        self.buf.extend_from_slice(&b.to_le_bytes());
        self.buf.extend_from_slice(&t.to_le_bytes());
        for v in vecs {
            for x in v {
                self.buf.extend_from_slice(&x.to_le_bytes());
            }
        }
        let sum = fnv1a(&self.buf);
        self.buf.extend_from_slice(&sum.to_le_bytes());
        debug_assert_eq!(self.buf.len(), record_len(D));
        self.records += 1;
        self.out
            .write_all(&self.buf)
            .map_err(|source| RecordError::Io {
                path: self.path.clone(),
                source,
            })
    }

    /// Appends one collision.
    pub fn write_event(&mut self, c: &Collision<D>) -> Result<(), RecordError> {
        let tag = match c.event.kind {
            EventKind::Body => TAG_BODY,
            EventKind::Wall => TAG_WALL,
            EventKind::Reset => TAG_RESET,
            EventKind::Edit if self.steered => TAG_EDIT,
            EventKind::Edit => {
                return Err(RecordError::NotSteered {
                    path: self.path.clone(),
                })
            }
        };
        // Resting bodies (version 11) set the tag's two high bits, one per body slot.
        let tag = tag | (u8::from(c.rests[0]) * REST_A) | (u8::from(c.rests[1]) * REST_B);
        // Turning bodies (version 13) set the next two.
        let tag = tag | (u8::from(c.pivots[0]) * PIVOT_A) | (u8::from(c.pivots[1]) * PIVOT_B);
        self.put(
            tag,
            c.event.a,
            c.event.b,
            c.event.time,
            [&c.pos[0].0, &c.vel[0].0, &c.pos[1].0, &c.vel[1].0],
        )
    }

    /// Writes the end record (the run stopped at `time`), flushes and returns the inner writer.
    pub fn finish(mut self, time: f64) -> Result<W, RecordError> {
        let z = [0.0; D];
        self.put(TAG_END, 0, 0, time, [&z, &z, &z, &z])?;
        let path = self.path.clone();
        self.out.into_inner().map_err(|e| RecordError::Io {
            path,
            source: e.into_error(),
        })
    }

    /// Pushes buffered records to the file.
    pub fn flush(&mut self) -> Result<(), RecordError> {
        self.out.flush().map_err(|source| RecordError::Io {
            path: self.path.clone(),
            source,
        })
    }
}
