//! Run files: the initial scene, then the event stream, written as the run goes.
//!
//! # Format (version 1, little-endian)
//!
//! | bytes | content |
//! |---|---|
//! | 8 | magic `CCDSIMRF` |
//! | 4 | format version (`u32`) |
//! | 4 | dimension `D` (`u32`) |
//! | 8 | header length `h` (`u64`) |
//! | h | the initial scene as JSON (the scene file format) |
//! | … | fixed-size records of `21 + 32·D` bytes each |
//!
//! Version 2 is version 1 plus records of tag 4, thermostat resets (`a` the body, `b` 0, the
//! first slot its position at `t` and its new velocity); it is written for scenes with an
//! Andersen thermostat only, so every other run file stays version 1, byte for byte.
//!
//! Version 3 is version 2 for scenes with growing radii (`settings.growth` in the header):
//! the records are the same, but their contacts and velocities follow the growth (see
//! [`crate::contact::growth`]), which a reader of version 2 would not know to check.
//!
//! Version 4 is version 2 for scenes with gravity (`settings.gravity` in the header): bodies
//! move on parabolas between events (see [`crate::contact::gravity`]), so positions, contacts and the
//! energy a reader checks differ from straight motion. A scene with gravity and growing radii
//! (see [`crate::contact::falling_growth`]) is version 4 too, the later of the two: its header carries
//! both settings, and a build that predates the combination refuses the header's scene.
//!
//! Version 5 is version 4 for scenes with kinematic bodies (`bodies[].kinematic`): bodies of
//! infinite mass that move in straight lines, meet no wall and no other kinematic body, and
//! whose collisions conserve neither momentum nor energy.
//!
//! Version 6 is version 5 for scenes with collision groups and masks (`bodies[].group`,
//! `bodies[].mask`, see [`crate::collision_filter`]): some pairs of bodies pass through each
//! other, which a reader of version 5 would take for missed collisions.
//!
//! Version 7 is version 6 for scenes with sensors (`sensors` in the header, see
//! [`crate::sensor`]), which a reader of version 6 would refuse as an unknown field. Sensor
//! events are not recorded: they follow from the recorded motions.
//!
//! Version 8 is any of the above with records of tag 5, **edits**: a program moved body `a`
//! or gave it a new velocity (`b` 0; the first slot its position at `t` after the edit and
//! its velocity from then on; see [`crate::Simulation::record_edits`]). It is written by
//! [`RunWriter::new_steered`], for runs a program steers, so that `verify` and the viewer
//! can replay them.
//!
//! Version 9 is version 8 whose edit records may also add and remove bodies and change
//! collision filters (`b` ≠ 0, see [`crate::edit`]): bodies added may fill slots past the
//! scene's. Every steered run file is written in it; version 8 files still read.
//!
//! Version 10 is version 9 for scenes with moving walls (`moving_walls` in the header, see
//! [`crate::world::time_of_impact`]), steered or not: wall events may name a moving wall (`b` from
//! the number of static walls on), and edit records of code 5 give one a new velocity.
//!
//! Version 11 is version 10 for scenes where bodies rest on walls (`settings.rest_speed`,
//! see [`crate::contact::resting`]): a wall event after which the body rests on the wall, sliding
//! along it, sets bit 6 of its tag (`0x40`); a body event after which body `a` (`b`) still
//! rests on the wall it rested on before sets bit 6 (bit 7, `0x80`).
//!
//! A record is: tag `u8` (1 body event, 2 wall event, 3 end of run, 4 reset, 5 edit; in
//! version 11 bits 6 and 7 flag resting bodies), `a: u32`, `b: u32`,
//! `t: f64`, then for two body slots the position at `t` and the velocity after the event
//! (`D` `f64`s each; the second slot is zero for wall events and the end record), then an
//! FNV-1a checksum (`u32`) of the record's preceding bytes. The end record's `t` is the time
//! the run stopped at. Fixed-size records make the `k`-th event seekable in O(1).

mod export;
mod reader;
mod writer;

pub use export::{export_jsonl, ExportError};
pub(crate) use reader::{more_follows, read_frame, read_header, Frame};
pub use reader::{open_run, run_file_version, AnyRunReader, RunReader, Tail};
pub use writer::RunWriter;

