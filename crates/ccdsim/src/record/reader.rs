//! Reading run files, tolerating a truncated tail.

use super::{
    fnv1a, record_len, RecordError, RunRecord, MAGIC, PIVOT_A, PIVOT_B, PREAMBLE_LEN, REST_A,
    REST_B, TAG_BODY, TAG_EDIT, TAG_END, TAG_RESET, TAG_WALL, VERSION, VERSION_EDITS,
    VERSION_MOVING_WALLS, VERSION_NEWEST, VERSION_PIVOTS, VERSION_POOL, VERSION_RESTING,
    VERSION_ROUGH, VERSION_SHEARED, VERSION_SLOTS,
};
use crate::event::Event;
use crate::geom::Vector;
use crate::scene::Scene;
use crate::sim::Collision;
use std::fs::File;
use std::io::{BufReader, Read, Seek, SeekFrom};
use std::path::Path;

/// How a run file ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Tail {
    /// Not read to the end yet.
    Unread,
    /// It ends with an end record: the run stopped cleanly.
    Complete,
    /// It ends after a complete event without an end record (the run was killed or is still
    /// being written).
    NoEnd,
    /// It ends with `bytes` bytes of an incomplete or torn record, which were ignored.
    Truncated {
        /// Bytes ignored.
        bytes: u64,
    },
}

impl Tail {
    /// A one-line warning for a file that did not end cleanly (`None` for a complete file,
    /// or one not read to the end): what `verify` and `export` print.
    #[must_use]
    pub fn warning(&self) -> Option<String> {
        match self {
            Tail::Truncated { bytes } => Some(format!(
                "the run file ends with {bytes} bytes of an incomplete record (ignored)"
            )),
            Tail::NoEnd => Some("the run file has no end record (the run was interrupted)".into()),
            Tail::Complete | Tail::Unread => None,
        }
    }
}

/// Reads the records of a `D`-dimensional run file in order.
pub struct RunReader<R: Read, const D: usize> {
    input: R,
    path: String,
    scene: Scene<D>,
    data_start: u64,
    index: u64,
    tail: Tail,
    buf: Vec<u8>,
    /// The file's format version.
    version: u32,
    /// Records checked in order so far (the furthest read): what [`Sequence`] has seen.
    checked: u64,
    /// What the records read in order so far imply: the time reached, the body slots.
    seq: Sequence,
}

/// What a run's records, read in order, have established: the checks that need the records
/// before (times never go backwards; every body index names a slot the scene or an edit
/// made). It holds one flag per slot, and slots only grow the way the simulation grows
/// them, so what it allocates is bounded by the records read, never by a number a record
/// claims.
#[derive(Clone, Debug)]
struct Sequence {
    /// Time of the last record, seconds (the scene's start time before the first).
    last_time: f64,
    /// Whether each body slot is vacant (removed, or reserved and not yet filled).
    vacant: Vec<bool>,
    /// How many slots are vacant.
    vacancies: usize,
    /// An added body's first record waiting for its id record: its slot and time bits.
    pending_add: Option<(u32, u64)>,
}

/// A run reader of either dimension.
pub enum AnyRunReader {
    /// A 2D run.
    D2(RunReader<BufReader<File>, 2>),
    /// A 3D run.
    D3(RunReader<BufReader<File>, 3>),
}

/// Opens a run file of either dimension and reads its header.
pub fn open_run(path: &Path) -> Result<AnyRunReader, RecordError> {
    let name = path.display().to_string();
    let io = |source| RecordError::Io {
        path: name.clone(),
        source,
    };
    let file = File::open(path).map_err(io)?;
    let size = file.metadata().map_err(io)?.len();
    let mut file = BufReader::with_capacity(1 << 16, file);
    let (version, dim, json) = read_header(&mut file, &name, Some(size))?;
    refuse_pool(version, &name)?;
    let data_start = (PREAMBLE_LEN + json.len()) as u64;
    Ok(match dim {
        2 => AnyRunReader::D2(RunReader::from_parts(
            file, name, &json, data_start, version,
        )?),
        3 => AnyRunReader::D3(RunReader::from_parts(
            file, name, &json, data_start, version,
        )?),
        d => {
            return Err(RecordError::Header {
                path: name,
                why: format!("dimension {d} is not 2 or 3"),
            })
        }
    })
}

