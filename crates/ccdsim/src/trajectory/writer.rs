//! A trajectory file of either format, chosen by name.

use super::frame::Frame;
use super::gsd::GsdWriter;
use super::xyz::XyzWriter;
use std::fs::File;
use std::io::{self, BufWriter};
use std::path::Path;

/// A trajectory file format.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TrajectoryFormat {
    /// Extended XYZ (text, full precision): `.xyz`, `.extxyz`.
    ExtendedXyz,
    /// GSD, HOOMD schema (binary, `f32`): `.gsd`.
    Gsd,
}

impl TrajectoryFormat {
    /// The format a file name asks for by its extension, or an error listing the known ones.
    pub fn from_path(path: &Path) -> Result<Self, String> {
        let ext = path
            .extension()
            .and_then(|e| e.to_str())
            .map(str::to_ascii_lowercase);
        match ext.as_deref() {
            Some("xyz" | "extxyz") => Ok(TrajectoryFormat::ExtendedXyz),
            Some("gsd") => Ok(TrajectoryFormat::Gsd),
            _ => Err(format!(
                "cannot tell the trajectory format of {}: name it .xyz or .extxyz (extended \
                 XYZ) or .gsd (GSD)",
                path.display()
            )),
        }
    }
}

/// A trajectory file being written.
pub enum TrajectoryWriter {
    /// Extended XYZ.
    Xyz(XyzWriter<BufWriter<File>>),
    /// GSD.
    Gsd(GsdWriter<BufWriter<File>>),
}

impl TrajectoryWriter {
    /// Creates (truncates) the file at `path` in `format`.
    pub fn create(path: &Path, format: TrajectoryFormat) -> io::Result<Self> {
        let file = BufWriter::new(File::create(path)?);
        Ok(match format {
            TrajectoryFormat::ExtendedXyz => TrajectoryWriter::Xyz(XyzWriter::new(file)),
            TrajectoryFormat::Gsd => TrajectoryWriter::Gsd(GsdWriter::create(
                file,
                concat!("ccdsim ", env!("CARGO_PKG_VERSION")),
            )?),
        })
    }

    /// Creates (truncates) the file at `path` in `format` for a run that keeps spins
    /// (`rotational`, see [`crate::World::is_rotational`]): each frame then holds the
    /// bodies' angular velocities too (extended XYZ: the `angvel` property; GSD:
    /// `log/particles/angular_velocity`). Without spins, as [`TrajectoryWriter::create`].
    pub fn create_for(path: &Path, format: TrajectoryFormat, rotational: bool) -> io::Result<Self> {
        if !rotational || format == TrajectoryFormat::ExtendedXyz {
            // Extended XYZ frames say what they hold in their own header line.
            return Self::create(path, format);
        }
        let file = BufWriter::new(File::create(path)?);
        Ok(TrajectoryWriter::Gsd(GsdWriter::create_with_spins(
            file,
            concat!("ccdsim ", env!("CARGO_PKG_VERSION")),
        )?))
    }

    /// Appends one frame.
    pub fn write<const D: usize>(&mut self, frame: &Frame<D>) -> io::Result<()> {
        match self {
            TrajectoryWriter::Xyz(w) => w.write(frame),
            TrajectoryWriter::Gsd(w) => w.write(frame),
        }
    }

    /// Flushes the file; errors that a drop would swallow surface here.
    pub fn finish(self) -> io::Result<()> {
        match self {
            TrajectoryWriter::Xyz(w) => w.finish().and_then(|mut f| f.get_mut().sync_all()),
            TrajectoryWriter::Gsd(w) => w.finish().and_then(|mut f| f.get_mut().sync_all()),
        }
    }
}