/// First 8 bytes of every run file.
pub const MAGIC: [u8; 8] = *b"CCDSIMRF";
/// Format version of run files without thermostat resets.
pub const VERSION: u32 = 1;
/// Format version of run files of scenes with a thermostat (version 1 plus reset records).
pub const VERSION_RESETS: u32 = 2;
/// Format version of run files of scenes with growing radii.
pub const VERSION_GROWTH: u32 = 3;
/// Format version of run files of scenes with gravity.
pub const VERSION_GRAVITY: u32 = 4;
/// Format version of run files of scenes with kinematic bodies (with or without gravity).
pub const VERSION_KINEMATIC: u32 = 5;
/// Format version of run files of scenes with collision groups and masks.
pub const VERSION_FILTERS: u32 = 6;
/// Format version of run files of scenes with sensors.
pub const VERSION_SENSORS: u32 = 7;
/// Format version of steered run files, which may hold edit records.
pub const VERSION_EDITS: u32 = 8;
/// Format version of steered run files whose edits may add and remove bodies and change
/// collision filters.
pub const VERSION_SLOTS: u32 = 9;
/// Format version of run files of scenes with moving walls.
pub const VERSION_MOVING_WALLS: u32 = 10;
/// Format version of run files of scenes where bodies rest on walls.
pub const VERSION_RESTING: u32 = 11;
/// Format version of run files of scenes where bodies rest on segments too: a wall record
/// of a body with the segment it slides on is its arrival at the segment's end (see
/// [`crate::contact::ledge`]), flagged as resting when it goes on along the next segment, which
/// the record then names.
pub const VERSION_SEGMENT_RESTING: u32 = 12;
/// Format version of run files of scenes where bodies rest on segments, in which they may
/// also turn about a segment's end point (see [`crate::motion::pivot`]): version 12 whose records
/// may set tag bit 5 (`0x20`, body `a`) or bit 4 (`0x10`, body `b`) for a body that turns
/// about an end point after the event, with the position and velocity its turn starts from.
/// On a wall record naming a segment the body slid on, the bit says it rolls over that
/// segment's end; a later wall record of that body, while it turns, ends the turn: naming
/// the segment turned about without the rest bit, it comes off (falling, its state the
/// record's); with the rest bit, it rests on the segment named (swung back or landed).
pub const VERSION_PIVOTS: u32 = 13;
/// Format version of run files of rotational scenes (rough bodies, or spins set; see
/// [`crate::motion::spin`]): version 10's records, whose velocity changes may have a
/// tangential part. Spins are not recorded: they follow from the scene's and each
/// collision's impulse (`m·Δv`), applied at the contact point, so that a reader replays them
/// exactly as `verify` does. Bodies never rest on walls in these scenes.
pub const VERSION_ROUGH: u32 = 14;
/// Format version of run files of sheared periodic scenes (`settings.shear_rate`, see
/// [`crate::contact::lees_edwards`]): version 14's records, whose positions lie in the box
/// after exits through a y face that moved the body along x by the strain offset and
/// changed its x velocity by `γ̇ L_y`, and whose collisions meet between images of
/// neighbouring layers. No rest or turn flags (a sheared box has no walls).
pub const VERSION_SHEARED: u32 = 15;
/// The newest format version of runs of ccdsim scenes this build reads (pool shots have a
/// format of their own, [`VERSION_POOL`]).
pub const VERSION_NEWEST: u32 = VERSION_SHEARED;
/// Format version of run files of pool shots (`ccdsim::billiards::PoolRunWriter`): the same
/// preamble, a pool scene as the header and records of their own (see
/// `ccdsim::billiards::run_file`); [`open_run`] refuses them and says where to read them.
pub const VERSION_POOL: u32 = 16;

