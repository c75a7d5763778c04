//! Binary encodings of the viewer API's answers (little-endian arrays the page reads as typed
//! arrays), and the JSON run description.
//!
//! | endpoint | layout |
//! |---|---|
//! | `/api/bodies` | the scene's `f64` radii, then its `f64` ids, each padded to the run's slot count `n` (meta's `bodies`) with radius 0 and id 0 for slots the scene does not have |
//! | `/api/state` | `f64` header of [`STATE_HEADER`] values (its `n` is the snapshot's slot count, at most meta's `bodies`), then `f32` positions at the snapshot time (`n·D`), then `f32` velocities at the snapshot time (`n·D`), then, only when bodies were added or removed by then, the slot section: one `f64` [`SLOT_SECTION`], `f64` radii (`n`, 0 for a vacant slot), `f64` ids (`n`), `u8` flags (`n`: bit 0 kinematic, bit 1 vacant); then, only in a run with moving walls, zero bytes up to a multiple of 8 and the wall section: one `f64` [`WALL_SECTION`], then per moving wall `1 + 2·D` `f64`s: the time of its last edit (the scene's start time before any), its displacement from its scene geometry then, its velocity since; then, only in a run where bodies rest on walls (`settings.rest_speed`), zero bytes up to a multiple of 8 and the rest section: one `f64` [`REST_SECTION`], `f64` supports (`n`: the static wall each body rests on, −1 for none), then `f64` accelerations (`n·D`: each body's until its next event, its slide along its wall for a resting body, `g` for a falling one, 0 for a kinematic body, a vacant slot or a turning body); then, only when some body turns about a segment's end point at the snapshot's time (2D), the pivot section (aligned as the rest section, which it follows): one `f64` [`PIVOT_SECTION`], one `f64` count `m`, then per turning body 8 `f64`s: its slot, the point it turns about (`x`, `y`), the time its turn started, and its position (`x`, `y`) and velocity (`x`, `y`) then |
//! | `/api/events` | per event `4 + 4·D` `f64`s: `t`, kind (0 body, 1 wall, 2 thermostat reset, 3 edit), `a`, `b`, position and velocity of slot 0, then of slot 1; in a run where bodies rest on walls, one more `f64` per event: its rest flags (bit 0: body `a` rests on a wall after it, bit 1: body `b` does, bit 2: body `a` of a wall event turns about an end point of segment `b` after it) |
//! | `/api/boxes` | per box `2 + 2·D` `f32`s: depth, leaf (0/1), min corner, max corner |
//!
//! A state answer without the slot section has the scene's radii, ids and kinematic flags
//! (`/api/bodies`, meta's `kinematic`), and slots past its `n` are vacant. Edit events
//! (kind 3) carry the edit code in `b` (see [`ccdsim::edit`]): 0 a new motion and 4 a new
//! filter restate body `a`'s state in slot 0; 1 adds body `a` (slot 0 its state, slot 1's
//! position its radius and mass, ∞ for a kinematic body); 2, which follows each 1, holds the
//! bits of its id in slot 1's first position component and no state; 3 removes body `a`,
//! which stops at slot 0's position and leaves its slot vacant; 5 gives moving wall `a`
//! (`a` counts among meta's `moving_walls`, and names no body) a new motion: slot 0's
//! position is its displacement from its scene geometry at `t`, slot 0's velocity its
//! velocity from then on. Moving wall `a` is where meta's `moving_walls[a]` is, translated
//! by that displacement plus the velocity times the time since. Wall events (kind 1) name a
//! moving wall in `b` from the number of meta's `walls` on.
//!
//! In a run where bodies rest on walls (meta's `rest_speed` is there), a body moves between
//! events with its own acceleration: `g` (meta's `gravity`) unless it is kinematic, or, once
//! a wall event flags it (bit 0), the acceleration of a body sliding on that wall (meta's
//! `slides[b]`), which a body event that flags it keeps; any other record naming it without
//! its flag makes it fall under `g` again. The rest section gives every body's support and
//! acceleration at the snapshot.
//!
//! A wall event whose rest flags have bit 2 ([`PIVOT_A`], runs with 2D segments bodies rest
//! on, format version 13, see [`ccdsim::motion::pivot`]) starts a turn of body `a` about the end
//! point of segment `b` that it reached (of the segment's ends `a`, `b`, the end `b` when
//! `(p − a)·(b − a) ≥ ½|b − a|²` for the event's position `p`, else `a`): with `up = −g/|g|`,
//! `left` its quarter turn counter-clockwise, and the body at distance `r` from the point `e`,
//! its centre is at `e + r·(cos θ·up + sin θ·left)` where `θ̈ = (|g|/r)·sin θ`, from the angle
//! and rate of the event's position and velocity (`θ` from `up`, counter-clockwise; the
//! velocity's part along `−sin θ·up + cos θ·left`, over `r`). The next event naming the body
//! ends the turn (its state is then the event's). The pivot section gives the turns under way
//! at the snapshot.
//!
//! Answers of runs without moving walls have neither meta's `moving_walls` nor the state's
//! wall section: they are what they were before moving walls existed, byte for byte. Answers
//! of runs where no body rests (no `settings.rest_speed`) have neither meta's `rest_speed`
//! and `slides`, nor the state's rest section, nor the events' rest flags; answers where no
//! body turns have no pivot section and no bit 2 in the rest flags, as before turns existed.

