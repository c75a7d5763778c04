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
//! Either check depends only on the world's stored states and the event, never on the finder,
//! so every finder halts at the same event with the same reason.

use crate::finder::finite_event;
use crate::geom::Vector;
use crate::narrow::{contact_beyond_range, toi_circle_wall};
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
    /// [`RESOLUTION_LIMIT`](crate::resolution::RESOLUTION_LIMIT) of its radius.
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
}

/// The first involved body of an event at `time` that is not resolved, as a [`Halt`].
#[must_use]
#[inline]
pub fn unresolved<const D: usize>(world: &World<D>, time: f64, bodies: &[usize]) -> Option<Halt> {
    for &i in bodies {
        let m = world.motion(i);
        let pos = m.at(time);
        if !crate::resolution::resolves(time, pos, m.vel, world.radius(i)) {
            return Some(Halt::Resolution {
                time,
                body: i,
                error: crate::resolution::resolution_error(time, pos, m.vel),
            });
        }
    }
    None
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
#[must_use]
pub fn beyond_range<const D: usize>(world: &World<D>) -> Option<Halt> {
    let time = world.now();
    let n = world.len();
    let moving = |i: usize| world.velocity(i) != Vector::ZERO;
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
            if toi_circle_wall(&m, world.radius(i), wall) == Some(f64::INFINITY) {
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
            .velocity(i)
            .0
            .map(|c| if c.abs() <= tiny { 0 } else { c.to_bits() })
    };
    // Sorted by key, then by exact velocity: bodies moving alike (all those at rest, say)
    // form runs whose pairs are skipped at once.
    let mut order: Vec<Candidate<D>> = (0..n)
        .map(|i| (key(i), world.velocity(i).0.map(f64::to_bits), i))
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
                        let dp = mj.at(t0) - mi.at(t0);
                        let sigma = world.radius(i) + world.radius(j);
                        if contact_beyond_range(dp, mj.vel - mi.vel, sigma) {
                            best = Some((i, j));
                        }
                    }
                }
            }
        }
    }
    best
}

/// `finder_answer` unless it is `None` and a contact lies beyond the largest time, in which
/// case that halt: a helper for [`Simulation`](crate::Simulation).
pub(crate) fn check_exhausted<const D: usize>(
    world: &World<D>,
    finder_answer: Option<crate::Event>,
) -> Result<Option<crate::Event>, Halt> {
    match finite_event(finder_answer) {
        Some(e) => Ok(Some(e)),
        None => match beyond_range(world) {
            Some(halt) => Err(halt),
            None => Ok(None),
        },
    }
}
