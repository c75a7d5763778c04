//! The `cells` finder: a uniform grid, cached predictions per body and an event queue; a
//! bounded number of predictions and O(log n) queue work per event.
//!
//! # How it works
//!
//! * **Grid** ([`grid`]): cells at least the largest contact distance `σ_max = r₁ + r₂` (the
//!   two largest radii) wide, times `1 + MARGIN`. Every body is filed in one cell (its first
//!   four bodies in fixed slots, any others in an overflow list). A body's *neighbourhood* is
//!   the 3^D block of cells around its own. Each cell also lists the walls that come within
//!   `r_max` (times the same margin) of it.
//! * **Predictions** ([`predict`]): for each body `i` the finder caches `best(i)`, the minimum
//!   under [`Event`]'s full order (time, kind, a, b) of the times of impact of `i` with every
//!   body in its neighbourhood, every wall of its cell and (periodic worlds, when its cell is
//!   a *border cell*, first or last along some axis) its box exit, together with the image of the partner it was computed for. Each time is computed by the
//!   same pure function on the same stored states, with the same argument order, as
//!   [`all_pairs_next_event`](super::all_pairs_next_event): a cached time *is* the oracle's
//!   time for that pair (image), bit for bit, as long as neither body's state changed.
//! * **Crossings**: the time body `i` leaves its cell through a face shared with another cell.
//!   Crossings are internal: they move the body to the next cell and offer it the pairs of the
//!   layer of cells that just became neighbours, and the walls its new cell lists but its old
//!   cell did not. They are never returned and change no stored state.
//! * **Queue** ([`tournament`], keys in [`key`]): one entry per body keyed by
//!   `min(best(i), crossing(i))` in a tournament tree (every node holds the smallest key
//!   below it, inline). Keys are compared in the full event order; a crossing goes first at
//!   equal times.
//!
//! `next_event` looks at the top of the queue: a crossing is processed; a body event whose
//! partner changed since it was computed (each cached event records its partner's
//! [`World::change_count`] then; an event promoted from second place, whose count is not
//! kept, is evaluated again on the current states instead and must come out bit for bit the
//! same) is *stale*: the body's second cached event takes its place if it is known, else the
//! body is recomputed from scratch; anything else is returned. `update` refiles the bodies
//! that changed if they left their cell, and recomputes them. Nothing else is touched: a
//! collision costs two neighbourhood scans (in crossing mode, for two bodies in interior
//! cells, one pass over the union of their blocks giving the same records, see [`pair`]), a
//! few queue operations and, now and then, one rescan for a body whose cached event involved
//! the colliding bodies.
//!
//! # Why every returned event is the oracle's
//!
//! Call a term *live* if it is the time of impact of a pair (or body and wall) on the current
//! stored states. Two invariants hold between calls:
//!
//! 1. *Every key is a lower bound of what it stands for.* `best(i)` is a minimum of terms that
//!    were live when computed. A term computed with partner `j` stays live until `j` (or `i`)
//!    changes; when `i` changes it is recomputed at once, and when `j` changes the entry may
//!    be stale: still a lower bound of `i`'s other terms, which have not changed. A key that
//!    passes the check at the top is a live term: its partner's change count is the one
//!    recorded when it was computed, after `i`'s last change (a full scan records the counts
//!    afresh; a crossing records them for the events it finds and keeps those of the event it
//!    carries over), so it is the same function of the same states; a promoted key is
//!    evaluated again (same pair, same image, same function, current states). A key whose
//!    partner changed is called stale even if its time would come out the same: the partner
//!    was recomputed at its change, after the key was computed and after `i`'s last change,
//!    so its records cover the pair's current term as far as invariant 2 asks, and `i` may
//!    drop it. The second cached event `second(i)` is, while known, a lower bound of every
//!    term of `i` but `best(i)`'s own: a full scan keeps the two smallest terms, and a merge
//!    that lowers `best` demotes the old `best` (a lower bound of all the rest) to `second`. When `best(i)` is stale its term is gone, the new term of
//!    that pair is covered by the partner (which was recomputed when it changed), and every
//!    other term of `i` is at least `second(i)`: promoting `second(i)` keeps the invariant.
//!    After a promotion `second(i)` is unknown until the next full scan.
//! 2. *Every live term whose pair is responsible is covered by a key.* Call a pair responsible
//!    when the bodies are in neighbouring cells (a body and a wall: the wall is listed by the
//!    body's cell; a body and its box exit: the body is in a border cell, as if the box's
//!    faces were walls listed by the border cells only). The pair's term was computed at the later of (a) the last state change of
//!    either body (full recompute of that body, which scans its whole neighbourhood and its
//!    cell's walls), (b) the last crossing of either body that made them neighbours (the layer
//!    scan; for a body and a wall, the last crossing of the body from a cell that did not list
//!    the wall into one that does; for a box exit, the last crossing of the body from a cell
//!    that is not a border cell into one that is). Since then the term is covered by that body's records: merges only lower them,
//!    a promotion keeps the coverage (see 1), and a full recompute covers the pair again.
//!
//! Let `E` be the oracle's event: the minimum live term, at time `t`. While a crossing or a
//! stale key precedes `E` in the queue, it is processed, never returned (crossings are finitely
//! many before `t` since each moves a body one cell forward; a stale key is replaced by its
//! body's live minimum). When the top is a live key it is a live term, hence `≥ E`. It is also
//! `≤ E`, because `E`'s pair is responsible: every crossing of `E`'s bodies before `t` has been
//! processed, so at time `t` each body lies in its cell, up to the rounding of crossing times
//! (far below the margin); at `t` the two bodies are `σ ≤ σ_max` apart (a body is within `r`
//! of its wall; a body leaving the box is on a face of it, and only border cells reach the
//! faces: every other cell is at least one whole cell away from them), and cells that are not neighbours are at least one cell, `σ_max (1 + MARGIN)`,
//! apart. So the top *is* `E`, ties included, since keys order exactly like events. When the
//! top key lies at an infinite time, `E` is at an infinite time too (or there is none), and
//! `next_event` answers `None`, as the oracle does (see [`finite_event`](super::finite_event)).
//!
//! Outer cells of an open world extend to infinity, so bodies that leave the initial bounding
//! box are still filed; two outer cells that are not neighbours still have a whole inner cell
//! between them.
//!
//! A periodic world has no walls; its grid tiles the box `[0, L)` and neighbour cells across
//! the box faces carry the image shift ±L. Stored positions stay in the box (exits are
//! events, see [`crate::contact::periodic`]), so the image that makes two bodies neighbours is one of
//! the `3^D` images the oracle tries, and with at least three cells per axis two cells are
//! neighbours through one image only: the contact that matters is the one through the
//! neighbouring image, and the time cached for it is the oracle's: the same function on the
//! same states, lower index first, with the shift as the oracle writes it (`k·L`, `k ∈ {−1,
//! 0, 1}` per axis; a partner listed first gets `0 − s`, so zero components stay `+0`). An
//! axis too short for three cells is a single cell whose three images are all scanned, like
//! the oracle does.
//!
//! A sheared box ([`crate::contact::lees_edwards`]) slides the rows of cells along its y faces
//! past each other, so which cells neighbour a border row across those faces changes with
//! time. There, the cells of a body's neighbourhood reached across a y face are replaced by
//! the whole opposite row (every x, the neighbouring z), every pair is evaluated by the
//! oracle's sheared function over all images
//! ([`toi_bodies_sheared`](crate::contact::lees_edwards::toi_bodies_sheared)), a crossing
//! into a border row rescans the whole new neighbourhood (elsewhere the layer entered, which
//! lies off the y faces), and neighbour lists are not used: the argument above
//! holds with "neighbours" read as these sets, since two bodies that touch across a y face
//! are both in border rows and in neighbouring z layers.
//!
//! A scan of an interior block (every cell present, zero shift) gathers the bodies of its
//! cells from their slots and evaluates them four at a time ([`gather`]): each lane is the
//! oracle's function on its pair's states in the oracle's order, bit for bit, and the offers
//! are the scalar scan's, so the records are the same (the order of offers does not matter,
//! see [`pair`]). A block with a cell that overflows its slots, and every border block, is
//! scanned body by body.
//!
//! The margin covers rounding as long as positions are computed to better than `MARGIN·σ_max`
//! (that is, `|x| + |v|·|t|` below about 10⁹ σ_max), which is far beyond where the simulation's
//! own overlap tolerance of 10⁻⁹ would already fail.
//!
//! # Gravity: crossings on parabolas, and bodies on a face
//!
//! Under gravity a body's coordinate along an axis is a parabola, and a crossing is a root of
//! `x(t) − bound` ([`Grid::next_crossing_falling`](grid::Grid::next_crossing_falling)). The
//! argument above needs every body to lie in its cell until its crossing. Seen from inside a
//! cell, the parabola over a face either opens towards the cell (the body leaves at the
//! earlier root and may come back at the later one) or away from it (the body is inside only
//! between the roots and leaves for good at the later one). A body filed on a face at rest
//! (`x = bound`, `v = 0`, as integer coordinates in a hand-written scene put it) gives a
//! double root, which rounding can also turn into no root or disordered roots. Such a graze
//! is no crossing when the parabola opens towards the cell; but when it opens away (a body
//! resting on the lower face of its cell, gravity pulling it down) the body is outside
//! from that instant on. Counting that as a graze, as the finder once did, left the body
//! filed in a cell it had left: it fell through the cells below without crossing them, its
//! neighbourhood scans never met the floor's cell, and collisions were missed. So a face
//! whose parabola opens away from the cell is always crossed: at the later root, or at the
//! finder's clock when that root lies before it (rounding) or there is none. The cell on the
//! other side computes the same roots from the same bound and sees the parabola open towards
//! it, so the body does not bounce back. That cell also passes over a face the body leaves and
//! comes back through at one instant (roots closer than the time's rounding: a body on the
//! face moving off it at a speed of 10⁻¹⁶ m/s that rounding left behind, falling back):
//! crossed, it would be crossed back out of the first cell at that instant, for ever.
//!
//! # Growing radii
//!
//! In a growing world ([`crate::contact::growth`]) contact distances grow with time. `init` then sizes
//! the grid, the wall reach and the lists for the radii at a *horizon* `t_h`, by default the
//! time at which the radii have grown by [`GROWTH_HEADROOM`] of their current size: every
//! argument above holds for contacts at times up to `t_h` with `σ_max` read as `σ_max(t_h)`.
//! Pairs are evaluated by the growing functions with the oracle's arguments, four at a time by
//! the kernel's growing form (`narrow_lanes::toi_sides_growing`, each lane the scalar
//! function's result bit for bit; overlapping pairs go to the scalar function).
//! When the top of the queue lies beyond `t_h`, or the queue holds nothing at a finite time
//! (bodies too far apart to be paired by a grid sized for `t_h` may still grow into each
//! other later), the oracle's event does too (if it lay at or before `t_h`, the top would be
//! it), so nothing is returned: the finder rebuilds everything
//! from the stored states at the current time for a horizon at least at that key's time (a
//! live term or a lower bound of one, so the oracle's event comes at or before it) and at
//! least twice as far, and asks again. After many rebuilds in a row without an event (bodies
//! that never meet: the window has doubled each time), the query is answered by the
//! all-pairs search itself. A rebuild is O(n); radii grow by 5 % between rebuilds.
//!
//! # List mode (Verlet neighbour lists with a skin)
//!
//! With a skin `s > 0` (option `cells_skin`, relative to `σ_max`) and a periodic world of
//! fewer than 2²⁷ bodies, the finder scans per-body neighbour lists ([`lists`]) instead of
//! the 3^D block of cells. (In open worlds a body flying off would leave shells forever,
//! where the crossings of outer cells, which extend to infinity, stop: they keep crossings.)
//!
//! * Each body `i` has a *shell centre* `X_i`, its position when its list was last built,
//!   and a shell, the ball of radius `h = s/2` around it. A *shell exit* is the time its
//!   stored motion reaches the surface of its shell (the later root of a quadratic, solved
//!   without cancellation from a time at which the body is inside; recomputed whenever the
//!   body is predicted). Exits take the crossings' place: keys of the crossing class (first at
//!   equal times), internal, never returned, changing no stored state.
//! * The grid files bodies by shell centre, in cells at least `(σ_max + s + slack)(1 +
//!   MARGIN)` wide (`slack = 4·MARGIN·σ_max`): bodies change cell only when their list is
//!   rebuilt, and there are no crossings at all. Walls are filed with the reach `r_max + h +
//!   MARGIN·σ_max + slack`.
//! * `N(i)` lists, with the image code of the shift, exactly the bodies `j` with
//!   `|X_j − X_i + shift| ≤ σ_max + s + slack` (≥ `r_i + r_j + s + slack`). The test is
//!   symmetric bit for bit (the displacement seen from `j` is the exact negation), and at
//!   every rebuild of `i` the lists of the bodies it gains or loses are updated; since only
//!   a rebuild moves a centre, the lists always equal the relation on the current centres.
//! * A rebuild of `N(i)` applies that test to the bodies of the cells of the 3^D block around
//!   the cell of `X_i` whose box, moved by the cell's image shift, comes within the overlap
//!   distance of `X_i`, per-axis gaps taken less `2·MARGIN·(σ_max + s + slack)`: the centres
//!   of a cell's bodies lie in its box up to rounding (far below that margin), so a skipped
//!   cell holds no body whose shell overlaps `i`'s, and the lists still equal the relation.
//!   The shell centres are also filed cell by cell in fixed slots ([`slots`]), so a rebuild
//!   reads a cell's centres as one run and tests its slots lane by lane, each lane doing
//!   `Lists::overlap`'s operations in its order (the same outcome bit for bit); the order of
//!   the entries it produces follows the slots, and no result depends on it (see
//!   `collect_overlapping`).
//! * A full recompute of `i` scans `N(i)` (same pure functions, same argument order and
//!   shift convention as above: a list keeps its partners of higher index first, so the
//!   order is known per entry from its place, and `0 − s` is computed once per image code;
//!   partners go four at a time through a four-lane SIMD kernel, `narrow_lanes::toi_sides`,
//!   whose lanes perform the scalar function's operations in its order, each lane with its
//!   pair's balls in the oracle's order (the quad where the two parts meet chooses them lane
//!   by lane), and hand every rare path back to it, so its times are the scalar ones bit for
//!   bit, offered in list order; a last quad of fewer entries is padded and its padding
//!   lanes dropped), the walls
//!   of the cell of `X_i` and, if that cell is a border cell, the box exit. A rebuild at a
//!   shell exit moves `X_i` to the body's position then, refiles it, rebuilds `N(i)` and
//!   offers `i` only the pairs new to `N(i)`, the walls new to its cell and, if it moved
//!   from a cell that is not a border cell into one that is, its box exit, then
//!   schedules its next exit. A state change that leaves the stored position outside the
//!   shell (a box exit moves it by a period, `L > 2σ_max ≥ 4h`) rebuilds the list at the
//!   change time before the recompute.
//!
//! Why it is exact: the invariants of the proof above hold with "responsible" read as "listed
//! in each other's lists" (a body and a wall: the wall is filed for the cell of the body's
//! shell centre; a body and its box exit: that cell is a border cell), since a pair's term was computed at the later of the last state change of
//! either body (full recompute: the whole list) and the rebuild that listed the pair (the
//! pairs new to the list are offered). A stale entry cannot occur: lists equal the overlap
//! relation. Let `E` be the oracle's event at time `t`, pair `(i, j)`. Every shell exit before
//! `t` is processed before `E` (exits go first at equal times; finitely many, since each
//! moves its body by `h` along its path and in a periodic world each moving body has a box
//! exit, an event, within a bounded time), so at `t` each body is within `h` of its centre
//! (up to the rounding of exit times and positions, far below `slack`). The bodies touch at
//! `t` through one image: `|p_j − p_i + shift| = r_i + r_j`, hence `|X_j − X_i + shift| ≤ r_i
//! + r_j + 2h + rounding ≤ σ_max + s + slack`: the pair is listed, with that image (the box
//! is wider than twice the contact distance, so the contact image is the listed one; on an
//! axis of a single cell all three images are tried, like the oracle does, and each that
//! overlaps is listed). For a wall, the centre is within `r_i` of it at `t`, so the wall is
//! within `r_i + h + rounding` of the cell of `X_i` and is filed there. For a box exit, the
//! body is on a face at `t`, so `X_i` is within `h + rounding` of that face, and cells are
//! wider than that: the cell of `X_i` is a border cell. So `E` is covered and
//! the top of the queue is `E`, as above.
//!
//! Edits behind the clock: a list rebuilt at `t_r` after an edit's time `t` leaves its body
//! possibly outside its shell at `t`; `update` rebuilds those lists again at `t` (a rebuild is
//! valid at any time: afterwards the body is in its shell from `t` to its next exit) and
//! recomputes their bodies, so every body is in its shell from the clock on.
//!
//! # Prefetch hints
//!
//! Once the records no longer fit in a core's cache, a collision waits on memory more than it
//! computes. When the finder's structures and the body records take 2 MiB or more
//! (`HINTS_FROM_BYTES`), `next_event`, as it returns an event, hints the lines its caller is
//! about to need: the cell records of both bodies' 3^D blocks (or both bodies' list blocks),
//! both bodies' paths in the queue, and the cached and body records of the holders of the
//! queue's runner-up key ([`TournamentQueue::runner_up`]), most often the next event. Those
//! misses then run while the caller resolves the event and rescans its bodies, instead of
//! one after another when each is needed. A scan hints its candidates' records (a list scan
//! its partners', a list rebuild its cells' slot records) before evaluating them, so the
//! misses of one scan overlap instead of waiting one after another. Hints are not loads: they
//! change no result and cannot fault ([`crate::prefetch`]). Below 2 MiB the data stays
//! cached and they would only cost instructions.
//!
//! # Edits behind the finder's clock
//!
//! `next_event` may process crossings beyond the time of a state change made afterwards (a
//! velocity set after peeking). `update` then undoes, latest first, every crossing processed
//! after the change's time (moving the body back and recomputing it), so cells again match
//! positions at that time.
//!
//! # Modules
//!
//! The two modes live in their own modules, chosen once by `init` ([`Mode`]): [`crossings`]
//! (the crossing, its undo log, the crossing-mode `recompute`, `schedule`, `update` and
//! `validate`) and [`lists`] (the lists, shells and their rebuilds, the list-mode
//! `recompute`, `schedule`, `update` and `validate`). What both use stays here and in
//! `predict` (cached predictions, walls, box exits), `grid`, `slots`, `gather`, `pair` (the
//! crossing mode's collision pair scan), `key` and `tournament` (the queue).

