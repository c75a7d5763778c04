//! Every body's lazy state, every resting body's support, and every moving wall's motion, as
//! replayed from a run file.

use ccdsim::motion::{start_motions, translated};

use ccdsim::motion::pivot::Pivot;
use ccdsim::motion::Path;
use ccdsim::Motion;
use ccdsim::WallMotion;
use ccdsim::{Collision, EventKind, Scene, Vector, Wall};
use std::sync::Arc;

/// The edit codes of a run file's edit records (the `b` field), as [`ccdsim::edit`] writes
/// them (a unit test keeps the two in step).
pub mod edit_code {
    /// A new position or velocity: the first slot holds the body's state.
    pub const MOTION: u32 = 0;
    /// A body added: its state in the first slot; its radius and mass (∞: kinematic) in the
    /// second slot's position. Always followed by [`ADD_ID`].
    pub const ADD: u32 = 1;
    /// The id of the body just added: the bits of the second slot's first position
    /// component. Carries no state (its first slot is zero).
    pub const ADD_ID: u32 = 2;
    /// A body removed: where it stopped in the first slot; its slot is vacant from then on.
    pub const REMOVE: u32 = 3;
    /// A new collision filter: the first slot restates the body's state.
    pub const FILTER: u32 = 4;
    /// A moving wall's new velocity: `a` names the wall among the scene's moving walls (not
    /// a body); the first slot holds its displacement from the scene's geometry at the
    /// record's time and its velocity from then on.
    pub const WALL_MOTION: u32 = 5;
}

use edit_code::{ADD, ADD_ID, FILTER, MOTION, REMOVE, WALL_MOTION};

/// A body's support when it rests on no wall (see [`BodyStates::support`]).
const NO_SUPPORT: u32 = u32::MAX;

/// The slots' radii, ids, kinematic flags and vacancies.
///
/// They change only when a body is added or removed, which most runs never do, while the
/// keyframe index keeps one [`BodyStates`] per keyframe. So the table is shared (an [`Arc`])
/// between the states it was copied into, and copied on the first write after that
/// ([`Arc::make_mut`]): a run without adds and removals keeps one table for all its
/// keyframes, 8 bytes of pointer each, and a run with them keeps one per keyframe interval
/// in which a slot changed, the same order of memory as the motions themselves.
#[derive(Clone, Debug, PartialEq)]
struct SlotTable {
    /// Radius per slot, metres; 0 for a vacant slot.
    radius: Vec<f64>,
    /// User id per slot (`u64::MAX` for a vacant slot, as the simulation keeps it).
    id: Vec<u64>,
    /// Kinematic bodies (and vacant slots, kept at rest as the simulation keeps them).
    kinematic: Vec<bool>,
    /// Vacant slots.
    vacant: Vec<bool>,
    /// True once a body was added or removed.
    edited: bool,
}

impl SlotTable {
    fn heap_bytes(&self) -> usize {
        self.radius.len() * (2 * std::mem::size_of::<u64>() + 2)
    }
}

/// The stored state of every body slot (structure of arrays): body `i` is at `pos[i]` at
/// time `time[i]` and moves with `vel[i]`, so its position at `t` is `pos + vel·(t − time)`,
/// or, in a run with gravity `g`, `pos + vel·(t − time) + ½·g·(t − time)²` (its velocity then
/// is `vel + g·(t − time)`); kinematic bodies move in straight lines even under gravity.
///
/// Slots are the simulation's: a run that adds and removes bodies (see [`ccdsim::edit`])
/// grows the slots as bodies are added past the last one, and a removed body's slot is
/// *vacant* ([`BodyStates::is_vacant`]: at rest where the body stopped, radius 0, drawn by
/// no one) until a body is added there. Slots the simulation reserved but the run never
/// filled are not known here: [`BodyStates::len`] counts the slots up to the last one used.
///
/// In a run where bodies rest on walls (the scene's `settings.rest_speed`, run files of format
/// version 11, or 12 when they rest on 2D segments too, see [`ccdsim::contact::resting`]), each body
/// also has a *support*: the static plane or segment it rests on, if any
/// ([`BodyStates::support`]). A resting body slides along its wall with the acceleration
/// [`ccdsim::contact::resting::slide_acceleration`] gives instead of `g`
/// ([`BodyStates::acceleration`]). The records' flags say which bodies rest: a wall event
/// flagged for its body puts it on that wall, a body event flagged for one of its bodies keeps
/// that body on the wall it rested on, and any record naming a body without its flag lifts it
/// off (it falls under `g` again). So a body reaching the end of the segment it slides on
/// (format 12, see [`ccdsim::contact::ledge`]) flies off when that wall event has no flag, and rests
/// on the segment going straight on when the event is flagged and names that one.
///
/// In such a run with 2D segments (format version 13, see [`ccdsim::motion::pivot`]), a body too slow
/// to fly off a segment's end rolls over it: a wall event of a body with the segment it slid
/// on, flagged as turning (`pivots[0]`), starts a *turn* about the end point of that segment
/// it reached ([`ccdsim::contact::ledge::end_reached`]), from the record's position and velocity
/// ([`BodyStates::turn`]). Until the next record naming the body, its position and velocity
/// come from that turn ([`Pivot::position`], [`Pivot::velocity`]), not from its stored state
/// and an acceleration (a turning body has none: [`BodyStates::acceleration`] is `None` for
/// it, as the simulation's [`ccdsim::World::gravity_of`]). That next record ends the turn and
/// gives the body its new state (released and falling, or resting on a segment).
///
/// The moving walls of a run (a scene's `moving_walls`, see [`ccdsim::world::time_of_impact`]) are kept
/// here too, since the same records move them: moving wall `k` is its scene geometry
/// displaced by [`BodyStates::wall_motion`]`(k)`, which each of its edit records
/// ([`edit_code::WALL_MOTION`]) restates ([`BodyStates::moving_wall_at`]).
///
/// Replaying a run's records with [`BodyStates::apply`] reproduces the simulation's stored
/// states of its bodies and its moving walls' motions bit for bit, since a run file records
/// exactly the states a collision or edit stored.
#[derive(Clone, Debug, PartialEq)]
pub struct BodyStates<const D: usize> {
    /// Reference positions, metres.
    pub pos: Vec<Vector<D>>,
    /// Velocities, metres per second.
    pub vel: Vec<Vector<D>>,
    /// Reference times, seconds.
    pub time: Vec<f64>,
    /// The acceleration of every body between events (the scene's `settings.gravity`), if
    /// the run has gravity, metres per second squared; a body resting on a wall slides with
    /// its own (see [`BodyStates::acceleration`]).
    pub gravity: Option<Vector<D>>,
    /// The static wall each slot's body rests on ([`NO_SUPPORT`]: none); empty in a run
    /// where bodies never rest (no `settings.rest_speed`).
    supports: Vec<u32>,
    /// The acceleration of a body sliding on each static wall (`None` where none rests),
    /// which never changes: shared by every copy; empty where bodies never rest.
    slides: Arc<[Option<Vector<D>>]>,
    /// The bodies turning about a segment's end point (slot and turn), in the order they
    /// started; empty unless some body turns (never outside 2D runs with gravity where
    /// bodies rest on segments).
    turns: Vec<(usize, Pivot)>,
    /// The scene's static walls, which never change: shared by every copy (a turn is about
    /// the end point of one of its segments).
    walls: Arc<[Wall<D>]>,
    slots: Arc<SlotTable>,
    /// The moving walls' scene geometry, which never changes: shared by every copy.
    wall_bases: Arc<[Wall<D>]>,
    /// How each moving wall moves since its last edit (or since the start).
    wall_motions: Vec<WallMotion<D>>,
}