use crate::playback::{Playback, Snapshot};
use ccdsim::finder::DebugBox;
use ccdsim::{Collision, EventKind, Vector, FINDER_NAMES};

/// Number of `f64` values before the arrays of a `/api/state` answer: time, events applied,
/// slots, dimension, last event's kind (−1 none, 0 body, 1 wall, 2 reset, 3 edit), time,
/// `a`, `b`.
pub const STATE_HEADER: usize = 8;

/// The `f64` that opens the slot section of a `/api/state` answer (see the module docs).
pub const SLOT_SECTION: f64 = 1.0;

/// The `f64` that opens the wall section of a `/api/state` answer (see the module docs).
pub const WALL_SECTION: f64 = 2.0;

/// The `f64` that opens the rest section of a `/api/state` answer (see the module docs).
pub const REST_SECTION: f64 = 3.0;

/// Bit of an event's rest flags (runs where bodies rest on walls): body `a` rests after it.
pub const REST_A: u8 = 1;
/// Bit of an event's rest flags: body `b` of a body event rests after it.
pub const REST_B: u8 = 2;
/// Bit of an event's rest flags: body `a` of a wall event turns about an end point of segment
/// `b` after it (see the module docs).
pub const PIVOT_A: u8 = 4;

/// The `f64` that opens the pivot section of a `/api/state` answer (see the module docs).
pub const PIVOT_SECTION: f64 = 4.0;

/// `f64`s per turning body in the pivot section: slot, point (2), start time, start position
/// (2), start velocity (2).
pub const PIVOT_STRIDE: usize = 8;

/// Bit of a slot's flags in the slot section: the body is kinematic.
pub const SLOT_KINEMATIC: u8 = 1;
/// Bit of a slot's flags in the slot section: the slot is vacant.
pub const SLOT_VACANT: u8 = 2;

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

/// Radii then ids of the scene's bodies, padded to the run's slot count (radius 0, id 0).
#[must_use]
pub fn encode_bodies<const D: usize>(p: &Playback<D>) -> Vec<u8> {
    let scene = p.scene();
    let (n, slots) = (scene.bodies.len(), p.slots());
    let mut out = Vec::with_capacity(16 * slots);
    for b in &scene.bodies {
        put_f64(&mut out, b.radius);
    }
    for _ in n..slots {
        put_f64(&mut out, 0.0);
    }
    for i in 0..slots {
        put_f64(&mut out, if i < n { scene.id_of(i) as f64 } else { 0.0 });
    }
    out
}

