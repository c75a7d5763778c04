//! Why a simulation stops before its events run out, and the checks that find out.
//!
//! Two limits of `f64` end a run early, and the run says so instead of going on wrongly or
//! stopping in silence:
//!
//! * **Beyond the largest time.** Bodies slowed down to speeds near the smallest `f64` (an
//!   inelastic collapse) meet again only after more seconds than the largest float holds. No
//!   finder returns such a contact (see [`finite_event`](crate::finder::finite_event)); when a
//!   finder has no event left, [`beyond_range`] looks for one and names it.
//! * **Resolution.** Before each event the simulation checks that every involved body is
//!   still resolved ([`crate::resolution`]): the clock's rounding times its speed, and its
//!   coordinates' rounding, stay within `5e-10` of its radius. Past that, contact times and
//!   positions are noise, so the event is not resolved.
//!
//! * **Resting.** Under gravity a ball whose bounces on a wall die away (restitution below 1)
//!   ends touching it with no normal speed: the collision changes nothing, and the same event
//!   would come again at the same time for ever. When a wall collision left the body's state
//!   as it was and the finder names that very event again, the run stops.
//!
//! * **Inelastic collapse.** Without the TC model, bodies with restitution below 1 can collide
//!   ever faster, infinitely many times in a finite time; the run stops when a body's
//!   collisions come a million times faster than the mean ([`Halt::InelasticCollapse`]).
//!
//! Each check depends only on the world's stored states and the events, never on the finder,
//! so every finder halts at the same event with the same reason.

use crate::contact::narrow::contact_beyond_range;
use crate::contact::toi_body_wall;
use crate::event::{Event, EventKind};
use crate::geom::Vector;
use crate::resolution::RESOLUTION_LIMIT;
use crate::world::World;

/// What a contact beyond the largest time is with.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Partner {
    /// Another body, by index.
    Body(usize),
    /// A wall, by index.
    Wall(usize),
    /// A face of the periodic box (the body's exit from it).
    BoxFace,
}

impl std::fmt::Display for Partner {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Partner::Body(j) => write!(f, "body {j}"),
            Partner::Wall(w) => write!(f, "wall {w}"),
            Partner::BoxFace => write!(f, "a face of the periodic box"),
        }
    }
}