mod candidate;
mod crossings;
mod gather;
mod grid;
mod key;
mod lists;
mod options;
mod pair;
mod predict;
mod slots;
mod tournament;

use super::{DebugBox, Finder, FinderError, FinderMemory, FinderOptions};
use crate::contact::lees_edwards::ShearedBox;
use crate::event::Event;
use crate::geom::{Aabb, Vector};
use crate::prefetch::prefetch;
use crate::wall::Wall;
use crate::world::World;
use candidate::Probe;
use grid::{Grid, MARGIN};
use key::{Key, MAX_INDEX};
use lists::{Lists, MAX_LIST_BODIES};
pub use options::OPTIONS;
use predict::{Cached, UNKNOWN_CHANGES};
use tournament::TournamentQueue;

/// Crossing code of a body that crosses no face.
const NO_CROSSING: u8 = 0x7F;
/// Flag on a crossing code: the body's queue key is the crossing, not its cached event.
const KEY_IS_CROSSING: u8 = 0x80;
/// Flag on a second image code: the second cached event is known.
const SECOND_KNOWN: u8 = 0x80;
/// Working set (the finder's structures and the body records), bytes, from which prefetch
/// hints are given: below it the data stays in a core's level-2 cache (1 MiB and more on
/// current x86-64 cores), where a hint only costs instructions (callgrind, 2D N = 10⁴:
/// +20 % instructions with hints, no wall-clock gain).
const HINTS_FROM_BYTES: usize = 2 << 20;

