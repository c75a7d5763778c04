//! Export of run files to JSON Lines.

use super::{RecordError, RunReader, RunRecord};
use crate::event::EventKind;
use crate::geom::Vector;
use crate::scene::Wall;
use serde::Serialize;
use std::io::{Read, Write};

/// Why an export failed.
#[derive(Debug, thiserror::Error)]
pub enum ExportError {
    /// Reading the run failed.
    #[error(transparent)]
    Read(#[from] RecordError),
    /// Writing the output failed.
    #[error("writing the export: {0}")]
    Write(#[from] std::io::Error),
}

#[derive(Serialize)]
struct Header<'a, const D: usize> {
    version: u32,
    dim: usize,
    bodies: Vec<BodyOut<D>>,
    walls: &'a [Wall<D>],
    start_time: f64,
    restitution: f64,
    /// Sides of the periodic box, for periodic scenes only.
    #[serde(skip_serializing_if = "Option::is_none")]
    periodic: Option<Vector<D>>,
    /// The Andersen thermostat, for thermostatted scenes only.
    #[serde(skip_serializing_if = "Option::is_none")]
    thermostat: Option<crate::thermostat::Thermostat>,
    /// Uniform gravity, for scenes with gravity only.
    #[serde(skip_serializing_if = "Option::is_none")]
    gravity: Option<crate::gravity::Gravity>,
    /// Sensor regions, for scenes with sensors only.
    #[serde(skip_serializing_if = "<[_]>::is_empty")]
    sensors: &'a [crate::sensor::Sensor<D>],
}

#[derive(Serialize)]
struct BodyOut<const D: usize> {
    id: u64,
    radius: f64,
    /// `null` for a kinematic body (infinite mass).
    mass: Option<f64>,
    /// Kinematic bodies only.
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    kinematic: bool,
    /// Collision groups and mask, for bodies that set them.
    #[serde(skip_serializing_if = "Option::is_none")]
    group: Option<u32>,
    #[serde(skip_serializing_if = "Option::is_none")]
    mask: Option<u32>,
    pos: Vector<D>,
    vel: Vector<D>,
}

#[derive(Serialize)]
struct EventOut<'a, const D: usize> {
    t: f64,
    kind: &'static str,
    a: u64,
    b: u64,
    pos: &'a [Vector<D>],
    vel: &'a [Vector<D>],
}

/// Writes a run as JSON Lines: a header object, then one object per event (see the README).
/// Body events name bodies by id; wall events give the wall index as `b`. Returns the number
/// of events written.
pub fn export_jsonl<R: Read, W: Write, const D: usize>(
    reader: &mut RunReader<R, D>,
    out: &mut W,
) -> Result<u64, ExportError> {
    let scene = reader.scene().clone();
    let header = Header {
        version: super::version_for(&scene),
        dim: D,
        bodies: scene
            .bodies
            .iter()
            .enumerate()
            .map(|(i, b)| BodyOut {
                id: scene.id_of(i),
                radius: b.radius,
                mass: Some(b.effective_mass()).filter(|m| m.is_finite()),
                kinematic: b.kinematic,
                group: b.group,
                mask: b.mask,
                pos: b.pos,
                vel: b.vel,
            })
            .collect(),
        walls: &scene.walls,
        start_time: scene.start_time,
        restitution: scene.settings.restitution,
        periodic: scene.periodic,
        thermostat: scene.settings.thermostat,
        gravity: scene.settings.gravity,
        sensors: &scene.sensors,
    };
    serde_json::to_writer(&mut *out, &header).map_err(std::io::Error::from)?;
    out.write_all(b"\n")?;
    let mut count = 0;
    while let Some(rec) = reader.next_record()? {
        let RunRecord::Event(c) = rec else { break };
        let k = c.body_count();
        let (kind, b) = match c.event.kind {
            EventKind::Body => ("body", scene.id_of(c.event.b as usize)),
            EventKind::Wall => ("wall", u64::from(c.event.b)),
            EventKind::Reset => ("reset", 0),
            EventKind::Edit => ("edit", 0),
        };
        let line = EventOut {
            t: c.event.time,
            kind,
            a: scene.id_of(c.event.a as usize),
            b,
            pos: &c.pos[..k],
            vel: &c.vel[..k],
        };
        serde_json::to_writer(&mut *out, &line).map_err(std::io::Error::from)?;
        out.write_all(b"\n")?;
        count += 1;
    }
    out.flush()?;
    Ok(count)
}