/// Why a simulation stopped while events remained.
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
pub enum Halt {
    /// Body `body` will touch `partner`, but after more seconds than the largest `f64`
    /// (1.8·10³⁰⁸) holds: its speed has decayed to near the smallest float.
    #[error(
        "the next contact, body {body} with {partner}, lies beyond the largest representable \
         time (1.8e308 s): the run stops at t = {time:e} s"
    )]
    BeyondRange {
        /// The body.
        body: usize,
        /// What it will touch.
        partner: Partner,
        /// The simulated time the run stopped at, seconds.
        time: f64,
    },
    /// At the next event, at `time`, body `body` is no longer resolved: the rounding of the
    /// clock times its speed, plus that of its coordinates, is `error` metres, more than
    /// [`crate::resolution::RESOLUTION_LIMIT`] of its radius.
    #[error(
        "at t = {time:e} s the rounding of time and position ({error:.2e} m) exceeds 5e-10 of the \
         radius of body {body}: f64 can no longer resolve its contacts, so the run stops \
         before this event (start nearer t = 0, or nearer the origin)"
    )]
    Resolution {
        /// The event's time, seconds.
        time: f64,
        /// The body.
        body: usize,
        /// Its resolution error, metres.
        error: f64,
    },
    /// Under gravity body `body` touches wall `wall` at `time` without any normal speed, and
    /// the collision there changed nothing and would repeat at the same time for ever, or it
    /// bounces off it in hops too low to resolve (rising less than
    /// [`crate::resolution::RESOLUTION_LIMIT`] of its radius; the clock's rounding can keep
    /// such hops going for ever, each a few ulps of time long): a ball come to rest on a floor
    /// where bodies do not rest (no `settings.rest_speed`, or a wall that does not hold them,
    /// such as a rod, a segment in 3D, on which it would roll), or one wedged between two
    /// walls, alternating between them (see [`crate::contact::resting`]). The run stops.
    #[error(
        "at t = {time:e} s body {body} touches wall {wall} with no normal speed under gravity, again and again at one instant or in hops too low to resolve (it rests there, or is wedged between two walls): such contacts are not simulated, so the run stops (settings.rest_speed lets bodies rest on single planes, and on segments in 2D)"
    )]
    Resting {
        /// The time, seconds.
        time: f64,
        /// The body.
        body: usize,
        /// The wall it rests on.
        wall: usize,
    },
    /// Bodies `a` and `b` touch at `time` without normal speed while their accelerations
    /// press them together (a body come to rest on another one resting on a wall, see
    /// [`crate::contact::resting`]): the collision there changed nothing and would repeat at the same
    /// time for ever. Bodies resting on bodies are not simulated: the run stops.
    #[error(
        "at t = {time:e} s bodies {a} and {b} touch with no normal speed while gravity presses them together (one rests on the other): bodies resting on bodies are not simulated, so the run stops (settings.tc keeps such bounces elastic)"
    )]
    RestingOnBody {
        /// The time, seconds.
        time: f64,
        /// The body of lower index.
        a: usize,
        /// The other body.
        b: usize,
    },
    /// An inelastic collapse: body `body` had `collisions` body–body collisions within `span`
    /// seconds, up to `time`, against a mean free time of `mean_free_time` seconds (see
    /// `sim/collapse.rs`): bodies with restitution below 1 lose their relative speed and their
    /// collisions pile up without end. The run stops after that collision; the TC model
    /// (`settings.tc`) prevents it.
    #[error(
        "at t = {time:e} s body {body} had {collisions} collisions within {span:.2e} s, against a mean free time of {mean_free_time:.2e} s: an inelastic collapse (restitution below 1 lets colliding bodies lose their relative speed until collisions pile up without end), so the run stops; set settings.tc (the TC model: collisions less than tc apart are elastic), e.g. a small fraction of the mean free time"
    )]
    InelasticCollapse {
        /// The time of the collision that closed the window, seconds.
        time: f64,
        /// The body.
        body: usize,
        /// Its collisions in the window.
        collisions: u32,
        /// The window's length, seconds.
        span: f64,
        /// The run's mean free time so far, seconds.
        mean_free_time: f64,
    },
    /// Arrival `arrival` (its index in the scene's `arrivals`) cannot enter at `time`: a body
    /// or a moving wall occupies its place ([`crate::scene::arrival`]). The run stops there, after
    /// every event at or before that time.
    #[error(
        "at t = {time:e} s arrivals[{arrival}] cannot enter: a body or a moving wall is in its place, so the run stops there (space the arrivals so that each finds its place free)"
    )]
    ArrivalBlocked {
        /// The arrival's time, seconds.
        time: f64,
        /// Its index in the scene's `arrivals`.
        arrival: usize,
    },
    /// Body `body`, sliding on segment `wall`, reaches its end at `time` too slowly to fly
    /// clear of the edge. No longer raised: such a body rolls over the edge, turning about
    /// the end point ([`crate::motion::pivot`]). Kept so that code matching on halts still builds.
    #[error(
        "at t = {time:e} s body {body} slides off the end of wall {wall} too slowly to fly clear of it (this build does not stop there: such a body rolls over the edge)"
    )]
    OverEdge {
        /// The time, seconds.
        time: f64,
        /// The body.
        body: usize,
        /// The segment it slides on.
        wall: usize,
    },
}

/// The simulation's per-event resolution check, with a fast path: up to a time `fast_until`
/// computed from bounds on every body's speed and coordinates, every body is resolved, and an
/// event there needs one comparison; past it (or without such bounds) each event's bodies are
/// checked ([`event_resolved`]). The answer is the same either way.
#[derive(Clone, Copy, Debug)]
pub(crate) struct ResolutionGuard {
    /// `|t|` up to which every body is resolved (`-∞`: no fast path).
    fast_until: f64,
    /// What the clock's rounding may cost the fastest body, metres: the resolution limit of
    /// the smallest radius less the coordinates' rounding (`≤ 0`: no fast path).
    budget: f64,
    /// The smallest mass, kilograms.
    m_min: f64,
    /// An upper bound of the kinetic energy, joules.
    kinetic: f64,
    /// Kinetic energies up to which `fast_until` stays as it is, joules: the fast path's
    /// bound moves in powers of two, so most additions leave it alone (growing worlds add
    /// energy at every collision).
    same_until: f64,
}