/// Counters of a [`Cells`] finder since its last `init`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct CellsStats {
    /// Cell crossings processed (internal, never returned).
    pub crossings: u64,
    /// Cached events found stale at the top of the queue.
    pub stale: u64,
    /// Full neighbourhood scans.
    pub recomputes: u64,
    /// Crossings undone (list mode: lists rebuilt again) because a state changed behind
    /// them.
    pub undone: u64,
    /// Shell exits processed (list mode; internal, never returned).
    pub rebuilds: u64,
    /// Growing radii: whole rebuilds of the grid for a later horizon.
    pub regrids: u64,
}

/// The finder's mode, chosen once by `init` (see the module docs). Each has its own module:
/// [`crossings`] (cells crossed as bodies move, every world) and [`lists`] (Verlet
/// neighbour lists with a skin, periodic worlds); the code shared by both (the grid, the
/// cached predictions, the queue, walls and box exits) stays in this module and `predict`,
/// and dispatches on the mode once per entry point.
// One per finder: its size does not matter, and boxing the lists would add an indirection to
// every list scan.
#[allow(clippy::large_enum_variant)]
#[derive(Clone, Debug)]
enum Mode<const D: usize> {
    /// Cell crossings.
    Crossings,
    /// Cell crossings of bodies falling under gravity (the roots of quadratics): a mode of
    /// its own, so that the straight-line crossings pay nothing for gravity.
    FallingCrossings,
    /// Neighbour lists, with their structures.
    Lists(Lists<D>),
}

