//! Replaying a run and checking the numerical rules, independently of any finder.
//!
//! For every event the [`Verifier`] checks: times never go backwards; the recorded positions
//! follow from the previous states; the bodies touch (gap within `1e-9` of the contact
//! distance); momentum is conserved in body–body collisions and kinetic energy in elastic
//! ones; and no pair of bodies and no body and wall came closer than `(1 − 1e-9)` times their
//! contact distance at any time (a missed collision), using closed-form closest approach
//! rather than the simulator's narrow phase. In a periodic scene, positions are compared and
//! distances measured between nearest images, and closest approaches are searched over every
//! image the relative motion passes.
//!
//! The miss check looks at the pairs that its own broad phase (`verify/proximity.rs`: a hash
//! grid of swept boxes in slabs of time, sharing no code with the finders) says may have come close,
//! so a replay costs about as much per event as the simulation; [`Verifier::all_pairs`]
//! checks every pair instead, for tests and small runs.
//!
//! With growing radii ([`crate::contact::growth`]) contact distances are taken at each time, the miss
//! check minimises the distance less the growth (a convex function of time) in closed form
//! (an end of the stretch, or where its derivative vanishes), and kinetic energy, which growth collisions add, is not checked: instead the
//! impulse must lie along the line of centres (the wall's normal) and give the normal
//! relative velocity the growth rule asks for, `u' = (1 + e)·σ̇ − e·u` (at a moving wall,
//! relative to the wall), with `e` the collision's restitution as the simulation chose it:
//! the pair's mean of the bodies' own, or 1 under the TC model (`verify/restitution.rs`).
//!
//! Under uniform gravity ([`crate::contact::gravity`]) bodies follow parabolas between events: the
//! expected positions are the falling ones and velocities just before an event are the stored
//! ones plus `g` times the time since. Two bodies share the acceleration, so a pair's relative
//! motion stays linear and the pair checks run on positions and velocities taken at the start
//! of each stretch; the closest approach to a wall follows the parabola (see `verify/falling.rs`).
//! Kinetic energy is not conserved between events, so an elastic collision must conserve the
//! kinetic energy of the pair (of the body, at a wall) at the contact time, and the report
//! carries the potential energy as well.
//!
//! Under gravity with growing radii ([`crate::contact::falling_growth`]) the growth rule is checked
//! with the velocities at the contact time, two falling bodies' miss check is growth's (their
//! relative motion is linear), and the closest approach along a parabola (to a wall, or of a
//! falling body to a kinematic one) is taken less the growth (see the `falling` module).

mod closest;
mod falling;
mod moving_walls;
mod pool;
mod proximity;
mod restitution;
mod slots;
mod spins;

use crate::collision_filter::CollisionFilter;
use crate::contact::lees_edwards::ShearedBox;
use crate::contact::narrow::wall_normal;
use crate::contact::periodic::min_image;
use crate::contact::pivot_contact::{first_contact_points, toi_pivot_wall, Parabola};
use crate::event::EventKind;
use crate::geom::Vector;
use crate::motion::pivot::Pivot;
use crate::motion::GrowthLaw;
use crate::motion::{Motion, Path};
use crate::scene::Scene;
use crate::sim::Collision;
use crate::thermostat::ResetClock;
use crate::wall::{wall_clearance, Wall};
use crate::world::{from_2d, to_2d, wall_2d};
use closest::{closest_approach, closest_approach_growing, closest_to_wall};
use falling::{closest_to_point_falling, closest_to_wall_falling};
pub use pool::{PoolReport, PoolVerifier};
use proximity::Proximity;
use restitution::Restitutions;
use spins::Spins;

/// A body's motion between records as the pivot contact search takes it (2D).
enum TurnOrFall {
    /// Turning about a segment's end point.
    Turn(Pivot),
    /// Falling (or flying, or sliding) on a parabola.
    Fall(Parabola),
}

/// Most quarter periodic boxes a pair's relative motion between two events is followed
/// across. Two bodies resolved at time `t` (speed times the spacing of floats at `t` within
/// `5·10⁻¹⁰` of the radius, see the numerical rules in docs/numerics.md) move apart by at
/// most about `9·10⁶ r_max` by then, and a periodic box's sides exceed `4 r_max`: fewer than
/// `4·10⁷` quarter boxes.
const MAX_PIECES: u64 = 1 << 26;

/// Allowed overlap relative to the contact distance.
pub const OVERLAP_TOLERANCE: f64 = 1e-9;
/// Allowed relative change of a pair's momentum or kinetic energy in one collision.
pub const CONSERVATION_TOLERANCE: f64 = 1e-12;

/// The first rule a run breaks.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("event {index} (t = {time}): {what}")]
pub struct Violation {
    /// Index of the offending event (0-based), or the event count for end-of-run checks.
    pub index: u64,
    /// Its time, seconds.
    pub time: f64,
    /// What is wrong.
    pub what: String,
}

/// Totals of a verified run.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct VerifyReport {
    /// Events checked.
    pub events: u64,
    /// Body–body collisions.
    pub body_collisions: u64,
    /// Body–wall collisions.
    pub wall_collisions: u64,
    /// Thermostat resets, each checked against the sequence the scene's seed gives.
    pub resets: u64,
    /// Edits by the program that steered the run (format version 8: `set_velocity`,
    /// `set_position`), each checked to put its body where it overlaps nothing.
    pub edits: u64,
    /// Energy the edits added (kinetic plus, under gravity, potential), joules: the run's
    /// energy drift, less this, is what its collisions changed.
    pub edit_energy: f64,
    /// Work the moving walls did on the bodies at their collisions, joules (see
    /// [`crate::world::time_of_impact`]; under growing radii, with what the growth added at them): the
    /// run's energy drift, less this and the edits' energy, is what its other collisions
    /// changed.
    pub wall_work: f64,
    /// Largest overlap seen (relative to the contact distance), at events or in between.
    pub max_overlap: f64,
    /// Kinetic energy at the start, joules.
    pub kinetic_energy_start: f64,
    /// Kinetic energy at the end, joules (under gravity, of the velocities at the end time).
    pub kinetic_energy_end: f64,
    /// Potential energy in the gravity field at the start, joules: `−Σ m·g·x` (zero at the
    /// origin, and zero without gravity). Kinetic plus potential energy is what elastic
    /// collisions conserve under gravity.
    pub potential_energy_start: f64,
    /// Potential energy in the gravity field at the end, joules (see
    /// [`VerifyReport::potential_energy_start`]).
    pub potential_energy_end: f64,
    /// Rotational kinetic energy at the start, joules (0 unless the scene is rotational,
    /// see [`crate::motion::spin`]).
    pub rotational_energy_start: f64,
    /// Rotational kinetic energy at the end, joules, of the spins replayed from the
    /// collisions' impulses.
    pub rotational_energy_end: f64,
}

impl VerifyReport {
    /// Kinetic plus potential energy at the start, joules.
    #[must_use]
    pub fn energy_start(&self) -> f64 {
        self.kinetic_energy_start + self.potential_energy_start
    }

    /// Kinetic plus potential energy at the end, joules.
    #[must_use]
    pub fn energy_end(&self) -> f64 {
        self.kinetic_energy_end + self.potential_energy_end
    }
}

/// Replays a run event by event, checking each.
pub struct Verifier<const D: usize> {
    motion: Vec<Motion<D>>,
    radius: Vec<f64>,
    mass: Vec<f64>,
    walls: Vec<Wall<D>>,
    /// The table the walls form ([`crate::wall::table_edges`]), for the edits' placements.
    table: Vec<(Vector<D>, Vector<D>)>,
    /// The moving walls' geometry at the start, and how each moves now.
    moving: Vec<Wall<D>>,
    wall_motion: Vec<crate::motion::WallMotion<D>>,
    period: Option<Vector<D>>,
    /// The periodic box's Lees–Edwards shear, in a sheared scene.
    shear: Option<ShearedBox<D>>,
    /// Each collision's coefficient of restitution, as the simulation chooses it.
    restitutions: Restitutions,
    /// Which bodies are kinematic (infinite mass, straight lines, no walls, no other
    /// kinematic body); empty when none is.
    kinematic: Vec<bool>,
    /// Collision groups and masks by body index; empty when no body sets them.
    filters: Vec<CollisionFilter>,
    last_time: f64,
    report: VerifyReport,
    /// The thermostat's reset sequence, regenerated from the scene, if it has one.
    resets: Option<ResetClock>,
    /// The broad phase of the miss check; `None`: every pair is checked.
    grid: Option<Proximity<D>>,
    /// Slab length, seconds: a typical body crosses about one cell per slab.
    slab: f64,
    /// Growing radii, if the scene has them (origin: its start time).
    growth: Option<GrowthLaw>,
    /// The acceleration of every body, if the scene has gravity.
    gravity: Option<Vector<D>>,
    /// Vacant slots by index (bodies removed, see [`crate::edit`]); empty while none is.
    vacant: Vec<bool>,
    /// The first record of an added body, waiting for its id record.
    pending_add: Option<Collision<D>>,
    /// `settings.rest_speed`, if bodies rest on walls (see [`crate::contact::resting`]).
    rest_speed: Option<f64>,
    /// The least restitution of the scene and its bodies: a wall bounce leaves at least
    /// this fraction of the normal speed (the TC model only raises it).
    least_restitution: f64,
    /// The static wall each body rests on, by index, as the records say; empty unless
    /// bodies rest on walls.
    supports: Vec<Option<usize>>,
    /// The turn about a segment's end point each body makes, and that segment, by index, as
    /// the records say (see [`crate::motion::pivot`]); empty unless bodies rest on walls.
    pivots: Vec<Option<(Pivot, usize)>>,
    /// Each static wall's slide acceleration where bodies rest on it
    /// ([`crate::scene::slides`]); empty unless bodies rest on walls.
    slides: Vec<Option<Vector<D>>>,
    /// Each slot's spin, replayed, in a rotational scene.
    spins: Option<Spins>,
}