impl ResolutionGuard {
    /// The guard for `world`'s current states. Valid while kinetic energy does not grow
    /// (collisions with restitution ≤ 1 never make it grow; an edit reports what it adds
    /// through [`ResolutionGuard::add_energy`]).
    ///
    /// Speeds are bounded by `√(2K / m_min)` (one body holding all the kinetic energy `K`).
    /// Coordinates are bounded in a periodic box (positions stay within a box length of it) and
    /// inside closed polygons of segments (validation keeps every body inside them); other
    /// worlds get no fast path.
    pub(crate) fn new<const D: usize>(world: &World<D>) -> Self {
        // Under gravity kinetic energy grows as bodies fall: no speed bound, no fast path.
        // Kinematic bodies and moving walls go as fast as they are told, and push others
        // faster.
        let coordinate_bound = if world.gravity().is_some()
            || world.has_kinematic()
            || world.moving_wall_count() > 0
        {
            None
        } else if let Some(size) = world.periodic() {
            Some(2.0 * size.0.iter().fold(0.0f64, |m, &l| m.max(l)))
        } else {
            let loops = world.table();
            (D == 2 && !loops.is_empty()).then(|| {
                loops
                    .iter()
                    .flat_map(|(a, b)| a.0.into_iter().chain(b.0))
                    .fold(0.0f64, |m, c| m.max(c.abs()))
            })
        };
        let (mut m_min, mut r_min) = (f64::INFINITY, f64::INFINITY);
        for i in 0..world.len() {
            m_min = m_min.min(world.mass(i));
            r_min = r_min.min(world.radius(i));
        }
        let budget = coordinate_bound.map_or(f64::NEG_INFINITY, |c| {
            RESOLUTION_LIMIT * r_min - crate::resolution::ulp(c)
        });
        let mut guard = ResolutionGuard {
            fast_until: f64::NEG_INFINITY,
            budget,
            m_min,
            // 1 % over the sum covers its rounding.
            kinetic: world.kinetic_energy() * 1.01,
            same_until: f64::NEG_INFINITY,
        };
        guard.refresh();
        guard
    }

    /// Body edits (a new velocity) may add up to `energy` joules of kinetic energy.
    pub(crate) fn add_energy(&mut self, energy: f64) {
        self.kinetic += energy.max(0.0) * 1.01;
        if self.kinetic > self.same_until {
            self.refresh();
        }
    }

    fn refresh(&mut self) {
        let speed_bound = (2.0 * self.kinetic / self.m_min).sqrt();
        (self.fast_until, self.same_until) = if !(self.budget > 0.0 && speed_bound.is_finite()) {
            // No fast path, whatever is added.
            (f64::NEG_INFINITY, f64::INFINITY)
        } else if speed_bound == 0.0 {
            (f64::INFINITY, self.kinetic)
        } else {
            // The largest power of two whose ulp keeps `speed · ulp` within the budget: every
            // |t| below it has an ulp no larger.
            let below = (self.budget / speed_bound).log2().floor() as i32;
            let fast_until = 2f64.powi((below + 52).clamp(-1000, 1023));
            // `below` stays while `budget / speed ≥ 2^below`: up to a speed of
            // `budget · 2^−below`. A millionth short of it, so that the rounding of the
            // logarithm never keeps a bound that should have moved.
            let speed_max = self.budget * 2f64.powi(-below);
            let same_until = 0.5 * self.m_min * speed_max * speed_max * (1.0 - 1e-6);
            let same_until = if same_until.is_finite() {
                same_until
            } else {
                self.kinetic
            };
            (fast_until, same_until)
        };
    }

    /// True when every body involved in `e` is resolved at its time.
    #[inline(always)]
    pub(crate) fn resolved<const D: usize>(&self, world: &World<D>, e: &Event) -> bool {
        e.time.abs() < self.fast_until || event_resolved(world, e)
    }
}

/// True when every body involved in `e` is resolved at its time (see
/// [`crate::resolution`]): the check the simulation makes before each event, kept to a few
/// instructions per body.
#[must_use]
#[inline]
pub fn event_resolved<const D: usize>(world: &World<D>, e: &Event) -> bool {
    let clock = crate::resolution::ulp_of_finite(e.time);
    let body = |i: u32| {
        let b = &world.bodies()[i as usize];
        if world.has_pivots() && world.pivot(i as usize).is_some() {
            // Its stored motion is where it is parked, not where it turns.
            return crate::resolution::resolves(
                e.time,
                world.position_at(i as usize, e.time),
                world.velocity_at(i as usize, e.time),
                b.radius,
            );
        }
        let (pos, vel) = match world.gravity() {
            None => (b.motion.at(e.time), b.motion.vel),
            Some(g) => (
                b.motion.falling_at(e.time, &g),
                b.motion.falling_velocity(e.time, &g),
            ),
        };
        crate::resolution::resolution_error_at(clock, pos, vel)
            <= crate::resolution::RESOLUTION_LIMIT * b.radius
    };
    body(e.a) && (e.kind != EventKind::Body || body(e.b))
}