/// The volume (area) fraction of the bodies of `world`, radii scaled by `grown`, in the
/// periodic box of sides `size` (vacant slots left out).
fn packing_fraction<const D: usize>(world: &World<D>, grown: f64, size: &Vector<D>) -> f64 {
    let filled: f64 = (0..world.len())
        .filter(|&i| !world.is_vacant(i))
        .map(|i| crate::geom::ball_volume::<D>(world.radius(i) * grown))
        .sum();
    filled / size.0.iter().product::<f64>()
}

/// Largest `cells_skin` (relative to the largest contact distance).
pub const MAX_CELLS_SKIN: f64 = 1.0;
/// Smallest non-zero `cells_skin`.
pub const MIN_CELLS_SKIN: f64 = 1e-3;

/// Refuses a `cells_skin` the finder cannot run with: it must be 0 (cell crossings) or in
/// `[MIN_CELLS_SKIN, MAX_CELLS_SKIN]` (neighbour lists).
pub fn check_options(o: &FinderOptions) -> Result<(), FinderError> {
    let Some(s) = o.cells_skin else {
        return Ok(());
    };
    if s == 0.0 || (MIN_CELLS_SKIN..=MAX_CELLS_SKIN).contains(&s) {
        Ok(())
    } else {
        Err(FinderError::Option {
            option: "cells_skin",
            why: format!(
                "{s} is neither 0 nor in [{MIN_CELLS_SKIN}, {MAX_CELLS_SKIN}] (times the \
                 largest contact distance)"
            ),
        })
    }
}