impl<const D: usize> BodyStates<D> {
    /// The states at the start of a run of `scene`.
    #[must_use]
    pub fn from_scene(scene: &Scene<D>) -> Self {
        let n = scene.bodies.len();
        BodyStates {
            pos: scene.bodies.iter().map(|b| b.pos).collect(),
            vel: scene.bodies.iter().map(|b| b.vel).collect(),
            time: vec![scene.start_time; n],
            gravity: scene.gravity(),
            supports: match scene.settings.rest_speed {
                Some(_) => vec![NO_SUPPORT; n],
                None => Vec::new(),
            },
            slides: ccdsim::scene::slides(scene).into(),
            turns: Vec::new(),
            walls: scene.walls.clone().into(),
            slots: Arc::new(SlotTable {
                radius: scene.bodies.iter().map(|b| b.radius).collect(),
                id: (0..n).map(|i| scene.id_of(i)).collect(),
                kinematic: scene.bodies.iter().map(|b| b.kinematic).collect(),
                vacant: vec![false; n],
                edited: false,
            }),
            wall_bases: scene.moving_walls.iter().map(|m| m.wall).collect(),
            // As the simulation starts them: at their scene geometry, at the scene's velocity.
            wall_motions: start_motions(&scene.moving_walls, scene.start_time),
        }
    }

    /// Number of slots (bodies and vacant slots).
    #[must_use]
    pub fn len(&self) -> usize {
        self.pos.len()
    }

