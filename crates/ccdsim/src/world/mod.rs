//! Body state, kept lazily: body `i` holds a reference position, its velocity and the time at
//! which the position holds.
//!
//! Everything a collision touches about a body is one record, [`Body`]: what every time of
//! impact reads (motion and radius) first, then the mass and the change count that resolving
//! a collision and validating a prediction read (64 bytes in 2D, 80 in 3D). A finder looking
//! at a candidate partner touches one or two cache lines, and a collision finds its bodies'
//! masses and counts in lines it has already loaded: in a 2D gas of 10⁶ bodies that is about
//! 15 % more collisions per second than with masses and counts in arrays of their own. Ids,
//! read only by tools, live in a separate array.

mod rotation;
pub mod time_of_impact;

pub use time_of_impact::{
    toi_bodies_in, toi_body_moving_wall, toi_body_segment, toi_body_wall_in, toi_body_wall_resting,
    toi_pair_resting,
};

use crate::collision_filter::CollisionFilter;
use crate::contact::lees_edwards::ShearedBox;
use crate::geom::Vector;
use crate::motion::{start_motions, translated, Body, GrowthLaw, Laws, Motion, Path, WallMotion};
use crate::scene::{BodySpec, Scene, SceneError};
use crate::wall::Wall;
use rotation::Rotation;

/// [`World::support`] of a body that rests on no wall, as stored.
const NO_SUPPORT: u32 = u32::MAX;

/// The bit of a stored support that says the body has just slid off that segment's end
/// instead (see [`World::departed`]); [`NO_SUPPORT`] has it too, so one test tells a support.
const DEPARTED: u32 = 1 << 31;

/// The bit of a stored support that says the body has just come off that segment's end point
/// after turning about it (see [`World::released`]).
const RELEASED: u32 = 1 << 30;

/// Wall index `w` as stored in a support, below the flag bits.
fn wall_bits(w: usize) -> u32 {
    u32::try_from(w)
        .ok()
        .filter(|w| w & (DEPARTED | RELEASED) == 0)
        .expect("fewer than 2^30 walls")
}

/// A body turning about the end point of a segment (see [`World::pivot`]), and what parking
/// it hid: its own collision filter.
#[derive(Clone, Copy, Debug)]
struct Pivoting<const D: usize> {
    body: usize,
    pivot: crate::motion::pivot::Pivot,
    /// The segment whose end point it turns about.
    wall: usize,
    filter: CollisionFilter,
    /// The velocity it started turning with (its parked one is zero), m/s.
    velocity: Vector<D>,
}

pub(crate) use crate::motion::pivot::{from_2d, to_2d, wall_2d};

impl<const D: usize> Body<D> {
    /// Body `spec` as a scene starts it at time `t` (seconds): its stored motion from `t`.
    fn at(spec: &BodySpec<D>, t: f64) -> Self {
        Body {
            motion: Motion {
                pos: spec.pos,
                vel: spec.vel,
                time: t,
            },
            radius: spec.radius,
            mass: spec.effective_mass(),
            changes: 0,
        }
    }
}

/// Bodies and walls of a running simulation.
///
/// Only collisions (and explicit edits) change a body's stored state, and only that body's:
/// its position at time `t` is `pos + vel · (t − time)`.
#[derive(Clone, Debug)]
pub struct World<const D: usize> {
    bodies: Vec<Body<D>>,
    /// User ids by body index; empty while every slot holds the body whose id is its index
    /// (no scene ids of their own, no edits), which saves 8 bytes a body in large gases.
    id: Vec<u64>,
    /// `0, 1, …, len − 1`, built the first time [`World::ids`] is asked for while `id` is
    /// empty, so that it can lend a slice.
    identity_ids: std::sync::OnceLock<Vec<u64>>,
    walls: Vec<Wall<D>>,
    /// The edges of the table the static walls form ([`crate::wall::table_edges`]), computed
    /// once: edits check every placement against it.
    table: Vec<(Vector<D>, Vector<D>)>,
    /// The moving walls' geometry at the scene's start (see [`crate::world::time_of_impact`]).
    moving_walls: Vec<Wall<D>>,
    /// Where each moving wall is and how it moves.
    wall_motions: Vec<WallMotion<D>>,
    periodic: Option<Vector<D>>,
    /// The periodic box's Lees–Edwards shear, if the scene shears it.
    shear: Option<ShearedBox<D>>,
    restitution: f64,
    /// Per-body restitution, by body index; empty when every body has the scene's.
    restitutions: Vec<f64>,
    /// The TC model's duration, seconds, if any (see [`World::pair_restitution`]).
    tc: Option<f64>,
    /// Under the TC model: each body's last collision time, seconds (−∞ before any).
    last_collision: Vec<f64>,
    /// True when bodies have their own restitution or the TC model is on: collisions then
    /// look up their restitution (see [`World::pair_restitution`]).
    restitution_rules: bool,
    thermostat: Option<crate::thermostat::Thermostat>,
    /// Collision groups and masks, by body index; empty when no body sets them.
    filters: Vec<CollisionFilter>,
    /// Vacant slots by index (see [`World::is_vacant`]); empty while every slot holds a body.
    vacant: Vec<bool>,
    /// The vacant slots, the most recently vacated last: bodies added fill them first.
    free: Vec<usize>,
    /// `settings.rest_speed`, m/s, if bodies come to rest on walls (see [`crate::contact::resting`]).
    rest_speed: Option<f64>,
    /// Under `rest_speed`: the static wall each body rested on last, by body index
    /// ([`NO_SUPPORT`] for none; with [`DEPARTED`] set, the segment it slid off), and its
    /// change count then: the body rests on it while the count is unchanged, so that any
    /// change of its state (which counts) lifts it off at no cost to the code that changes
    /// it. Empty otherwise.
    supports: Vec<(u32, u64)>,
    /// Under `rest_speed`: the acceleration of a body sliding on each static wall, by wall
    /// index (`None` where no body rests); empty otherwise.
    slides: Vec<Option<Vector<D>>>,
    /// Bodies turning about the end point of a segment (see [`crate::motion::pivot`]), parked where
    /// finders see them: at rest, falling by nothing, colliding with nothing. Few at a time.
    pivots: Vec<Pivoting<D>>,
    /// The id the next added body gets unless it names its own: above every id so far.
    next_id: u64,
    laws: Laws<D>,
    now: f64,
    /// Spins, inertia factors and tangential restitutions of a rotational scene's bodies.
    rotation: Option<Rotation>,
}