/// The grid finder with cached predictions and an event queue; see the module docs.
#[derive(Clone, Debug)]
pub struct Cells<const D: usize> {
    grid: Grid<D>,
    /// Cached predictions of each body, one record per body.
    cached: Vec<Cached<D>>,
    queue: TournamentQueue,
    /// The world is periodic.
    periodic: bool,
    /// The sheared box, in a sheared world (see the module docs).
    shear: Option<ShearedBox<D>>,
    /// Wall index of the first periodic face (the number of walls).
    faces_from: usize,
    /// Crossings processed since the last `update`: body, code, time.
    log: Vec<(u32, u8, f64)>,
    /// Time of the last crossing processed or event returned: cells match positions then.
    clock: f64,
    /// Image shift of each image code.
    shifts: Vec<Vector<D>>,
    stats: CellsStats,
    peak_bytes: usize,
    /// The skin of the list mode relative to the largest contact distance (0: crossings).
    skin: f64,
    /// Whether the skin was left to the finder (`cells_skin` unset): it then chooses lists
    /// by the world's packing at each `init` ([`super::auto_cells_skin_at`]).
    auto_skin: bool,
    /// The mode `init` chose, with its structures.
    mode: Mode<D>,
    /// Prefetch hints are on: the working set is larger than a core's cache (see `init`).
    hints: bool,
    /// Growing worlds: the time up to which the grid (and lists) are sized for the contact
    /// distances; `+∞` when radii are fixed (see "Growing radii" in the module docs).
    horizon: f64,
    /// Growing worlds: a horizon asked for beyond the default one, for the next `init`.
    wanted_horizon: f64,
    /// Growing worlds: rebuilds since the last event returned.
    regrids_in_a_row: u32,
    /// The world's growth law, if radii grow: pairs then take the growing functions (and the
    /// four-lane kernel its growing form).
    growth: Option<crate::motion::GrowthLaw>,
    /// The world's laws, if any is in force (growth, gravity): what the narrow phase's
    /// dispatchers are given.
    laws: Option<crate::motion::Laws<D>>,
    /// The world's gravity, if any: crossings are then the roots of quadratics.
    gravity: Option<Vector<D>>,
    /// Which bodies are kinematic (they do not fall), by index; empty when none is.
    kinematic: Vec<bool>,
    /// Where bodies rest on walls (see [`crate::contact::resting`]): each body's acceleration
    /// ([`World::acceleration`]) by index; empty otherwise.
    accels: Vec<Vector<D>>,
    /// The world's collision filters by body index (see [`crate::collision_filter`]);
    /// empty when every pair collides.
    filters: Vec<crate::CollisionFilter>,
    /// True when any of `filters`, `kinematic` and `accels` is kept (see `update_mirrors`).
    mirrors: bool,
}

impl<const D: usize> Default for Cells<D> {
    fn default() -> Self {
        Self::new()
    }
}

impl<const D: usize> Cells<D> {
    /// An empty finder; [`Finder::init`] fills it.
    #[must_use]
    pub fn new() -> Self {
        Cells {
            grid: Grid::new(0, 1.0, Vector::ZERO, Vector::ZERO, None),
            cached: Vec::new(),
            queue: TournamentQueue::default(),
            periodic: false,
            shear: None,
            faces_from: 0,
            log: Vec::new(),
            clock: 0.0,
            shifts: Vec::new(),
            stats: CellsStats::default(),
            peak_bytes: 0,
            skin: 0.0,
            auto_skin: false,
            mode: Mode::Crossings,
            hints: false,
            horizon: f64::INFINITY,
            wanted_horizon: f64::NEG_INFINITY,
            regrids_in_a_row: 0,
            growth: None,
            laws: None,
            gravity: None,
            kinematic: Vec::new(),
            accels: Vec::new(),
            filters: Vec::new(),
            mirrors: false,
        }
    }