impl<const D: usize> Verifier<D> {
    /// Starts from the run's initial scene.
    #[must_use]
    pub fn new(scene: &Scene<D>) -> Self {
        let mut verifier = Self::start(scene);
        let rotational = verifier.rotational_energy(scene.start_time);
        verifier.report.rotational_energy_start = rotational;
        verifier.report.rotational_energy_end = rotational;
        verifier
    }

    /// [`Verifier::new`] but for the rotational energy.
    fn start(scene: &Scene<D>) -> Self {
        let motion: Vec<Motion<D>> = scene
            .bodies
            .iter()
            .map(|b| Motion {
                pos: b.pos,
                vel: b.vel,
                time: scene.start_time,
            })
            .collect();
        // Kinematic bodies count for nothing in the energy sums (their mass is infinite, and
        // their collisions are checked without conservation laws).
        let mass: Vec<f64> = scene
            .bodies
            .iter()
            .map(|b| if b.kinematic { 0.0 } else { b.effective_mass() })
            .collect();
        let kinematic: Vec<bool> = if scene.bodies.iter().any(|b| b.kinematic) {
            scene.bodies.iter().map(|b| b.kinematic).collect()
        } else {
            Vec::new()
        };
        let ke = motion
            .iter()
            .zip(&mass)
            .map(|(m, ms)| 0.5 * ms * m.vel.norm_sq())
            .sum();
        let radius: Vec<f64> = scene.bodies.iter().map(|b| b.radius).collect();
        let growth = scene.settings.growth.map(|g| GrowthLaw {
            rate: g.rate,
            origin: scene.start_time,
        });
        let gravity = scene.gravity();
        let r_max = radius.iter().fold(0.0f64, |m, &r| m.max(r));
        let mean_speed =
            motion.iter().map(|m| speed(m.vel)).sum::<f64>() / motion.len().max(1) as f64;
        let slab = slab_length(r_max, mean_speed, gravity).unwrap_or(f64::MAX);
        let pe = potential_energy(&motion, &mass, gravity, scene.start_time);
        let mut grid = Proximity::new(&radius, scene.periodic, scene.start_time);
        // A sheared box moves the neighbours across its y faces, which the grid does not
        // follow: every pair is checked instead.
        let sheared = scene.shear().is_some();
        grid.start_slab(scene.start_time, slab_end(scene.start_time, slab));
        let grown = growth.map_or(1.0, |g| g.scale(grid.end));
        for (i, m) in motion.iter().enumerate() {
            let acc = gravity.filter(|_| !scene.bodies[i].kinematic);
            grid.file(i, m, radius[i] * grown, scene.start_time, acc);
        }
        Verifier {
            rest_speed: scene.settings.rest_speed,
            least_restitution: scene
                .bodies
                .iter()
                .filter_map(|b| b.restitution)
                .fold(scene.settings.restitution, f64::min),
            supports: match scene.settings.rest_speed {
                Some(_) => vec![None; scene.bodies.len()],
                None => Vec::new(),
            },
            pivots: match scene.settings.rest_speed {
                Some(_) => vec![None; scene.bodies.len()],
                None => Vec::new(),
            },
            slides: crate::scene::slides(scene),
            spins: Spins::of(scene),
            growth,
            gravity,
            vacant: Vec::new(),
            pending_add: None,
            grid: (!sheared).then_some(grid),
            slab,
            motion,
            radius,
            mass,
            walls: scene.walls.clone(),
            table: crate::wall::table_edges(&scene.walls),
            moving: scene.moving_walls.iter().map(|m| m.wall).collect(),
            wall_motion: crate::motion::start_motions(&scene.moving_walls, scene.start_time),
            period: scene.periodic,
            shear: scene.shear(),
            restitutions: Restitutions::new(scene),
            kinematic,
            filters: scene.filters(),
            last_time: scene.start_time,
            resets: scene
                .settings
                .thermostat
                .map(|th| ResetClock::new(&th, scene.bodies.len(), scene.start_time)),
            report: VerifyReport {
                kinetic_energy_start: ke,
                kinetic_energy_end: ke,
                potential_energy_start: pe,
                potential_energy_end: pe,
                ..Default::default()
            },
        }
    }

    /// Starts from the run's initial scene, checking every pair of bodies at every event:
    /// `O(n)` per event, the reference the grid's answers are tested against.
    #[must_use]
    pub fn all_pairs(scene: &Scene<D>) -> Self {
        Verifier {
            grid: None,
            ..Self::new(scene)
        }
    }

    /// True for a kinematic body.
    fn is_kinematic(&self, i: usize) -> bool {
        self.kinematic.get(i).copied().unwrap_or(false)
    }

    /// Body `i`'s acceleration: the scene's gravity, unless it is kinematic; for a body
    /// resting on a wall, its slide along it.
    fn g(&self, i: usize) -> Option<Vector<D>> {
        let g = self.gravity.filter(|_| !self.is_kinematic(i))?;
        match self.supports.get(i).copied().flatten() {
            Some(w) => crate::contact::resting::slide_acceleration(&g, &self.walls[w]),
            None => Some(g),
        }
    }

    /// Body `i`'s position at `t` on its current motion.
    fn pos_of(&self, i: usize, t: f64) -> Vector<D> {
        if let Some((p, _)) = self.pivot(i) {
            return from_2d(p.position(t));
        }
        self.pos_at(&self.motion[i], t, self.g(i))
    }

    /// Body `i`'s velocity at `t` on its current motion.
    fn vel_of(&self, i: usize, t: f64) -> Vector<D> {
        if let Some((p, _)) = self.pivot(i) {
            return from_2d(p.velocity(t));
        }
        self.vel_at(&self.motion[i], t, self.g(i))
    }

    /// Body `i`'s turn about a segment's end point, if it turns, and that segment.
    fn pivot(&self, i: usize) -> Option<&(Pivot, usize)> {
        self.pivots.get(i).and_then(Option::as_ref)
    }

    /// Body `i`'s motion as the contact search of [`crate::contact::pivot_contact`] takes it.
    fn mover(&self, i: usize) -> TurnOrFall {
        match self.pivot(i) {
            Some((p, _)) => TurnOrFall::Turn(*p),
            None => {
                let m = self.motion[i];
                TurnOrFall::Fall(Parabola {
                    pos: to_2d(m.pos),
                    vel: to_2d(m.vel),
                    acc: to_2d(self.g(i).unwrap_or(Vector::ZERO)),
                    time: m.time,
                })
            }
        }
    }

    /// [`Verifier::pair_overlap`] when body `i` or `j` turns about a segment's end point: the
    /// first time their centres come within `(1 − 2·OVERLAP_TOLERANCE)` of their contact
    /// distance over `[t0, t1]`, by the search of [`crate::contact::pivot_contact`] (which skips no
    /// root), and the overlap then; `None` when they never do.
    fn pivot_pair_overlap(&self, i: usize, j: usize, t0: f64, t1: f64) -> Option<(f64, f64)> {
        let sigma = self.radius[i] + self.radius[j];
        let reach = sigma * (1.0 - 2.0 * OVERLAP_TOLERANCE);
        let at = match (self.mover(i), self.mover(j)) {
            (TurnOrFall::Turn(p), TurnOrFall::Turn(q)) => {
                first_contact_points(&p, &q, reach, t0, t1)
            }
            (TurnOrFall::Turn(p), TurnOrFall::Fall(q))
            | (TurnOrFall::Fall(q), TurnOrFall::Turn(p)) => {
                first_contact_points(&p, &q, reach, t0, t1)
            }
            (TurnOrFall::Fall(_), TurnOrFall::Fall(_)) => unreachable!("one of them turns"),
        }?;
        let d = (self.pos_of(j, at) - self.pos_of(i, at)).norm();
        Some(((sigma - d) / sigma, at))
    }

    /// [`Verifier::wall_overlap`] for a body turning about a segment's end point, as
    /// [`Verifier::pivot_pair_overlap`]: its own point, and the inside of segments ending
    /// there, are the turn's business (checked at its end).
    fn pivot_wall_overlap(&self, i: usize, w: usize, t: f64) -> (f64, f64) {
        let Some((p, _)) = self.pivot(i) else {
            unreachable!("a turning body");
        };
        let r = self.radius[i];
        let t0 = self.motion[i].time;
        let (wall, vel) = self.wall_at(w, t0);
        let reach = r * (1.0 - 2.0 * OVERLAP_TOLERANCE);
        match toi_pivot_wall(p, reach, &wall_2d(&wall), to_2d(vel), t0, t0, t) {
            Some(at) => {
                let clearance = wall_clearance(&self.wall_at(w, at).0, self.pos_of(i, at));
                ((r - clearance) / r, at)
            }
            None => (0.0, t),
        }
    }

