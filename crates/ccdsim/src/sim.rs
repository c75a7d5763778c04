//! The simulation loop: find the next event, resolve it, tell the finder, repeat.

use crate::contact::periodic::wrap_point;
use crate::contact::pivot_end::PivotEnd;
use crate::event::{Event, EventKind};
use crate::finder::{make_finder, Finder, FinderError, FinderOptions};
use crate::geom::Vector;
use crate::halt::{beyond_range, unresolved, Halt, ResolutionGuard};
use crate::histogram::{Histogram, HistogramCounts};
use crate::moving_wall_tracker::MovingWallTracker;
use crate::observables::thermodynamic::{observables, Observables};
use crate::resolve::{
    resolve_body_body_contact, resolve_body_wall, resolve_exit, resolve_slide_end, SlideEnd,
};
use crate::scene::arrival::{arrival_order, Arrival};
use crate::scene::{Scene, SceneError};
use crate::sensor::SensorEvent;
use crate::thermostat::ResetClock;
use crate::world::World;
use image_counts::ImageCounts;
use pivot_events::PivotEvents;

mod body_slots;
mod collapse;
mod image_counts;
pub(crate) mod pivot_events;
mod sensor_tracker;
mod wall_chain;
pub(crate) use body_slots::reserve_count;
use collapse::CollapseWatch;
pub use collapse::{COLLAPSE_COLLISIONS, COLLAPSE_SPAN};
use wall_chain::WallChain;
pub use wall_chain::WEDGED_AFTER;
mod resets;

pub use crate::event::Collision;
pub use sensor_tracker::SensorTracker;

/// Counters kept while running.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Stats {
    /// Events resolved: body and wall collisions, and thermostat resets.
    pub events: u64,
    /// Body–body collisions resolved.
    pub body_collisions: u64,
    /// Body–wall collisions resolved.
    pub wall_collisions: u64,
    /// Largest overlap seen at any contact, relative to the contact distance (`r_i + r_j`, or
    /// `r` for walls).
    pub max_overlap: f64,
    /// Kinetic energy when the simulation was created, joules.
    pub kinetic_energy_start: f64,
    /// Collision virial: the sum over body–body collisions of `r_ab · J_a`, the line of centres
    /// (from `b` to `a`, nearest images in periodic worlds) dotted with the impulse `a`
    /// received, kg·m²/s. Pressure and the compressibility factor follow from it (see
    /// [`crate::observables`]).
    pub virial: f64,
    /// Thermostat resets applied (see [`crate::thermostat`]); counted in `events` too.
    pub resets: u64,
    /// Work the moving walls did on the bodies at their collisions, joules (see
    /// [`crate::world::time_of_impact`]): the kinetic energy those collisions changed, which under
    /// growing radii includes what the growth rule adds at them; 0 without moving walls.
    pub wall_work: f64,
    /// Periodic worlds: box exits applied (a body leaving through a face and re-entering
    /// through the opposite one). Not events: never returned, recorded or counted above.
    pub exits: u64,
    /// Bodies the scene's `arrivals` brought in so far (see [`crate::scene::arrival`]).
    pub arrivals: u64,
    /// The energy they brought in, joules: kinetic plus, under gravity, potential
    /// (`−m g·x`) at their entry (kinematic arrivals bring none).
    pub arrival_energy: f64,
}