    /// A finder with the options `options` (`cells_skin`), refused as [`check_options`]
    /// says.
    pub fn with_options(options: &FinderOptions) -> Result<Self, FinderError> {
        check_options(options)?;
        Ok(Cells {
            skin: options.cells_skin.unwrap_or(super::auto_cells_skin(D)),
            auto_skin: options.cells_skin.is_none(),
            ..Self::new()
        })
    }

    /// True when the finder runs in list mode (set by `init`).
    #[must_use]
    pub fn uses_lists(&self) -> bool {
        matches!(self.mode, Mode::Lists(_))
    }

    /// Counters since the last `init`.
    #[must_use]
    pub fn stats(&self) -> CellsStats {
        self.stats
    }

    /// Cells per axis of the grid.
    #[must_use]
    pub fn grid_dims(&self) -> [usize; D] {
        self.grid.dims()
    }

    fn bytes(&self) -> usize {
        self.grid.bytes()
            + self.queue.bytes()
            + std::mem::size_of::<Cached<D>>() * self.cached.capacity()
            + std::mem::size_of::<(u32, u8, f64)>() * self.log.capacity()
            + match &self.mode {
                Mode::Crossings | Mode::FallingCrossings => 0,
                Mode::Lists(lists) => lists.bytes(),
            }
    }

    /// Checks the structures against `world`: the cell lists, the queue, every key being the
    /// minimum of the body's cached event and next crossing, and every body lying in its cell
    /// (up to rounding) at the finder's clock (the last crossing or event it went through).
    /// For tests.
    pub fn validate(&self, world: &World<D>) -> Result<(), String> {
        self.grid.validate(|i| self.cached[i].coords)?;
        self.queue.validate()?;
        match self.mode {
            Mode::Crossings | Mode::FallingCrossings => self.validate_crossing_mode(world),
            Mode::Lists(_) => self.validate_list_mode(world),
        }
    }

    /// Checks body `i`'s cached records, in either mode: no cached event that never happens,
    /// the runner-up not before the best, the partner's recorded change count neither
    /// ahead of the partner nor, when equal, naming an event that no longer re-evaluates bit
    /// for bit, and, for a body filed in a border cell of a periodic world, its box exit
    /// covered (not before its cached event, which is a lower bound of its covered terms).
    fn validate_cached(&self, world: &World<D>, i: usize) -> Result<(), String> {
        if self.periodic && self.grid.is_border(&self.cached[i].coords) {
            let exit = self.box_exit(world, &Probe::of(world, i));
            if exit.is_some_and(|exit| exit < self.cached[i].best) {
                return Err(format!(
                    "body {i}: its box exit is before its cached event in a border cell"
                ));
            }
        }
        for k in [self.cached[i].best, self.cached[i].second] {
            if k.time == Key::NEVER.time && !k.is_never() {
                return Err(format!("body {i}: cached an event that never happens"));
            }
        }
        if self.cached[i].best > self.cached[i].second
            && self.cached[i].second_image & SECOND_KNOWN != 0
        {
            return Err(format!("body {i}: second cached event before the first"));
        }
        let changes = self.cached[i].partner_changes;
        if let Some(j) = self.cached[i].best.partner(i) {
            if changes != UNKNOWN_CHANGES && changes > world.change_count(j) {
                return Err(format!("body {i}: partner {j}'s recorded count is ahead"));
            }
            if changes == world.change_count(j) && !self.evaluates_the_same(world, i) {
                return Err(format!(
                    "body {i}: cached event with unchanged partner {j} is not live"
                ));
            }
        } else if changes != UNKNOWN_CHANGES {
            return Err(format!("body {i}: a partner count without a partner"));
        }
        Ok(())
    }

    /// Hints the lines the caller of `next_event` needs next, for the event of `key`: it
    /// changes the event's bodies, then asks for their neighbourhoods and sets their keys
    /// (see the module docs).
    #[inline(never)]
    fn hint_event(&self, world: &World<D>, key: Key) {
        let a = key.event().a as usize;
        let partner = key.partner(a);
        for i in std::iter::once(a).chain(partner) {
            self.queue.prefetch_path(i);
            match &self.mode {
                Mode::Crossings | Mode::FallingCrossings => {
                    self.grid.prefetch_block(&self.cached[i].coords)
                }
                Mode::Lists(lists) => lists.prefetch_list(i),
            }
        }
        self.hint_runner_up(world);
    }

    /// Hints the first lines read for the queue's runner-up, most often the next key popped
    /// after the top's: they arrive while the top's is processed.
    #[inline(never)]
    fn hint_runner_up(&self, world: &World<D>) {
        let next = self.queue.runner_up();
        if !next.is_never() {
            let (b, c) = next.holders();
            self.queue.prefetch_path(b);
            for i in [b, c] {
                prefetch(&self.cached[i]);
                prefetch(&world.bodies()[i]);
            }
        }
    }
}

/// Growing radii: the grid is sized for the radii they reach when they have grown by this
/// fraction of their current size (see "Growing radii" in the module docs).
const GROWTH_HEADROOM: f64 = 0.05;

/// Growing radii: rebuilds in a row, each doubling the horizon, before a query is answered
/// by the all-pairs search instead (only bodies that never meet get there).
const MAX_REGRIDS_IN_A_ROW: u32 = 48;