    /// True when bodies `i` and `j` never meet: both kinematic, or kept apart by their
    /// collision filters (see [`crate::collision_filter`]).
    fn never_meet(&self, i: usize, j: usize) -> bool {
        (self.is_kinematic(i) && self.is_kinematic(j))
            || (!self.filters.is_empty() && !self.filters[i].collides(&self.filters[j]))
    }

    fn fail(&self, time: f64, what: String) -> Violation {
        Violation {
            index: self.report.events,
            time,
            what,
        }
    }

    /// Checks the next event of the run and applies it.
    pub fn check(&mut self, c: &Collision<D>) -> Result<(), Violation> {
        let t = c.event.time;
        // Draws due at an edit's time are judged before it, others' after them.
        self.skip_void_resets(t, c.event.kind == EventKind::Edit);
        if self.pending_add.is_some() || crate::edit::Edit::starts_add(c) {
            return self.check_add(c);
        }
        if crate::edit::Edit::moves_a_wall(c) {
            return self.check_wall_motion(c);
        }
        if !t.is_finite() || t < self.last_time {
            return Err(self.fail(
                t,
                format!("time goes backwards (previous event at {})", self.last_time),
            ));
        }
        if let Some(clock) = &self.resets {
            let due = clock.next_time();
            // A reset at a collision's time comes after it.
            if due < t && c.event.kind != EventKind::Reset {
                return Err(self.fail(
                    t,
                    format!(
                        "the thermostat reset of body {} due at {due} is missing",
                        clock.next_body()
                    ),
                ));
            }
        }
        let k = c.body_count();
        let ids = [c.event.a as usize, c.event.b as usize];
        // An edit may move its body anywhere (a teleport): its new position is checked by
        // `check_edit` instead. Removing a body or changing its filter does not move it.
        let teleport = c.event.kind == EventKind::Edit && c.event.b == 0;
        let moved = usize::from(!teleport) * k;
        for (s, &i) in ids[..moved].iter().enumerate() {
            let expect = self.pos_of(i, t);
            let dt = (t - self.motion[i].time).abs();
            let fall = self.g(i).map_or(0.0, |g| 0.5 * g.norm() * dt * dt);
            let scale = 1.0 + expect.norm() + self.motion[i].vel.norm() * dt + fall;
            // A motion that cannot reach `t` (a position beyond the largest float) fails too.
            let off = self.image(c.pos[s] - expect, t).norm();
            if beyond(off, 1e-9 * scale) || !expect.is_finite() {
                return Err(self.fail(
                    t,
                    format!(
                        "body {i} recorded at {:?}, its motion puts it at {:?}",
                        c.pos[s].0, expect.0
                    ),
                ));
            }
            if !c.vel[s].is_finite() {
                return Err(self.fail(t, format!("body {i} gets a non-finite velocity")));
            }
        }
        self.advance_slabs(t)?;
        for &i in &ids[..k] {
            self.check_no_miss(i, t)?;
        }
        match c.event.kind {
            EventKind::Body => self.check_pair(c, ids[0], ids[1])?,
            EventKind::Wall => self.check_wall(c, ids[0], ids[1])?,
            EventKind::Reset => self.check_reset(c, ids[0])?,
            EventKind::Edit => self.check_slot_edit(c, ids[0])?,
        }
        let supports = self.check_rests(c, &ids[..k])?;
        for (s, &i) in ids[..k].iter().enumerate() {
            self.motion[i] = Motion {
                pos: c.pos[s],
                vel: c.vel[s],
                time: t,
            };
            if let Some(slot) = self.supports.get_mut(i) {
                *slot = supports[s];
            }
            let turn = self.turn_after(c, s, i)?;
            if let Some(slot) = self.pivots.get_mut(i) {
                *slot = turn;
            }
            self.refile(i, t);
        }
        self.last_time = t;
        self.report.events += 1;
        Ok(())
    }

    fn check_pair(&mut self, c: &Collision<D>, i: usize, j: usize) -> Result<(), Violation> {
        let t = c.event.time;
        let seen;
        let mut before = (self.vel_of(i, t), self.vel_of(j, t));
        let c = match self.shear {
            None => c,
            Some(bx) => {
                // Every check below on the images that met: `i`'s record, and `j`'s image
                // next to it, moving a layer's speed faster or slower (see
                // `crate::contact::lees_edwards`); velocities before, in the same frames.
                let (vi, vj) = before;
                let (d, layer) = bx.nearest_image(c.pos[1] - c.pos[0], t);
                let mut image = *c;
                image.pos[1] = c.pos[0] + d;
                image.vel[1] = bx.image_velocity(c.vel[1], layer);
                before = (
                    self.record_frame(vi, i, c.pos[0], t),
                    bx.image_velocity(self.record_frame(vj, j, c.pos[1], t), layer),
                );
                seen = image;
                &seen
            }
        };
        if !self.filters.is_empty() && !self.filters[i].collides(&self.filters[j]) {
            return Err(self.fail(
                t,
                format!("bodies {i} and {j} collide, but their collision filters keep them apart"),
            ));
        }
        let sigma = self.radius_at(i, t) + self.radius_at(j, t);
        let gap = (self.image(c.pos[1] - c.pos[0], t).norm() - sigma) / sigma;
        if beyond(gap, OVERLAP_TOLERANCE) {
            return Err(self.fail(
                t,
                format!(
                    "bodies {i} and {j} collide at a distance (gap {:e} of the contact distance)",
                    gap
                ),
            ));
        }
        self.report.max_overlap = self.report.max_overlap.max(-gap);
        let (mi, mj) = (self.mass[i], self.mass[j]);
        // Just before the collision: under gravity the stored velocities have changed since.
        let (vi, vj) = before;
        // Chosen before the collision counts for the TC model, as the simulation does.
        let e = self.restitutions.pair(i, j, t);
        self.restitutions.note(i, t);
        self.restitutions.note(j, t);
        if self.is_kinematic(i) || self.is_kinematic(j) {
            // A kinematic body (infinite mass) is a moving wall: neither momentum nor energy
            // is kept, and two of them never meet. The kinematic body keeps its velocity, and
            // the dynamic one bounces off it as off a wall moving with it: the relative normal
            // velocity turns from `u` to `−e·u` (with growth, to `(1 + e)·σ̇ − e·u`).
            if self.is_kinematic(i) && self.is_kinematic(j) {
                return Err(self.fail(t, format!("kinematic bodies {i} and {j} collide")));
            }
            let (k, v0, v1) = if self.is_kinematic(i) {
                (i, vi, c.vel[0])
            } else {
                (j, vj, c.vel[1])
            };
            if (v1 - v0).norm() > 1e-9 * (v0.norm() + v1.norm() + f64::MIN_POSITIVE) {
                return Err(self.fail(
                    t,
                    format!(
                        "kinematic body {k} changes velocity from {:?} to {:?}",
                        v0.0, v1.0
                    ),
                ));
            }
            // A body left resting on a wall took the wall's reaction too (see
            // `resting::pressed_impulse`); the rule is for free bounces.
            if c.rests == [false; 2] {
                let grow = self
                    .growth
                    .map_or(0.0, |law| law.speed(self.radius[i] + self.radius[j]));
                self.check_pair_rule(c, grow, (vi, vj), e)?;
                self.spin_pair(c, (i, j), (vi, vj), grow)?;
            }
            let e0 = 0.5 * (mi * vi.norm_sq() + mj * vj.norm_sq());
            let e1 = 0.5 * (mi * c.vel[0].norm_sq() + mj * c.vel[1].norm_sq());
            self.report.body_collisions += 1;
            self.report.kinetic_energy_end += e1 - e0;
            return Ok(());
        }
        let p0 = vi * mi + vj * mj;
        let p1 = c.vel[0] * mi + c.vel[1] * mj;
        // Relative to the momenta summed before and after: growing bodies that meet at rest
        // push each other apart, and the sum after is rounded at their scale, not at zero.
        let scale = (vi * mi).norm()
            + (vj * mj).norm()
            + (c.vel[0] * mi).norm()
            + (c.vel[1] * mj).norm()
            + f64::MIN_POSITIVE;
        if c.rests != [false; 2] {
            return self.check_held_pair(c, i, j, (vi, vj), p1 - p0, scale);
        }
        if beyond((p1 - p0).norm(), CONSERVATION_TOLERANCE * scale) {
            return Err(self.fail(
                t,
                format!(
                    "momentum of bodies {i} and {j} changes by {:e} (relative)",
                    (p1 - p0).norm() / scale
                ),
            ));
        }
        let e0 = 0.5 * (mi * vi.norm_sq() + mj * vj.norm_sq());
        let e1 = 0.5 * (mi * c.vel[0].norm_sq() + mj * c.vel[1].norm_sq());
        let grow = self
            .growth
            .map_or(0.0, |law| law.speed(self.radius[i] + self.radius[j]));
        let turned = self.spin_pair(c, (i, j), (vi, vj), grow)?;
        let (r0, r1) = (turned.before, turned.after);
        if self.growth.is_some() {
            self.check_pair_rule(c, grow, (vi, vj), e)?;
        } else {
            // Rough collisions keep the total energy only when the tangential restitution
            // is ±1 (see `spins`).
            let e = if self.spins.is_some() && self.pair_tangential(i, j).abs() != 1.0 {
                0.0
            } else {
                e
            };
            let who = format!("bodies {i} and {j}");
            let lab = e0 + r0 + turned.slack / CONSERVATION_TOLERANCE;
            self.check_energy(t, (e0 + r0, e1 + r1), lab, e, &who)?;
        }
        self.report.body_collisions += 1;
        self.report.kinetic_energy_end += e1 - e0;
        Ok(())
    }