/// The format version a run of `scene` is written in.
#[must_use]
pub fn version_for<const D: usize>(scene: &crate::scene::Scene<D>) -> u32 {
    if scene.shear().is_some() {
        VERSION_SHEARED
    } else if scene.is_rotational() {
        VERSION_ROUGH
    } else if crate::scene::slides(scene)
        .iter()
        .zip(&scene.walls)
        .any(|(slide, wall)| slide.is_some() && matches!(wall, crate::wall::Wall::Segment { .. }))
    {
        VERSION_PIVOTS
    } else if scene.settings.rest_speed.is_some() {
        VERSION_RESTING
    } else if !scene.moving_walls.is_empty() {
        VERSION_MOVING_WALLS
    } else if !scene.sensors.is_empty() {
        VERSION_SENSORS
    } else if scene.bodies.iter().any(crate::scene::BodySpec::is_filtered) {
        VERSION_FILTERS
    } else if scene.bodies.iter().any(|b| b.kinematic) {
        VERSION_KINEMATIC
    } else if scene.settings.gravity.is_some() {
        VERSION_GRAVITY
    } else if scene.settings.growth.is_some() {
        VERSION_GROWTH
    } else if scene.settings.thermostat.is_some() {
        VERSION_RESETS
    } else {
        VERSION
    }
}
/// Bytes before the header JSON.
pub const PREAMBLE_LEN: usize = 24;

pub(crate) const TAG_BODY: u8 = 1;
pub(crate) const TAG_WALL: u8 = 2;
pub(crate) const TAG_END: u8 = 3;
pub(crate) const TAG_RESET: u8 = 4;
pub(crate) const TAG_EDIT: u8 = 5;
/// Tag bit: body `a` of the record rests on a wall after it (version 11).
pub(crate) const REST_A: u8 = 0x40;
/// Tag bit: body `b` of a body event rests on a wall after it (version 11).
pub(crate) const REST_B: u8 = 0x80;
/// Tag bit: body `a` of the record turns about a segment's end point after it (version 13).
pub(crate) const PIVOT_A: u8 = 0x20;
/// Tag bit: body `b` of a body event turns about a segment's end point after it (version 13).
pub(crate) const PIVOT_B: u8 = 0x10;

/// Size in bytes of one record in a `D`-dimensional run file.
#[must_use]
pub const fn record_len(dim: usize) -> usize {
    1 + 4 + 4 + 8 + 4 * 8 * dim + 4
}

pub(crate) fn fnv1a(bytes: &[u8]) -> u32 {
    let mut h: u32 = 0x811c_9dc5;
    for &b in bytes {
        h ^= u32::from(b);
        h = h.wrapping_mul(0x0100_0193);
    }
    h
}

/// Why a run file cannot be read or written.
#[derive(Debug, thiserror::Error)]
pub enum RecordError {
    /// An I/O error, with the path.
    #[error("{path}: {source}")]
    Io {
        /// The file.
        path: String,
        /// The error.
        source: std::io::Error,
    },
    /// The file does not start with the magic value.
    #[error("{0}: not a ccdsim run file (bad magic value)")]
    NotARunFile(String),
    /// The file was written by another format version.
    #[error("{path}: run file format version {found}, this build reads versions 1 to {supported}")]
    Version {
        /// The file.
        path: String,
        /// Version in the file.
        found: u32,
        /// Version this build reads.
        supported: u32,
    },
    /// The header is cut short or its scene is invalid.
    #[error("{path}: bad header: {why}")]
    Header {
        /// The file.
        path: String,
        /// What is wrong.
        why: String,
    },
    /// Bytes follow the end record.
    #[error("{path}: trailing data after the end record, at byte {offset}")]
    TrailingData {
        /// The file.
        path: String,
        /// Offset of the first byte after the end record.
        offset: u64,
    },
    /// An edit record for a run file not opened as steered.
    #[error(
        "{path}: edits (set_velocity, set_position) need a steered run file \
         (RunWriter::new_steered or create_steered)"
    )]
    NotSteered {
        /// The file.
        path: String,
    },
    /// A record in the middle of the file is damaged.
    #[error("{path}: record {index} is corrupt ({why})")]
    Corrupt {
        /// The file.
        path: String,
        /// Record index (0-based).
        index: u64,
        /// What is wrong.
        why: String,
    },
}

/// One record of a run file.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum RunRecord<const D: usize> {
    /// A resolved collision.
    Event(crate::sim::Collision<D>),
    /// The run stopped cleanly at this simulated time, seconds.
    End(f64),
}