impl<const D: usize> Cells<D> {
    /// Rebuilds the grid of a growing world for a horizon at `beyond` at least (its top key's
    /// time) and at least twice as far as the current one: `None` to go on with the query, or
    /// the query's answer when rebuilds no longer make progress (bodies that never meet).
    fn regrid(&mut self, world: &World<D>, beyond: f64) -> Option<Option<Event>> {
        self.regrids_in_a_row += 1;
        if self.regrids_in_a_row > MAX_REGRIDS_IN_A_ROW {
            self.regrids_in_a_row = 0;
            return Some(super::all_pairs_next_event(world));
        }
        let now = world.now();
        let window = 2.0 * (self.horizon - now).max(0.0);
        self.wanted_horizon = if beyond.is_finite() {
            beyond.max(now + window)
        } else {
            now + window
        };
        let (stats, regrids) = (self.stats, self.regrids_in_a_row);
        self.init(world)
            .expect("a world the finder served serves again");
        self.stats = stats;
        self.stats.regrids += 1;
        self.regrids_in_a_row = regrids;
        None
    }

    /// Copies the changed bodies' filters, kinematic flags and accelerations into the
    /// finder's mirrors of them. Out of line: a world without filters, kinematic bodies or
    /// resting contacts keeps no mirror, and its `update` tests one flag.
    #[inline(never)]
    fn update_mirrors(&mut self, world: &World<D>, changed: &[usize]) {
        if !self.filters.is_empty() {
            // A changed body may have changed its filter (`set_collision_filter`), or its
            // slot may have been emptied or filled (`remove_body`, `add_body`).
            for &i in changed {
                self.filters[i] = world.filters()[i];
            }
        }
        if !self.kinematic.is_empty() {
            for &i in changed {
                self.kinematic[i] = world.is_kinematic(i);
            }
        }
        if !self.accels.is_empty() {
            // A body comes to rest on a wall, or leaves it, only when its state changes.
            for &i in changed {
                self.accels[i] = world.acceleration(i);
            }
        }
    }
}