/// The format version of the run file at `path`, from its preamble: tells a pool shot's run
/// file ([`VERSION_POOL`], read by `ccdsim::billiards::open_pool_run`) from a scene's
/// ([`open_run`]).
///
/// # Errors
/// The file cannot be read, is not a run file, or has a version this build does not read.
pub fn run_file_version(path: &Path) -> Result<u32, RecordError> {
    let name = path.display().to_string();
    let io = |source| RecordError::Io {
        path: name.clone(),
        source,
    };
    let mut file = File::open(path).map_err(io)?;
    let mut pre = [0u8; PREAMBLE_LEN];
    let got = read_full(&mut file, &mut pre).map_err(io)?;
    if got < 8 || pre[..8] != MAGIC {
        return Err(RecordError::NotARunFile(name));
    }
    if got < 12 {
        return Err(RecordError::Header {
            path: name,
            why: "file ends inside the preamble".into(),
        });
    }
    let version = u32::from_le_bytes(pre[8..12].try_into().expect("4 bytes"));
    check_version(version, &name)?;
    Ok(version)
}

fn check_version(version: u32, name: &str) -> Result<(), RecordError> {
    if (VERSION..=VERSION_NEWEST).contains(&version) || version == VERSION_POOL {
        Ok(())
    } else {
        Err(RecordError::Version {
            path: name.into(),
            found: version,
            supported: VERSION_NEWEST,
        })
    }
}

/// A pool shot's run file read as a scene's: an error that says what it is.
fn refuse_pool(version: u32, name: &str) -> Result<(), RecordError> {
    if version == VERSION_POOL {
        return Err(RecordError::Header {
            path: name.into(),
            why: format!(
                "format version {VERSION_POOL} is a pool shot's run file (`ccdsim verify`, \
                 `view` and `export` read it; in Rust, ccdsim::billiards::open_pool_run)"
            ),
        });
    }
    Ok(())
}

/// Reads the preamble and the scene JSON. `size`, when the input's length is known, bounds the
/// header length; either way the header is read as it arrives, never into a buffer of a length
/// the file claims (a corrupt length of 2³⁶ must be an error, not an allocation failure).
pub(crate) fn read_header<R: Read>(
    input: &mut R,
    name: &str,
    size: Option<u64>,
) -> Result<(u32, u32, String), RecordError> {
    let mut pre = [0u8; PREAMBLE_LEN];
    let got = read_full(input, &mut pre).map_err(|source| RecordError::Io {
        path: name.into(),
        source,
    })?;
    if got < 8 || pre[..8] != MAGIC {
        return Err(RecordError::NotARunFile(name.into()));
    }
    if got < PREAMBLE_LEN {
        return Err(RecordError::Header {
            path: name.into(),
            why: "file ends inside the preamble".into(),
        });
    }
    let version = u32::from_le_bytes(pre[8..12].try_into().expect("4 bytes"));
    check_version(version, name)?;
    let dim = u32::from_le_bytes(pre[12..16].try_into().expect("4 bytes"));
    let len = u64::from_le_bytes(pre[16..24].try_into().expect("8 bytes"));
    if let Some(size) = size {
        let room = size.saturating_sub(PREAMBLE_LEN as u64);
        if len > room {
            return Err(RecordError::Header {
                path: name.into(),
                why: format!(
                    "header length {len} exceeds the {room} bytes the file holds after its \
                     preamble (corrupt or truncated file)"
                ),
            });
        }
    }
    let mut json = Vec::new();
    input
        .take(len)
        .read_to_end(&mut json)
        .map_err(|source| RecordError::Io {
            path: name.into(),
            source,
        })?;
    if (json.len() as u64) < len {
        return Err(RecordError::Header {
            path: name.into(),
            why: format!(
                "file ends inside the scene header ({} of {len} bytes)",
                json.len()
            ),
        });
    }
    let json = String::from_utf8(json).map_err(|_| RecordError::Header {
        path: name.into(),
        why: "scene header is not UTF-8".into(),
    })?;
    Ok((version, dim, json))
}

/// What reading the next fixed-size, checksummed record of a run file found.
pub(crate) enum Frame {
    /// A whole record whose checksum holds, in the buffer.
    Whole,
    /// The end of the file: nothing more, or a cut or torn last record (ignored).
    End(Tail),
    /// A damaged record with more data after it: corruption.
    Damaged,
}