    /// [`Verifier::check_pair`] when a body rests on a plane after the collision (see
    /// [`crate::contact::resting`]): the planes took the pushes of the bodies pressed into them, so
    /// the momentum change `dp` must lie along their normals, and no energy is made.
    fn check_held_pair(
        &mut self,
        c: &Collision<D>,
        i: usize,
        j: usize,
        (vi, vj): (Vector<D>, Vector<D>),
        dp: Vector<D>,
        scale: f64,
    ) -> Result<(), Violation> {
        let t = c.event.time;
        let mut basis: Vec<Vector<D>> = Vec::new();
        for (s, k) in [(0, i), (1, j)] {
            let support = self.supports.get(k).copied().flatten();
            let (true, Some(w), Some(g)) = (c.rests[s], support, self.gravity) else {
                continue;
            };
            let normal = crate::contact::resting::support_normal(&self.walls[w], &g);
            let mut u = normal;
            for b in &basis {
                u = u - *b * u.dot(*b);
            }
            if u.norm() > 1e-9 * normal.norm() {
                basis.push(u * (1.0 / u.norm()));
            }
        }
        let mut rest = dp;
        for b in &basis {
            rest = rest - *b * rest.dot(*b);
        }
        if rest.norm() > CONSERVATION_TOLERANCE * scale {
            return Err(self.fail(
                t,
                format!(
                    "momentum of bodies {i} and {j} along the planes they rest on changes by {:e} \
                     (relative)",
                    rest.norm() / scale
                ),
            ));
        }
        let (mi, mj) = (self.mass[i], self.mass[j]);
        let e0 = 0.5 * (mi * vi.norm_sq() + mj * vj.norm_sq());
        let e1 = 0.5 * (mi * c.vel[0].norm_sq() + mj * c.vel[1].norm_sq());
        if e1 > e0 * (1.0 + CONSERVATION_TOLERANCE) + f64::MIN_POSITIVE {
            return Err(self.fail(
                t,
                format!("bodies {i} and {j}, held by their planes, gain energy: {e0} -> {e1}"),
            ));
        }
        self.report.body_collisions += 1;
        self.report.kinetic_energy_end += e1 - e0;
        Ok(())
    }

    /// Passes over the thermostat's draws due before `t` (or at `t`, `inclusive`) that name a
    /// kinematic body or a vacant slot: the simulation does not reset them (see
    /// [`crate::thermostat`]).
    fn skip_void_resets(&mut self, t: f64, inclusive: bool) {
        while let Some(clock) = &mut self.resets {
            let due = clock.next_time();
            let kinematic = self.kinematic.get(clock.next_body()).copied();
            if !(due < t || (inclusive && due == t)) || kinematic != Some(true) {
                break;
            }
            clock.skip();
        }
    }

    fn check_reset(&mut self, c: &Collision<D>, i: usize) -> Result<(), Violation> {
        let t = c.event.time;
        let mass = self.mass[i];
        let Some(clock) = self.resets.as_mut() else {
            return Err(self.fail(t, "a thermostat reset in a run without a thermostat".into()));
        };
        let (due, body) = (clock.next_time(), clock.next_body());
        let mut expect = clock.take::<D>(mass);
        if let Some(bx) = self.shear {
            expect.velocity[0] += bx.flow(c.pos[0][1]);
        }
        if (due, body) != (t, i) || expect.velocity != c.vel[0] {
            return Err(self.fail(
                t,
                format!(
                    "thermostat reset of body {i} at {t}: the scene's sequence resets body \
                     {body} at {due} to {:?}",
                    expect.velocity.0
                ),
            ));
        }
        let e0 = 0.5 * mass * self.vel_of(i, t).norm_sq();
        let e1 = 0.5 * mass * c.vel[0].norm_sq();
        self.report.resets += 1;
        self.report.kinetic_energy_end += e1 - e0;
        Ok(())
    }

    /// A program's edit of body `i`'s motion (see [`EventKind::Edit`]): its new state must
    /// overlap no body it collides with and no wall, and stay inside a closed table. The
    /// energy it adds (kinetic and, under gravity, potential) is counted in the report.
    fn check_edit(&mut self, c: &Collision<D>, i: usize) -> Result<(), Violation> {
        let t = c.event.time;
        let (pos, vel) = (c.pos[0], c.vel[0]);
        self.check_placement(i, pos, t)?;
        let (m, g) = (self.mass[i], self.g(i));
        let kinetic = 0.5 * m * (vel.norm_sq() - self.vel_of(i, t).norm_sq());
        let potential = g.map_or(0.0, |g| -m * g.dot(pos - self.pos_of(i, t)));
        self.report.edits += 1;
        self.report.edit_energy += kinetic + potential;
        Ok(())
    }

    /// Body `i` (its radius, filter and kind as they are now) may be put at `pos` at `t`: it
    /// overlaps no body it collides with, and (unless kinematic) crosses no wall and stays
    /// inside a closed table.
    fn check_placement(&self, i: usize, pos: Vector<D>, t: f64) -> Result<(), Violation> {
        if !pos.is_finite() {
            return Err(self.fail(t, format!("an edit puts body {i} at a non-finite position")));
        }
        let r = self.radius_at(i, t);
        for j in (0..self.motion.len()).filter(|&j| j != i) {
            if self.never_meet(i, j) {
                continue;
            }
            let sigma = r + self.radius_at(j, t);
            let d = self.image(self.pos_of(j, t) - pos, t).norm();
            if (sigma - d) / sigma > OVERLAP_TOLERANCE {
                return Err(self.fail(
                    t,
                    format!("an edit puts body {i} into body {j} (distance {d}, contact {sigma})"),
                ));
            }
        }
        if !self.is_kinematic(i) {
            for w in 0..self.wall_count() {
                let clearance = wall_clearance(&self.wall_at(w, t).0, pos);
                if (r - clearance) / r > OVERLAP_TOLERANCE {
                    return Err(self.fail(
                        t,
                        format!(
                            "an edit puts body {i} across wall {w} (centre {:?} at {clearance} \
                             from it, radius {r})",
                            pos.0
                        ),
                    ));
                }
            }
            let loops = &self.table;
            if D == 2 && !loops.is_empty() && !crate::wall::inside_even_odd(loops, pos[0], pos[1]) {
                return Err(self.fail(t, format!("an edit puts body {i} outside the table")));
            }
        }
        Ok(())
    }

    fn check_wall(&mut self, c: &Collision<D>, i: usize, w: usize) -> Result<(), Violation> {
        let t = c.event.time;
        if self.is_kinematic(i) {
            return Err(self.fail(t, format!("kinematic body {i} hits wall {w}")));
        }
        if w >= self.wall_count() {
            return Err(self.fail(t, format!("body {i} hits wall {w}, which does not exist")));
        }
        let (wall, wall_velocity) = self.wall_at(w, t);
        let r = self.radius_at(i, t);
        let gap = (wall_clearance(&wall, c.pos[0]) - r) / r;
        if beyond(gap, OVERLAP_TOLERANCE) {
            return Err(self.fail(
                t,
                format!(
                    "body {i} hits wall {w} at a distance (gap {:e} of its radius)",
                    gap
                ),
            ));
        }
        self.report.max_overlap = self.report.max_overlap.max(-gap);
        let m = self.mass[i];
        let before = self.vel_of(i, t);
        let e0 = 0.5 * m * before.norm_sq();
        let e1 = 0.5 * m * c.vel[0].norm_sq();
        let moving = w >= self.walls.len();
        if !moving && self.supports.get(i).copied().flatten() == Some(w) {
            return self.check_slide_end(c, i, w);
        }
        self.check_turn_end(c, i, w)?;
        // Chosen before the collision counts for the TC model, as the simulation does; going
        // on along the segment that continues the one it slides on (a shelf in pieces) is no
        // collision there.
        let e = self.restitutions.wall(i, t);
        if !(c.rests[0] && !moving && self.goes_on(i, w, c.pos[0])) {
            self.restitutions.note(i, t);
        }
        // In a moving wall's frame the collision is a static wall's (a static wall's velocity
        // is zero, and `v − 0` is `v`).
        let (v0, v1) = (before - wall_velocity, c.vel[0] - wall_velocity);
        let who = format!("body {i} at wall {w}");
        match (self.growth, wall_normal(&wall, c.pos[0])) {
            (Some(law), Some(n)) => {
                let grow = law.speed(self.radius[i]);
                let lab = magnitude(before) + magnitude(c.vel[0]) + magnitude(wall_velocity);
                self.check_growth_rule(t, n, (v0, v1), lab, (grow, e), &who)?;
                self.spin_wall(c, i, (before, wall_velocity), n, grow)?;
            }
            (Some(_), None) => {}
            // Coming to rest: `check_rests` checks the velocity along the wall.
            (None, _) if c.rests[0] => {}
            (None, n) => {
                let turned = match n {
                    Some(n) => self.spin_wall(c, i, (before, wall_velocity), n, 0.0)?,
                    None => spins::Turned::default(),
                };
                let (r0, r1) = (turned.before, turned.after);
                let e = match &self.spins {
                    Some(_) if self.wall_tangential(i).abs() != 1.0 => 0.0,
                    _ => e,
                };
                let (e0, e1) = (0.5 * m * v0.norm_sq() + r0, 0.5 * m * v1.norm_sq() + r1);
                let speed = before.norm() + c.vel[0].norm() + wall_velocity.norm();
                // The replayed spins' slack, as energy, widens the rounding allowed.
                let lab = 0.5 * m * speed * speed + r0 + turned.slack / CONSERVATION_TOLERANCE;
                self.check_energy(t, (e0, e1), lab, e, &who)?;
            }
        }
        if moving {
            // The kinetic energy the collision changed, the growth's share included under
            // growing radii (see `crate::world::time_of_impact`).
            self.report.wall_work += e1 - e0;
        }
        self.report.wall_collisions += 1;
        self.report.kinetic_energy_end += e1 - e0;
        Ok(())
    }