impl<const D: usize> Finder<D> for Cells<D> {
    fn name(&self) -> &'static str {
        "cells"
    }

    fn init(&mut self, world: &World<D>) -> Result<(), FinderError> {
        let unsupported = |why: &str| {
            Err(FinderError::Unsupported {
                finder: "cells",
                why: why.to_string(),
            })
        };
        if D > 3 {
            return unsupported("more than 3 dimensions");
        }
        let n = world.len();
        if n > MAX_INDEX || world.walls().len() + 2 * D > MAX_INDEX {
            return unsupported("more than 2^31 − 1 bodies or walls");
        }
        let now = world.now();
        // Growing radii: size everything for the radii at a horizon, rebuilt before it passes.
        self.horizon = f64::INFINITY;
        self.growth = world.growth().copied();
        self.laws = world.laws().copied();
        self.gravity = world.gravity();
        self.filters = world.filters().to_vec();
        self.kinematic = if world.has_kinematic() {
            (0..n).map(|i| world.is_kinematic(i)).collect()
        } else {
            Vec::new()
        };
        self.accels = if self.resting() {
            (0..n).map(|i| world.acceleration(i)).collect()
        } else {
            Vec::new()
        };
        self.mirrors =
            !(self.filters.is_empty() && self.kinematic.is_empty() && self.accels.is_empty());
        let mut grown = 1.0;
        if let Some(law) = world.growth() {
            let window = (law.scale(now) * GROWTH_HEADROOM / law.rate).max(0.0);
            self.horizon = (now + window).max(self.wanted_horizon);
            grown = law.scale(self.horizon);
        }
        self.wanted_horizon = f64::NEG_INFINITY;
        let (r1, r2) = world.two_largest_radii();
        let (r1, r2) = (r1 * grown, r2 * grown);
        let sigma_max = if n >= 2 { r1 + r2 } else { 2.0 * r1.max(0.5) };
        let period = world.periodic();
        self.periodic = period.is_some();
        self.shear = world.shear();
        self.faces_from = world.walls().len();
        let (mut lo, mut hi) = (Vector::ZERO, Vector::ZERO);
        if period.is_none() {
            lo = Vector::splat(f64::INFINITY);
            hi = Vector::splat(f64::NEG_INFINITY);
            let mut grow = |p: Vector<D>| {
                lo = lo.min(p);
                hi = hi.max(p);
            };
            for i in 0..n {
                grow(world.stored_position_at(i, now));
            }
            for wall in world.walls() {
                match *wall {
                    Wall::Segment { a, b } => {
                        grow(a);
                        grow(b);
                    }
                    Wall::Plane { point, .. } => grow(point),
                }
            }
            if n == 0 && world.walls().is_empty() {
                lo = Vector::ZERO;
                hi = Vector::ZERO;
            }
        }
        // List mode: periodic worlds only (in an open world a body flying off would leave
        // shells forever, where the crossings of the outer cells, which extend to infinity,
        // stop).
        let relative_skin = match period {
            Some(size) if self.auto_skin => {
                super::auto_cells_skin_at(D, packing_fraction(world, grown, &size))
            }
            _ => self.skin,
        };
        let list_mode =
            relative_skin > 0.0 && period.is_some() && self.shear.is_none() && n < MAX_LIST_BODIES;
        let skin = if list_mode {
            relative_skin * sigma_max
        } else {
            0.0
        };
        let slack = 4.0 * MARGIN * sigma_max;
        let width = if list_mode {
            (sigma_max + skin + slack) * (1.0 + MARGIN)
        } else {
            sigma_max * (1.0 + MARGIN)
        };
        self.grid = Grid::new(n, width, lo, hi, period);
        self.mode = if list_mode {
            Mode::Lists(Lists::new(
                n,
                skin,
                sigma_max + skin + slack,
                self.grid.cell_count(),
            ))
        } else {
            if world.gravity().is_some() {
                Mode::FallingCrossings
            } else {
                Mode::Crossings
            }
        };
        self.cached = vec![Cached::NONE; n];
        for i in 0..n {
            let p = world.stored_position_at(i, now);
            let k = self.grid.coords_of_point(&p);
            self.cached[i].coords = self.grid.insert(i, k);
            if let Mode::Lists(lists) = &mut self.mode {
                lists.centre[i] = p;
                let c = self.grid.cell_at(&self.cached[i].coords);
                lists.slots.insert(i, c, &p);
            }
        }
        self.grid
            .file_walls(world.walls(), r1 + 0.5 * skin + MARGIN * sigma_max + slack);
        self.shifts = (0..3usize.pow(D as u32))
            .map(|code| self.grid.shift_of(code as u8))
            .collect();
        if let Mode::Lists(lists) = &mut self.mode {
            lists.set_shifts(&self.shifts);
        }
        self.queue = TournamentQueue::new(n);
        self.log = Vec::new();
        self.clock = now;
        self.stats = CellsStats::default();
        if let Mode::Lists(_) = self.mode {
            self.build_all_lists(n);
        }
        for i in 0..n {
            self.recompute(world, i);
        }
        self.stats.recomputes = 0;
        self.peak_bytes = self.bytes();
        self.hints =
            self.peak_bytes + n * std::mem::size_of::<crate::motion::Body<D>>() >= HINTS_FROM_BYTES;
        Ok(())
    }

    fn update(&mut self, world: &World<D>, changed: &[usize]) {
        let Some(t) = changed
            .iter()
            .map(|&i| world.time(i))
            .min_by(f64::total_cmp)
        else {
            return;
        };
        if self.mirrors {
            self.update_mirrors(world, changed);
        }
        match self.mode {
            Mode::Crossings | Mode::FallingCrossings => {
                self.update_crossing_mode(world, t, changed)
            }
            Mode::Lists(_) => self.update_list_mode(world, t, changed),
        }
    }

    /// Every body recomputed through `update` (O(n) scans of its neighbourhood), keeping the
    /// grid, the wall filing and, in list mode, every list whose body is still inside its
    /// shell: a rebuild would file every body anew and build every list.
    fn all_changed(&mut self, world: &World<D>) -> Result<(), FinderError> {
        if world.len() != self.cached.len() {
            return self.init(world);
        }
        let all: Vec<usize> = (0..world.len()).collect();
        self.update(world, &all);
        Ok(())
    }

    fn next_event(&mut self, world: &World<D>) -> Option<Event> {
        loop {
            let Some(i) = self.queue.top() else {
                // Nothing left at a finite time. A growing world's bodies may still grow into
                // each other beyond the horizon, farther apart than the grid sized for it can
                // see (they never came near enough to be paired): rebuild it for a later one.
                if self.horizon < f64::INFINITY {
                    if let Some(answer) = self.regrid(world, f64::INFINITY) {
                        return answer;
                    }
                    continue;
                }
                return None;
            };
            let key = self.queue.top_key();
            if key.seconds() > self.horizon {
                // Growing radii: past the horizon the grid may miss contacts; rebuild it.
                if let Some(answer) = self.regrid(world, key.seconds()) {
                    return answer;
                }
                continue;
            }
            if key.seconds() == f64::INFINITY {
                // Every key is a lower bound of what it stands for (see above), so every
                // event left lies at an infinite time, which never comes (`finite_event`).
                return None;
            }
            if key.is_crossing() {
                match self.mode {
                    Mode::Crossings | Mode::FallingCrossings => self.cross(world, i, key.seconds()),
                    Mode::Lists(_) => self.exit_shell(world, i, key.seconds()),
                }
                continue;
            }
            if !self.is_live(world, i) {
                self.stats.stale += 1;
                if !self.promote_second(world, i) {
                    self.recompute(world, i);
                }
                continue;
            }
            let e = key.event();
            self.regrids_in_a_row = 0;
            self.clock = self.clock.max(e.time);
            if self.hints {
                self.hint_event(world, key);
            }
            return Some(e);
        }
    }

    fn debug_boxes(&mut self, _world: &World<D>) -> Vec<DebugBox<D>> {
        let mut out = Vec::new();
        for c in 0..self.grid.cell_count() as u32 {
            if self.grid.cell(c).len == 0 {
                continue;
            }
            let (lo, hi) = self.grid.nominal_box(&self.grid.coords(c));
            out.push(DebugBox {
                aabb: Aabb { min: lo, max: hi },
                depth: 0,
                leaf: false,
            });
        }
        out
    }

    fn counters(&self) -> Vec<(&'static str, u64)> {
        let s = self.stats;
        vec![
            ("crossings", s.crossings),
            ("stale", s.stale),
            ("recomputes", s.recomputes),
            ("undone", s.undone),
            ("rebuilds", s.rebuilds),
            ("regrids", s.regrids),
        ]
    }

    fn memory(&self) -> Option<FinderMemory> {
        let bytes = self.bytes();
        Some(FinderMemory {
            bytes,
            peak_bytes: self.peak_bytes.max(bytes),
        })
    }
}

#[cfg(test)]
mod tests;