/// Reads the next record of `buf.len()` bytes from `input` (`path` names the file in
/// errors): a torn last record is a truncated tail, damage followed by data is corruption.
pub(crate) fn read_frame<R: Read>(
    input: &mut R,
    buf: &mut [u8],
    path: &str,
) -> Result<Frame, RecordError> {
    let got = read_full(input, buf).map_err(|source| RecordError::Io {
        path: path.into(),
        source,
    })?;
    if got == 0 {
        return Ok(Frame::End(Tail::NoEnd));
    }
    let torn = Frame::End(Tail::Truncated { bytes: got as u64 });
    if got < buf.len() {
        return Ok(torn);
    }
    if !checksum_ok(buf) {
        return Ok(if more_follows(input, path)? {
            Frame::Damaged
        } else {
            torn
        });
    }
    Ok(Frame::Whole)
}

/// Whether any byte follows what has been read from `input` (it consumes one byte if so);
/// `path` names the file in errors.
pub(crate) fn more_follows<R: Read>(input: &mut R, path: &str) -> Result<bool, RecordError> {
    let mut probe = [0u8; 1];
    let more = read_full(input, &mut probe).map_err(|source| RecordError::Io {
        path: path.into(),
        source,
    })?;
    Ok(more > 0)
}

fn read_full<R: Read>(input: &mut R, buf: &mut [u8]) -> std::io::Result<usize> {
    let mut got = 0;
    while got < buf.len() {
        match input.read(&mut buf[got..]) {
            Ok(0) => break,
            Ok(k) => got += k,
            Err(e) if e.kind() == std::io::ErrorKind::Interrupted => {}
            Err(e) => return Err(e),
        }
    }
    Ok(got)
}

impl<R: Read, const D: usize> RunReader<R, D> {
    /// Reads the header of a `D`-dimensional run from `input`; `name` is used in errors.
    pub fn new(mut input: R, name: String) -> Result<Self, RecordError> {
        let (version, dim, json) = read_header(&mut input, &name, None)?;
        refuse_pool(version, &name)?;
        if dim as usize != D {
            return Err(RecordError::Header {
                path: name,
                why: format!("the run is {dim}D, {D}D was expected"),
            });
        }
        let start = (PREAMBLE_LEN + json.len()) as u64;
        Self::from_parts(input, name, &json, start, version)
    }

    fn from_parts(
        input: R,
        path: String,
        json: &str,
        data_start: u64,
        version: u32,
    ) -> Result<Self, RecordError> {
        let scene = Scene::<D>::from_json(json).map_err(|e| RecordError::Header {
            path: path.clone(),
            why: e.to_string(),
        })?;
        // A run of this scene is written in `version_for(scene)`, or as a steered run in
        // version 9 (8 before it) when that is lower: a later version is not one this scene's
        // runs are written in (a raised version number, or a file from a later build).
        let newest = super::version_for(&scene).max(VERSION_SLOTS);
        if version > newest {
            return Err(RecordError::Header {
                path,
                why: format!(
                    "format version {version} is later than any a run of its scene is written in ({newest}; corrupt version number, or a file of a later build)"
                ),
            });
        }
        let seq = Sequence {
            last_time: scene.start_time,
            vacant: vec![false; scene.bodies.len()],
            vacancies: 0,
            pending_add: None,
        };
        Ok(RunReader {
            checked: 0,
            seq,
            input,
            path,
            scene,
            data_start,
            index: 0,
            tail: Tail::Unread,
            buf: vec![0; record_len(D)],
            version,
        })
    }

    /// The file's format version (see [`crate::record`]).
    #[must_use]
    pub fn version(&self) -> u32 {
        self.version
    }

    /// The scene the run started from.
    #[must_use]
    pub fn scene(&self) -> &Scene<D> {
        &self.scene
    }

    /// The file name given at opening.
    #[must_use]
    pub fn path(&self) -> &str {
        &self.path
    }

    /// Byte offset of the first record.
    #[must_use]
    pub fn data_start(&self) -> u64 {
        self.data_start
    }

    /// How the file ended; [`Tail::Unread`] until [`RunReader::next_record`] returned `None`.
    #[must_use]
    pub fn tail(&self) -> Tail {
        self.tail
    }

