//! Export of run files to JSON Lines.

use super::{RecordError, RunReader, RunRecord};
use crate::edit::Edit;
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
    gravity: Option<crate::motion::Gravity>,
    /// Sensor regions, for scenes with sensors only.
    #[serde(skip_serializing_if = "<[_]>::is_empty")]
    sensors: &'a [crate::sensor::Sensor<D>],
    /// Moving walls as the scene gives them (where they start, their velocity), for scenes
    /// with moving walls only; wall events name moving wall `k` as `walls.len() + k`.
    #[serde(skip_serializing_if = "<[_]>::is_empty")]
    moving_walls: &'a [crate::motion::MovingWall<D>],
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
    /// Added bodies: the slot (body index) they fill.
    #[serde(skip_serializing_if = "Option::is_none")]
    slot: Option<usize>,
    /// Added bodies: radius, metres.
    #[serde(skip_serializing_if = "Option::is_none")]
    radius: Option<f64>,
    /// Added bodies: mass, kilograms (absent for a kinematic body).
    #[serde(skip_serializing_if = "Option::is_none")]
    mass: Option<f64>,
    /// Added kinematic bodies only.
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    kinematic: bool,
    /// Added bodies and filter changes: the collision group and mask.
    #[serde(skip_serializing_if = "Option::is_none")]
    group: Option<u32>,
    #[serde(skip_serializing_if = "Option::is_none")]
    mask: Option<u32>,
    /// Added bodies with their own restitution.
    #[serde(skip_serializing_if = "Option::is_none")]
    restitution: Option<f64>,
    /// Runs where bodies rest on walls: for each body of the line, whether it rests on a
    /// wall after the event (see [`crate::contact::resting`]); absent when none does.
    #[serde(skip_serializing_if = "Option::is_none")]
    rests: Option<&'a [bool]>,
    /// Runs where bodies roll over segment ends: for each body of the line, whether it turns
    /// about a segment's end point after the event (see [`crate::motion::pivot`]), from the line's
    /// position and velocity; absent when none does.
    #[serde(skip_serializing_if = "Option::is_none")]
    pivots: Option<&'a [bool]>,
}

/// Writes a run as JSON Lines: a header object, then one object per event (see
/// docs/run-files.md).
/// Body events name bodies by id; wall events give the wall index as `b`. Edits are `edit`
/// (new position or velocity), `add` (with the body's slot, radius, mass, filter and
/// restitution; its id is `a`), `remove` and `filter` lines (see [`crate::edit`]). Returns the
/// number of lines written after the header.
pub fn export_jsonl<R: Read, W: Write, const D: usize>(
    reader: &mut RunReader<R, D>,
    out: &mut W,
) -> Result<u64, ExportError> {
    let scene = reader.scene().clone();
    let reader_path = reader.path().to_string();
    let header = Header {
        version: reader.version(),
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
        moving_walls: &scene.moving_walls,
    };
    serde_json::to_writer(&mut *out, &header).map_err(std::io::Error::from)?;
    out.write_all(b"\n")?;
    // Each slot's id: the scene's, then those of the bodies added.
    let mut ids: Vec<Option<u64>> = (0..scene.bodies.len())
        .map(|i| Some(scene.id_of(i)))
        .collect();
    // The reader checks every index against the slots the scene and the edits made; a slot
    // without an id (one reserved, never filled) is an error, never a made-up id.
    let id_of = |ids: &[Option<u64>], i: u32| {
        ids.get(i as usize).copied().flatten().ok_or_else(|| {
            std::io::Error::new(
                std::io::ErrorKind::InvalidData,
                format!(
                    "{}: a record names body slot {i}, which holds no body",
                    reader_path
                ),
            )
        })
    };
    let mut pending_add = None;
    let mut count = 0;
    while let Some(rec) = reader.next_record()? {
        let RunRecord::Event(c) = rec else { break };
        if Edit::starts_add(&c) {
            pending_add = Some(c);
            continue;
        }
        let k = c.body_count();
        let mut line = EventOut {
            t: c.event.time,
            kind: "edit",
            a: 0,
            b: 0,
            pos: &c.pos[..k],
            vel: &c.vel[..k],
            slot: None,
            radius: None,
            mass: None,
            kinematic: false,
            group: None,
            mask: None,
            restitution: None,
            rests: (c.rests != [false; 2]).then_some(&c.rests[..k]),
            pivots: (c.pivots != [false; 2]).then_some(&c.pivots[..k]),
        };
        let added;
        match c.event.kind {
            EventKind::Body => {
                (line.kind, line.a) = ("body", id_of(&ids, c.event.a)?);
                line.b = id_of(&ids, c.event.b)?;
            }
            EventKind::Wall => {
                (line.kind, line.a) = ("wall", id_of(&ids, c.event.a)?);
                line.b = u64::from(c.event.b);
            }
            EventKind::Reset => (line.kind, line.a) = ("reset", id_of(&ids, c.event.a)?),
            EventKind::Edit => {
                let first = pending_add.take();
                let edit = match &first {
                    Some(f) => Edit::decode(f, Some(&c)),
                    None => Edit::decode(&c, None),
                }
                .map_err(|why| std::io::Error::new(std::io::ErrorKind::InvalidData, why))?;
                match edit {
                    Edit::Motion { .. } => line.a = id_of(&ids, c.event.a)?,
                    Edit::Add {
                        body,
                        id,
                        radius,
                        mass,
                        filter,
                        restitution,
                        ..
                    } => {
                        if ids.len() <= body {
                            ids.resize(body + 1, None);
                        }
                        ids[body] = Some(id);
                        let first = first.expect("an add decodes from its first record");
                        added = [first.pos[0], first.vel[0]];
                        line.kind = "add";
                        line.a = id;
                        (line.pos, line.vel) = (&added[..1], &added[1..]);
                        line.slot = Some(body);
                        line.radius = Some(radius);
                        line.mass = mass.is_finite().then_some(mass);
                        line.kinematic = !mass.is_finite();
                        (line.group, line.mask) = (Some(filter.group), Some(filter.mask));
                        line.restitution = restitution;
                    }
                    Edit::Remove { .. } => {
                        (line.kind, line.a) = ("remove", id_of(&ids, c.event.a)?);
                        ids[c.event.a as usize] = None;
                    }
                    Edit::Filter { filter, .. } => {
                        (line.kind, line.a) = ("filter", id_of(&ids, c.event.a)?);
                        (line.group, line.mask) = (Some(filter.group), Some(filter.mask));
                    }
                    Edit::WallMotion { wall, .. } => {
                        // Named as wall events name it: after the static walls.
                        line.kind = "wall_velocity";
                        line.a = (scene.walls.len() + wall) as u64;
                    }
                }
            }
        }
        serde_json::to_writer(&mut *out, &line).map_err(std::io::Error::from)?;
        out.write_all(b"\n")?;
        count += 1;
    }
    out.flush()?;
    Ok(count)
}