    /// A wall record of body `i` with the segment `w` it slides on: its arrival at an end of
    /// `w`, flying clear of the edge with its velocity unchanged (see [`crate::contact::ledge`]; going
    /// on along the next segment is recorded as a landing on that one).
    fn check_slide_end(&mut self, c: &Collision<D>, i: usize, w: usize) -> Result<(), Violation> {
        let t = c.event.time;
        let (Wall::Segment { a, b }, Some(g)) = (self.walls[w], self.gravity) else {
            return Err(self.fail(t, format!("body {i} meets plane {w}, which it rests on")));
        };
        if c.rests[0] {
            return Err(self.fail(
                t,
                format!("body {i} lands on segment {w}, which it rests on"),
            ));
        }
        let v = self.vel_of(i, t);
        let p = c.pos[0];
        let u = b - a;
        let len = u.norm();
        let foot = (p - a).dot(u) / len;
        let r = self.radius_at(i, t);
        let tolerance = OVERLAP_TOLERANCE * r;
        if foot > tolerance && foot < len - tolerance {
            return Err(self.fail(
                t,
                format!("body {i} leaves segment {w} {foot} m from its end at a, not at an end"),
            ));
        }
        let scale = 1e-9 * (1.0 + v.norm());
        if (c.vel[0] - v).norm() > scale {
            return Err(self.fail(
                t,
                format!(
                    "body {i} leaves segment {w} with velocity {:?}, not the {:?} it slid with",
                    c.vel[0].0, v.0
                ),
            ));
        }
        let end = crate::contact::ledge::end_reached(a, b, p);
        let m = Motion {
            pos: p,
            vel: v,
            time: t,
        };
        // Rounding of the slide's position and speed, relative to `|v|²` and `r|g|`.
        let slack = 1e-9 * (v.norm_sq() + r * g.norm());
        if c.pivots[0] {
            // Rolling over the edge: too slow to fly clear.
            if crate::contact::ledge::edge_margin(&m, end, &g) >= slack {
                return Err(self.fail(
                    t,
                    format!(
                        "body {i} rolls over the end of segment {w} at {} m/s, fast enough to \
                         fly clear",
                        v.norm()
                    ),
                ));
            }
            self.report.wall_collisions += 1;
            return Ok(());
        }
        if crate::contact::ledge::edge_margin(&m, end, &g) <= -slack {
            return Err(self.fail(
                t,
                format!(
                    "body {i} flies off the end of segment {w} at {} m/s, too slowly to clear \
                     the edge",
                    v.norm()
                ),
            ));
        }
        self.report.wall_collisions += 1;
        Ok(())
    }

    /// True when body `i`, at `pos`, slides on a segment that segment `w` continues straight
    /// on from the end it has reached ([`crate::contact::ledge::continuation`]).
    fn goes_on(&self, i: usize, w: usize, pos: Vector<D>) -> bool {
        let Some(s) = self.supports.get(i).copied().flatten() else {
            return false;
        };
        let Wall::Segment { a, b } = self.walls[s] else {
            return false;
        };
        let end = crate::contact::ledge::end_reached(a, b, pos);
        crate::contact::ledge::continuation(&self.walls, &self.slides, s, end) == Some(w)
    }

    /// The turn body `i` (slot `s` of record `c`) makes after it, as the record's flag says
    /// (see [`crate::motion::pivot`]): about the end point of the segment the record names (the one
    /// it slid to the end of), or, after a body collision, about the point it turned about
    /// before; from the record's position and velocity.
    fn turn_after(
        &self,
        c: &Collision<D>,
        s: usize,
        i: usize,
    ) -> Result<Option<(Pivot, usize)>, Violation> {
        let t = c.event.time;
        if !c.pivots[s] {
            return Ok(None);
        }
        let (Some(g), true) = (self.gravity, D == 2) else {
            return Err(self.fail(t, format!("body {i} turns about a point without gravity")));
        };
        let segment = match (c.event.kind, self.pivot(i)) {
            (EventKind::Wall, _) => c.event.b as usize,
            (EventKind::Body, Some(&(_, w))) => w,
            _ => return Err(self.fail(t, format!("body {i} starts turning at no segment end"))),
        };
        let Some(Wall::Segment { a, b }) = self.walls.get(segment).copied() else {
            return Err(self.fail(
                t,
                format!("body {i} turns about wall {segment}, no segment"),
            ));
        };
        let r = self.radius[i];
        match crate::contact::ledge::recorded_turn((a, b), r, g, (c.pos[s], c.vel[s]), t) {
            Ok(pivot) => Ok(pivot.map(|p| (p, segment))),
            Err(_) => Err(self.fail(
                t,
                format!("body {i} turns about an end point of segment {segment} it does not touch"),
            )),
        }
    }

    /// A wall record of body `i` with wall `w` while it turns about a segment's end point:
    /// the turn ends (the turn's position and velocity are checked as any motion's). Coming
    /// off, a record naming the turn's own segment with no rest flag, must happen where the
    /// point stops pushing: `|g| cos θ = r θ̇²`. A record naming another wall is a collision
    /// with it (checked as any wall collision) or a landing on a segment that ends at the
    /// point, along it.
    fn check_turn_end(&self, c: &Collision<D>, i: usize, w: usize) -> Result<(), Violation> {
        let t = c.event.time;
        let Some(&(p, segment)) = self.pivot(i) else {
            return Ok(());
        };
        if c.rests[0] || w != segment {
            // Swung back or landed: `check_rests` checks it rests with no normal speed.
            return Ok(());
        }
        let (theta, rate) = p.angle_and_rate(t);
        let g = p.gravity_norm();
        let push = g * theta.cos() - p.radius() * rate * rate;
        if push.abs() > 1e-9 * g {
            return Err(self.fail(
                t,
                format!(
                    "body {i} comes off the point it turns about while pressing it ({push} m/s²)"
                ),
            ));
        }
        Ok(())
    }

    /// The walls the bodies of record `c` (`ids`) rest on after it, as its flags say, each
    /// checked against the rule of [`crate::contact::resting`]: after a wall collision, on a static
    /// plane gravity presses it on, which it left at most `rest_speed` fast, with no normal
    /// velocity; after a body collision, on its wall before, its velocity unchanged.
    fn check_rests(
        &self,
        c: &Collision<D>,
        ids: &[usize],
    ) -> Result<[Option<usize>; 2], Violation> {
        let t = c.event.time;
        let mut out = [None; 2];
        for (s, &i) in ids.iter().enumerate() {
            if !c.rests[s] {
                continue;
            }
            let (Some(rest_speed), Some(g)) = (self.rest_speed, self.gravity) else {
                return Err(self.fail(t, format!("body {i} rests without settings.rest_speed")));
            };
            out[s] = Some(match c.event.kind {
                EventKind::Wall => {
                    let w = c.event.b as usize;
                    let Some(wall) = self.walls.get(w).copied() else {
                        return Err(self.fail(t, format!("body {i} rests on wall {w}, no wall")));
                    };
                    if crate::contact::resting::slide_acceleration(&g, &wall).is_none() {
                        return Err(self.fail(
                            t,
                            format!(
                                "body {i} rests on wall {w}, which gravity does not press it on"
                            ),
                        ));
                    }
                    let normal = crate::contact::resting::support_normal(&wall, &g);
                    if let Wall::Segment { a, b } = wall {
                        // Between the ends, on the side gravity presses against.
                        let u = b - a;
                        let foot = (c.pos[0] - a).dot(u) / u.norm();
                        let tolerance = OVERLAP_TOLERANCE * self.radius_at(i, t);
                        let side = (c.pos[0] - a).dot(normal) / normal.norm();
                        if foot < -tolerance || foot > u.norm() + tolerance || side <= 0.0 {
                            return Err(self.fail(
                                t,
                                format!(
                                    "body {i} rests on segment {w} beyond its ends or under it"
                                ),
                            ));
                        }
                    }
                    // The speed it would have left with: the normal velocity reflected.
                    let unit = normal * (1.0 / normal.norm());
                    let vn = self.vel_of(i, t).dot(unit);
                    let e = self.least_restitution;
                    let outgoing = if vn < 0.0 { -e * vn } else { vn };
                    let scale = 1e-9 * (1.0 + self.vel_of(i, t).norm());
                    if outgoing > rest_speed + scale {
                        return Err(self.fail(
                            t,
                            format!(
                                "body {i} rests on wall {w} leaving it at {outgoing} m/s, \
                                 above rest_speed {rest_speed}"
                            ),
                        ));
                    }
                    let slide = crate::contact::resting::along_support(&self.vel_of(i, t), &wall);
                    if (c.vel[s] - slide).norm() > scale {
                        return Err(self.fail(
                            t,
                            format!(
                                "body {i} rests on wall {w} with velocity {:?}, not its \
                                 velocity along the wall {:?}",
                                c.vel[s].0, slide.0
                            ),
                        ));
                    }
                    w
                }
                EventKind::Body => {
                    let Some(w) = self.supports.get(i).copied().flatten() else {
                        return Err(
                            self.fail(t, format!("body {i} goes on resting, but did not rest"))
                        );
                    };
                    // Left as it was, or pressed into its wall: either way along it.
                    let normal = crate::contact::resting::support_normal(&self.walls[w], &g);
                    let v = c.vel[s];
                    let scale = 1e-9 * (1.0 + v.norm() + self.vel_of(i, t).norm());
                    if v.dot(normal).abs() > scale * normal.norm() {
                        return Err(self.fail(
                            t,
                            format!("body {i} goes on resting on wall {w} with a normal velocity"),
                        ));
                    }
                    w
                }
                _ => return Err(self.fail(t, format!("body {i} rests after an edit or reset"))),
            });
        }
        Ok(out)
    }