/// A snapshot: header, positions at its time, velocities at its time (under gravity the
/// stored velocities hold only at each body's last event), the slot section when bodies
/// were added or removed by then, the wall section in a run with moving walls, the rest
/// section in a run where bodies rest on walls, and the pivot section when bodies turn about
/// points.
#[must_use]
pub fn encode_snapshot<const D: usize>(s: &Snapshot<D>) -> Vec<u8> {
    let n = s.states.len();
    let mut out = Vec::with_capacity(8 * STATE_HEADER + 8 * D * n + 8 + 17 * n);
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
    if s.states.has_slot_edits() {
        put_f64(&mut out, SLOT_SECTION);
        for i in 0..n {
            put_f64(&mut out, s.states.radius(i));
        }
        for i in 0..n {
            put_f64(&mut out, s.states.id(i) as f64);
        }
        for i in 0..n {
            let mut flags = 0;
            if s.states.is_kinematic(i) {
                flags |= SLOT_KINEMATIC;
            }
            if s.states.is_vacant(i) {
                flags |= SLOT_VACANT;
            }
            out.push(flags);
        }
    }
    if s.states.wall_count() > 0 {
        // Aligned, so that a page can read the section as a Float64Array.
        out.resize(out.len().next_multiple_of(8), 0);
        put_f64(&mut out, WALL_SECTION);
        for k in 0..s.states.wall_count() {
            let m = s.states.wall_motion(k);
            put_f64(&mut out, m.time);
            for v in [m.offset, m.velocity] {
                for d in 0..D {
                    put_f64(&mut out, v[d]);
                }
            }
        }
    }
    if s.states.has_supports() {
        out.resize(out.len().next_multiple_of(8), 0);
        put_f64(&mut out, REST_SECTION);
        for i in 0..n {
            put_f64(&mut out, s.states.support(i).map_or(-1.0, |w| w as f64));
        }
        for i in 0..n {
            let a = s.states.acceleration(i).unwrap_or(Vector::ZERO);
            for d in 0..D {
                put_f64(&mut out, a[d]);
            }
        }
    }
    let turning: Vec<_> = s.states.turning().collect();
    if !turning.is_empty() {
        out.resize(out.len().next_multiple_of(8), 0);
        put_f64(&mut out, PIVOT_SECTION);
        put_f64(&mut out, turning.len() as f64);
        for (i, p) in turning {
            let m = s.states.motion(i);
            put_f64(&mut out, i as f64);
            let e = p.point();
            put_f64(&mut out, e[0]);
            put_f64(&mut out, e[1]);
            put_f64(&mut out, p.start_time());
            for v in [m.pos, m.vel] {
                put_f64(&mut out, v[0]);
                put_f64(&mut out, v[1]);
            }
        }
    }
    out
}

/// A window of events, each followed by its rest flags ([`REST_A`], [`REST_B`], [`PIVOT_A`]) when
/// `rests` (a run where bodies rest on walls, see [`Playback::has_rests`]).
#[must_use]
pub fn encode_events<const D: usize>(events: &[Collision<D>], rests: bool) -> Vec<u8> {
    let mut out = Vec::with_capacity(events.len() * 8 * (4 + 4 * D + usize::from(rests)));
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
        if rests {
            let flags = (u8::from(c.rests[0]) * REST_A)
                | (u8::from(c.rests[1]) * REST_B)
                | (u8::from(c.pivots[0]) * PIVOT_A);
            put_f64(&mut out, f64::from(flags));
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
/// `1 + rate·(t − origin)`), or `null`, the gravity (`[gx, gy(, gz)]`: a body at `p`
/// with velocity `v` at time `t0` is at `p + v·dt + ½·g·dt²` at `t0 + dt`), or `null`, and
/// the scene's kinematic bodies by index. `bodies` is the largest number of body slots over
/// the run (the scene's bodies, or more in a run that adds bodies past them),
/// `scene_bodies` the scene's, and `slot_edits` says whether bodies are added or removed.
/// A run with moving walls also has `moving_walls`: the scene's, each a wall (segment or
/// plane fields, where it is at the start) with its `velocity` from the start on. A run
/// where bodies rest on walls also has `rest_speed` (the scene's `settings.rest_speed`) and
/// `slides`: per static wall, the acceleration of a body resting on it (`[ax, ay(, az)]`), or
/// `null` where none rests.
#[must_use]
pub fn meta_json<const D: usize>(p: &Playback<D>, finder: &str) -> serde_json::Value {
    let e = p.extent();
    let mut meta = serde_json::json!({
        "file": p.path(),
        "dim": D,
        "bodies": p.slots(),
        "scene_bodies": p.scene().bodies.len(),
        "slot_edits": p.has_slot_edits(),
        "events": p.events(),
        "start_time": p.start_time(),
        "end_time": p.end_time(),
        "complete": p.complete(),
        "walls": p.scene().walls,
        "sensors": p.scene().sensors,
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
    });
    // Only when there are some: the description of every other run stays as it was.
    if !p.scene().moving_walls.is_empty() {
        meta["moving_walls"] = serde_json::json!(p.scene().moving_walls);
    }
    if let Some(rest_speed) = p.scene().settings.rest_speed {
        meta["rest_speed"] = serde_json::json!(rest_speed);
        meta["slides"] = serde_json::json!(ccdsim::scene::slides(p.scene()));
    }
    meta
}