/// The first body involved in `e` that is not resolved at its time, as a [`Halt`]; `None`
/// when all are.
#[cold]
#[must_use]
pub fn unresolved<const D: usize>(world: &World<D>, e: &Event) -> Option<Halt> {
    let involved = match e.kind {
        EventKind::Body => &[e.a, e.b][..],
        EventKind::Wall | EventKind::Reset | EventKind::Edit => &[e.a][..],
    };
    involved.iter().find_map(|&i| {
        let (pos, vel) = (
            world.position_at(i as usize, e.time),
            world.velocity_at(i as usize, e.time),
        );
        (!crate::resolution::resolves(e.time, pos, vel, world.radius(i as usize))).then(|| {
            Halt::Resolution {
                time: e.time,
                body: i as usize,
                error: crate::resolution::resolution_error(e.time, pos, vel),
            }
        })
    })
}

/// A contact of the world's stored states that lies beyond the largest time, if there is one;
/// meant for when a finder has no (finite) event left.
///
/// Searched in this order, and the first found is named: in a periodic box, any moving body
/// (it would leave the box, at a finite time if the finder had found it); then, body by body,
/// each wall; then pairs of bodies. A pair meets beyond the largest time only if their
/// velocities differ by less than `extent / f64::MAX` in every component (`extent` the span
/// of the bodies plus their largest diameter), so pairs are looked for only among bodies whose
/// velocities agree exactly in every component above `2⁵³` times that: `O(n log n)` plus the
/// pairs within such groups.
#[cold]
#[must_use]
pub fn beyond_range<const D: usize>(world: &World<D>) -> Option<Halt> {
    let time = world.now();
    let n = world.len();
    let moving = |i: usize| world.velocity(i) != Vector::ZERO || world.gravity().is_some();
    if world.periodic().is_some() {
        return (0..n).find(|&i| moving(i)).map(|body| Halt::BeyondRange {
            body,
            partner: Partner::BoxFace,
            time,
        });
    }
    for i in (0..n).filter(|&i| moving(i)) {
        let m = world.motion(i);
        for (w, wall) in world.walls().iter().enumerate() {
            let t = if world.laws().is_some_and(|l| l.resting) {
                crate::world::toi_body_wall_resting(world, i, w)
            } else {
                toi_body_wall(&m, world.radius(i), wall, world.laws())
            };
            if t == Some(f64::INFINITY) {
                return Some(Halt::BeyondRange {
                    body: i,
                    partner: Partner::Wall(w),
                    time,
                });
            }
        }
    }
    pair_beyond_range(world).map(|(body, j)| Halt::BeyondRange {
        body,
        partner: Partner::Body(j),
        time,
    })
}

/// A body in the pair search: its velocity key, its exact velocity's bits, its index.
type Candidate<const D: usize> = ([u64; D], [u64; D], usize);

/// The pair `(i, j)`, `i < j`, of lowest `i` then `j` among the candidates (see
/// [`beyond_range`]) that meets beyond the largest time.
fn pair_beyond_range<const D: usize>(world: &World<D>) -> Option<(usize, usize)> {
    let n = world.len();
    if n < 2 {
        return None;
    }
    let mut lo = [f64::INFINITY; D];
    let mut hi = [f64::NEG_INFINITY; D];
    let mut r_max = 0.0f64;
    let now = world.now();
    for i in 0..n {
        let p = world.position_at(i, now);
        for d in 0..D {
            lo[d] = lo[d].min(p[d]);
            hi[d] = hi[d].max(p[d]);
        }
        r_max = r_max.max(world.radius(i));
    }
    let extent = (0..D).map(|d| hi[d] - lo[d]).fold(0.0, f64::max) + 2.0 * r_max;
    // Two different floats within `tau` of each other are both below `2⁵³ tau` in size (a
    // factor 4 more covers the rounding of `extent` and of this bound).
    let tiny = extent / f64::MAX * 2f64.powi(55);
    let key = |i: usize| {
        world
            .velocity_at(i, now)
            .0
            .map(|c| if c.abs() <= tiny { 0 } else { c.to_bits() })
    };
    // Sorted by key, then by exact velocity: bodies moving alike (all those at rest, say)
    // form runs whose pairs are skipped at once.
    let mut order: Vec<Candidate<D>> = (0..n)
        .map(|i| (key(i), world.velocity_at(i, now).0.map(f64::to_bits), i))
        .collect();
    order.sort_unstable();
    let mut best: Option<(usize, usize)> = None;
    for group in order.chunk_by(|a, b| a.0 == b.0) {
        let alike: Vec<&[Candidate<D>]> = group.chunk_by(|a, b| a.1 == b.1).collect();
        for (k, first) in alike.iter().enumerate() {
            for second in &alike[k + 1..] {
                for &(_, _, a) in *first {
                    for &(_, _, b) in *second {
                        let (i, j) = (a.min(b), a.max(b));
                        if best.is_some_and(|best| (i, j) >= best) {
                            continue;
                        }
                        let (mi, mj) = (world.motion(i), world.motion(j));
                        let t0 = mi.time.max(mj.time);
                        let dp = world.position_at(j, t0) - world.position_at(i, t0);
                        let dv = world.velocity_at(j, t0) - world.velocity_at(i, t0);
                        let sigma = world.radius(i) + world.radius(j);
                        if contact_beyond_range(dp, dv, sigma) {
                            best = Some((i, j));
                        }
                    }
                }
            }
        }
    }
    best
}