    /// True when there are no slots.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.pos.is_empty()
    }

    /// Radius of the body in slot `i`, metres (at the run's start, in a run with growing
    /// radii); 0 when the slot is vacant.
    #[must_use]
    pub fn radius(&self, i: usize) -> f64 {
        self.slots.radius[i]
    }

    /// User id of the body in slot `i` (`u64::MAX` when the slot is vacant, as in the
    /// simulation).
    #[must_use]
    pub fn id(&self, i: usize) -> u64 {
        self.slots.id[i]
    }

    /// True when the body in slot `i` is kinematic (or the slot is vacant: kept at rest).
    #[must_use]
    pub fn is_kinematic(&self, i: usize) -> bool {
        self.slots.kinematic[i]
    }

    /// True when slot `i` holds no body: its body was removed, or the slot lies between the
    /// last one and a body added past it.
    #[must_use]
    pub fn is_vacant(&self, i: usize) -> bool {
        self.slots.vacant[i]
    }

    /// True once a body was added or removed: radii, ids, kinematic flags or the number of
    /// slots may then differ from the scene's.
    #[must_use]
    pub fn has_slot_edits(&self) -> bool {
        self.slots.edited
    }

    /// Number of moving walls.
    #[must_use]
    pub fn wall_count(&self) -> usize {
        self.wall_motions.len()
    }

    /// How moving wall `k` moves: its displacement from the scene's geometry at a reference
    /// time, and its velocity since then.
    #[must_use]
    pub fn wall_motion(&self, k: usize) -> WallMotion<D> {
        self.wall_motions[k]
    }

    /// Moving wall `k` where it is at time `t` (its scene geometry translated by its
    /// displacement then), as the simulation's [`ccdsim::World::wall_at`] has it.
    #[must_use]
    pub fn moving_wall_at(&self, k: usize, t: f64) -> Wall<D> {
        translated(&self.wall_bases[k], self.wall_motions[k].offset_at(t))
    }

    /// Checks that record `c` can be applied: every slot it names holds a body, except an
    /// added body's, which must be vacant or past the last slot (by at most
    /// `len().max(1024)`: the simulation reserves a quarter more slots at a time and fills
    /// the lowest first), and a moving wall's edit, which names one of the moving walls. An
    /// added body's id record ([`edit_code::ADD_ID`]) is checked by the caller, which knows
    /// the record before. A body flagged as resting after the record (versions 11 and 12) must
    /// rest on a static plane or segment bodies can rest on (a wall event's wall) or have
    /// rested before (a body event's body). A body flagged as turning about a point after the
    /// record (version 13) must be body `a` of a wall event naming a static segment, in a 2D
    /// run with gravity where bodies rest, not flagged as resting too, and must touch the end
    /// point of that segment it reached (see [`BodyStates::turn`]).
    pub fn check(&self, c: &Collision<D>) -> Result<(), String> {
        let a = c.event.a as usize;
        self.check_rests(c)?;
        if c.pivots != [false; 2] && c.event.kind != EventKind::Wall {
            // Refused whatever the record names (a wall event's flag is checked below).
            self.turn_after(c)?;
        }
        let present = |i: usize| -> Result<(), String> {
            if i >= self.len() {
                Err(format!(
                    "names body {i}, past the last slot ({})",
                    self.len()
                ))
            } else if self.is_vacant(i) {
                Err(format!("names body {i}, whose slot is vacant"))
            } else {
                Ok(())
            }
        };
        match c.event.kind {
            EventKind::Body => present(a).and_then(|()| present(c.event.b as usize)),
            EventKind::Wall => present(a).and_then(|()| self.turn_after(c).map(|_| ())),
            EventKind::Reset => present(a),
            EventKind::Edit => match c.event.b {
                MOTION | REMOVE | FILTER => present(a),
                ADD => {
                    let n = self.len();
                    if a < n && !self.is_vacant(a) {
                        return Err(format!("adds a body in slot {a}, which holds one"));
                    }
                    if a >= n + n.max(1024) {
                        return Err(format!(
                            "adds a body in slot {a}, far past the last slot ({n})"
                        ));
                    }
                    let r = c.pos[1][0];
                    if !(r.is_finite() && r > 0.0) {
                        return Err(format!("adds a body of radius {r} in slot {a}"));
                    }
                    Ok(())
                }
                ADD_ID => Ok(()),
                WALL_MOTION if a < self.wall_count() => Ok(()),
                WALL_MOTION => Err(format!(
                    "moves wall {a}, but the run has {} moving walls",
                    self.wall_count()
                )),
                code => Err(format!("an edit of unknown code {code}")),
            },
        }
    }

    /// The turn body `a` of record `c` starts after it, as its turning flag says (see
    /// [`BodyStates::turn`]): `None` without the flag, or when the record's state makes no
    /// turn ([`Pivot::new`] gives none: a body at rest straight above the point stays there
    /// as its stored state has it). Refuses a flag that cannot be (see
    /// [`BodyStates::check`]). Body `a` is present.
    fn turn_after(&self, c: &Collision<D>) -> Result<Option<Pivot>, String> {
        let (a, b) = (c.event.a as usize, c.event.b as usize);
        if c.pivots[1] {
            return Err(format!(
                "flags body {b} (slot 1) as turning about a point: only a wall event's body turns"
            ));
        }
        if !c.pivots[0] {
            return Ok(None);
        }
        if c.event.kind != EventKind::Wall {
            return Err(format!(
                "flags body {a} as turning about a point after a {:?} event, not a wall event",
                c.event.kind
            ));
        }
        let Some(g) = self.gravity else {
            return Err(format!(
                "turns body {a} about a point in a run without gravity"
            ));
        };
        if D != 2 {
            return Err(format!("turns body {a} about a point in a {D}D run"));
        }
        if self.supports.is_empty() {
            return Err(format!(
                "turns body {a} about a point in a run where no body rests"
            ));
        }
        if c.rests[0] {
            return Err(format!(
                "flags body {a} as both resting on wall {b} and turning about its end"
            ));
        }
        if self.is_kinematic(a) {
            return Err(format!("turns kinematic body {a} about a point"));
        }
        let Some(&Wall::Segment { a: p, b: q }) = self.walls.get(b) else {
            return Err(format!(
                "turns body {a} about an end of wall {b}, which is no static segment"
            ));
        };
        let r = self.radius(a);
        ccdsim::contact::ledge::recorded_turn((p, q), r, g, (c.pos[0], c.vel[0]), c.event.time)
            .map_err(|dist| {
                format!(
                    "turns body {a} about an end point of segment {b} it does not touch (its \
                     centre {dist} m from it, its radius {r} m)"
                )
            })
    }

    /// Checks the record's resting flags (see [`BodyStates::check`]).
    fn check_rests(&self, c: &Collision<D>) -> Result<(), String> {
        if c.rests == [false; 2] {
            return Ok(());
        }
        if self.supports.is_empty() {
            return Err("flags a resting body in a run where none rests".into());
        }
        let (a, b) = (c.event.a as usize, c.event.b as usize);
        match c.event.kind {
            EventKind::Wall if !c.rests[1] => match self.slides.get(b) {
                Some(Some(_)) => Ok(()),
                _ => Err(format!(
                    "rests body {a} on wall {b}, which holds no resting body"
                )),
            },
            EventKind::Body => {
                for (s, i) in [(0, a), (1, b)] {
                    if c.rests[s] && self.support(i).is_none() {
                        return Err(format!("keeps body {i} resting, but it rested on no wall"));
                    }
                }
                Ok(())
            }
            _ => Err("flags a resting body where none can rest".into()),
        }
    }

    /// Stores the states a recorded collision or edit left its bodies in: a body added fills
    /// its slot (the slots up to it grow, vacant), a body removed stops and leaves its slot
    /// vacant, an id record sets the added body's id, a moving wall's edit gives that wall
    /// its new motion (and touches no body). Every body the record names leaves its wall
    /// unless the record says it rests: on the wall of a wall event, or, after a body event,
    /// on the wall it rested on before. Every body the record names ends its turn, if it
    /// turned; a wall event flagged as turning starts body `a`'s (see [`BodyStates::turn`]).
    /// Assumes [`BodyStates::check`] passed.
    pub fn apply(&mut self, c: &Collision<D>) {
        let t = c.event.time;
        let a = c.event.a as usize;
        match c.event.kind {
            EventKind::Body => {
                let b = c.event.b as usize;
                let kept = [a, b].map(|i| self.supports.get(i).copied());
                self.set(a, c.pos[0], c.vel[0], t);
                self.set(b, c.pos[1], c.vel[1], t);
                for (s, i) in [(0, a), (1, b)] {
                    if let (true, Some(w)) = (c.rests[s], kept[s]) {
                        self.supports[i] = w;
                    }
                }
            }
            EventKind::Wall => {
                self.set(a, c.pos[0], c.vel[0], t);
                if c.rests[0] {
                    self.supports[a] = c.event.b;
                }
                if let Ok(Some(turn)) = self.turn_after(c) {
                    self.turns.push((a, turn));
                }
            }
            EventKind::Reset => self.set(a, c.pos[0], c.vel[0], t),
            EventKind::Edit => match c.event.b {
                ADD => {
                    if a >= self.len() {
                        self.grow(a + 1, c.pos[0], t);
                    }
                    self.set(a, c.pos[0], c.vel[0], t);
                    let s = self.slots_mut();
                    s.radius[a] = c.pos[1][0];
                    s.kinematic[a] = c.pos[1][1] == f64::INFINITY;
                    s.vacant[a] = false;
                    // The id record follows at once, at the same time.
                    s.id[a] = u64::MAX;
                }
                ADD_ID => self.slots_mut().id[a] = c.pos[1][0].to_bits(),
                REMOVE => {
                    self.set(a, c.pos[0], Vector::ZERO, t);
                    let s = self.slots_mut();
                    s.radius[a] = 0.0;
                    s.id[a] = u64::MAX;
                    s.kinematic[a] = true;
                    s.vacant[a] = true;
                }
                WALL_MOTION => {
                    self.wall_motions[a] = WallMotion {
                        offset: c.pos[0],
                        velocity: c.vel[0],
                        time: t,
                    };
                }
                // A new motion or filter: the body's state restated. (Unknown codes are
                // refused by `check`.)
                _ => self.set(a, c.pos[0], c.vel[0], t),
            },
        }
    }

    /// The slot table, to be written: copied first when keyframes share it.
    fn slots_mut(&mut self) -> &mut SlotTable {
        let s = Arc::make_mut(&mut self.slots);
        s.edited = true;
        s
    }

    /// Adds vacant slots up to `n`, at rest at `p` since `t`.
    fn grow(&mut self, n: usize, p: Vector<D>, t: f64) {
        self.pos.resize(n, p);
        self.vel.resize(n, Vector::ZERO);
        self.time.resize(n, t);
        if !self.supports.is_empty() {
            self.supports.resize(n, NO_SUPPORT);
        }
        let s = self.slots_mut();
        s.radius.resize(n, 0.0);
        s.id.resize(n, u64::MAX);
        s.kinematic.resize(n, true);
        s.vacant.resize(n, true);
    }

    /// Sets body `i`'s state, which lifts it off its wall (a record that leaves it resting
    /// puts it back) and ends its turn (a record that turns it starts a new one).
    fn set(&mut self, i: usize, p: Vector<D>, v: Vector<D>, t: f64) {
        self.pos[i] = p;
        self.vel[i] = v;
        self.time[i] = t;
        if let Some(s) = self.supports.get_mut(i) {
            *s = NO_SUPPORT;
        }
        if !self.turns.is_empty() {
            self.turns.retain(|&(j, _)| j != i);
        }
    }

    /// The turn of the body in slot `i` about a segment's end point, if it turns (see
    /// [`ccdsim::motion::pivot`]): started by a wall event flagged as turning, from that event's
    /// position and velocity (its stored state, [`BodyStates::motion`]), about the end point
    /// of the event's segment it reached; it lasts until the next record naming the body.
    #[must_use]
    pub fn turn(&self, i: usize) -> Option<&Pivot> {
        if self.turns.is_empty() {
            return None;
        }
        self.turns.iter().find(|&&(j, _)| j == i).map(|(_, p)| p)
    }

    /// The bodies turning about a segment's end point and their turns, in the order they
    /// started (see [`BodyStates::turn`]).
    pub fn turning(&self) -> impl Iterator<Item = (usize, &Pivot)> + '_ {
        self.turns.iter().map(|(i, p)| (*i, p))
    }

    /// The static wall (by index among the scene's `walls`) the body in slot `i` rests on,
    /// sliding along it, if it does: only in a run with `settings.rest_speed`.
    #[must_use]
    pub fn support(&self, i: usize) -> Option<usize> {
        match self.supports.get(i) {
            Some(&w) if w != NO_SUPPORT => Some(w as usize),
            _ => None,
        }
    }

    /// True in a run where bodies may rest on walls (the scene has `settings.rest_speed`):
    /// its states keep every body's support.
    #[must_use]
    pub fn has_supports(&self) -> bool {
        !self.supports.is_empty()
    }

    /// The acceleration of the body in slot `i` between events, metres per second squared:
    /// the run's gravity, or for a body resting on a wall the acceleration it slides with
    /// (`g − n (g·n)/(n·n)`); `None` without gravity or for a kinematic body (or a vacant
    /// slot), which moves in a straight line, and for a body turning about a point, whose
    /// motion is its turn ([`BodyStates::turn`]). As the simulation's
    /// [`ccdsim::World::gravity_of`].
    #[must_use]
    #[inline]
    pub fn acceleration(&self, i: usize) -> Option<Vector<D>> {
        let g = self.gravity.filter(|_| !self.is_kinematic(i))?;
        if self.turn(i).is_some() {
            return None;
        }
        Some(match self.support(i) {
            Some(w) => self.slides[w].unwrap_or(g),
            None => g,
        })
    }

    /// Body `i`'s stored state: for a turning body, the state its turn started from.
    #[must_use]
    pub fn motion(&self, i: usize) -> Motion<D> {
        Motion {
            pos: self.pos[i],
            vel: self.vel[i],
            time: self.time[i],
        }
    }

    /// Position of body `i` at time `t`, metres: on its straight line, or on its parabola
    /// in a run with gravity (under [`BodyStates::acceleration`]: a resting body's slides
    /// along its wall), or on its circle about the point it turns about
    /// ([`BodyStates::turn`]).
    #[must_use]
    pub fn position_at(&self, i: usize, t: f64) -> Vector<D> {
        self.path(i).position(t)
    }

    /// Velocity of body `i` at time `t`, metres per second: the stored one, or in a run with
    /// gravity that plus `a·(t − time)`, `a` its [`BodyStates::acceleration`]; along its
    /// circle for a turning body ([`BodyStates::turn`]).
    #[must_use]
    pub fn velocity_at(&self, i: usize, t: f64) -> Vector<D> {
        self.path(i).velocity(t)
    }

    /// Body `i`'s path from its last record: its turn about a point ([`BodyStates::turn`]),
    /// or its stored motion under its [`BodyStates::acceleration`].
    #[must_use]
    pub fn path(&self, i: usize) -> Path<D> {
        match self.turn(i) {
            Some(p) => Path::Turn(*p),
            None => Path::new(self.motion(i), self.acceleration(i)),
        }
    }

    /// Heap bytes held: the motions (the bodies' and the moving walls'), the supports, the
    /// turns, and the slot table as if this were its only holder.
    #[must_use]
    pub fn heap_bytes(&self) -> usize {
        Self::bytes_per_body() * self.len()
            + std::mem::size_of::<u32>() * self.supports.len()
            + std::mem::size_of::<(usize, Pivot)>() * self.turns.len()
            + std::mem::size_of::<WallMotion<D>>() * self.wall_count()
            + self.slot_table_bytes()
    }

    /// Heap bytes of the slot table (radii, ids, kinematic flags, vacancies), which copies
    /// of these states share until a body is added or removed in one of them.
    #[must_use]
    pub fn slot_table_bytes(&self) -> usize {
        self.slots.heap_bytes()
    }

    /// True when `self` and `other` share one slot table (see
    /// [`BodyStates::slot_table_bytes`]).
    #[must_use]
    pub fn shares_slot_table(&self, other: &Self) -> bool {
        Arc::ptr_eq(&self.slots, &other.slots)
    }

    /// Bytes one body's motion takes (the slot table is shared; see
    /// [`BodyStates::slot_table_bytes`]).
    #[must_use]
    pub const fn bytes_per_body() -> usize {
        (2 * D + 1) * std::mem::size_of::<f64>()
    }

    /// Bytes one body takes in the states of a run of `scene`: its motion, and its support
    /// in a run where bodies rest on walls.
    #[must_use]
    pub fn bytes_per_body_of(scene: &Scene<D>) -> usize {
        Self::bytes_per_body()
            + if scene.settings.rest_speed.is_some() {
                std::mem::size_of::<u32>()
            } else {
                0
            }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use ccdsim::edit::Edit;
    use ccdsim::{BodySpec, CollisionFilter};

    #[test]
    fn the_edit_codes_are_the_librarys() {
        let (p, v) = (Vector([1.0, 2.0]), Vector([0.5, 0.0]));
        let code = |e: Edit<2>| -> Vec<u32> { e.records(0.5).iter().map(|r| r.event.b).collect() };
        assert_eq!(
            code(Edit::Motion {
                body: 0,
                pos: p,
                vel: v
            }),
            [MOTION]
        );
        let add = Edit::Add {
            body: 3,
            id: 77,
            pos: p,
            vel: v,
            radius: 0.25,
            mass: f64::INFINITY,
            filter: CollisionFilter::DEFAULT,
            restitution: None,
        };
        assert_eq!(code(add), [ADD, ADD_ID]);
        assert_eq!(code(Edit::Remove { body: 0, pos: p }), [REMOVE]);
        assert_eq!(
            code(Edit::Filter {
                body: 0,
                pos: p,
                vel: v,
                filter: CollisionFilter::NONE
            }),
            [FILTER]
        );
        assert_eq!(
            code(Edit::WallMotion {
                wall: 1,
                offset: p,
                vel: v
            }),
            [WALL_MOTION]
        );
        // And the fields read here are the ones the library decodes.
        let rs = add.records(0.5);
        let Ok(Edit::Add {
            radius, mass, id, ..
        }) = Edit::decode(&rs[0], Some(&rs[1]))
        else {
            panic!("an add decodes");
        };
        assert_eq!((rs[0].pos[1][0], rs[0].pos[1][1]), (radius, mass));
        assert_eq!(rs[1].pos[1][0].to_bits(), id);
    }

    #[test]
    fn a_wall_edit_moves_its_wall_and_no_body() {
        use ccdsim::MovingWall;
        let scene = Scene::<2> {
            bodies: vec![
                BodySpec::new(Vector([0.0, 0.0]), Vector([1.0, 0.0]), 0.5),
                BodySpec::new(Vector([3.0, 0.0]), Vector([0.0, 1.0]), 0.5),
            ],
            moving_walls: vec![MovingWall {
                wall: Wall::Segment {
                    a: Vector([5.0, -1.0]),
                    b: Vector([5.0, 1.0]),
                },
                velocity: Vector([0.5, 0.0]),
            }],
            ..Scene::default()
        };
        let mut s = BodyStates::from_scene(&scene);
        assert_eq!(s.wall_count(), 1);
        // Without an edit, the wall moves at the scene's velocity from the start.
        assert_eq!(
            s.moving_wall_at(0, 2.0),
            Wall::Segment {
                a: Vector([6.0, -1.0]),
                b: Vector([6.0, 1.0]),
            }
        );
        let bodies = (s.pos.clone(), s.vel.clone(), s.time.clone());
        // At t = 2 the wall (displaced by 1 m) turns up at 2 m/s. The record names wall 0,
        // which is also a body's slot: that body must not move.
        let edit = Edit::<2>::WallMotion {
            wall: 0,
            offset: Vector([1.0, 0.0]),
            vel: Vector([0.0, 2.0]),
        }
        .records(2.0)[0];
        s.check(&edit).unwrap();
        s.apply(&edit);
        assert_eq!((s.pos.clone(), s.vel.clone(), s.time.clone()), bodies);
        assert!(!s.has_slot_edits());
        assert_eq!(
            s.moving_wall_at(0, 3.0),
            Wall::Segment {
                a: Vector([6.0, 1.0]),
                b: Vector([6.0, 3.0]),
            }
        );
        let mut far = edit;
        far.event.a = 1;
        assert!(s.check(&far).unwrap_err().contains("1 moving walls"));
    }

    #[test]
    fn the_records_flags_put_bodies_on_their_walls_and_lift_them_off() {
        use ccdsim::Gravity;
        use ccdsim::{Event, Settings};
        let incline = Wall::Plane {
            point: Vector([0.0, 0.0]),
            normal: Vector([-1.0, 1.0]),
        };
        let scene = Scene::<2> {
            settings: Settings {
                gravity: Gravity::new(&[0.0, -10.0]),
                rest_speed: Some(0.5),
                ..Settings::default()
            },
            bodies: vec![
                BodySpec::new(Vector([0.0, 1.0]), Vector([1.0, 0.0]), 0.5),
                BodySpec::new(Vector([3.0, 1.0]), Vector([0.0, 0.0]), 0.5),
                BodySpec {
                    kinematic: true,
                    ..BodySpec::new(Vector([6.0, 1.0]), Vector([0.0, -1.0]), 0.5)
                },
            ],
            walls: vec![
                Wall::Plane {
                    point: Vector([0.0, 0.0]),
                    normal: Vector([0.0, 1.0]),
                },
                incline,
                Wall::Segment {
                    a: Vector([-9.0, 0.0]),
                    b: Vector([-9.0, 9.0]),
                },
            ],
            ..Scene::default()
        };
        let g = Vector([0.0, -10.0]);
        let record = |kind, a, b, t: f64, rests| Collision {
            event: Event {
                time: t,
                kind,
                a,
                b,
            },
            pos: [Vector([0.0, 0.5]), Vector([3.0, 0.5])],
            vel: [Vector([1.0, 0.0]), Vector([-1.0, 0.0])],
            rests,
            pivots: [false; 2],
        };
        let mut s = BodyStates::from_scene(&scene);
        assert!(s.has_supports());
        assert_eq!((s.support(0), s.acceleration(0)), (None, Some(g)));
        assert_eq!(s.acceleration(2), None, "kinematic bodies never fall");
        let apply = |s: &mut BodyStates<2>, c: &Collision<2>| {
            s.check(c).unwrap();
            s.apply(c);
        };
        // Body 0 comes to rest on the floor, body 1 on the incline.
        apply(&mut s, &record(EventKind::Wall, 0, 0, 1.0, [true, false]));
        apply(&mut s, &record(EventKind::Wall, 1, 1, 1.0, [true, false]));
        assert_eq!(s.support(0), Some(0));
        assert_eq!(s.acceleration(0), Some(Vector([0.0, 0.0])));
        assert_eq!(s.position_at(0, 3.0), Vector([2.0, 0.5]), "it slides on");
        assert_eq!(s.acceleration(1), Some(Vector([-5.0, -5.0])));
        // A body event that keeps body 0 resting and not body 1: body 1 falls again.
        apply(&mut s, &record(EventKind::Body, 0, 1, 2.0, [true, false]));
        assert_eq!((s.support(0), s.support(1)), (Some(0), None));
        assert_eq!(s.acceleration(1), Some(g));
        // Keyframes keep the supports.
        let copy = s.clone();
        // A wall event without the flag lifts it off, so does an edit.
        apply(&mut s, &record(EventKind::Wall, 0, 2, 3.0, [false; 2]));
        assert_eq!(s.support(0), None);
        apply(&mut s, &record(EventKind::Wall, 1, 1, 3.0, [true, false]));
        apply(
            &mut s,
            &Edit::Motion {
                body: 1,
                pos: Vector([3.0, 0.5]),
                vel: Vector::ZERO,
            }
            .records(4.0)[0],
        );
        assert_eq!(s.support(1), None);
        assert_eq!(copy.support(0), Some(0));
        // Refused: a rest on a vertical segment (gravity runs along it) or after a reset; a
        // body event keeping a body resting that did not rest.
        for (c, why) in [
            (
                record(EventKind::Wall, 0, 2, 5.0, [true, false]),
                "holds no",
            ),
            (
                record(EventKind::Body, 0, 1, 5.0, [false, true]),
                "rested on no",
            ),
            (
                record(EventKind::Reset, 0, 0, 5.0, [true, false]),
                "none can",
            ),
        ] {
            let err = s.check(&c).unwrap_err();
            assert!(err.contains(why), "{err}");
        }
        // In a run where bodies never rest, any flag is refused and nothing is kept.
        let plain = BodyStates::from_scene(&Scene {
            settings: Settings {
                gravity: Gravity::new(&[0.0, -10.0]),
                ..Settings::default()
            },
            ..scene.clone()
        });
        assert!(!plain.has_supports());
        let err = plain
            .check(&record(EventKind::Wall, 0, 0, 1.0, [true, false]))
            .unwrap_err();
        assert!(err.contains("none rests"), "{err}");
        assert_eq!(plain.heap_bytes() + 4 * 3, copy.heap_bytes());
    }

    #[test]
    fn adds_and_removes_change_the_slots_and_share_the_table_until_then() {
        let scene = Scene::<2> {
            bodies: vec![BodySpec::new(Vector([0.0, 0.0]), Vector([1.0, 0.0]), 0.5)],
            ..Scene::default()
        };
        let mut s = BodyStates::from_scene(&scene);
        let copy = s.clone();
        assert!(s.shares_slot_table(&copy) && !s.has_slot_edits());
        let add = Edit::<2>::Add {
            body: 3,
            id: 9,
            pos: Vector([5.0, 1.0]),
            vel: Vector([0.0, -1.0]),
            radius: 0.25,
            mass: f64::INFINITY,
            filter: CollisionFilter::DEFAULT,
            restitution: None,
        }
        .records(2.0);
        for r in &add {
            s.check(r).unwrap();
            s.apply(r);
        }
        assert!(!s.shares_slot_table(&copy) && s.has_slot_edits());
        assert_eq!(copy.len(), 1, "the copy is untouched");
        assert_eq!(s.len(), 4);
        for i in [1, 2] {
            assert!(
                s.is_vacant(i) && s.radius(i) == 0.0 && s.is_kinematic(i),
                "slot {i}"
            );
        }
        assert!(!s.is_vacant(3));
        assert_eq!((s.radius(3), s.id(3), s.is_kinematic(3)), (0.25, 9, true));
        assert_eq!(s.position_at(3, 3.0), Vector([5.0, 0.0]));
        // A second add at slot 3 is refused; one far past the slots too.
        assert!(s.check(&add[0]).unwrap_err().contains("holds one"));
        let mut far = add[0];
        far.event.a = 5000;
        assert!(s.check(&far).unwrap_err().contains("far past"));
        let remove = Edit::<2>::Remove {
            body: 0,
            pos: Vector([2.0, 0.0]),
        }
        .records(2.0)[0];
        s.check(&remove).unwrap();
        s.apply(&remove);
        assert!(s.is_vacant(0) && s.radius(0) == 0.0);
        assert_eq!(s.position_at(0, 10.0), Vector([2.0, 0.0]), "at rest");
        assert!(s.check(&remove).unwrap_err().contains("vacant"));
        // Vacant slot 1 takes the next body.
        let mut again = add[0];
        again.event.a = 1;
        s.check(&again).unwrap();
    }

    /// A ball of radius 0.2 on a shelf at y = 1 from x = 0 to 2 over a floor, moving right at
    /// 1 m/s under g = (0, −10): too slow to fly off the end (1² < r g), it rolls over it.
    fn roll_over_scene() -> Scene<2> {
        use ccdsim::Gravity;
        use ccdsim::Settings;
        Scene {
            settings: Settings {
                restitution: 0.5,
                gravity: Gravity::new(&[0.0, -10.0]),
                rest_speed: Some(1.0),
                ..Settings::default()
            },
            bodies: vec![BodySpec::new(
                Vector([1.5, 1.2 + 1e-6]),
                Vector([1.0, 0.0]),
                0.2,
            )],
            walls: vec![
                Wall::Plane {
                    point: Vector([0.0, 0.0]),
                    normal: Vector([0.0, 1.0]),
                },
                Wall::Segment {
                    a: Vector([0.0, 1.0]),
                    b: Vector([2.0, 1.0]),
                },
            ],
            ..Scene::default()
        }
    }

    #[test]
    fn a_turning_flag_turns_the_body_about_the_segments_end_until_its_next_record() {
        use ccdsim::Simulation;
        let scene = roll_over_scene();
        let mut sim = Simulation::new(&scene, "all-pairs").unwrap();
        let mut s = BodyStates::from_scene(&scene);
        let mut records = Vec::new();
        while let Some(c) = sim.step_event_until(3.0) {
            s.check(&c).unwrap();
            s.apply(&c);
            records.push((c, s.clone()));
            if records.len() == 4 {
                break;
            }
        }
        // Land, roll over the end, come off, the floor.
        let roll = records[1].0;
        assert!(
            roll.pivots[0] && roll.event.kind == EventKind::Wall,
            "{roll:?}"
        );
        let turning = &records[1].1;
        let pivot = *turning.turn(0).expect("the flag starts a turn");
        assert_eq!(
            pivot.point(),
            Vector([2.0, 1.0]),
            "about the end it reached"
        );
        assert_eq!(pivot.start_time(), roll.event.time);
        assert_eq!(turning.turning().map(|(i, _)| i).collect::<Vec<_>>(), [0]);
        assert_eq!(turning.acceleration(0), None, "a turn, not a parabola");
        assert_eq!(turning.support(0), None);
        assert!(turning.heap_bytes() > records[0].1.heap_bytes());
        let off = records[2].0;
        assert!(
            !off.pivots[0] && off.event.kind == EventKind::Wall,
            "{off:?}"
        );
        // Mid-turn, the states are where the simulation has the ball, to the bit, and on
        // the circle about the end point; the parabola from the same state is elsewhere.
        let (t0, t1) = (roll.event.time, off.event.time);
        let mut again = Simulation::new(&scene, "all-pairs").unwrap();
        for f in [0.1, 0.37, 0.5, 0.83, 0.99] {
            let t = t0 + f * (t1 - t0);
            again.run_until(t);
            assert_eq!(turning.position_at(0, t), again.position(0), "t = {t}");
            assert_eq!(turning.velocity_at(0, t), again.world().velocity_at(0, t));
            assert_eq!(turning.position_at(0, t), pivot.position(t));
            let from_end = turning.position_at(0, t) - Vector([2.0, 1.0]);
            assert!((from_end.norm() - 0.2).abs() < 1e-12, "{from_end:?}");
            let g = Vector([0.0, -10.0]);
            let falling = turning.motion(0).falling_at(t, &g);
            assert!((falling - turning.position_at(0, t)).norm() > 1e-6);
        }
        // Its next record ends the turn: it falls under g from the record's state.
        let released = &records[2].1;
        assert!(released.turn(0).is_none() && released.turning().next().is_none());
        assert_eq!(released.acceleration(0), Some(Vector([0.0, -10.0])));
        assert_eq!(released.motion(0).pos, off.pos[0]);
        // So does an edit, and the copy kept as a keyframe keeps its turn.
        let mut edited = turning.clone();
        let kick = Edit::Motion {
            body: 0,
            pos: turning.position_at(0, t0 + 0.01),
            vel: Vector([0.0, 3.0]),
        }
        .records(t0 + 0.01)[0];
        edited.check(&kick).unwrap();
        edited.apply(&kick);
        assert!(edited.turn(0).is_none() && turning.turn(0).is_some());
    }

    #[test]
    fn turning_flags_that_cannot_be_are_refused() {
        use ccdsim::Gravity;
        use ccdsim::{Settings, Simulation};
        let scene = roll_over_scene();
        let mut sim = Simulation::new(&scene, "all-pairs").unwrap();
        let land = sim.step_event_until(3.0).unwrap();
        let roll = sim.step_event_until(3.0).unwrap();
        assert!(roll.pivots[0], "{roll:?}");
        let mut s = BodyStates::from_scene(&scene);
        s.check(&land).unwrap();
        s.apply(&land);
        s.check(&roll).unwrap();
        let refused = |s: &BodyStates<2>, c: Collision<2>, why: &str| {
            let err = s.check(&c).expect_err(why);
            assert!(err.contains(why), "{err}: not {why}");
        };
        let mut body = roll;
        body.event.kind = EventKind::Body;
        body.event.b = 0;
        refused(&s, body, "not a wall event");
        let mut reset = roll;
        reset.event.kind = EventKind::Reset;
        refused(&s, reset, "not a wall event");
        let mut second = roll;
        second.pivots = [false, true];
        refused(&s, second, "slot 1");
        let mut both = roll;
        both.rests[0] = true;
        refused(&s, both, "both resting");
        let mut floor = roll;
        floor.event.b = 0;
        refused(&s, floor, "no static segment");
        let mut past = roll;
        past.event.b = 7;
        refused(&s, past, "no static segment");
        let mut away = roll;
        away.pos[0] += Vector([0.0, 0.05]);
        refused(&s, away, "does not touch");
        // The same record in runs where it cannot be: no gravity, no resting, 3D.
        let mut weightless = scene.clone();
        weightless.settings.gravity = None;
        refused(
            &BodyStates::from_scene(&weightless),
            roll,
            "without gravity",
        );
        let mut restless = scene.clone();
        restless.settings.rest_speed = None;
        refused(
            &BodyStates::from_scene(&restless),
            roll,
            "where no body rests",
        );
        let mut kinematic = scene.clone();
        kinematic.bodies[0].kinematic = true;
        refused(&BodyStates::from_scene(&kinematic), roll, "kinematic");
        let space = Scene::<3> {
            settings: Settings {
                gravity: Gravity::new(&[0.0, -10.0, 0.0]),
                rest_speed: Some(1.0),
                ..Settings::default()
            },
            bodies: vec![BodySpec::new(Vector([2.0, 1.2, 0.0]), Vector::ZERO, 0.2)],
            walls: vec![Wall::Segment {
                a: Vector([0.0, 1.0, 0.0]),
                b: Vector([2.0, 1.0, 0.0]),
            }],
            ..Scene::default()
        };
        let lift = |v: Vector<2>| Vector([v[0], v[1], 0.0]);
        let roll3 = Collision::<3> {
            event: roll.event,
            pos: roll.pos.map(lift),
            vel: roll.vel.map(lift),
            rests: [false; 2],
            pivots: [true, false],
        };
        let err = BodyStates::from_scene(&space).check(&roll3).unwrap_err();
        assert!(err.contains("3D run"), "{err}");
    }
}