    /// A collision of restitution `e` took the kinetic energy of `who` from `e0` to `e1`: an
    /// elastic one keeps it, to rounding; an inelastic one does not add to it. Rounding is
    /// relative to `e0` and to `lab`, the energy at the speeds the simulation computed with
    /// (in a moving wall's frame `e0` can be far smaller: a body riding along with the wall).
    fn check_energy(
        &self,
        t: f64,
        (e0, e1): (f64, f64),
        lab: f64,
        e: f64,
        who: &str,
    ) -> Result<(), Violation> {
        let tol = CONSERVATION_TOLERANCE * (e0 + lab) + f64::MIN_POSITIVE;
        let bad = if e == 1.0 {
            beyond((e1 - e0).abs(), tol)
        } else {
            beyond(e1 - e0, tol)
        };
        if bad {
            return Err(self.fail(
                t,
                format!("kinetic energy of {who} changes from {e0} to {e1}"),
            ));
        }
        Ok(())
    }

    /// The growth rule for the body collision `c` whose contact distance grows at `grow`
    /// metres per second (zero for fixed radii, where the rule is plain restitution), the
    /// bodies' velocities just before it `(vi, vj)` and the pair's restitution `e`.
    fn check_pair_rule(
        &self,
        c: &Collision<D>,
        grow: f64,
        (vi, vj): (Vector<D>, Vector<D>),
        e: f64,
    ) -> Result<(), Violation> {
        let (i, j) = (c.event.a as usize, c.event.b as usize);
        // From the second body towards the first, as the rule takes it.
        let n = self.image(c.pos[0] - c.pos[1], c.event.time);
        // Rounding is relative to the bodies' own speeds, not only to their relative one: a
        // body riding along with a kinematic one, or two falling side by side.
        let lab = magnitude(vi) + magnitude(vj) + magnitude(c.vel[0]) + magnitude(c.vel[1]);
        self.check_growth_rule(
            c.event.time,
            n,
            (vi - vj, c.vel[0] - c.vel[1]),
            lab,
            (grow, e),
            &format!("bodies {i} and {j}"),
        )
    }

    /// A collision's change of velocity `v0 → v1` (of the first body less the second; of the
    /// body alone at a wall) lies along `n` and turns the normal velocity `u` (along `n`,
    /// which points towards the first body) into `(1 + e)·σ̇ − e·u` when `u < σ̇`, where
    /// `σ̇ = grow` is the speed at which the contact distance grows (zero for fixed radii) and
    /// `e` the collision's restitution. Rounding is relative to these velocities and to
    /// `lab`, the sum of the speeds the simulation computed them from (m/s).
    fn check_growth_rule(
        &self,
        t: f64,
        n: Vector<D>,
        (v0, v1): (Vector<D>, Vector<D>),
        lab: f64,
        (grow, e): (f64, f64),
        who: &str,
    ) -> Result<(), Violation> {
        let n = n * (1.0 / n.norm());
        let (u0, u1, g) = (v0.dot(n), v1.dot(n), grow);
        let want = if u0 < g { (1.0 + e) * g - e * u0 } else { u0 };
        let change = v1 - v0;
        let sideways = (change - n * change.dot(n)).norm();
        let scale = magnitude(v0) + magnitude(v1) + g + lab + f64::MIN_POSITIVE;
        // Rough collisions change the velocity across the normal too: `spins` checks that.
        let sideways = if self.spins.is_some() { 0.0 } else { sideways };
        if beyond((u1 - want).abs(), 1e-9 * scale) || beyond(sideways, 1e-9 * scale) {
            return Err(self.fail(
                t,
                format!(
                    "{who}: normal velocity {u0} becomes {u1}, the {rule} rule asks for {want} \
                     (and no change across the normal; found {sideways:e})",
                    rule = if g == 0.0 { "restitution" } else { "growth" }
                ),
            ));
        }
        Ok(())
    }

    /// Radius of body `i` at time `t`, metres (grown, in a growing scene).
    fn radius_at(&self, i: usize, t: f64) -> f64 {
        self.growth
            .map_or(self.radius[i], |law| law.radius_at(self.radius[i], t))
    }

    /// Files body `i` in the grid (if any) anew from `t`, on its current motion.
    fn refile(&mut self, i: usize, t: f64) {
        let (r, acc) = (self.radius_until_slab_end(i), self.g(i));
        // A turning body stays within its radius of its point: filed there, at rest, twice
        // as large.
        let turn = self.pivot(i).map(|(p, _)| Motion {
            pos: from_2d(p.point()),
            vel: Vector::ZERO,
            time: t,
        });
        if let Some(grid) = &mut self.grid {
            match turn {
                Some(m) => grid.file(i, &m, 2.0 * r, t, None),
                None => grid.file(i, &self.motion[i], r, t, acc),
            }
        }
    }

    /// The radius body `i` reaches by the end of the current slab, to file it with.
    fn radius_until_slab_end(&self, i: usize) -> f64 {
        match &self.grid {
            Some(g) => self.radius_at(i, g.end),
            None => self.radius[i],
        }
    }

    /// Growth speed of body `i`'s radius, metres per second (0 for fixed radii).
    fn growth_speed(&self, i: usize) -> f64 {
        self.growth.map_or(0.0, |law| law.speed(self.radius[i]))
    }

    /// The largest overlap of bodies `i` and `j` (relative to their contact distance) over
    /// `[t0, t1]`, and when; `Ok(None)` when a cheap bound shows they stayed apart; `Err` when
    /// their relative motion in a periodic box is too long to follow (see
    /// [`Verifier::approach`]).
    fn pair_overlap(
        &self,
        i: usize,
        j: usize,
        t0: f64,
        t1: f64,
    ) -> Result<Option<(f64, f64)>, String> {
        if self.pivot(i).is_some() || self.pivot(j).is_some() {
            return Ok(self.pivot_pair_overlap(i, j, t0, t1));
        }
        let (mi, mj) = (self.motion[i], self.motion[j]);
        let sigma0 = self.radius_at(i, t0) + self.radius_at(j, t0);
        let sigma1 = self.radius_at(i, t1) + self.radius_at(j, t1);
        let (gi, gj) = (self.g(i), self.g(j));
        let (pi, vi) = (self.pos_at(&mi, t0, gi), self.vel_at(&mi, t0, gi));
        let (pj, vj) = (self.pos_at(&mj, t0, gj), self.vel_at(&mj, t0, gj));
        let acc = gj.unwrap_or(Vector::ZERO) - gi.unwrap_or(Vector::ZERO);
        let span = (t1 - t0).max(0.0);
        let mut travel = (vj - vi).norm() * span + 0.5 * acc.norm() * span * span;
        if let Some(bx) = self.shear {
            // Images of other layers move faster by the layers' speed; those more than a
            // layer from the nearest cannot come near while y moves less than half a box.
            let layer = bx.nearest_image(pj - pi, t0).1;
            travel += bx.layer_speed().abs() * (layer.abs() + 1.0) * span;
            if (vj[1] - vi[1]).abs() * span >= 0.5 * bx.size[1] {
                travel = f64::INFINITY;
            }
        }
        if self.image(pj - pi, t0).norm() - travel > sigma1 * (1.0 + 1e-6) {
            // Cheap bound: they stay apart (the distance to any image changes no faster than
            // the relative motion).
            return Ok(None);
        }
        if acc != Vector::ZERO {
            // A kinematic body and a falling one (open worlds only): the relative motion is a
            // parabola.
            // With growing radii, `d` is the distance less what the contact distance grew.
            let grow = self.growth_speed(i) + self.growth_speed(j);
            let (d, s) = closest_to_point_falling(pj - pi, vj - vi, acc, span, grow);
            let sigma_at = self.radius_at(i, t0 + s) + self.radius_at(j, t0 + s);
            return Ok(Some((relative(sigma0 - d, sigma_at), t0 + s)));
        }
        let grow = self.growth_speed(i) + self.growth_speed(j);
        // `d` is the distance less what the contact distance grew by since `t0`. Under
        // gravity the relative motion of two falling bodies is linear from the states at `t0`.
        let (d, at) = self
            .approach(pi, vi, pj, vj, (t0, t1 - t0), grow)
            .ok_or_else(|| {
                format!(
                "bodies {i} and {j} move apart by more than {MAX_PIECES} quarter periodic boxes \
                 between t = {t0} and t = {t1}, more than two bodies whose positions are \
                 resolved at that time can (see the resolution rule); verify does not follow \
                 them"
            )
            })?;
        let sigma_at = self.radius_at(i, t0 + at) + self.radius_at(j, t0 + at);
        Ok(Some((relative(sigma0 - d, sigma_at), t0 + at)))
    }