impl<const D: usize> World<D> {
    /// Builds the world of a scene after validating it.
    pub fn from_scene(scene: &Scene<D>) -> Result<Self, SceneError> {
        scene.validate()?;
        let t = scene.start_time;
        let bodies = scene.bodies.iter().map(|b| Body::at(b, t)).collect();
        Ok(Self::around(scene, bodies))
    }

    /// Builds the world of a scene after validating it, as [`World::from_scene`], taking the
    /// scene: its body list becomes the world's in place, so a large scene and its world are
    /// never held at once (a million-body scene holds about 110 MB of bodies, its world 64 MB).
    pub fn from_owned_scene(mut scene: Scene<D>) -> Result<Self, SceneError> {
        scene.validate()?;
        let mut world = Self::around(&scene, Vec::new());
        let t = scene.start_time;
        // `Vec`'s in-place collection reuses the specs' allocation for the bodies, and the
        // shrink hands its tail back.
        world.bodies = std::mem::take(&mut scene.bodies)
            .into_iter()
            .map(|b| Body::at(&b, t))
            .collect();
        world.bodies.shrink_to_fit();
        Ok(world)
    }

    /// The world of a validated scene with the given `bodies` (built from its body list).
    fn around(scene: &Scene<D>, bodies: Vec<Body<D>>) -> Self {
        let n = scene.bodies.len();
        World {
            bodies,
            id: if (0..n).all(|i| scene.id_of(i) == i as u64) {
                Vec::new()
            } else {
                (0..n).map(|i| scene.id_of(i)).collect()
            },
            identity_ids: std::sync::OnceLock::new(),
            walls: scene.walls.clone(),
            table: crate::wall::table_edges(&scene.walls),
            moving_walls: scene.moving_walls.iter().map(|m| m.wall).collect(),
            wall_motions: start_motions(&scene.moving_walls, scene.start_time),
            periodic: scene.periodic,
            shear: scene.shear(),
            restitution: scene.settings.restitution,
            restitutions: if scene.bodies.iter().any(|b| b.restitution.is_some()) {
                scene
                    .bodies
                    .iter()
                    .map(|b| b.restitution.unwrap_or(scene.settings.restitution))
                    .collect()
            } else {
                Vec::new()
            },
            tc: scene.settings.tc,
            restitution_rules: scene.settings.tc.is_some()
                || scene.bodies.iter().any(|b| b.restitution.is_some()),
            last_collision: if scene.settings.tc.is_some() {
                vec![f64::NEG_INFINITY; n]
            } else {
                Vec::new()
            },
            thermostat: scene.settings.thermostat,
            filters: scene.filters(),
            vacant: Vec::new(),
            free: Vec::new(),
            pivots: Vec::new(),
            next_id: (0..n)
                .map(|i| scene.id_of(i))
                .max()
                .map_or(0, |m| m.saturating_add(1)),
            rest_speed: scene.settings.rest_speed,
            supports: match scene.settings.rest_speed {
                Some(_) => vec![(NO_SUPPORT, 0); n],
                None => Vec::new(),
            },
            slides: crate::scene::slides(scene),
            laws: Laws {
                growth: scene.settings.growth.map(|g| GrowthLaw {
                    rate: g.rate,
                    origin: scene.start_time,
                }),
                gravity: scene.gravity(),
                kinematic: scene.bodies.iter().any(|b| b.kinematic),
                filtered: scene.bodies.iter().any(BodySpec::is_filtered),
                resting: scene.settings.rest_speed.is_some(),
            },
            now: scene.start_time,
            rotation: Rotation::of(scene),
        }
    }

    /// Number of body slots: every index below it names a body or a vacant slot (see
    /// [`World::is_vacant`]; without `remove_body` and `add_body`, every slot holds a body).
    #[must_use]
    pub fn len(&self) -> usize {
        self.bodies.len()
    }

