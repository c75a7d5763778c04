//! Binary encodings of the viewer API's answers (little-endian arrays the page reads as typed
//! arrays), and the JSON run description.
//!
//! | endpoint | layout |
//! |---|---|
//! | `/api/bodies` | `f64` radii (`n`), then `f64` ids (`n`) |
//! | `/api/state` | `f64` header of [`STATE_HEADER`] values, then `f32` positions at the snapshot time (`n·D`), then `f32` velocities at the snapshot time (`n·D`) |
//! | `/api/events` | per event `4 + 4·D` `f64`s: `t`, kind (0 body, 1 wall, 2 thermostat reset), `a`, `b`, position and velocity of slot 0, then of slot 1 |
//! | `/api/boxes` | per box `2 + 2·D` `f32`s: depth, leaf (0/1), min corner, max corner |

use crate::playback::{Playback, Snapshot};
use ccdsim::finder::DebugBox;
use ccdsim::{Collision, EventKind, FINDER_NAMES};

/// Number of `f64` values before the arrays of a `/api/state` answer: time, events applied,
/// bodies, dimension, last event's kind (−1 none, 0 body, 1 wall, 2 reset), time, `a`, `b`.
pub const STATE_HEADER: usize = 8;

fn put_f64(out: &mut Vec<u8>, x: f64) {
    out.extend_from_slice(&x.to_le_bytes());
}

fn put_f32(out: &mut Vec<u8>, x: f64) {
    out.extend_from_slice(&(x as f32).to_le_bytes());
}

fn kind_code(kind: EventKind) -> f64 {
    match kind {
        EventKind::Body => 0.0,
        EventKind::Wall => 1.0,
        EventKind::Reset => 2.0,
        EventKind::Edit => 3.0,
    }
}

/// Radii then ids of every body.
#[must_use]
pub fn encode_bodies<const D: usize>(p: &Playback<D>) -> Vec<u8> {
    let scene = p.scene();
    let mut out = Vec::with_capacity(16 * scene.bodies.len());
    for b in &scene.bodies {
        put_f64(&mut out, b.radius);
    }
    for i in 0..scene.bodies.len() {
        put_f64(&mut out, scene.id_of(i) as f64);
    }
    out
}

/// A snapshot: header, positions at its time, velocities at its time (under gravity the
/// stored velocities hold only at each body's last event).
#[must_use]
pub fn encode_snapshot<const D: usize>(s: &Snapshot<D>) -> Vec<u8> {
    let n = s.states.len();
    let mut out = Vec::with_capacity(8 * STATE_HEADER + 8 * D * n);
    put_f64(&mut out, s.time);
    put_f64(&mut out, s.applied as f64);
    put_f64(&mut out, n as f64);
    put_f64(&mut out, D as f64);
    match &s.last {
        Some(c) => {
            put_f64(&mut out, kind_code(c.event.kind));
            put_f64(&mut out, c.event.time);
            put_f64(&mut out, f64::from(c.event.a));
            put_f64(&mut out, f64::from(c.event.b));
        }
        None => {
            for x in [-1.0, 0.0, 0.0, 0.0] {
                put_f64(&mut out, x);
            }
        }
    }
    for i in 0..n {
        let p = s.states.position_at(i, s.time);
        for k in 0..D {
            put_f32(&mut out, p[k]);
        }
    }
    for i in 0..n {
        let v = s.states.velocity_at(i, s.time);
        for k in 0..D {
            put_f32(&mut out, v[k]);
        }
    }
    out
}

/// A window of events.
#[must_use]
pub fn encode_events<const D: usize>(events: &[Collision<D>]) -> Vec<u8> {
    let mut out = Vec::with_capacity(events.len() * 8 * (4 + 4 * D));
    for c in events {
        put_f64(&mut out, c.event.time);
        put_f64(&mut out, kind_code(c.event.kind));
        put_f64(&mut out, f64::from(c.event.a));
        put_f64(&mut out, f64::from(c.event.b));
        for slot in 0..2 {
            for v in [c.pos[slot], c.vel[slot]] {
                for k in 0..D {
                    put_f64(&mut out, v[k]);
                }
            }
        }
    }
    out
}

/// A finder's boxes.
#[must_use]
pub fn encode_boxes<const D: usize>(boxes: &[DebugBox<D>]) -> Vec<u8> {
    let mut out = Vec::with_capacity(boxes.len() * 4 * (2 + 2 * D));
    for b in boxes {
        put_f32(&mut out, f64::from(b.depth));
        put_f32(&mut out, if b.leaf { 1.0 } else { 0.0 });
        for k in 0..D {
            put_f32(&mut out, b.aabb.min[k]);
        }
        for k in 0..D {
            put_f32(&mut out, b.aabb.max[k]);
        }
    }
    out
}

/// The run's description as JSON: file, dimension, counts, times, walls, bounds, the
/// largest speed, the keyframe interval, the finders that can draw boxes, the growth of
/// the radii (`{"rate", "origin"}`: radii at time `t` are `/api/bodies`'s times
/// `1 + rate·(t − origin)`), or `null`, and the gravity (`[gx, gy(, gz)]`: a body at `p`
/// with velocity `v` at time `t0` is at `p + v·dt + ½·g·dt²` at `t0 + dt`), or `null`.
#[must_use]
pub fn meta_json<const D: usize>(p: &Playback<D>, finder: &str) -> serde_json::Value {
    let e = p.extent();
    serde_json::json!({
        "file": p.path(),
        "dim": D,
        "bodies": p.scene().bodies.len(),
        "events": p.events(),
        "start_time": p.start_time(),
        "end_time": p.end_time(),
        "complete": p.complete(),
        "walls": p.scene().walls,
        "bounds": { "min": e.bounds.min, "max": e.bounds.max },
        "max_speed": e.max_speed,
        "keyframe_interval": p.index().interval,
        "keyframes": p.index().keyframes.len(),
        "finder": finder,
        "finders": FINDER_NAMES,
        "growth": p.scene().settings.growth.map(|g| serde_json::json!({
            "rate": g.rate,
            "origin": p.scene().start_time,
        })),
        "gravity": p.scene().settings.gravity,
        "kinematic": p
            .scene()
            .bodies
            .iter()
            .enumerate()
            .filter(|(_, b)| b.kinematic)
            .map(|(i, _)| i)
            .collect::<Vec<_>>(),
    })
}