    /// The largest overlap of body `i` with wall `w` (relative to its radius) from its
    /// reference time to `t`, and when.
    fn wall_overlap(&self, i: usize, w: usize, t: f64) -> (f64, f64) {
        if self.pivot(i).is_some() {
            return self.pivot_wall_overlap(i, w, t);
        }
        let (mi, wall) = self.motion_against(i, w);
        let (d, at) = match &self.g(i) {
            Some(g) => closest_to_wall_falling(&wall, &mi, t, g, self.growth_speed(i)),
            None => closest_to_wall(&wall, &mi, t, self.growth_speed(i)),
        };
        let r0 = self.radius_at(i, mi.time);
        (relative(r0 - d, self.radius_at(i, at)), at)
    }

    /// Body `i` is about to change course at `t`: no body or wall may have come too close
    /// to it since the later of their reference times.
    fn check_no_miss(&mut self, i: usize, t: f64) -> Result<(), Violation> {
        let mi = self.motion[i];
        for j in self.candidates(i) {
            if self.never_meet(i, j) {
                continue;
            }
            let mj = self.motion[j];
            let t0 = self.from(&mi).max(self.from(&mj));
            let found = self
                .pair_overlap(i, j, t0, t)
                .map_err(|why| self.fail(t, why))?;
            let Some((overlap, at)) = found else {
                continue;
            };
            if beyond(overlap, OVERLAP_TOLERANCE) {
                return Err(self.fail(t, format!("bodies {i} and {j} overlap by {overlap:e} of their contact distance at t = {at} (a missed collision)")));
            }
            self.report.max_overlap = self.report.max_overlap.max(overlap);
        }
        for w in 0..self.wall_count() {
            if self.is_kinematic(i) {
                break;
            }
            let (overlap, at) = self.wall_overlap(i, w, t);
            if beyond(overlap, OVERLAP_TOLERANCE) {
                return Err(self.fail(t, format!("body {i} crosses wall {w} by {overlap:e} of its radius at t = {} (a missed collision)", at)));
            }
            self.report.max_overlap = self.report.max_overlap.max(overlap);
        }
        Ok(())
    }

    /// Ends the replay at `end_time`: every pair's last stretch of motion is checked, and the
    /// kinetic energy recomputed from scratch.
    pub fn finish(mut self, end_time: f64) -> Result<VerifyReport, Violation> {
        let end = end_time.max(self.last_time);
        if self.pending_add.is_some() {
            return Err(self.fail(
                end_time,
                "an added body's record without its id record".into(),
            ));
        }
        self.skip_void_resets(end_time, false);
        if let Some(clock) = &self.resets {
            if clock.next_time() < end_time {
                return Err(self.fail(
                    end_time,
                    format!(
                        "the thermostat reset of body {} due at {} is missing",
                        clock.next_body(),
                        clock.next_time()
                    ),
                ));
            }
        }
        if self.grid.is_some() {
            self.advance_slabs(end)?;
            self.check_pairs_until(end, "after the last event ")?;
        } else {
            for i in 0..self.motion.len() {
                self.check_pairs_upto(i, end)?;
            }
        }
        for i in 0..self.motion.len() {
            self.check_walls_upto(i, end)?;
        }
        self.report.kinetic_energy_end = (0..self.motion.len())
            .map(|i| 0.5 * self.mass[i] * self.vel_of(i, end).norm_sq())
            .sum();
        self.report.potential_energy_end =
            potential_energy(&self.motion, &self.mass, self.gravity, end);
        self.report.rotational_energy_end = self.rotational_energy(end);
        if let Some(g) = self.gravity {
            // A turning body is where its turn puts it, not where it would have fallen to.
            for (i, turn) in self.pivots.iter().enumerate() {
                if let Some((p, _)) = turn {
                    let fallen = self.motion[i].falling_at(end, &g);
                    let turned = from_2d(p.position(end));
                    self.report.potential_energy_end -= self.mass[i] * g.dot(turned - fallen);
                }
            }
        }
        Ok(self.report)
    }

    /// All-pairs mode: pairs `(i, j > i)` from their later reference time to `t`.
    fn check_pairs_upto(&mut self, i: usize, t: f64) -> Result<(), Violation> {
        let mi = self.motion[i];
        for j in i + 1..self.motion.len() {
            self.check_pair_span(
                i,
                j,
                mi.time.max(self.motion[j].time),
                t,
                "after the last event ",
            )?;
        }
        Ok(())
    }

    fn check_walls_upto(&mut self, i: usize, t: f64) -> Result<(), Violation> {
        if self.is_kinematic(i) {
            return Ok(());
        }
        for w in 0..self.wall_count() {
            let (overlap, at) = self.wall_overlap(i, w, t);
            if beyond(overlap, OVERLAP_TOLERANCE) {
                return Err(self.fail(
                    at,
                    format!("body {i} crosses wall {w} after the last event (a missed collision)"),
                ));
            }
        }
        Ok(())
    }

    /// Bodies `i` and `j` did not come too close over `[t0, t1]` (their current motions).
    fn check_pair_span(
        &mut self,
        i: usize,
        j: usize,
        t0: f64,
        t1: f64,
        when: &str,
    ) -> Result<(), Violation> {
        if t1 < t0 || self.never_meet(i, j) {
            return Ok(());
        }
        let found = self
            .pair_overlap(i, j, t0, t1)
            .map_err(|why| self.fail(t1, why))?;
        let Some((overlap, at)) = found else {
            return Ok(());
        };
        if beyond(overlap, OVERLAP_TOLERANCE) {
            return Err(self.fail(
                at,
                format!(
                    "bodies {i} and {j} overlap by {overlap:e} of their contact distance \
                     {when}at t = {at} (a missed collision)"
                ),
            ));
        }
        self.report.max_overlap = self.report.max_overlap.max(overlap);
        Ok(())
    }

    /// Grid mode: every pair sharing a cell, from the later of its bodies' starts in the slab
    /// to `t` (at most the slab's end).
    fn check_pairs_until(&mut self, t: f64, when: &str) -> Result<(), Violation> {
        let Some(grid) = &self.grid else {
            return Ok(());
        };
        let (pairs, wide) = (grid.pairs(), grid.wide());
        for (i, j) in pairs {
            let t0 = self.from(&self.motion[i]).max(self.from(&self.motion[j]));
            self.check_pair_span(i, j, t0, t, when)?;
        }
        // A wide body against every other, each pair of wide bodies once (never listed:
        // `n` pairs per wide body).
        for &w in &wide {
            for j in 0..self.motion.len() {
                let both_wide = self.grid.as_ref().is_some_and(|g| g.is_wide(j));
                if j == w || (both_wide && j < w) {
                    continue;
                }
                let (i, j) = (w.min(j), w.max(j));
                let t0 = self.from(&self.motion[i]).max(self.from(&self.motion[j]));
                self.check_pair_span(i, j, t0, t, when)?;
            }
        }
        Ok(())
    }

    /// Grid mode: closes slabs until the current one holds `t`. The closed slab's pairs are
    /// checked to its end, then every body is filed again for the next slab, which lasts
    /// until about one cell's crossing at the mean speed, and at least until `t`.
    fn advance_slabs(&mut self, t: f64) -> Result<(), Violation> {
        let Some(end) = self.grid.as_ref().map(|g| g.end) else {
            return Ok(());
        };
        if t <= end {
            return Ok(());
        }
        self.check_pairs_until(end, "")?;
        let mean_speed = (0..self.motion.len())
            .map(|i| speed(self.vel_of(i, end)))
            .sum::<f64>()
            / self.motion.len().max(1) as f64;
        let r_max = self.radius.iter().fold(0.0f64, |m, &r| m.max(r));
        if let Some(slab) = slab_length(r_max, mean_speed, self.gravity) {
            self.slab = slab;
        }
        let next_end = slab_end(end, self.slab).max(t);
        let grown = self.growth.map_or(1.0, |g| g.scale(next_end));
        let acc: Vec<Option<Vector<D>>> = (0..self.motion.len()).map(|i| self.g(i)).collect();
        let grid = self.grid.as_mut().expect("grid mode");
        grid.start_slab(end, next_end);
        for (i, m) in self.motion.iter().enumerate() {
            grid.file(i, m, self.radius[i] * grown, m.time.max(end), acc[i]);
        }
        Ok(())
    }

    /// When a motion's unchecked stretch starts: its reference time, or the current slab's
    /// start if later (what came before was checked when that slab closed).
    fn from(&self, m: &Motion<D>) -> f64 {
        match &self.grid {
            Some(g) => m.time.max(g.start),
            None => m.time,
        }
    }

    /// The bodies the miss check of body `i` looks at: its grid neighbours, or every body.
    fn candidates(&self, i: usize) -> Vec<usize> {
        match &self.grid {
            Some(g) => g.neighbours(i),
            None => (0..self.motion.len()).filter(|&j| j != i).collect(),
        }
    }
}

impl<const D: usize> Verifier<D> {
    /// Position at `t` of a body moving as `m`: along a straight line, or falling.
    fn pos_at(&self, m: &Motion<D>, t: f64, g: Option<Vector<D>>) -> Vector<D> {
        Path::new(*m, g).position(t)
    }