/// Why a simulation could not be created.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SimError {
    /// The scene is invalid.
    #[error(transparent)]
    Scene(#[from] SceneError),
    /// The finder cannot be made or cannot serve the scene.
    #[error(transparent)]
    Finder(#[from] FinderError),
    /// A body index is out of range or a value is not finite.
    #[error("{0}")]
    Input(String),
}

/// An exact event-driven simulation: a [`World`] and a [`Finder`].
///
/// ```
/// use ccdsim::{Scene, BodySpec, Simulation, Vector};
/// let scene = Scene::<2> {
///     bodies: vec![
///         BodySpec::new(Vector([0.0, 0.0]), Vector([1.0, 0.0]), 0.5),
///         BodySpec::new(Vector([3.0, 0.0]), Vector([-1.0, 0.0]), 0.5),
///     ],
///     ..Scene::default()
/// };
/// let mut sim = Simulation::new(&scene, "all-pairs").unwrap();
/// let hit = sim.step_event().unwrap();
/// assert_eq!(hit.event.time, 1.0);
/// assert_eq!(hit.vel, [Vector([-1.0, 0.0]), Vector([1.0, 0.0])]);
/// assert!(sim.step_event().is_none()); // they fly apart for ever
/// ```
pub struct Simulation<const D: usize> {
    world: World<D>,
    finder: Box<dyn Finder<D>>,
    pending: Option<Option<Event>>,
    halt: Option<Halt>,
    guard: ResolutionGuard,
    stats: Stats,
    start_time: f64,
    /// Periodic worlds: per body, the whole periods its stored position has been shifted by
    /// box exits, so that `stored + images · L` is its unwrapped position. None otherwise.
    images: ImageCounts<D>,
    /// The thermostat's reset sequence, if the scene has one.
    thermostat: Option<ResetClock>,
    /// Under gravity, the last event if its collision changed no body's position or velocity
    /// (a body come to rest on a wall, or pressed on one), and the one before if that changed
    /// nothing either: if the finder names one of them again, the run would loop at one
    /// instant for ever (a body wedged between two walls that hold it alternates between
    /// them), and halts ([`Halt::Resting`], [`Halt::RestingOnBody`]).
    idle: [Option<Event>; 2],
    /// Under gravity: the last wall events of one body in a row that came at one instant, or
    /// after hops too low to resolve. Past [`WEDGED_AFTER`], a body caught in a wedge whose
    /// speed has decayed into subnormal floats, or bouncing on a floor at a fixed point of the
    /// clock's rounding, halts the run ([`Halt::Resting`], see `sim/wall_chain.rs`).
    instant: WallChain,
    /// The scene's sensors, if it has any (see [`crate::sensor`]).
    sensors: Option<SensorTracker<D>>,
    /// Edits made since the last [`Simulation::take_edits`], as records, when
    /// [`Simulation::record_edits`] is on.
    edits: Option<Vec<Collision<D>>>,
    /// The largest radius a body added to a vacant slot may have without the finder being
    /// re-initialised (see [`body_slots::sized_radius`]).
    sized_radius: f64,
    /// Bodies that move freely (neither kinematic nor vacant): those the thermostat resets.
    free_bodies: usize,
    /// Each body's next contact with a moving wall, if the world has moving walls (see
    /// [`crate::world::time_of_impact`]).
    moving: Option<MovingWallTracker>,
    /// The events of bodies turning about segment ends, which finders do not see.
    pivots: PivotEvents,
    /// Where an inelastic collapse can happen, each body's recent collisions (see
    /// `sim/collapse.rs`).
    collapse: Option<CollapseWatch>,
    /// The scene's arrivals still to come, each with its index in the scene, last to come
    /// first (see [`crate::scene::arrival`]).
    arrivals: Vec<(usize, Arrival<D>)>,
    /// The next arrival's time, seconds; infinite when none is left. Read on every event.
    arrival_at: f64,
}

impl<const D: usize> Simulation<D> {
    /// A simulation of `scene` with the finder called `finder` and default options.
    pub fn new(scene: &Scene<D>, finder: &str) -> Result<Self, SimError> {
        Self::with_finder(scene, make_finder(finder, &FinderOptions::default())?)
    }

    /// A simulation of `scene` with the given finder.
    pub fn with_finder(scene: &Scene<D>, finder: Box<dyn Finder<D>>) -> Result<Self, SimError> {
        let mut sim = Self::from_world(World::from_scene(scene)?, finder)?;
        if !scene.sensors.is_empty() {
            sim.sensors = Some(SensorTracker::new(&sim.world, scene.sensors.clone()));
        }
        let mut order = arrival_order(&scene.arrivals);
        order.reverse();
        sim.arrivals = order
            .into_iter()
            .map(|k| (k, scene.arrivals[k].clone()))
            .collect();
        sim.arrival_at = sim.arrivals.last().map_or(f64::INFINITY, |a| a.1.time);
        Ok(sim)
    }

    /// A simulation of an already built world (see [`World::from_scene`]) with the given
    /// finder; lets a caller drop a large scene before the finder allocates its structures.
    pub fn from_world(world: World<D>, mut finder: Box<dyn Finder<D>>) -> Result<Self, SimError> {
        finder.init(&world)?;
        let stats = Stats {
            kinetic_energy_start: world.kinetic_energy(),
            ..Stats::default()
        };
        let images = ImageCounts::new(world.len(), world.periodic().is_some());
        let thermostat = world
            .thermostat()
            .map(|th| ResetClock::new(th, world.len(), world.now()));
        let moving = (world.moving_wall_count() > 0).then(|| MovingWallTracker::new(&world));
        let collapse = CollapseWatch::new(&world);
        Ok(Simulation {
            collapse,
            moving,
            thermostat,
            images,
            start_time: world.now(),
            guard: ResolutionGuard::new(&world),
            sized_radius: body_slots::sized_radius(&world),
            free_bodies: (0..world.len()).filter(|&i| !world.is_kinematic(i)).count(),
            world,
            finder,
            pending: None,
            halt: None,
            stats,
            idle: [None; 2],
            instant: WallChain::NONE,
            sensors: None,
            edits: None,
            pivots: PivotEvents::default(),
            arrivals: Vec::new(),
            arrival_at: f64::INFINITY,
        })
    }

    /// The bodies and walls.
    #[must_use]
    pub fn world(&self) -> &World<D> {
        &self.world
    }

    /// The finder's name.
    #[must_use]
    pub fn finder_name(&self) -> &'static str {
        self.finder.name()
    }

    /// The finder, e.g. to ask for its debug boxes.
    pub fn finder_mut(&mut self) -> (&mut dyn Finder<D>, &World<D>) {
        (self.finder.as_mut(), &self.world)
    }

    /// Current simulated time, seconds.
    #[must_use]
    pub fn time(&self) -> f64 {
        self.world.now()
    }

    /// Counters so far.
    #[must_use]
    pub fn stats(&self) -> &Stats {
        &self.stats
    }

    /// Simulated time at which the simulation was created, seconds.
    #[must_use]
    pub fn start_time(&self) -> f64 {
        self.start_time
    }

    /// Temperature, collision rate, pressure and compressibility factor over the whole run so
    /// far (from [`Simulation::start_time`] to the current time); see [`crate::observables`].
    #[must_use]
    pub fn observables(&self) -> Observables {
        observables(
            &self.world,
            self.stats.body_collisions,
            self.stats.virial,
            self.world.now() - self.start_time,
        )
    }

    /// Position of body `i` at the current time (in a periodic world, inside the box; in a
    /// sheared one, on a y face at most).
    #[must_use]
    pub fn position(&self, i: usize) -> Vector<D> {
        let p = self.world.position_at(i, self.world.now());
        self.wrapped(p)
    }

    /// `p` moved into the periodic box by whole periods, if the world has one. In a sheared
    /// box only along x and z: folding across a y face moves a body to another layer, whose
    /// velocity differs (see [`crate::contact::lees_edwards`]), and the stored position, which
    /// goes with the stored velocity, is already in the box up to rounding.
    fn wrapped(&self, p: Vector<D>) -> Vector<D> {
        let Some(size) = self.world.periodic() else {
            return p;
        };
        let mut w = wrap_point(p, &size);
        if self.world.shear().is_some() {
            w[1] = p[1];
        }
        w
    }

    /// The periodic image of body `i` now: the whole periods `k` such that
    /// [`Simulation::position`]` + k · L` is its unwrapped position (the path it travelled,
    /// never folded back into the box). All zeros in a world without a periodic box.
    #[must_use]
    pub fn image(&self, i: usize) -> [i64; D] {
        let Some(size) = self.world.periodic() else {
            return [0; D];
        };
        let raw = self.world.position_at(i, self.world.now());
        let wrapped = self.wrapped(raw);
        let mut k = self.images.get(i);
        for d in 0..D {
            // `raw − wrapped` is a whole number of periods, up to the rounding of the wrap.
            k[d] += ((raw[d] - wrapped[d]) / size[d]).round() as i64;
        }
        k
    }

    /// Unwrapped position of body `i` now, metres: its position plus the periods it crossed
    /// (see [`Simulation::image`]), and in a sheared box the strain of the layers it crossed
    /// along y (`k_y γ̇ L_y t` along x); the position itself in a world without a periodic box.
    #[must_use]
    pub fn unwrapped_position(&self, i: usize) -> Vector<D> {
        let mut p = self.position(i);
        if let Some(size) = self.world.periodic() {
            let k = self.image(i);
            for d in 0..D {
                p[d] += k[d] as f64 * size[d];
            }
            if let Some(bx) = self.world.shear() {
                // The layers above slide: a body `k_y` layers up has moved with them.
                p[0] += bx.unwrapped_shift(k[1], self.world.now());
            }
        }
        p
    }

    /// Why the simulation stopped while events remained, if it did: a contact beyond the
    /// largest time, or an event at which `f64` no longer resolves a body (see
    /// [`crate::halt`]). Once halted, no event is returned until an edit
    /// ([`Simulation::set_velocity`]) changes the world.
    #[must_use]
    pub fn halt(&self) -> Option<Halt> {
        self.halt
    }

    /// The finder's next event: a collision or, in periodic worlds, a box exit; `None` also
    /// when the simulation halts (see [`Simulation::halt`]).
    #[inline(always)]
    fn next_raw(&mut self) -> Option<Event> {
        if let Some(answer) = self.pending {
            return answer;
        }
        // Finders return finite events only (`finite_event`); the two halts are the cold
        // paths.
        let mut found = self.finder.next_event(&self.world);
        if self.moving.is_some() {
            found = self.with_moving_walls(found);
        }
        if !self.pivots.is_empty() {
            found = self.with_pivots(found);
        }
        let answer = match found {
            // Both halts of resting contacts need gravity: one test keeps them off the
            // hot path of a world without it.
            Some(e)
                if self.world.gravity().is_some()
                    && (self.idle[0].is_some()
                        || self.world.has_resting()
                        || self.instant.is_long())
                    && self.halts_before(&e) =>
            {
                None
            }
            Some(e) if self.guard.resolved(&self.world, &e) => Some(e),
            Some(e) => {
                self.halt = unresolved(&self.world, &e);
                None
            }
            None => {
                self.halt = beyond_range(&self.world);
                None
            }
        };
        // Returned as computed, not read back from `pending`: the event loop stores it once
        // and loads nothing (23 instructions an event fewer, callgrind, 2D gas).
        self.pending = Some(answer);
        answer
    }

    /// Under gravity, true (with [`Simulation::halt`] set) when the run stops before the
    /// finder's event `e`: it repeats a collision that changed nothing ([`Halt::Resting`],
    /// [`Halt::RestingOnBody`]).
    #[inline(never)]
    fn halts_before(&mut self, e: &Event) -> bool {
        // The same event again after collisions that changed nothing, or one wall event too
        // many of a body at one instant or after hops too low to resolve.
        let repeats = (self.idle[0].is_some() && self.idle.contains(&Some(*e)))
            || (self.instant.is_long() && self.continues_chain(e));
        let halt = if repeats {
            Some(match e.kind {
                EventKind::Body => Halt::RestingOnBody {
                    time: e.time,
                    a: e.a as usize,
                    b: e.b as usize,
                },
                _ => Halt::Resting {
                    time: e.time,
                    body: e.a as usize,
                    wall: e.b as usize,
                },
            })
        } else {
            None
        };
        if halt.is_some() {
            self.halt = halt;
        }
        halt.is_some()
    }

    /// True when wall event `e` continues the chain of unresolved wall events (under gravity).
    fn continues_chain(&self, e: &Event) -> bool {
        let g = self.world.gravity().map_or(0.0, |g| g.norm());
        let r = self.world.radius_at(e.a as usize, e.time);
        self.instant.continues(e, g, r)
    }

    /// The next event of any source: the finder's (collision or box exit) or the thermostat's
    /// reset, whichever comes first (the collision on a tie). A reset also comes when the
    /// finder has none, or has halted after the reset's time.
    #[inline(always)]
    fn next_any(&mut self) -> Option<Event> {
        let found = self.next_raw();
        if self.thermostat.is_none() {
            return found;
        }
        self.with_resets(found)
    }

    /// [`Simulation::next_any`] with a thermostat: the earlier of the finder's event `found`
    /// and the next reset. Out of line: the event loop of a world without a thermostat stays
    /// as tight as it was before thermostats.
    #[inline(never)]
    fn with_resets(&mut self, found: Option<Event>) -> Option<Event> {
        // Without a free body every draw is void (see `crate::thermostat`): the clock waits,
        // and an added body has the draws due by then judged first.
        let Some(clock) = self.thermostat.as_ref().filter(|_| self.free_bodies > 0) else {
            return found;
        };
        let t = clock.next_time();
        let halted_after = match self.halt {
            Some(
                Halt::Resolution { time, .. }
                | Halt::Resting { time, .. }
                | Halt::RestingOnBody { time, .. }
                | Halt::ArrivalBlocked { time, .. }
                | Halt::OverEdge { time, .. }
                | Halt::InelasticCollapse { time, .. },
            ) => time > t,
            Some(Halt::BeyondRange { .. }) => true,
            None => found.is_none(),
        };
        match found {
            Some(e) if e.time <= t => Some(e),
            _ if t.is_finite() && (found.is_some() || halted_after) => {
                Some(Event::reset(t, clock.next_body()))
            }
            _ => found,
        }
    }

    /// The earlier of the finder's event `found` and the first contact with a moving wall.
    /// Out of line: most worlds have no moving walls, and the event loop stays as tight as
    /// it was without them.
    #[cold]
    #[inline(never)]
    fn with_moving_walls(&mut self, found: Option<Event>) -> Option<Event> {
        let moving = self.moving.as_mut().and_then(MovingWallTracker::next_event);
        Event::earliest(found, moving)
    }

    /// The earlier of the finder's event `found` and the first event of a pivoting body (out
    /// of line, as [`Simulation::with_moving_walls`]).
    #[cold]
    #[inline(never)]
    fn with_pivots(&mut self, found: Option<Event>) -> Option<Event> {
        Event::earliest(found, self.pivots.next())
    }

    /// True when the next arrival comes at or before `t` and before the next event `found`
    /// (after every event at its time), or before the time the run halted at: an arrival
    /// changes what happens after it. A run halted because an arrival was blocked stays so.
    #[cold]
    #[inline(never)]
    fn arrives_before(&self, found: Option<&Event>, t: f64) -> bool {
        let at = self.arrival_at;
        at <= t
            && match (found, self.halt) {
                (Some(e), _) => at < e.time,
                (None, None) => true,
                (None, Some(Halt::BeyondRange { .. })) => true,
                (None, Some(h)) => at < h.time(),
            }
    }

    /// Brings in the next arrival at its time, as [`Simulation::add_body`] would; halts with
    /// [`Halt::ArrivalBlocked`] if its place is taken.
    #[cold]
    #[inline(never)]
    fn apply_arrival(&mut self) {
        let Some((k, arrival)) = self.arrivals.last().cloned() else {
            return;
        };
        let time = arrival.time;
        if time > self.world.now() {
            if let Some(s) = &mut self.sensors {
                s.advance_to(&self.world, time);
            }
            self.world.set_now(time);
        }
        match self.add_body(arrival.body) {
            Ok(i) => {
                self.arrivals.pop();
                self.arrival_at = self.arrivals.last().map_or(f64::INFINITY, |a| a.1.time);
                self.stats.arrivals += 1;
                // Kinematic bodies, of infinite mass, count in no energy.
                if !self.world.is_kinematic(i) {
                    let m = self.world.mass(i);
                    let potential = self
                        .world
                        .gravity()
                        .map_or(0.0, |g| -m * g.dot(self.world.position_at(i, time)));
                    self.stats.arrival_energy +=
                        0.5 * m * self.world.velocity_at(i, time).norm_sq() + potential;
                }
            }
            Err(_) => {
                self.halt = Some(Halt::ArrivalBlocked { time, arrival: k });
                self.pending = Some(None);
            }
        }
    }

    /// True for a box exit (a wall event naming a face after the walls, static and moving).
    fn is_exit(&self, e: &Event) -> bool {
        e.kind == EventKind::Wall
            && e.b as usize >= self.world.walls().len() + self.world.moving_wall_count()
    }

    /// The stored states of `bodies` changed: the finder and the moving walls' queue take
    /// them in.
    #[inline]
    fn bodies_changed(&mut self, bodies: &[usize]) {
        self.finder.update(&self.world, bodies);
        if self.moving.is_some() {
            self.moving_walls_see(bodies);
        }
        if self.world.has_resting() {
            self.pivots_see(bodies);
        }
    }

    /// The pivoting bodies' events take in the new states of `bodies` (out of line, as
    /// [`Simulation::with_moving_walls`]).
    #[cold]
    #[inline(never)]
    fn pivots_see(&mut self, bodies: &[usize]) {
        if !self.pivots.is_empty() || self.world.pivoting().next().is_some() {
            self.pivots.bodies_changed(&self.world, bodies);
        }
    }

    /// The moving walls' queue takes in the new states of `bodies` (out of line, as
    /// [`Simulation::with_moving_walls`]).
    #[cold]
    #[inline(never)]
    fn moving_walls_see(&mut self, bodies: &[usize]) {
        if let Some(m) = &mut self.moving {
            for &i in bodies {
                m.body_changed(&self.world, i);
            }
        }
    }

    /// Applies a box exit: the body re-enters through the opposite face; the current time
    /// becomes the exit's. Sensor events up to the exit are reported on the path before it,
    /// and the body's next one is sought on the path after it, with what it overlaps kept
    /// (the body has not moved: see [`SensorTracker::body_wrapped`]).
    #[inline(never)]
    fn apply_exit(&mut self, e: Event) {
        self.pending = None;
        if let Some(s) = &mut self.sensors {
            s.advance_to(&self.world, e.time);
        }
        self.world.set_now(e.time.max(self.world.now()));
        let face = e.b as usize - self.world.walls().len();
        let x_periods = resolve_exit(&mut self.world, e.a as usize, face, e.time);
        // `resolve_exit` moved the body back by one period through face `face` (and in a
        // sheared box along x, by `x_periods` periods beyond the strain).
        let step = if face % 2 == 1 { 1 } else { -1 };
        self.images.shift(e.a as usize, face / 2, step);
        if x_periods != 0 {
            self.images.add(e.a as usize, 0, x_periods);
        }
        self.bodies_changed(&[e.a as usize]);
        if let Some(s) = &mut self.sensors {
            s.body_wrapped(&self.world, e.a as usize);
        }
        self.stats.exits += 1;
    }

    /// The next event (collision), without resolving it.
    ///
    /// In a periodic world, box exits before it are applied on the way (so the current time
    /// may advance to the last of them), and `None` also comes when more than
    /// `1024 + 64 · n` exits in a row bring no collision (bodies that may fly for ever).
    #[inline(always)]
    pub fn peek_event(&mut self) -> Option<Event> {
        let guard = 1024 + 64 * self.world.len() as u64;
        let mut exits = 0;
        loop {
            let found = self.next_any();
            if self.arrival_at < f64::INFINITY && self.arrives_before(found.as_ref(), f64::INFINITY)
            {
                self.apply_arrival();
                continue;
            }
            let e = found?;
            if self.is_void_reset(&e) {
                self.skip_reset(e.time);
                continue;
            }
            if !self.is_exit(&e) {
                return Some(e);
            }
            if exits >= guard {
                return None;
            }
            self.apply_exit(e);
            exits += 1;
        }
    }

    /// Resolves the next event and returns it, or `None` when no event will ever happen (see
    /// [`Simulation::peek_event`] for periodic worlds).
    #[inline(always)]
    pub fn step_event(&mut self) -> Option<Collision<D>> {
        let event = self.peek_event()?;
        self.pending = None;
        Some(self.resolve(event))
    }

    #[inline(always)]
    fn resolve(&mut self, e: Event) -> Collision<D> {
        let (a, b) = (e.a as usize, e.b as usize);
        if let Some(s) = &mut self.sensors {
            // Every sensor event up to the collision, on the motions before it.
            s.advance_to(&self.world, e.time);
        }
        // The no-change event before this one, if there was one; cleared for good unless this
        // event changes nothing too.
        let idle_before = self.idle[0].take();
        self.world.set_now(e.time.max(self.world.now()));
        let overlap;
        // Growing radii: collisions add kinetic energy, which the resolution guard must know.
        let energy_before = self.world.growth().map(|_| self.involved_energy(&e));
        let out = match e.kind {
            EventKind::Body => {
                let before = self.world.velocity_at(a, e.time);
                // Only bodies with their own accelerations press together at a contact that
                // changes nothing (see `Halt::RestingOnBody`).
                let states = |w: &World<D>, t: f64| {
                    let at = |i: usize| (w.position_at(i, t), w.velocity_at(i, t));
                    (at(a), at(b))
                };
                let before_both = self
                    .world
                    .has_resting()
                    .then(|| states(&self.world, e.time));
                let contact = resolve_body_body_contact(&mut self.world, a, b, e.time);
                overlap = contact.overlap;
                self.stats.body_collisions += 1;
                let w = &self.world;
                // `x_a − x_b` is exactly `−(x_b − x_a)`, and the minimum image commutes with
                // negation (it rounds halves away from zero), so this is the virial term
                // `r_ab · Δv_a · m_a` without taking the image a second time.
                let r = -contact.separation;
                self.stats.virial += r.dot(w.velocity(a) - before) * w.mass(a);
                if before_both.is_some_and(|s| s == states(&self.world, e.time)) {
                    self.idle = [Some(e), idle_before];
                }
                self.bodies_changed(&[a, b]);
                let w = &self.world;
                if w.has_resting() {
                    let ((pa, va), (pb, vb)) = (w.recorded_state(a), w.recorded_state(b));
                    Collision {
                        event: e,
                        pos: [pa, pb],
                        vel: [va, vb],
                        rests: [w.support(a).is_some(), w.support(b).is_some()],
                        pivots: [w.pivot(a).is_some(), w.pivot(b).is_some()],
                    }
                } else {
                    Collision {
                        event: e,
                        pos: [w.position(a), w.position(b)],
                        vel: [w.velocity(a), w.velocity(b)],
                        rests: [false; 2],
                        pivots: [false; 2],
                    }
                }
            }
            // A pivoting body's turn ends (it comes off, swings back or lands).
            EventKind::Wall
                if self.world.has_resting()
                    && self.pivots.end_of(a).is_some_and(|(_, end)| end == e) =>
            {
                overlap = 0.0;
                self.resolve_pivot_end(e)
            }
            // A body meeting the segment it slides on: it has reached the end.
            EventKind::Wall if self.world.has_resting() && self.world.support(a) == Some(b) => {
                overlap = 0.0;
                self.resolve_slide_end(e)
            }
            EventKind::Wall => {
                let falling = self.world.gravity().is_some();
                let before = falling.then(|| {
                    (
                        self.world.position_at(a, e.time),
                        self.world.velocity_at(a, e.time),
                    )
                });
                let moving = b >= self.world.walls().len();
                let speed_before = moving.then(|| self.world.velocity_at(a, e.time).norm_sq());
                let rested = self.world.support(a).is_some();
                overlap = resolve_body_wall(&mut self.world, a, b, e.time);
                if let Some(v2) = speed_before {
                    let w = &self.world;
                    self.stats.wall_work += 0.5 * w.mass(a) * (w.velocity(a).norm_sq() - v2);
                }
                let rests = self.world.support(a).is_some();
                if (!rests || rested)
                    && before == Some((self.world.position(a), self.world.velocity(a)))
                {
                    // Nothing changed but, perhaps, the wall it rests on: the same event would
                    // come again, or it alternates between two walls (see `Halt::Resting`).
                    self.idle = [Some(e), idle_before];
                }
                if let Some(g) = self.world.gravity() {
                    let r = self.world.radius_at(a, e.time);
                    self.instant.note(&e, g.norm(), r);
                }
                self.stats.wall_collisions += 1;
                self.bodies_changed(&[a]);
                self.wall_collision(e, rests)
            }
            EventKind::Reset => {
                overlap = 0.0;
                self.apply_reset(e.time)
            }
            EventKind::Edit => unreachable!("edits are made by a program, never found"),
        };
        if let Some(before) = energy_before {
            self.guard.add_energy(self.involved_energy(&e) - before);
        }
        if let Some(s) = &mut self.sensors {
            s.body_changed(&self.world, a);
            if e.kind == EventKind::Body {
                s.body_changed(&self.world, b);
            }
        }
        self.stats.events += 1;
        self.stats.max_overlap = self.stats.max_overlap.max(overlap);
        if e.kind == EventKind::Body && self.collapse.is_some() {
            self.watch_collapse(&e);
        }
        out
    }

    /// Body event `e` was resolved where an inelastic collapse can happen: its bodies' windows
    /// take it in, and a window closed within a vanishing span halts the run after it
    /// ([`Halt::InelasticCollapse`]).
    #[cold]
    #[inline(never)]
    fn watch_collapse(&mut self, e: &Event) {
        let (elapsed, n, collisions) = (
            e.time - self.start_time,
            self.free_bodies as f64,
            self.stats.body_collisions as f64,
        );
        let mean_free_time = || elapsed * n / (2.0 * collisions);
        let Some(watch) = &mut self.collapse else {
            return;
        };
        // Both bodies' windows take the collision in; the lower index speaks first.
        let first = watch.note(e.a as usize, e.time, mean_free_time);
        let second = watch.note(e.b as usize, e.time, mean_free_time);
        let halt = first.or(second);
        if halt.is_some() {
            self.halt = halt;
            // No event after this one until an edit changes the world.
            self.pending = Some(None);
        }
    }

    /// Resolves wall event `e`, body `e.a` arriving at the end of the segment `e.b` it slides
    /// on ([`resolve_slide_end`]): the record names the segment it goes on to, if any.
    #[cold]
    fn resolve_slide_end(&mut self, mut e: Event) -> Collision<D> {
        let a = e.a as usize;
        match resolve_slide_end(&mut self.world, a, e.b as usize, e.time) {
            SlideEnd::GoesOn(next) => {
                e.b = u32::try_from(next).expect("wall indices fit events");
            }
            SlideEnd::FliesClear => {}
            SlideEnd::Pivots { laws_changed } => {
                self.stats.wall_collisions += 1;
                if laws_changed {
                    self.rebuild()
                        .expect("a finder re-initialised for a world it served");
                } else {
                    self.bodies_changed(&[a]);
                }
                return self.wall_collision(e, false);
            }
        }
        self.stats.wall_collisions += 1;
        self.bodies_changed(&[a]);
        self.wall_collision(e, self.world.support(a).is_some())
    }

    /// Resolves the end of body `e.a`'s turn about a segment's end point (see
    /// [`crate::contact::pivot_end`]): it comes off falling (it meets that point no more, see
    /// [`World::released`]), or rests on the segment it swings back onto or lands on, its
    /// velocity along it.
    #[cold]
    fn resolve_pivot_end(&mut self, e: Event) -> Collision<D> {
        let (a, t) = (e.a as usize, e.time);
        let (end, _) = self.pivots.end_of(a).expect("a pivoting body");
        let (_, w) = self.world.pivot(a).expect("a pivoting body");
        let (p, v) = (self.world.position_at(a, t), self.world.velocity_at(a, t));
        let rests = match end {
            PivotEnd::Release { .. } => {
                self.world.set_state(a, p, v, t);
                self.world.release(a, w);
                false
            }
            PivotEnd::Back { .. } | PivotEnd::Land { .. } => {
                let k = e.b as usize;
                let wall = self.world.walls()[k];
                let v2 = crate::contact::resting::along_support(&v, &wall);
                self.world.set_state(a, p, v2, t);
                let holds = self.world.slide_of(k).is_some();
                if holds {
                    self.world.rest_on(a, k);
                }
                holds
            }
        };
        self.stats.wall_collisions += 1;
        self.bodies_changed(&[a]);
        self.wall_collision(e, rests)
    }

    /// The record of wall event `e` just resolved: its body's new state, and whether it rests.
    fn wall_collision(&self, e: Event, rests: bool) -> Collision<D> {
        let (w, a) = (&self.world, e.a as usize);
        let (pos, vel) = w.recorded_state(a);
        Collision {
            event: e,
            pos: [pos, Vector::ZERO],
            vel: [vel, Vector::ZERO],
            rests: [rests, false],
            pivots: [w.pivot(a).is_some(), false],
        }
    }

    /// Kinetic energy of the bodies `e` involves, joules; a kinematic body has none to count
    /// (its infinite mass would make it ∞, or NaN at rest), as in [`World::kinetic_energy`].
    fn involved_energy(&self, e: &Event) -> f64 {
        let k = |i: u32| {
            let i = i as usize;
            if self.world.is_kinematic(i) {
                return 0.0;
            }
            0.5 * self.world.mass(i) * self.world.velocity(i).norm_sq()
        };
        match e.kind {
            EventKind::Body => k(e.a) + k(e.b),
            EventKind::Wall | EventKind::Reset | EventKind::Edit => k(e.a),
        }
    }

    /// Radius of body `i` now, metres (it grows in a growing world, see [`crate::contact::growth`]).
    #[must_use]
    pub fn radius(&self, i: usize) -> f64 {
        self.world.radius_at(i, self.world.now())
    }

    /// Multiplies every body's velocity by `factor` from the current time on (growing
    /// packings are cooled this way, see [`crate::contact::growth`]). O(n): every body's next
    /// events are computed anew ([`Finder::all_changed`]: the `cells` finder keeps its grid
    /// and lists). Journaled as one velocity edit per body when the journal is on
    /// ([`Simulation::record_edits`]).
    pub fn rescale_velocities(&mut self, factor: f64) -> Result<(), SimError> {
        if !(factor.is_finite() && factor >= 0.0) {
            return Err(SimError::Input(format!(
                "velocity factor {factor} is not a finite non-negative number"
            )));
        }
        self.world.scale_velocities(factor);
        if self.edits.is_some() {
            for i in 0..self.world.len() {
                if !self.world.is_vacant(i) {
                    self.journal_edit(i);
                }
            }
        }
        self.finder.all_changed(&self.world)?;
        self.states_replaced();
        Ok(())
    }

    /// Stops the growth of the radii at the current time: they keep their current values
    /// from now on (a scene written afterwards has them). O(n): the finder is rebuilt.
    pub fn stop_growth(&mut self) -> Result<(), SimError> {
        let now = self.world.now();
        self.world.stop_growth(now);
        self.rebuild()
    }

    /// Body `i`'s stored motion was replaced by an edit at the current time: its sensor
    /// events are computed anew.
    fn sensors_changed(&mut self, i: usize) {
        if let Some(s) = &mut self.sensors {
            s.body_changed(&self.world, i);
        }
    }

    /// The sensor events reported since the last call, in time order (see
    /// [`crate::sensor`]): bodies entering and leaving the scene's sensors as the clock
    /// passed them. Empty for a scene without sensors.
    pub fn take_sensor_events(&mut self) -> Vec<SensorEvent> {
        self.sensors
            .as_mut()
            .map(SensorTracker::take_events)
            .unwrap_or_default()
    }

    /// Turns the journal of edits on or off: while on, every `set_velocity` and
    /// `set_position` is kept as a record ([`EventKind::Edit`]: the body's position at the
    /// current time and its velocity from then on) for [`Simulation::take_edits`], so that a
    /// steered run can be written to a run file ([`crate::record::RunWriter::new_steered`])
    /// and replayed by `verify` and the viewer. Off by default.
    ///
    /// ```
    /// use ccdsim::record::RunWriter;
    /// use ccdsim::{BodySpec, Scene, Simulation, Vector};
    /// let scene = Scene::<2> {
    ///     bodies: vec![BodySpec::new(Vector([0.0, 0.0]), Vector([1.0, 0.0]), 0.5)],
    ///     ..Scene::default()
    /// };
    /// let mut sim = Simulation::new(&scene, "cells").unwrap();
    /// let mut run = RunWriter::new_steered(Vec::new(), "game".into(), &scene).unwrap();
    /// sim.record_edits(true);
    /// for frame in 0..60 {
    ///     sim.set_velocity(0, Vector([1.0, (frame % 2) as f64])).unwrap(); // steering
    ///     for record in sim.take_edits().iter().chain(&sim.advance(1.0 / 60.0)) {
    ///         run.write_event(record).unwrap();
    ///     }
    /// }
    /// let bytes = run.finish(sim.time()).unwrap();
    /// ```
    pub fn record_edits(&mut self, on: bool) {
        self.edits = if on {
            Some(self.edits.take().unwrap_or_default())
        } else {
            None
        };
    }

    /// The edits recorded since the last call, in order (see [`Simulation::record_edits`]);
    /// empty while the journal is off.
    pub fn take_edits(&mut self) -> Vec<Collision<D>> {
        self.edits.as_mut().map(std::mem::take).unwrap_or_default()
    }

    /// Journals a new position or velocity of body `i` just given at the current time.
    fn journal_edit(&mut self, i: usize) {
        self.journal(crate::edit::Edit::Motion {
            body: i,
            pos: self.world.position(i),
            vel: self.world.velocity(i),
        });
    }

    /// Journals `edit`, just made at the current time.
    fn journal(&mut self, edit: crate::edit::Edit<D>) {
        if let Some(log) = &mut self.edits {
            log.extend(edit.records(self.world.now()));
        }
    }

    /// The scene's sensors and what they hold, if it has any.
    #[must_use]
    pub fn sensors(&self) -> Option<&SensorTracker<D>> {
        self.sensors.as_ref()
    }

    /// After a change of every body: the finder and the resolution guard start afresh.
    fn rebuild(&mut self) -> Result<(), SimError> {
        self.finder.init(&self.world)?;
        self.sized_radius = body_slots::sized_radius(&self.world);
        self.states_replaced();
        Ok(())
    }

    /// After every body's stored state was replaced and the finder told: the moving walls',
    /// sensors' and pivots' events are computed anew and the resolution guard starts afresh.
    fn states_replaced(&mut self) {
        if let Some(m) = &mut self.moving {
            m.walls_changed(&self.world);
        }
        if let Some(s) = &mut self.sensors {
            for i in 0..self.world.len() {
                s.body_changed(&self.world, i);
            }
        }
        self.guard = ResolutionGuard::new(&self.world);
        self.pivots.reset(&self.world);
        self.pending = None;
        self.halt = None;
        self.idle = [None; 2];
        self.instant = WallChain::NONE;
    }

    /// Resolves the next event if it happens at or before `t` and returns it; otherwise
    /// returns `None` and changes nothing after `t` (box exits up to `t` are applied).
    pub fn step_event_until(&mut self, t: f64) -> Option<Collision<D>> {
        loop {
            let found = self.next_any();
            if self.arrival_at <= t && self.arrives_before(found.as_ref(), t) {
                self.apply_arrival();
                continue;
            }
            let e = found?;
            if e.time > t {
                return None;
            }
            if self.is_exit(&e) {
                self.apply_exit(e);
                continue;
            }
            if self.is_void_reset(&e) {
                self.skip_reset(e.time);
                continue;
            }
            self.pending = None;
            return Some(self.resolve(e));
        }
    }

    /// Resolves every event at or before `t`, calling `on_event` after each, then sets the
    /// current time to `t`. Returns the number of events resolved.
    pub fn run_until_with(&mut self, t: f64, mut on_event: impl FnMut(&Collision<D>)) -> u64 {
        let mut count = 0;
        while let Some(c) = self.step_event_until(t) {
            on_event(&c);
            count += 1;
        }
        // The clock moves to `t` unless an event at or before `t` could not be resolved: a
        // run halted there stays where it stopped. (A contact beyond the largest time, or an
        // unresolved event after `t`, leaves nothing unresolved before `t`.)
        let blocked = matches!(
            self.halt,
            Some(
                Halt::Resolution { time, .. }
                | Halt::Resting { time, .. }
                | Halt::RestingOnBody { time, .. }
                | Halt::ArrivalBlocked { time, .. }
                | Halt::OverEdge { time, .. }
                | Halt::InelasticCollapse { time, .. },
            ) if time <= t
        );
        if t > self.world.now() && !blocked {
            if let Some(s) = &mut self.sensors {
                s.advance_to(&self.world, t);
            }
            self.world.set_now(t);
        }
        count
    }

    /// Resolves every event at or before `t`; see [`Simulation::run_until_with`].
    pub fn run_until(&mut self, t: f64) -> u64 {
        self.run_until_with(t, |_| {})
    }

    /// Resolves up to `n` events, calling `on_event` after each; stops early when no event
    /// will ever happen. Returns the number resolved.
    pub fn run_events_with(&mut self, n: u64, mut on_event: impl FnMut(&Collision<D>)) -> u64 {
        let mut count = 0;
        while count < n {
            let Some(c) = self.step_event() else { break };
            on_event(&c);
            count += 1;
        }
        count
    }

    /// Resolves up to `n` events; see [`Simulation::run_events_with`].
    pub fn run_events(&mut self, n: u64) -> u64 {
        self.run_events_with(n, |_| {})
    }

    /// Advances the simulated time by `dt` seconds (one game frame) and returns the collisions
    /// that happened inside the frame, in order.
    pub fn advance(&mut self, dt: f64) -> Vec<Collision<D>> {
        let mut out = Vec::new();
        let until = self.world.now() + dt.max(0.0);
        self.run_until_with(until, |c| out.push(*c));
        out
    }

    /// Refuses an index that names no body: out of range, or a vacant slot.
    fn check_body(&self, i: usize) -> Result<(), SimError> {
        let n = self.world.len();
        if i >= n {
            return Err(SimError::Input(format!(
                "body {i} does not exist ({n} slots)"
            )));
        }
        if self.world.is_vacant(i) {
            return Err(SimError::Input(format!(
                "body {i} does not exist (its slot is vacant: removed, or reserved)"
            )));
        }
        Ok(())
    }

    /// What the bins of `histogram` hold now: the bodies present and not kinematic, by their
    /// centres (periodic worlds: in the box).
    #[must_use]
    pub fn histogram(&self, histogram: &Histogram) -> HistogramCounts {
        let t = self.world.now();
        histogram.count(
            (0..self.world.len())
                .filter(|&i| !self.world.is_vacant(i) && !self.world.is_kinematic(i))
                .map(|i| self.world.position_at(i, t)[histogram.axis]),
        )
    }

    /// Gives body `i` a new velocity from the current time on (a game's kick or steering).
    pub fn set_velocity(&mut self, i: usize, vel: Vector<D>) -> Result<(), SimError> {
        self.check_body(i)?;
        if !vel.is_finite() {
            return Err(SimError::Input(format!(
                "velocity of body {i} is not finite"
            )));
        }
        // The kinetic energy may grow: the guard's speed bound with it.
        let t = self.world.now();
        if !self.world.is_kinematic(i) {
            // (A kinematic body's infinite mass would make this ∞ − ∞; worlds with one have
            // no fast path to bound anyway.)
            let added =
                0.5 * self.world.mass(i) * (vel.norm_sq() - self.world.velocity_at(i, t).norm_sq());
            self.guard.add_energy(added);
        }
        self.restate(i, vel);
        self.journal_edit(i);
        self.edited(i);
        Ok(())
    }

    /// Gives body `i` the collision group and mask `filter` from the current time on (see
    /// [`crate::collision_filter`]): a game's ghost power-up, a door that opens. Refused,
    /// leaving everything as it was, when body `i` would then collide with a body it overlaps.
    /// Each finder updates only body `i`, except that the first filter of a world whose
    /// bodies had none rebuilds the finder once (O(n)). O(n) for the overlap check.
    pub fn set_collision_filter(
        &mut self,
        i: usize,
        filter: crate::CollisionFilter,
    ) -> Result<(), SimError> {
        self.check_body(i)?;
        let t = self.world.now();
        let pos = self.world.position_at(i, t);
        let (r, kinematic) = (self.world.radius_at(i, t), self.world.is_kinematic(i));
        if let Some(j) = self.overlapped_by(i, pos, r, kinematic, |j| {
            filter.collides(&self.world.filter(j))
        }) {
            return Err(SimError::Input(format!(
                "body {i} overlaps body {j}: it cannot be made to collide with it"
            )));
        }
        // Stored anew at the current time: a pair's contact is sought from the later of its
        // bodies' reference times, and a pair that passed through each other before now must
        // not be found in contact then.
        self.restate(i, self.world.velocity_at(i, t));
        self.journal(crate::edit::Edit::Filter {
            body: i,
            pos: self.world.position(i),
            vel: self.world.velocity(i),
            filter,
        });
        if self.world.set_filter(i, filter) {
            // The world's laws changed (pairs are now filtered): every finder starts afresh.
            return self.rebuild();
        }
        self.edited(i);
        Ok(())
    }

    /// Body `i`'s stored state was replaced by an edit at the current time: the finder and
    /// the sensors take it in, and what was found before (the next event, a halt, a resting
    /// contact) no longer holds.
    fn edited(&mut self, i: usize) {
        self.bodies_changed(&[i]);
        self.sensors_changed(i);
        self.pending = None;
        self.halt = None;
        self.idle = [None; 2];
        self.instant = WallChain::NONE;
    }

    /// The first body `j ≠ skip` that a ball of radius `r` put at `pos` now would overlap,
    /// among those it `collides` with (kinematic pairs never meet; vacant slots collide with
    /// nothing): O(n).
    fn overlapped_by(
        &self,
        skip: usize,
        pos: Vector<D>,
        r: f64,
        kinematic: bool,
        collides: impl Fn(usize) -> bool,
    ) -> Option<usize> {
        let t = self.world.now();
        (0..self.world.len()).find(|&j| {
            if j == skip
                || (kinematic && self.world.is_kinematic(j))
                || self.world.is_vacant(j)
                || !collides(j)
            {
                return false;
            }
            let d = self.world.position_at(j, t) - pos;
            let d = match (self.world.periodic(), self.world.shear()) {
                (Some(_), Some(bx)) => bx.nearest_image(d, t).0,
                (Some(size), None) => crate::contact::periodic::min_image(d, &size),
                (None, _) => d,
            };
            d.norm() < r + self.world.radius_at(j, t)
        })
    }

    /// Why a ball named `what`, of radius `r` and moving at `vel`, cannot be put at `pos`
    /// now, ignoring bodies: `pos` is not finite or not resolved by `f64` (see
    /// [`crate::resolution`]), outside a periodic box, or (unless kinematic) across a wall
    /// or outside the table a closed polygon of 2D segments forms.
    fn placement_error(
        &self,
        what: &str,
        pos: Vector<D>,
        vel: Vector<D>,
        r: f64,
        kinematic: bool,
    ) -> Option<String> {
        let t = self.world.now();
        if !pos.is_finite() {
            return Some(format!("position of {what} is not finite"));
        }
        if !crate::resolution::resolves(t, pos, vel, r) {
            return Some(format!(
                "{what} at {:?} is not resolved by f64 at t = {t} (see the numerical rules)",
                pos.0
            ));
        }
        if let Some(size) = self.world.periodic() {
            if (0..D).any(|d| !(0.0..size[d]).contains(&pos[d])) {
                return Some(format!(
                    "{what} at {:?} would lie outside the periodic box",
                    pos.0
                ));
            }
        }
        if kinematic {
            return None;
        }
        let walls = self.world.walls();
        let every_wall = walls.len() + self.world.moving_wall_count();
        if let Some(w) = (0..every_wall)
            .find(|&w| crate::wall::wall_clearance(&self.world.wall_at(w, t), pos) < r)
        {
            return Some(format!("{what} at {:?} would cross wall {w}", pos.0));
        }
        let loops = self.world.table();
        if D == 2 && !loops.is_empty() && !crate::wall::inside_even_odd(loops, pos[0], pos[1]) {
            return Some(format!("{what} at {:?} would lie outside the table", pos.0));
        }
        None
    }

    /// Stores body `i`'s state anew at the current time, with velocity `vel`: its position
    /// now (wrapped into a periodic box, its image kept) becomes its reference position.
    fn restate(&mut self, i: usize, vel: Vector<D>) {
        let image = self.image(i);
        let p = self.position(i);
        self.world.set_state(i, p, vel, self.world.now());
        if self.images.is_counting() {
            // The stored position is now the wrapped one: its image is the whole offset.
            self.images.set(i, image);
        }
    }

    /// Gives moving wall `k` (wall `walls().len() + k` in events, see
    /// [`crate::world::time_of_impact`]) the velocity `vel`, m/s, from the current time on: a game's
    /// paddle steered each frame, a piston started or stopped. The wall stays where it is now;
    /// bodies it then meets bounce off it exactly, with every finder. O(n · moving walls):
    /// every body's next contact with a moving wall is computed anew (the finder is not
    /// touched). Recorded as an edit when the journal is on ([`Simulation::record_edits`]).
    ///
    /// ```
    /// use ccdsim::{BodySpec, MovingWall, Scene, Simulation, Vector, Wall};
    /// let scene = Scene::<2> {
    ///     bodies: vec![BodySpec::new(Vector([0.0, 5.0]), Vector::ZERO, 0.5)],
    ///     moving_walls: vec![MovingWall {
    ///         wall: Wall::Plane { point: Vector([0.0, 0.0]), normal: Vector([0.0, 1.0]) },
    ///         velocity: Vector::ZERO,
    ///     }],
    ///     ..Scene::default()
    /// };
    /// let mut sim = Simulation::new(&scene, "cells").unwrap();
    /// sim.set_wall_velocity(0, Vector([0.0, 1.0])).unwrap(); // the floor rises at 1 m/s
    /// let hit = sim.step_event().unwrap();
    /// assert_eq!((hit.event.time, hit.event.b), (4.5, 0)); // wall 0: the first moving wall
    /// assert_eq!(hit.vel[0], Vector([0.0, 2.0])); // off a wall of infinite mass
    /// ```
    pub fn set_wall_velocity(&mut self, k: usize, vel: Vector<D>) -> Result<(), SimError> {
        let count = self.world.moving_wall_count();
        if k >= count {
            return Err(SimError::Input(format!(
                "moving wall {k} does not exist ({count} moving walls)"
            )));
        }
        if !vel.is_finite() {
            return Err(SimError::Input(format!(
                "velocity of moving wall {k} is not finite"
            )));
        }
        let t = self.world.now();
        self.world.set_wall_velocity(k, vel, t);
        if let Some(m) = &mut self.moving {
            m.walls_changed(&self.world);
        }
        self.pivots.reset(&self.world);
        let motion = self.world.wall_motion(k);
        self.journal(crate::edit::Edit::WallMotion {
            wall: k,
            offset: motion.offset,
            vel,
        });
        self.pending = None;
        self.halt = None;
        self.idle = [None; 2];
        self.instant = WallChain::NONE;
        Ok(())
    }

    /// Moves body `i` to `pos` at the current time, keeping its velocity (a game's teleport
    /// or respawn). Each finder updates only that body (no rebuild). Refused, leaving
    /// everything as it was, when `pos` is not finite or not resolved by `f64` (see
    /// [`crate::resolution`]), outside a periodic box, or where the body would overlap
    /// another body or a wall (a kinematic body may overlap walls and other kinematic
    /// bodies), or lie outside the table a closed polygon of 2D segments forms. O(n) for the
    /// overlap check.
    pub fn set_position(&mut self, i: usize, pos: Vector<D>) -> Result<(), SimError> {
        self.check_body(i)?;
        let t = self.world.now();
        let vel = self.world.velocity_at(i, t);
        let r = self.world.radius_at(i, t);
        let kinematic = self.world.is_kinematic(i);
        if let Some(why) = self.placement_error(&format!("body {i}"), pos, vel, r, kinematic) {
            return Err(SimError::Input(why));
        }
        // The bodies' own filters: a body turning about a segment's end is parked colliding
        // with nothing for the finders (see `World::pivot`), yet must not be overlapped.
        let filter = self.world.filter(i);
        if let Some(j) = self.overlapped_by(i, pos, r, kinematic, |j| {
            filter.collides(&self.world.filter(j))
        }) {
            return Err(SimError::Input(format!(
                "body {i} at {:?} would overlap body {j}",
                pos.0
            )));
        }
        self.world.set_state(i, pos, vel, t);
        if self.images.is_counting() {
            // A teleport starts a new path: its unwrapped position is where it now is.
            self.images.set(i, [0; D]);
        }
        self.journal_edit(i);
        self.edited(i);
        Ok(())
    }
}