    /// Records read so far.
    #[must_use]
    pub fn records_read(&self) -> u64 {
        self.index
    }

    /// The next record; `Ok(None)` at the end of the file (see [`RunReader::tail`]).
    /// A damaged record followed by more data is an error; a damaged last record is a
    /// truncated tail.
    pub fn next_record(&mut self) -> Result<Option<RunRecord<D>>, RecordError> {
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
        // A record whose checksum holds was written whole: whatever is wrong with it is
        // corruption, last record or not.
        let rec = decode::<D>(&self.buf, self.version)
            .and_then(|rec| check_numbers(&rec).map(|()| rec))
            .and_then(|rec| self.check_indices(rec))
            .map_err(|why| self.corrupt(why))?;
        if self.index == self.checked {
            // Read in order for the first time: the checks that need the records before.
            let mut seq = self.seq.clone();
            seq.accept(&rec, self.version)
                .map_err(|why| self.corrupt(why))?;
            self.seq = seq;
            self.checked += 1;
        }
        self.index += 1;
        if let RunRecord::End(_) = rec {
            self.tail = Tail::Complete;
            // Nothing may follow the end record: bytes there were written by something else,
            // or a run file was appended to another.
            if self.more_follows()? {
                return Err(RecordError::TrailingData {
                    path: self.path.clone(),
                    offset: self.data_start + self.index * record_len(D) as u64,
                });
            }
        }
        Ok(Some(rec))
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

    fn check_indices(&self, rec: RunRecord<D>) -> Result<RunRecord<D>, String> {
        if let RunRecord::Event(c) = &rec {
            let moving = self.scene.moving_walls.len() as u32;
            let (mut n, w) = (
                self.scene.bodies.len() as u32,
                self.scene.walls.len() as u32 + moving,
            );
            if self.version >= VERSION_SLOTS {
                // Bodies added during the run fill slots past the scene's (see
                // `crate::edit`): as many as the records read in order have made (an added
                // body's own records may name the next one, checked in `Sequence::accept`).
                n = u32::try_from(self.seq.vacant.len()).unwrap_or(u32::MAX);
                if c.event.kind == crate::event::EventKind::Edit
                    && matches!(c.event.b, crate::edit::ADD | crate::edit::ADD_ID)
                {
                    n = n.saturating_add(1);
                }
            }
            if c.rests != [false; 2] {
                use crate::event::EventKind;
                if self.scene.settings.rest_speed.is_none() {
                    return Err("a resting body in a run without settings.rest_speed".into());
                }
                let fits = match c.event.kind {
                    EventKind::Body => true,
                    EventKind::Wall => !c.rests[1] && c.event.b < self.scene.walls.len() as u32,
                    _ => false,
                };
                if !fits {
                    return Err("a resting body flagged where none can rest".into());
                }
            }
            let limit_b = match c.event.kind {
                crate::event::EventKind::Body => n,
                crate::event::EventKind::Wall => w,
                crate::event::EventKind::Reset => {
                    if self.scene.settings.thermostat.is_none() {
                        return Err("a thermostat reset in a run without a thermostat".into());
                    }
                    1
                }
                crate::event::EventKind::Edit => {
                    if self.version < VERSION_EDITS {
                        return Err(format!(
                            "an edit record in a run file of version {} (edits need 8)",
                            self.version
                        ));
                    }
                    if crate::edit::Edit::moves_a_wall(c) && c.event.a >= moving {
                        return Err(format!(
                            "an edit of moving wall {} in a scene of {moving}",
                            c.event.a
                        ));
                    }
                    if self.version < VERSION_SLOTS {
                        1
                    } else if self.version < VERSION_MOVING_WALLS {
                        crate::edit::EDIT_CODES_SLOTS
                    } else {
                        crate::edit::EDIT_CODES
                    }
                }
            };
            // A wall-velocity edit names a moving wall in `a` (checked above), not a body.
            let names_a_body = !(c.event.kind == crate::event::EventKind::Edit
                && crate::edit::Edit::moves_a_wall(c));
            if (names_a_body && c.event.a >= n) || c.event.b >= limit_b {
                return Err(format!(
                    "index out of range: a = {}, b = {}",
                    c.event.a, c.event.b
                ));
            }
        }
        Ok(rec)
    }

    /// Reads every remaining collision; stops at the end record or the end of the file.
    pub fn read_events(&mut self) -> Result<(Vec<Collision<D>>, Option<f64>), RecordError> {
        let mut out = Vec::new();
        while let Some(rec) = self.next_record()? {
            match rec {
                RunRecord::Event(c) => out.push(c),
                RunRecord::End(t) => return Ok((out, Some(t))),
            }
        }
        Ok((out, None))
    }
}

impl<R: Read + Seek, const D: usize> RunReader<R, D> {
    /// Moves to record `k` (0-based) so that the next read returns it. Records past the
    /// furthest read so far are read on the way, so that each is checked against those
    /// before it (see [`RunReader::next_record`]).
    pub fn seek_record(&mut self, k: u64) -> Result<(), RecordError> {
        let start = k.min(self.checked);
        let off = self.data_start + start * record_len(D) as u64;
        self.input
            .seek(SeekFrom::Start(off))
            .map_err(|source| RecordError::Io {
                path: self.path.clone(),
                source,
            })?;
        self.index = start;
        self.tail = Tail::Unread;
        while self.index < k {
            if self.next_record()?.is_none() {
                break;
            }
        }
        Ok(())
    }
}

/// True when a record's last four bytes are the FNV-1a checksum of the others.
pub(crate) fn checksum_ok(buf: &[u8]) -> bool {
    let n = buf.len();
    let sum = u32::from_le_bytes(buf[n - 4..].try_into().expect("4 bytes"));
    fnv1a(&buf[..n - 4]) == sum
}

/// Every number of a record that is a number must be finite: its time, and the positions
/// and velocities of its body slots. The second slot of an added body's records holds its
/// radius (finite, positive), mass (positive, infinite for a kinematic body) and the bits of
/// its filter, restitution (NaN: the scene's) and id; that of a filter edit the filter's bits.
fn check_numbers<const D: usize>(rec: &RunRecord<D>) -> Result<(), String> {
    use crate::edit::{ADD, ADD_ID, FILTER};
    use crate::event::EventKind;
    let c = match rec {
        RunRecord::End(t) if !t.is_finite() => return Err(format!("end time is {t}")),
        RunRecord::End(_) => return Ok(()),
        RunRecord::Event(c) => c,
    };
    if !c.event.time.is_finite() {
        return Err(format!("time is {}", c.event.time));
    }
    let field = |name: &str, slot: usize, v: &Vector<D>| match v.0.iter().find(|x| !x.is_finite()) {
        Some(x) => Err(format!("{name} of body slot {slot} is {x}")),
        None => Ok(()),
    };
    field("position", 0, &c.pos[0])?;
    field("velocity", 0, &c.vel[0])?;
    let edit = (c.event.kind == EventKind::Edit).then_some(c.event.b);
    match edit {
        Some(ADD) => {
            let (radius, mass) = (c.pos[1][0], c.pos[1][1]);
            if !(radius.is_finite() && radius > 0.0) {
                return Err(format!("an added body's radius is {radius}"));
            }
            if mass.is_nan() || mass <= 0.0 {
                return Err(format!("an added body's mass is {mass}"));
            }
        }
        Some(ADD_ID) => {}
        Some(FILTER) => field("position", 1, &c.pos[1])?,
        _ => {
            field("position", 1, &c.pos[1])?;
            field("velocity", 1, &c.vel[1])?;
        }
    }
    Ok(())
}

impl Sequence {
    /// Takes the next record of the run, read in order, or says why it cannot follow the
    /// records before: a time before the last, an added body's records apart or in a slot
    /// the simulation would not give it, a removal of a vacant slot.
    fn accept<const D: usize>(&mut self, rec: &RunRecord<D>, version: u32) -> Result<(), String> {
        use crate::edit::{ADD, ADD_ID, REMOVE};
        use crate::event::EventKind;
        let (t, c) = match rec {
            RunRecord::End(t) => (*t, None),
            RunRecord::Event(c) => (c.event.time, Some(c)),
        };
        if t < self.last_time {
            return Err(format!(
                "time {t} goes backwards (the record before is at {})",
                self.last_time
            ));
        }
        self.last_time = t;
        let edit = c.filter(|c| c.event.kind == EventKind::Edit && version >= VERSION_SLOTS);
        if let Some((slot, bits)) = self.pending_add {
            let ok = edit.is_some_and(|c| {
                c.event.b == ADD_ID && c.event.a == slot && c.event.time.to_bits() == bits
            });
            if !ok {
                return Err(format!(
                    "an added body's record (slot {slot}) is not followed by its id record"
                ));
            }
            self.pending_add = None;
            return Ok(());
        }
        let Some(c) = edit else {
            return Ok(());
        };
        let slot = c.event.a as usize;
        match c.event.b {
            ADD => {
                if slot < self.vacant.len() {
                    if !self.vacant[slot] {
                        return Err(format!("a body is added in slot {slot}, which holds one"));
                    }
                } else if slot == self.vacant.len() && self.vacancies == 0 {
                    // The simulation appends `reserve_count` slots, vacant but the first.
                    let n = self.vacant.len();
                    let count = crate::sim::reserve_count(n);
                    self.vacant.resize(n + count, true);
                    self.vacancies += count;
                } else {
                    return Err(format!(
                        "a body is added in slot {slot}, not a vacant one nor the next ({})",
                        self.vacant.len()
                    ));
                }
                self.vacant[slot] = false;
                self.vacancies -= 1;
                self.pending_add = Some((c.event.a, c.event.time.to_bits()));
            }
            ADD_ID => {
                return Err(format!("an id record (slot {slot}) without its added body"));
            }
            REMOVE => {
                if self.vacant.get(slot).copied().unwrap_or(true) {
                    return Err(format!(
                        "a body is removed from slot {slot}, which holds none"
                    ));
                }
                self.vacant[slot] = true;
                self.vacancies += 1;
            }
            _ => {}
        }
        Ok(())
    }
}

/// One record of a file of format `version`: its flags must be ones that version has.
fn decode<const D: usize>(buf: &[u8], version: u32) -> Result<RunRecord<D>, String> {
    let u32_at = |k: usize| u32::from_le_bytes(buf[k..k + 4].try_into().expect("4 bytes"));
    let f64_at = |k: usize| f64::from_le_bytes(buf[k..k + 8].try_into().expect("8 bytes"));
    let (a, b, t) = (u32_at(1), u32_at(5), f64_at(9));
    if t.is_nan() {
        return Err("time is NaN".into());
    }
    let vec_at = |slot: usize| {
        let mut v = Vector::<D>::ZERO;
        for k in 0..D {
            v[k] = f64_at(17 + 8 * (slot * D + k));
        }
        v
    };
    let c = |event| Collision {
        event,
        pos: [vec_at(0), vec_at(2)],
        vel: [vec_at(1), vec_at(3)],
        rests: [buf[0] & REST_A != 0, buf[0] & REST_B != 0],
        pivots: [buf[0] & PIVOT_A != 0, buf[0] & PIVOT_B != 0],
    };
    let flags = match version {
        // Bodies of rotational and sheared scenes never rest on walls.
        VERSION_ROUGH | VERSION_SHEARED => 0,
        v if v >= VERSION_PIVOTS => REST_A | REST_B | PIVOT_A | PIVOT_B,
        v if v >= VERSION_RESTING => REST_A | REST_B,
        _ => 0,
    };
    match buf[0] & !flags {
        TAG_BODY if a < b => Ok(RunRecord::Event(c(Event::body(t, a as usize, b as usize)))),
        TAG_WALL => Ok(RunRecord::Event(c(Event::wall(t, a as usize, b as usize)))),
        // The fields a record kind does not use are written as zero.
        TAG_END if a == 0 && b == 0 => Ok(RunRecord::End(t)),
        TAG_RESET if b == 0 => Ok(RunRecord::Event(c(Event::reset(t, a as usize)))),
        TAG_END | TAG_RESET => Err(format!(
            "{} record with a = {a}, b = {b} (written as zero)",
            if buf[0] & !flags == TAG_END {
                "an end"
            } else {
                "a reset"
            }
        )),
        TAG_EDIT => Ok(RunRecord::Event(c(Event {
            b,
            ..Event::edit(t, a as usize)
        }))),
        _ => Err(format!(
            "bad tag {:#04x} (for format version {version}) or body order {a} ≥ {b}",
            buf[0]
        )),
    }
}