    /// Velocity at `t` of a body moving as `m`: the stored one, or under gravity that plus
    /// `g` times the time since its reference time.
    fn vel_at(&self, m: &Motion<D>, t: f64, g: Option<Vector<D>>) -> Vector<D> {
        Path::new(*m, g).velocity(t)
    }

    /// The displacement `dp` itself, or its nearest image at time `t` in a periodic scene.
    fn image(&self, dp: Vector<D>, t: f64) -> Vector<D> {
        if let Some(bx) = self.shear {
            return bx.nearest_image(dp, t).0;
        }
        match self.period {
            Some(size) => min_image(dp, &size),
            None => dp,
        }
    }

    /// Smallest distance, less `grow` times the time offset (growing radii; 0 for fixed ones),
    /// between two points moving linearly over `[0, span]` (between nearest images in a
    /// periodic scene), and the time offset where it occurs. `None` in a periodic scene when
    /// the relative motion crosses more than [`MAX_PIECES`] quarter boxes: the work grows
    /// with that count, which a long span (a corrupt time) could make any size.
    fn approach(
        &self,
        pa: Vector<D>,
        va: Vector<D>,
        pb: Vector<D>,
        vb: Vector<D>,
        (t0, span): (f64, f64),
        grow: f64,
    ) -> Option<(f64, f64)> {
        let closest = |dp: Vector<D>, dv: Vector<D>, span: f64| {
            if grow > 0.0 {
                closest_approach_growing(dp, dv, span, grow)
            } else {
                closest_approach(Vector::ZERO, Vector::ZERO, dp, dv, span)
            }
        };
        if let Some(bx) = self.shear {
            return self.approach_sheared(&bx, pb - pa, vb - va, (t0, span), closest);
        }
        let Some(size) = self.period else {
            return Some(closest(pb - pa, vb - va, span));
        };
        // Pieces short enough that the relative motion crosses a quarter box at most; in each,
        // every image next to the nearest one at its start is tried.
        let dv = vb - va;
        let span = span.max(0.0);
        let pieces = quarter_box_pieces(dv.norm(), span, &size)?;
        let mut best = (f64::INFINITY, 0.0);
        for k in 0..pieces {
            let s0 = span * k as f64 / pieces as f64;
            let s1 = span * (k + 1) as f64 / pieces as f64;
            let start = min_image(pb - pa + dv * s0, &size);
            for code in 0..3usize.pow(D as u32) {
                let mut dp = start;
                let mut c = code;
                for d in 0..D {
                    dp[d] += ((c % 3) as f64 - 1.0) * size[d];
                    c /= 3;
                }
                let (dist, at) = closest(dp, dv, s1 - s0);
                let dist = dist - grow * s0;
                if dist < best.0 {
                    best = (dist, s0 + at);
                }
            }
        }
        Some(best)
    }

    /// [`Verifier::approach`] in a sheared box, for the relative motion `dp + dv·τ` from time
    /// `t0`: the images of other layers move faster along x by the layers' speed, so the
    /// pieces are short enough for the fastest image that can come near to cross a quarter
    /// box, and in each the images next to the nearest one in each of the three nearest
    /// layers are tried, each with its own relative velocity.
    fn approach_sheared(
        &self,
        bx: &ShearedBox<D>,
        dp: Vector<D>,
        dv: Vector<D>,
        (t0, span): (f64, f64),
        closest: impl Fn(Vector<D>, Vector<D>, f64) -> (f64, f64),
    ) -> Option<(f64, f64)> {
        let size = bx.size;
        let span = span.max(0.0);
        let layers = (dp[1].abs() + dv[1].abs() * span) / size[1] + 2.0;
        let speed = dv.norm() + bx.layer_speed().abs() * layers;
        let pieces = quarter_box_pieces(speed, span, &size)?;
        let mut best = (f64::INFINITY, 0.0);
        for k in 0..pieces {
            let s0 = span * k as f64 / pieces as f64;
            let s1 = span * (k + 1) as f64 / pieces as f64;
            let at = t0 + s0;
            let (start, layer) = bx.nearest_image(dp + dv * s0, at);
            for up in [-1.0, 0.0, 1.0] {
                // The layer `up` above the nearest: shifted by the offset, then brought to its
                // nearest x image.
                let mut base = start;
                base[1] += up * size[1];
                base[0] += up * bx.offset(at);
                base[0] -= size[0] * (base[0] / size[0]).round();
                let vel = bx.image_velocity(dv, layer + up);
                for code in 0..3usize.pow(D as u32 - 1) {
                    let mut p = base;
                    let mut c = code;
                    for d in (0..D).filter(|&d| d != 1) {
                        p[d] += ((c % 3) as f64 - 1.0) * size[d];
                        c /= 3;
                    }
                    let (dist, when) = closest(p, vel, s1 - s0);
                    if dist < best.0 {
                        best = (dist, s0 + when);
                    }
                }
            }
        }
        Some(best)
    }

    /// Velocity `v` of body `i`'s motion (its state since its last event, continued past any
    /// exit from a sheared box) in the frame of the image of it recorded at `recorded` at
    /// time `t`: the layers between them change the velocity by the layers' speed.
    fn record_frame(&self, v: Vector<D>, i: usize, recorded: Vector<D>, t: f64) -> Vector<D> {
        let Some(bx) = self.shear else {
            return v;
        };
        let layer = bx.nearest_image(recorded - self.pos_of(i, t), t).1;
        bx.image_velocity(v, -layer)
    }
}

/// How many pieces a relative motion at `speed` over `span` seconds is cut into so that each
/// crosses a quarter of the smallest side of the box `size` at most; `None` beyond
/// [`MAX_PIECES`] (the work grows with the count, which a corrupt time could make any size).
fn quarter_box_pieces<const D: usize>(speed: f64, span: f64, size: &Vector<D>) -> Option<u64> {
    let side = (0..D).map(|d| size[d]).fold(f64::INFINITY, f64::min);
    let pieces = ((speed * span) / (0.25 * side)).ceil().max(1.0);
    (!beyond(pieces, MAX_PIECES as f64)).then_some(pieces as u64)
}

/// The length of a slab of the proximity grid, seconds: the time a body at the mean speed
/// takes to cross `2 r_max`, about a cell, falling under `gravity` if the scene has it
/// (`speed·τ + ½|g|·τ² = 2 r_max`), at most `f64::MAX`; `None` when nothing moves or falls.
/// Only where slabs end depends on it, never how much work a slab takes: a body whose box
/// over a long slab covers many cells is filed as a wide one.
fn slab_length<const D: usize>(r_max: f64, speed: f64, gravity: Option<Vector<D>>) -> Option<f64> {
    let reach = 2.0 * r_max;
    let g = gravity.map_or(0.0, |g| g.norm());
    if g > 0.0 {
        // The positive root of ½g·τ² + speed·τ − reach, in the cancellation-free form.
        let tau = 2.0 * reach / (speed + (speed * speed + 2.0 * g * reach).sqrt());
        return (tau > 0.0 && !tau.is_nan()).then_some(tau.min(f64::MAX));
    }
    (speed > 0.0).then(|| (reach / speed).min(f64::MAX))
}

/// `x > limit`, or `x` is NaN: a check whose value could not be computed (positions beyond
/// the largest float, `∞ − ∞`) fails rather than passes.
#[allow(clippy::neg_cmp_op_on_partial_ord)]
pub(super) fn beyond(x: f64, limit: f64) -> bool {
    !(x <= limit)
}

/// The sum of `v`'s components' magnitudes, a scale for rounding that, unlike the Euclidean
/// norm, does not underflow to zero for speeds below 10⁻¹⁶² m/s (a body stopped by repeated
/// inelastic collisions at one instant gets there).
fn magnitude<const D: usize>(v: Vector<D>) -> f64 {
    v.0.iter().map(|x| x.abs()).sum()
}

/// An overlap `depth` relative to the contact distance `sigma`; NaN (a failed check) when
/// `sigma` is not finite: radii grown beyond the largest float (a growing run carried to
/// 10³⁰⁸ s) would make any overlap look like none.
fn relative(depth: f64, sigma: f64) -> f64 {
    if sigma.is_finite() {
        depth / sigma
    } else {
        f64::NAN
    }
}

/// The end of a slab of length `slab` from `start`: finite, so that a body at rest stays
/// where it is at the slab's end (`0 · ∞` would put it nowhere).
fn slab_end(start: f64, slab: f64) -> f64 {
    (start + slab).min(f64::MAX)
}

/// `|v|` without underflow: the norm of a velocity of 10⁻¹⁷⁰ m/s, whose square is below the
/// smallest `f64`, is 10⁻¹⁷⁰, not 0.
fn speed<const D: usize>(v: Vector<D>) -> f64 {
    let m = v.0.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    if m == 0.0 || !m.is_finite() {
        return m;
    }
    m * v.0.iter().map(|x| (x / m) * (x / m)).sum::<f64>().sqrt()
}

/// Potential energy at `t` of bodies moving as `motion` in the gravity field, joules:
/// `−Σ m·g·x(t)`; zero without gravity.
fn potential_energy<const D: usize>(
    motion: &[Motion<D>],
    mass: &[f64],
    gravity: Option<Vector<D>>,
    t: f64,
) -> f64 {
    let Some(g) = gravity else {
        return 0.0;
    };
    motion
        .iter()
        .zip(mass)
        .map(|(m, ms)| -ms * g.dot(m.falling_at(t, &g)))
        .sum()
}