    /// True when there are no body slots.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.bodies.is_empty()
    }

    /// True when slot `i` holds no body: its body was removed, or the slot was reserved for
    /// bodies to come ([`crate::Simulation::add_body`]). A vacant slot is kept as a kinematic
    /// ball at rest that collides with nothing (group and mask 0), so every finder passes it
    /// by like the oracle does; tools skip it (it has no energy, momentum or sensor events).
    #[must_use]
    #[inline]
    pub fn is_vacant(&self, i: usize) -> bool {
        self.vacant.get(i).copied().unwrap_or(false)
    }

    /// Number of bodies: slots that are not vacant.
    #[must_use]
    pub fn body_count(&self) -> usize {
        self.bodies.len() - self.free.len()
    }

    /// The slot of the body with user id `id`, if one holds it. O(n).
    #[must_use]
    pub fn index_of(&self, id: u64) -> Option<usize> {
        (0..self.len()).find(|&i| self.id(i) == id && !self.is_vacant(i))
    }

    /// The user id of the body in slot `i` (`u64::MAX` for a vacant slot).
    #[must_use]
    #[inline]
    pub fn id(&self, i: usize) -> u64 {
        self.id.get(i).copied().unwrap_or(i as u64)
    }

    /// The ids by slot, written out from here on: a slot is about to hold another id than
    /// its index.
    fn ids_mut(&mut self) -> &mut Vec<u64> {
        if self.id.len() < self.bodies.len() {
            self.id = (0..self.bodies.len() as u64).collect();
            self.identity_ids = std::sync::OnceLock::new();
        }
        &mut self.id
    }

    /// The id a body added without one gets: above every id given so far.
    #[must_use]
    pub fn next_id(&self) -> u64 {
        self.next_id
    }

    /// The vacant slot the next added body fills, if any (adding a body needs one).
    #[must_use]
    pub fn free_slot(&self) -> Option<usize> {
        self.free.last().copied()
    }

    /// Appends `count` vacant slots, slot `len + k` parked with the position and radius
    /// `park(k)` at the current time (among the bodies, like them: where it costs a grid
    /// finder least). The world's laws change when it
    /// had no kinematic bodies or no filters: a finder serving it must then be re-initialised,
    /// as it must after any new slot.
    pub(crate) fn reserve(&mut self, count: usize, park: impl Fn(usize) -> (Vector<D>, f64)) {
        let now = self.now;
        self.allow_vacancies();
        self.ids_mut();
        for k in 0..count {
            let (pos, radius) = park(k);
            self.bodies.push(Body {
                motion: Motion {
                    pos,
                    vel: Vector::ZERO,
                    time: now,
                },
                radius,
                mass: f64::INFINITY,
                changes: 0,
            });
            self.id.push(u64::MAX);
            self.filters.push(CollisionFilter::NONE);
            self.vacant.push(true);
            if !self.restitutions.is_empty() {
                self.restitutions.push(self.restitution);
            }
            if self.tc.is_some() {
                self.last_collision.push(f64::NEG_INFINITY);
            }
            if self.rest_speed.is_some() {
                self.supports.push((NO_SUPPORT, 0));
            }
            if let Some(rotation) = &mut self.rotation {
                rotation.push_vacant();
            }
        }
        // Filled lowest slot first.
        let n = self.bodies.len();
        self.free.extend((n - count..n).rev());
    }

    /// Makes room for vacant slots: a vacancy flag and a collision filter per slot, and the
    /// laws under which finders pass vacant slots by (kinematic bodies, filtered pairs).
    fn allow_vacancies(&mut self) {
        let n = self.bodies.len();
        self.vacant.resize(n, false);
        if self.filters.is_empty() {
            self.filters = vec![CollisionFilter::DEFAULT; n];
        }
        self.laws.kinematic = true;
        self.laws.filtered = true;
    }

    /// The largest and second-largest radius of the slots, metres (0 for missing ones).
    #[must_use]
    pub fn two_largest_radii(&self) -> (f64, f64) {
        let (mut r1, mut r2) = (0.0f64, 0.0f64);
        for r in self.radii() {
            if r > r1 {
                r2 = r1;
                r1 = r;
            } else if r > r2 {
                r2 = r;
            }
        }
        (r1, r2)
    }

    /// Puts the body `spec`, with user id `id` and its position and velocity holding at the
    /// current time, in the vacant slot filled next; returns the slot. The world's laws change
    /// when the body is the first with its own restitution. A finder serving the world must be
    /// told through [`Finder::update`](crate::Finder::update), or re-initialised if the laws
    /// changed or the radius exceeds what it was sized for.
    ///
    /// # Panics
    /// When no slot is vacant ([`World::reserve`] first).
    pub(crate) fn occupy(&mut self, spec: &BodySpec<D>, id: u64) -> usize {
        let i = self.free.pop().expect("a vacant slot was reserved");
        let b = &mut self.bodies[i];
        b.motion = Motion {
            pos: spec.pos,
            vel: spec.vel,
            time: self.now,
        };
        b.radius = spec.radius;
        b.mass = spec.effective_mass();
        b.changes += 1;
        self.ids_mut()[i] = id;
        self.next_id = self.next_id.max(id.saturating_add(1));
        self.vacant[i] = false;
        self.filters[i] = spec.filter();
        if spec.restitution.is_some() && self.restitutions.is_empty() {
            self.restitutions = vec![self.restitution; self.bodies.len()];
            self.restitution_rules = true;
        }
        if !self.restitutions.is_empty() {
            self.restitutions[i] = spec.restitution.unwrap_or(self.restitution);
        }
        if self.tc.is_some() {
            self.last_collision[i] = f64::NEG_INFINITY;
        }
        if let Some(rotation) = &mut self.rotation {
            rotation.occupy(i, spec);
        }
        i
    }

    /// Empties slot `i` at the current time: its body stops where it is, becomes a kinematic
    /// ball at rest colliding with nothing, and the slot is filled next. The world's laws
    /// change when it had no kinematic bodies or no filters (re-initialise a finder then);
    /// otherwise a finder needs [`Finder::update`](crate::Finder::update) of `i`.
    pub(crate) fn vacate(&mut self, i: usize) {
        let now = self.now;
        let pos = self.position_at(i, now);
        self.pivots.retain(|p| p.body != i);
        self.allow_vacancies();
        let b = &mut self.bodies[i];
        b.motion = Motion {
            pos,
            vel: Vector::ZERO,
            time: now,
        };
        b.mass = f64::INFINITY;
        b.changes += 1;
        self.ids_mut()[i] = u64::MAX;
        self.filters[i] = CollisionFilter::NONE;
        self.vacant[i] = true;
        self.free.push(i);
        if let Some(rotation) = &mut self.rotation {
            rotation.spins[i] = Vector::ZERO;
        }
    }

    /// Current simulated time, seconds: every event before it has been resolved.
    #[must_use]
    pub fn now(&self) -> f64 {
        self.now
    }

    pub(crate) fn set_now(&mut self, t: f64) {
        debug_assert!(t >= self.now);
        self.now = t;
    }

    /// The stored state of body `i`: its reference position, velocity and reference time.
    #[must_use]
    #[inline]
    pub fn motion(&self, i: usize) -> Motion<D> {
        self.bodies[i].motion
    }

    /// Position of body `i` at time `t`, metres.
    #[must_use]
    #[inline]
    pub fn position_at(&self, i: usize, t: f64) -> Vector<D> {
        if self.laws.resting {
            self.position_at_resting(i, t)
        } else {
            self.free_position_at(i, t)
        }
    }

    /// Position of body `i` at time `t` as the finders see it, metres: its stored motion
    /// advanced by [`World::gravity_of`]. This is [`World::position_at`] except for a body
    /// turning about a segment's end (see [`World::pivot`]), which the finders see parked
    /// where its turn started.
    #[must_use]
    #[inline]
    pub fn stored_position_at(&self, i: usize, t: f64) -> Vector<D> {
        if self.pivots.is_empty() {
            return self.position_at(i, t);
        }
        Path::new(self.bodies[i].motion, self.gravity_of(i)).position(t)
    }

    /// Velocity of body `i` at time `t` as the finders see it, metres per second (see
    /// [`World::stored_position_at`]): zero for a body turning about a segment's end.
    #[must_use]
    #[inline]
    pub fn stored_velocity_at(&self, i: usize, t: f64) -> Vector<D> {
        if self.pivots.is_empty() {
            return self.velocity_at(i, t);
        }
        Path::new(self.bodies[i].motion, self.gravity_of(i)).velocity(t)
    }

    /// [`World::position_at`] in a world where no body rests on a wall: without the call
    /// out that resting needs, so that hot callers that know it stay leaf functions.
    #[inline(always)]
    pub(crate) fn free_position_at(&self, i: usize, t: f64) -> Vector<D> {
        self.free_path(i).position(t)
    }

    /// [`World::velocity_at`] in a world where no body rests on a wall (see
    /// [`World::free_position_at`]).
    #[inline(always)]
    pub(crate) fn free_velocity_at(&self, i: usize, t: f64) -> Vector<D> {
        self.free_path(i).velocity(t)
    }

    /// [`World::path`] in a world where no body rests on a wall: a parabola under gravity,
    /// a straight line without it or for a kinematic body.
    #[inline(always)]
    fn free_path(&self, i: usize) -> Path<D> {
        let b = &self.bodies[i];
        match &self.laws.gravity {
            Some(g) if !b.is_kinematic() => Path::Parabola(b.motion, *g),
            _ => Path::Line(b.motion),
        }
    }

    /// Body `i`'s path from its last event to its next: where it is and how fast it moves at
    /// any time in between ([`Path::position`], [`Path::velocity`]).
    #[must_use]
    #[inline]
    pub fn path(&self, i: usize) -> Path<D> {
        if self.laws.resting {
            self.resting_path(i)
        } else {
            self.free_path(i)
        }
    }

    /// [`World::position_at`] where bodies rest on walls (out of line: the common worlds'
    /// callers stay small).
    #[inline(never)]
    fn position_at_resting(&self, i: usize, t: f64) -> Vector<D> {
        self.resting_path(i).position(t)
    }

    /// [`World::velocity_at`] where bodies rest on walls (out of line, as
    /// `position_at_resting`).
    #[inline(never)]
    fn velocity_at_resting(&self, i: usize, t: f64) -> Vector<D> {
        self.resting_path(i).velocity(t)
    }

    /// [`World::path`] where bodies rest on walls: a turn about a segment's end, or a
    /// parabola under the body's own acceleration ([`World::gravity_of`]), or a line.
    #[inline]
    fn resting_path(&self, i: usize) -> Path<D> {
        match self.pivot(i) {
            Some((pivot, _)) => Path::Turn(*pivot),
            None => Path::new(self.bodies[i].motion, self.gravity_of(i)),
        }
    }

    /// True when bodies may rest on walls (`settings.rest_speed`, see [`crate::contact::resting`]).
    #[must_use]
    #[inline]
    pub fn has_resting(&self) -> bool {
        self.laws.resting
    }

    /// The acceleration of body `i` between events, m/s²: the world's gravity, or for a body
    /// resting on a wall the acceleration it slides with (see [`crate::contact::resting`]); `None`
    /// without gravity or for a kinematic body (which moves in a straight line).
    #[must_use]
    #[inline]
    pub fn gravity_of(&self, i: usize) -> Option<Vector<D>> {
        let g = self
            .laws
            .gravity
            .filter(|_| !self.bodies[i].is_kinematic())?;
        if !self.pivots.is_empty() && self.pivot(i).is_some() {
            // Parked: finders see it at rest.
            return None;
        }
        Some(match self.support(i) {
            Some(w) => self.slides[w].unwrap_or(g),
            None => g,
        })
    }

    /// The acceleration of body `i` between events, m/s²: [`World::gravity_of`], zero when
    /// that is `None`.
    #[must_use]
    #[inline]
    pub fn acceleration(&self, i: usize) -> Vector<D> {
        self.gravity_of(i).unwrap_or(Vector::ZERO)
    }

    /// The static wall body `i` rests on, sliding along it (see [`crate::contact::resting`]), if it
    /// does: only under `settings.rest_speed`, and until its state next changes.
    #[must_use]
    #[inline]
    pub fn support(&self, i: usize) -> Option<usize> {
        match self.supports.get(i) {
            Some(&(w, changes))
                if w & (DEPARTED | RELEASED) == 0 && changes == self.bodies[i].changes =>
            {
                Some(w as usize)
            }
            _ => None,
        }
    }

    /// The segment body `i` has just slid off over an end, flying clear of it (see
    /// [`crate::contact::ledge`]), while its state is still the one it left with: its next contact
    /// with that segment is its return to the end point, not the touch it left at.
    #[must_use]
    pub fn departed(&self, i: usize) -> Option<usize> {
        match self.supports.get(i) {
            Some(&(w, changes))
                if w != NO_SUPPORT && w & DEPARTED != 0 && changes == self.bodies[i].changes =>
            {
                Some((w & !DEPARTED) as usize)
            }
            _ => None,
        }
    }

    /// Body `i`, whose state was just set, has slid off segment `w` over an end.
    pub(crate) fn depart(&mut self, i: usize, w: usize) {
        self.supports[i] = (wall_bits(w) | DEPARTED, self.bodies[i].changes);
    }

    /// The segment body `i` has just come off after turning about one of its end points (see
    /// [`crate::contact::pivot_end`]), while its state is still the one it came off with: it touches
    /// that point then without pressing it, and leaves it falling (`v·g > 0`), so it meets
    /// that point no more.
    #[must_use]
    pub fn released(&self, i: usize) -> Option<usize> {
        match self.supports.get(i) {
            Some(&(w, changes))
                if w != NO_SUPPORT
                    && w & DEPARTED == 0
                    && w & RELEASED != 0
                    && changes == self.bodies[i].changes =>
            {
                Some((w & !RELEASED) as usize)
            }
            _ => None,
        }
    }

    /// Body `i`, whose state was just set, has come off an end point of segment `w`.
    pub(crate) fn release(&mut self, i: usize, w: usize) {
        self.supports[i] = (wall_bits(w) | RELEASED, self.bodies[i].changes);
    }

    /// The motion of body `i` if it is turning about the end point of a segment (see
    /// [`crate::motion::pivot`]; 2D only), and that segment's index. Finders see such a body parked
    /// where the turn started, at rest, falling by nothing and colliding with nothing: the
    /// simulation finds its events itself. [`World::position_at`], [`World::velocity_at`]
    /// and [`World::filter`] tell its true state.
    #[must_use]
    pub fn pivot(&self, i: usize) -> Option<(&crate::motion::pivot::Pivot, usize)> {
        self.pivots
            .iter()
            .find(|p| p.body == i)
            .map(|p| (&p.pivot, p.wall))
    }

    /// True when some body turns about a segment's end ([`World::pivot`]).
    #[must_use]
    #[inline]
    pub fn has_pivots(&self) -> bool {
        !self.pivots.is_empty()
    }

    /// The bodies turning about segment ends, in the order they started ([`World::pivot`]).
    pub fn pivoting(&self) -> impl Iterator<Item = usize> + '_ {
        self.pivots.iter().map(|p| p.body)
    }

    /// Body `i`, at `pos` with velocity `vel` at the start time of `pivot` (the state `pivot`
    /// was made from), starts turning with `pivot` about the end point of segment `w`: it is
    /// parked there (see [`World::pivot`]) until its state is next set, which restores its
    /// collision filter. Returns true when that changed the world's laws (its first
    /// collision filter): a finder serving it must then be re-initialised, else told of `i`.
    pub(crate) fn start_pivot(
        &mut self,
        i: usize,
        pivot: crate::motion::pivot::Pivot,
        w: usize,
        (pos, vel): (Vector<D>, Vector<D>),
    ) -> bool {
        self.set_state(i, pos, Vector::ZERO, pivot.start_time());
        let filter = self.filter(i);
        let first = self.filters.is_empty();
        if first {
            self.filters = vec![CollisionFilter::DEFAULT; self.bodies.len()];
            self.laws.filtered = true;
        }
        self.filters[i] = CollisionFilter::NONE;
        self.pivots.push(Pivoting {
            body: i,
            pivot,
            wall: w,
            filter,
            velocity: vel,
        });
        first
    }

    /// The state a record gives body `i` after an event: its reference position and stored
    /// velocity, or for a body turning about a segment's end the velocity it started with
    /// (from which, with the position, [`crate::motion::pivot::Pivot::new`] makes its turn again).
    #[must_use]
    pub fn recorded_state(&self, i: usize) -> (Vector<D>, Vector<D>) {
        let vel = match self.pivots.iter().find(|p| p.body == i) {
            Some(p) => p.velocity,
            None => self.bodies[i].motion.vel,
        };
        (self.bodies[i].motion.pos, vel)
    }

    /// Ends body `i`'s turn, if it turns, giving it back its collision filter; its parked
    /// state stays until set anew.
    fn end_pivot(&mut self, i: usize) {
        if let Some(k) = self.pivots.iter().position(|p| p.body == i) {
            let p = self.pivots.swap_remove(k);
            self.filters[i] = p.filter;
        }
    }

    /// `settings.rest_speed`, m/s: bodies leaving a collision with a plane gravity presses
    /// them on at most this fast come to rest on it (see [`crate::contact::resting`]).
    #[must_use]
    pub fn rest_speed(&self) -> Option<f64> {
        self.rest_speed
    }

    /// The acceleration of a body sliding on static wall `w`, m/s², if bodies may rest on it
    /// (a plane gravity presses them on, under `settings.rest_speed`).
    #[must_use]
    pub fn slide_of(&self, w: usize) -> Option<Vector<D>> {
        self.slides.get(w).copied().flatten()
    }

    /// The acceleration of a body sliding on each static wall, by wall index ([`World::slide_of`]);
    /// empty unless bodies rest on walls.
    pub(crate) fn slides(&self) -> &[Option<Vector<D>>] {
        &self.slides
    }

    /// Body `i`, whose state was just set, rests on static wall `w` from now on.
    pub(crate) fn rest_on(&mut self, i: usize, w: usize) {
        debug_assert!(self.slide_of(w).is_some());
        self.supports[i] = (wall_bits(w), self.bodies[i].changes);
    }

    /// Puts body `i` on static wall `w` (`Some`), sliding along it, or lifts it off (`None`),
    /// for tools that rebuild a world from a record (a viewer restoring the state at some
    /// instant from a run file whose records say which bodies rest): call it after
    /// [`World::set_motion`], which lifts the body off. Returns false, and changes nothing,
    /// when no body can rest on `w` (see [`World::slide_of`]) or there is no body `i`. As
    /// for [`World::set_motion`], a finder serving this world must be told.
    pub fn set_support(&mut self, i: usize, w: Option<usize>) -> bool {
        if i >= self.len() {
            return false;
        }
        match w {
            Some(w) if self.slide_of(w).is_some() => self.rest_on(i, w),
            Some(_) => return false,
            None => {
                if let Some(s) = self.supports.get_mut(i) {
                    s.0 = NO_SUPPORT;
                }
            }
        }
        true
    }

    /// True for a kinematic body (infinite mass, see [`crate::BodySpec::kinematic`]).
    #[must_use]
    #[inline]
    pub fn is_kinematic(&self, i: usize) -> bool {
        self.bodies[i].is_kinematic()
    }

    /// True when bodies `i` and `j` collide: always, unless their collision groups and masks
    /// say they pass through each other (see [`crate::collision_filter`]).
    #[must_use]
    #[inline]
    pub fn collides(&self, i: usize, j: usize) -> bool {
        crate::collision_filter::pair_collides(&self.filters, i, j)
    }

    /// Body `i`'s collision group and mask.
    #[must_use]
    #[inline]
    pub fn filter(&self, i: usize) -> CollisionFilter {
        if let Some(p) = self.pivots.iter().find(|p| p.body == i) {
            return p.filter;
        }
        self.filters.get(i).copied().unwrap_or_default()
    }

    /// Every body's collision group and mask by body index, or an empty slice when every body
    /// has the default (all pairs collide).
    #[must_use]
    #[inline]
    pub fn filters(&self) -> &[CollisionFilter] {
        &self.filters
    }

    /// Gives body `i` the collision filter `filter`. The first filter of a world that had none
    /// changes its laws: a finder serving it must then be re-initialised; later ones need only
    /// [`Finder::update`](crate::Finder::update) of body `i`, once its state is stored anew
    /// at the current time (so that its change count moves, and no contact of a pair that
    /// passed through each other is sought before now). Returns true when the laws changed.
    pub(crate) fn set_filter(&mut self, i: usize, filter: CollisionFilter) -> bool {
        let first = self.filters.is_empty();
        if first {
            self.filters = vec![CollisionFilter::DEFAULT; self.bodies.len()];
            self.laws.filtered = true;
        }
        match self.pivots.iter_mut().find(|p| p.body == i) {
            Some(p) => p.filter = filter,
            None => self.filters[i] = filter,
        }
        first
    }

    /// True when the world has kinematic bodies.
    #[must_use]
    #[inline]
    pub fn has_kinematic(&self) -> bool {
        self.laws.kinematic
    }

    /// Velocity of body `i` at time `t`, metres per second: its stored velocity, or under
    /// gravity that velocity plus `g·(t − time)`.
    #[must_use]
    #[inline]
    pub fn velocity_at(&self, i: usize, t: f64) -> Vector<D> {
        if self.laws.resting {
            self.velocity_at_resting(i, t)
        } else {
            self.free_velocity_at(i, t)
        }
    }

    /// Reference position of body `i`, metres (valid at its reference time [`World::time`]).
    #[must_use]
    #[inline]
    pub fn position(&self, i: usize) -> Vector<D> {
        self.bodies[i].motion.pos
    }

    /// Stored velocity of body `i`, metres per second (valid at its reference time
    /// [`World::time`]; without gravity, at all times until its next change).
    #[must_use]
    #[inline]
    pub fn velocity(&self, i: usize) -> Vector<D> {
        self.bodies[i].motion.vel
    }

    /// Reference time of body `i`, seconds: when its stored position holds.
    #[must_use]
    #[inline]
    pub fn time(&self, i: usize) -> f64 {
        self.bodies[i].motion.time
    }

    /// Stored radius of body `i`, metres: its radius at all times, or, in a growing world
    /// (see [`World::growth`]), at the growth's origin.
    #[must_use]
    #[inline]
    pub fn radius(&self, i: usize) -> f64 {
        self.bodies[i].radius
    }

    /// Radius of body `i` at time `t`, metres: the stored radius, grown by the growth law if
    /// the world grows.
    #[must_use]
    #[inline]
    pub fn radius_at(&self, i: usize, t: f64) -> f64 {
        match &self.laws.growth {
            None => self.bodies[i].radius,
            Some(law) => law.radius_at(self.bodies[i].radius, t),
        }
    }

    /// The growth law of a growing world (radii grow linearly in time, see
    /// [`crate::contact::growth`]), or `None` when radii are fixed.
    #[must_use]
    #[inline]
    pub fn growth(&self) -> Option<&GrowthLaw> {
        self.laws.growth.as_ref()
    }

    /// The acceleration every body undergoes between events, metres per second squared, in a
    /// world with gravity (see [`crate::contact::gravity`]).
    #[must_use]
    #[inline]
    pub fn gravity(&self) -> Option<Vector<D>> {
        self.laws.gravity
    }

    /// The laws in force (growth, gravity) as the narrow phase's dispatchers take them:
    /// `None` when radii are fixed and bodies move in straight lines.
    #[must_use]
    #[inline]
    pub fn laws(&self) -> Option<&Laws<D>> {
        self.laws.in_force()
    }

    /// Stops the growth at time `t`: the stored radii become the radii at `t`, and stay.
    /// A finder serving this world must be re-initialised.
    pub fn stop_growth(&mut self, t: f64) {
        if let Some(law) = self.laws.growth.take() {
            for b in &mut self.bodies {
                b.radius = law.radius_at(b.radius, t);
            }
        }
    }

    /// Every body's hot record (stored motion and radius), by body index.
    #[must_use]
    #[inline]
    pub fn bodies(&self) -> &[Body<D>] {
        &self.bodies
    }

    /// Reference positions, metres, by body index (each valid at its body's reference time).
    pub fn positions(&self) -> impl ExactSizeIterator<Item = Vector<D>> + '_ {
        self.bodies.iter().map(|b| b.motion.pos)
    }

    /// Velocities, metres per second, by body index.
    pub fn velocities(&self) -> impl ExactSizeIterator<Item = Vector<D>> + '_ {
        self.bodies.iter().map(|b| b.motion.vel)
    }

    /// Reference times, seconds, by body index.
    pub fn times(&self) -> impl ExactSizeIterator<Item = f64> + '_ {
        self.bodies.iter().map(|b| b.motion.time)
    }

    /// Radii, metres, by body index.
    pub fn radii(&self) -> impl ExactSizeIterator<Item = f64> + '_ {
        self.bodies.iter().map(|b| b.radius)
    }

    /// Mass of body `i`, kilograms.
    #[must_use]
    #[inline]
    pub fn mass(&self, i: usize) -> f64 {
        self.bodies[i].mass
    }

    /// Masses, kilograms, by body index.
    pub fn masses(&self) -> impl ExactSizeIterator<Item = f64> + '_ {
        self.bodies.iter().map(|b| b.mass)
    }

    /// User ids, by body index (`u64::MAX` for a vacant slot).
    #[must_use]
    pub fn ids(&self) -> &[u64] {
        if self.id.len() == self.bodies.len() {
            &self.id
        } else {
            self.identity_ids
                .get_or_init(|| (0..self.bodies.len() as u64).collect())
        }
    }

    /// The static walls.
    #[must_use]
    pub fn walls(&self) -> &[Wall<D>] {
        &self.walls
    }

    /// The edges of the table the static walls form, empty without one (see
    /// [`crate::wall::table_edges`]): a body's centre lies inside them by the even–odd rule.
    #[must_use]
    pub(crate) fn table(&self) -> &[(Vector<D>, Vector<D>)] {
        &self.table
    }

    /// Number of moving walls (see [`crate::world::time_of_impact`]); moving wall `k` is wall
    /// `walls().len() + k` in events.
    #[must_use]
    pub fn moving_wall_count(&self) -> usize {
        self.moving_walls.len()
    }

    /// Moving wall `k`'s geometry at the scene's start time.
    #[must_use]
    pub fn moving_wall_base(&self, k: usize) -> Wall<D> {
        self.moving_walls[k]
    }

    /// How moving wall `k` moves now.
    #[must_use]
    pub fn wall_motion(&self, k: usize) -> WallMotion<D> {
        self.wall_motions[k]
    }

    /// Wall `w` (static, or moving when `w ≥ walls().len()`) where it is at time `t`.
    #[must_use]
    pub fn wall_at(&self, w: usize, t: f64) -> Wall<D> {
        match w.checked_sub(self.walls.len()) {
            None => self.walls[w],
            Some(k) => translated(&self.moving_walls[k], self.wall_motions[k].offset_at(t)),
        }
    }

    /// Wall `w`'s velocity, m/s: zero for a static wall.
    #[must_use]
    pub fn wall_velocity(&self, w: usize) -> Vector<D> {
        match w.checked_sub(self.walls.len()) {
            None => Vector::ZERO,
            Some(k) => self.wall_motions[k].velocity,
        }
    }

    /// Moving wall `k` translates at `velocity` from time `t` on (where it is then stays).
    pub(crate) fn set_wall_velocity(&mut self, k: usize, velocity: Vector<D>, t: f64) {
        let m = &mut self.wall_motions[k];
        *m = WallMotion {
            offset: m.offset_at(t),
            velocity,
            time: t,
        };
    }

    /// The sides of the periodic box, for periodic worlds (see [`crate::contact::periodic`]).
    #[must_use]
    pub fn periodic(&self) -> Option<Vector<D>> {
        self.periodic
    }

    /// The periodic box with its Lees–Edwards shear, for sheared worlds (see
    /// [`crate::contact::lees_edwards`]); `None` otherwise.
    #[must_use]
    #[inline]
    pub fn shear(&self) -> Option<ShearedBox<D>> {
        self.shear
    }

    /// The scene's coefficient of restitution (`settings.restitution`): every collision's,
    /// unless bodies have their own or the TC model makes a collision elastic (see
    /// [`World::pair_restitution`]).
    #[must_use]
    pub fn restitution(&self) -> f64 {
        self.restitution
    }

    /// Coefficient of restitution of body `i` (its own, or the scene's).
    #[must_use]
    #[inline]
    pub fn body_restitution(&self, i: usize) -> f64 {
        self.restitutions
            .get(i)
            .copied()
            .unwrap_or(self.restitution)
    }

    /// The restitution of a collision of bodies `i` and `j` at time `t`: 1 under the TC model
    /// when either collided less than `tc` before `t`, else the mean of their restitutions.
    #[must_use]
    #[inline]
    pub fn pair_restitution(&self, i: usize, j: usize, t: f64) -> f64 {
        if !self.restitution_rules {
            return self.restitution;
        }
        if self.within_tc(i, t) || self.within_tc(j, t) {
            return 1.0;
        }
        if self.restitutions.is_empty() {
            self.restitution
        } else {
            0.5 * (self.restitutions[i] + self.restitutions[j])
        }
    }

    /// The restitution of a collision of body `i` with a wall at time `t`: 1 under the TC
    /// model when it collided less than `tc` before `t`, else its own restitution.
    #[must_use]
    #[inline]
    pub fn wall_restitution(&self, i: usize, t: f64) -> f64 {
        if !self.restitution_rules {
            return self.restitution;
        }
        if self.within_tc(i, t) {
            1.0
        } else {
            self.body_restitution(i)
        }
    }

    /// True when the world keeps its bodies' angular velocities (rough bodies, or spins set
    /// in the scene; see [`Scene::is_rotational`]).
    #[must_use]
    #[inline]
    pub fn is_rotational(&self) -> bool {
        self.rotation.is_some()
    }

    /// Angular velocity of body `i`, radians per second (about the third axis in 2D); zero in
    /// a world that keeps no spins. Constant between events.
    #[must_use]
    pub fn spin(&self, i: usize) -> Vector<3> {
        self.rotation.as_ref().map_or(Vector::ZERO, |r| r.spins[i])
    }

    /// Moment-of-inertia factor `q` of body `i` (its moment of inertia is `q·m·r²`).
    #[must_use]
    pub fn inertia_factor(&self, i: usize) -> f64 {
        self.rotation
            .as_ref()
            .map_or(crate::motion::spin::default_inertia::<D>(), |r| {
                r.inertia[i]
            })
    }

    /// Tangential restitution of a collision of bodies `i` and `j`: the mean of their values
    /// (−1, smooth, in a world that keeps no spins).
    #[must_use]
    pub fn pair_tangential_restitution(&self, i: usize, j: usize) -> f64 {
        self.rotation.as_ref().map_or(-1.0, |r| {
            let (a, b) = (r.tangential[i], r.tangential[j]);
            if a == b {
                a
            } else {
                0.5 * (a + b)
            }
        })
    }

    /// Tangential restitution of a collision of body `i` with a wall: the body's.
    #[must_use]
    pub fn wall_tangential_restitution(&self, i: usize) -> f64 {
        self.rotation.as_ref().map_or(-1.0, |r| r.tangential[i])
    }

    /// Sets the angular velocity of body `i` (a collision's outcome).
    pub(crate) fn set_spin(&mut self, i: usize, spin: Vector<3>) {
        if let Some(r) = &mut self.rotation {
            r.spins[i] = spin;
        }
    }

    /// Rotational kinetic energy `Σ ½·q·m·r²·|ω|²` of the bodies that move freely, joules (0
    /// in a world that keeps no spins; radii at the current time).
    #[must_use]
    pub fn rotational_energy(&self) -> f64 {
        let Some(r) = &self.rotation else {
            return 0.0;
        };
        let now = self.now;
        (0..self.len())
            .filter(|&i| self.mass(i).is_finite())
            .map(|i| {
                crate::motion::spin::rotational_energy(
                    r.inertia[i],
                    self.mass(i),
                    self.radius_at(i, now),
                    r.spins[i],
                )
            })
            .sum()
    }

    /// The TC model's duration, seconds, if the scene sets one.
    #[must_use]
    pub fn tc(&self) -> Option<f64> {
        self.tc
    }

    /// True under the TC model when body `i` collided less than `tc` before `t`.
    #[inline]
    fn within_tc(&self, i: usize, t: f64) -> bool {
        self.tc.is_some_and(|tc| t - self.last_collision[i] < tc)
    }

    /// Notes that bodies `i` and `j` collided at time `t` (for the TC model).
    #[inline]
    pub(crate) fn note_pair_collision(&mut self, i: usize, j: usize, t: f64) {
        if self.tc.is_some() {
            self.last_collision[i] = t;
            self.last_collision[j] = t;
        }
    }

    /// Notes that body `i` collided at time `t` (for the TC model).
    #[inline]
    pub(crate) fn note_collision(&mut self, i: usize, t: f64) {
        if self.tc.is_some() {
            self.last_collision[i] = t;
        }
    }

    /// The scene's Andersen thermostat, if any.
    #[must_use]
    pub fn thermostat(&self) -> Option<&crate::thermostat::Thermostat> {
        self.thermostat.as_ref()
    }

    /// How many times body `i`'s stored state has been replaced; a cached prediction about
    /// body `i` is still valid while this count is unchanged.
    #[must_use]
    #[inline]
    pub fn change_count(&self, i: usize) -> u64 {
        self.bodies[i].changes
    }

    /// Replaces body `i`'s state: position `pos` holding at time `t`, velocity `vel`.
    pub(crate) fn set_state(&mut self, i: usize, pos: Vector<D>, vel: Vector<D>, t: f64) {
        if !self.pivots.is_empty() {
            self.end_pivot(i);
        }
        let b = &mut self.bodies[i];
        b.motion = Motion { pos, vel, time: t };
        // Counting the change lifts a resting body off its wall (see `World::support`); a
        // collision that leaves it resting says so after.
        b.changes += 1;
    }

    /// Replaces body `i`'s stored state with `motion`, for tools that rebuild a world from a
    /// record (a viewer restoring the state at some instant from a run file). A running
    /// [`Simulation`](crate::Simulation) only lends its world immutably, so this cannot
    /// desynchronise a simulation from its finder; a finder serving this world must be told
    /// through [`Finder::update`](crate::Finder::update) or re-initialised.
    pub fn set_motion(&mut self, i: usize, motion: Motion<D>) {
        self.set_state(i, motion.pos, motion.vel, motion.time);
    }

    /// Sets the current simulated time, seconds, for tools that rebuild a world at a given
    /// instant (see [`World::set_motion`]); the caller promises that no event lies between the
    /// stored states' times and `t`.
    pub fn set_time(&mut self, t: f64) {
        self.now = t;
    }

    /// Multiplies every velocity by `factor` at the current time: each body's stored position
    /// moves to now. A finder serving this world must be re-initialised.
    pub fn scale_velocities(&mut self, factor: f64) {
        let now = self.now;
        for i in 0..self.bodies.len() {
            let (p, v) = (self.position_at(i, now), self.velocity_at(i, now));
            self.set_state(i, p, v * factor, now);
        }
    }

    /// Total kinetic energy of the stored velocities, joules (under gravity each at its
    /// body's reference time, and zero for a body turning about a segment's end, which is
    /// stored parked; see [`World::kinetic_energy_at`]). Kinematic bodies, of infinite mass,
    /// are left out.
    #[must_use]
    pub fn kinetic_energy(&self) -> f64 {
        self.bodies
            .iter()
            .filter(|b| !b.is_kinematic())
            .map(|b| 0.5 * b.mass * b.motion.vel.norm_sq())
            .sum()
    }

    /// Total kinetic energy at time `t`, joules: under gravity, of the velocities at `t`.
    #[must_use]
    pub fn kinetic_energy_at(&self, t: f64) -> f64 {
        if self.laws.gravity.is_none() {
            return self.kinetic_energy();
        }
        (0..self.len())
            .filter(|&i| !self.is_kinematic(i))
            .map(|i| 0.5 * self.mass(i) * self.velocity_at(i, t).norm_sq())
            .sum()
    }

    /// Potential energy in the gravity field at time `t`, joules: `−Σ m·g·x(t)` (zero at the
    /// origin; zero without gravity). Kinetic plus potential energy is what elastic
    /// collisions conserve under gravity.
    #[must_use]
    pub fn potential_energy_at(&self, t: f64) -> f64 {
        let Some(g) = self.laws.gravity else {
            return 0.0;
        };
        (0..self.len())
            .filter(|&i| !self.is_kinematic(i))
            .map(|i| -self.mass(i) * g.dot(self.position_at(i, t)))
            .sum()
    }

    /// Total momentum of the dynamic bodies' stored velocities, kg·m/s (kinematic ones, of
    /// infinite mass, are left out; a body turning about a segment's end is stored parked,
    /// at rest).
    #[must_use]
    pub fn momentum(&self) -> Vector<D> {
        self.bodies
            .iter()
            .filter(|b| !b.is_kinematic())
            .fold(Vector::ZERO, |acc, b| acc + b.motion.vel * b.mass)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::{gas, GasConfig};

    #[test]
    fn an_owned_scene_builds_the_same_world() {
        let mut scene = gas::<3>(&GasConfig {
            n: 300,
            packing: 0.3,
            radius_min: 0.3,
            radius_max: 0.5,
            speed_max: 2.0,
            seed: 7,
            ..GasConfig::default()
        })
        .unwrap();
        scene.bodies[4].id = Some(1000);
        scene.bodies[9].restitution = Some(0.5);
        scene.bodies[11].kinematic = true;
        let borrowed = World::from_scene(&scene).unwrap();
        let owned = World::from_owned_scene(scene).unwrap();
        let state = |w: &World<3>| {
            (0..w.len())
                .map(|i| {
                    let b = &w.bodies[i];
                    (b.motion, b.radius.to_bits(), b.mass.to_bits(), b.changes)
                })
                .collect::<Vec<_>>()
        };
        assert_eq!(state(&owned), state(&borrowed));
        assert_eq!(owned.ids(), borrowed.ids());
        assert_eq!(owned.next_id(), 1001);
        assert_eq!(owned.restitutions, borrowed.restitutions);
        assert!(owned.is_kinematic(11) && owned.laws.kinematic);
        assert_eq!(owned.bodies.capacity(), owned.len());
    }

    #[test]
    fn ids_are_written_out_only_once_a_slot_holds_another_id_than_its_index() {
        let scene = gas::<2>(&GasConfig {
            n: 10,
            packing: 0.2,
            ..GasConfig::default()
        })
        .unwrap();
        let mut world = World::from_owned_scene(scene).unwrap();
        assert!(world.id.is_empty());
        assert_eq!(world.ids(), (0..10).collect::<Vec<u64>>());
        assert_eq!(
            (world.id(7), world.index_of(7), world.next_id()),
            (7, Some(7), 10)
        );
        world.vacate(3);
        assert_eq!(world.id.len(), 10);
        assert_eq!(world.ids()[3], u64::MAX);
        assert_eq!((world.id(3), world.index_of(3)), (u64::MAX, None));
        world.reserve(2, |_| (Vector::ZERO, 0.1));
        let spec = BodySpec::new(Vector::ZERO, Vector::ZERO, 0.1);
        let (a, b) = (world.occupy(&spec, 42), world.occupy(&spec, 43));
        assert_eq!((a, b), (10, 11));
        assert_eq!(world.ids().len(), 12);
        assert_eq!(
            (world.ids()[3], world.ids()[10], world.ids()[11]),
            (u64::MAX, 42, 43)
        );
        assert_eq!((world.index_of(43), world.next_id()), (Some(11), 44));
    }

    #[test]
    fn an_owned_scene_is_validated() {
        let mut scene = gas::<2>(&GasConfig {
            n: 10,
            packing: 0.2,
            ..GasConfig::default()
        })
        .unwrap();
        scene.bodies[3].radius = -1.0;
        assert!(World::from_owned_scene(scene).is_err());
    }
}