impl Halt {
    /// The simulated time the halt names, seconds: that of the event the run stops before
    /// (for [`Halt::BeyondRange`], the time the run stopped at).
    #[must_use]
    pub fn time(&self) -> f64 {
        match *self {
            Halt::BeyondRange { time, .. }
            | Halt::Resolution { time, .. }
            | Halt::Resting { time, .. }
            | Halt::RestingOnBody { time, .. }
            | Halt::ArrivalBlocked { time, .. }
            | Halt::OverEdge { time, .. }
            | Halt::InelasticCollapse { time, .. } => time,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::{gas, GasConfig};
    use crate::resolution::resolves;

    /// Energy added in small steps (a growing world's collisions) leaves the guard's bound
    /// where a bound computed afresh after every step would be: it skips recomputing only
    /// while that cannot change it, across many powers of two of the speed.
    #[test]
    fn added_energy_moves_the_bound_as_a_fresh_one_would() {
        let fresh = |g: &ResolutionGuard| {
            let mut f = *g;
            f.refresh();
            f.fast_until
        };
        for (budget, m_min, start) in [(1e-9, 0.5, 1.0), (3.7e-7, 2.0, 1e-3), (1e-12, 1e-3, 0.0)] {
            let mut g = ResolutionGuard {
                fast_until: f64::NEG_INFINITY,
                budget,
                m_min,
                kinetic: start,
                same_until: f64::NEG_INFINITY,
            };
            g.refresh();
            let first = g.fast_until;
            let mut x = 0x9e37_79b9_7f4a_7c15u64;
            let mut skipped = 0;
            for _ in 0..20_000 {
                x ^= x << 13;
                x ^= x >> 7;
                x ^= x << 17;
                // Steps from 10⁻⁶ of the energy to about a fiftieth of it.
                let step = (g.kinetic.max(1e-3)) * (x >> 11) as f64 / (1u64 << 53) as f64 * 0.02
                    + 1e-6 * g.kinetic;
                let before = g.fast_until;
                g.add_energy(step);
                skipped += usize::from(g.fast_until == before);
                assert_eq!(g.fast_until.to_bits(), fresh(&g).to_bits(), "{g:?}");
            }
            assert!(g.fast_until > 0.0 && g.fast_until < first / 1e30, "{g:?}");
            assert!(skipped > 0);
        }
    }

    /// Below the guard's `fast_until`, every body is resolved by the exact rule, at times as
    /// late as the guard allows, even with all the energy in one body.
    #[test]
    fn the_fast_path_never_accepts_what_the_exact_check_refuses() {
        for (periodic, seed) in [(true, 1), (false, 2), (true, 3)] {
            let scene = gas::<2>(&GasConfig {
                n: 200,
                packing: 0.3,
                periodic,
                seed,
                ..GasConfig::default()
            })
            .unwrap();
            let world = World::from_scene(&scene).unwrap();
            let guard = ResolutionGuard::new(&world);
            assert!(guard.fast_until > 1.0, "{guard:?}");
            let t = guard.fast_until * (1.0 - f64::EPSILON);
            let k = world.kinetic_energy();
            for i in 0..world.len() {
                // The fastest this body can go: all the kinetic energy in it.
                let speed = (2.0 * k / world.mass(i)).sqrt();
                let m = world.motion(i);
                let dir = m.vel * (1.0 / m.vel.norm().max(f64::MIN_POSITIVE));
                assert!(
                    resolves(t, m.pos, dir * speed, world.radius(i)),
                    "body {i} at t = {t}"
                );
            }
        }
    }
}
