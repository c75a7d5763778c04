//! The thesis's broad phase (§4.4–4.7, Algorithm 4): a bounding-volume hierarchy over swept
//! boxes with an adaptive time step Δ, rebuilt for every event.
//!
//! # The method
//!
//! For a query at the world's current time `now`, every body gets a leaf box enclosing its
//! ball at `now` and at `now + Δ` (for straight-line motion, that box holds the ball at every
//! time in between). The tree is built top-down by splitting the bodies at the median of an
//! axis that cycles with the level (x, y, then z), with `select_nth_unstable` (linear time),
//! into a flat balanced array (`SweptTree::build` in `tree.rs`). Algorithm 3's self- and
//! pair-checks (`SweptTree::earliest_body_event`) hand every pair of bodies
//! whose leaf boxes overlap to the narrow phase, which keeps the earliest event with time
//! ≤ `now + Δ`. While none is found, Δ ← Δ·grow and the boxes are refitted leaves-to-root
//! ("Update Hierarchy", `SweptTree::refit`); once one is found,
//! Δ ← Δ·shrink. `grow`, `shrink` and the first Δ come from [`FinderOptions`] (thesis: 2,
//! ½). Δ never shrinks below [`MIN_DT_FRACTION`] of the first Δ, so a burst of simultaneous
//! events cannot drive it to zero (from where growing would never end).
//!
//! # Why the event is exactly the oracle's
//!
//! Candidates are accepted only if their computed time is ≤ `now + Δ`, and the minimum is
//! taken under the event order. So if every pair whose computed time of impact lies in
//! `[now, now + Δ]` reaches the narrow phase, the accepted minimum is the minimum over all
//! pairs, bit for bit (the narrow phase is the very function the oracle calls, with the lower
//! index first), and when nothing is accepted, every pair's event is later than `now + Δ`.
//!
//! Two facts make every such pair reach the narrow phase:
//!
//! - **No event lies before `now`.** Every pair's time of impact is ≥ `now` on every state a
//!   [`Simulation`](crate::sim::Simulation) produces: initially all reference times equal
//!   `now`; a pair of unchanged bodies keeps the time it had at the last query, which was not
//!   earlier than the event then resolved (the minimum), which became `now`; a pair with a
//!   changed body is evaluated from that body's new reference time, which is `now`.
//!   (`run_until` moves `now` forward only past times with no event.) So a computed time
//!   ≤ `now + Δ` lies in `[now, now + Δ]`, the interval the leaf boxes sweep.
//! - **Rounding cannot separate the boxes.** At the computed time the two balls are within
//!   their contact distance up to rounding, so both lie in their swept boxes up to rounding.
//!   The narrow phase's root is the exact root of a quadratic whose coefficients carry
//!   relative errors of a few ε, so at the computed time the squared gap is off by at most
//!   about 20·ε·M², M = σ + |Δv|·(time since the later reference time) — a distance error of
//!   about √(20ε)·M ≈ 7·10⁻⁸·M, even for grazing contacts. Positions `p + v·(t − t_i)` and the
//!   event time `t0 + dt` carry errors of a few ε times the coordinates' and absolute times'
//!   magnitudes. Each leaf box is therefore padded by
//!   `1e-5·(r + |v|₁·(now + Δ − t_i)) + 1e-12·(|p|∞ + |v|₁·(|t_i| + |now + Δ|))`
//!   (`swept_box` in `tree.rs`); the pair's two paddings sum to more than a hundred
//!   times the first bound and thousands of times the second, and cost nothing measurable.
//!
//! # Walls
//!
//! Walls are few and never move, so they stay out of the tree: each body's earliest wall
//! event (over all walls, ties by wall index) is cached with the body's
//! [`World::change_count`] and recomputed only when that count moves — after an event, for the
//! one or two bodies involved, O(walls) each. The earliest wall event `W` is the minimum of
//! the cache (a linear scan). The Δ loop also stops once `now + Δ ≥ W.time` with no body event
//! found: every body event is then later than `W`, which is the answer. The final answer is
//! the earlier of the body event and `W` under the event order.
//!
//! # Periodic boxes
//!
//! In a periodic world ([`crate::contact::periodic`]) the oracle's time for a pair is the earliest
//! contact over the images `k·L`, `k ∈ {−1, 0, 1}^D`, of the second body
//! ([`crate::contact::periodic::toi_circle_circle_periodic`]), and each body's exit from the box is
//! an event named like a wall. Exits depend on one body's state, so they go into the wall cache beside the walls
//! (a periodic scene has none) and bound the growth of Δ like wall events do. The tree is
//! built over the stored positions, which lie in the box, as before; besides its self-check
//! it is pair-checked against each of its images shifted by `k·L` for half of the non-zero
//! `k` (those whose first non-zero component is positive; `SweptTree::shifts`). Every pair
//! that reaches the narrow phase, by any check, is evaluated by the oracle's periodic
//! function with the lower index first, so a pair evaluated twice gives the same time twice.
//!
//! Why every pair with a time in `[now, now + Δ]` still reaches it: at the computed time `t`
//! the first body touches the second's image `k` up to rounding, so the first body's box
//! overlaps the second's shifted by `k·L` (the argument above, the shift being one more
//! rounded addition); the same boxes shifted back by `−k·L` overlap too, so whichever of `k`
//! and `−k` is in the half finds the pair. A shifted box is grown by `4·10⁻¹²·max L`, which
//! covers the few ε of `L` that the shift adds to the box and to the narrow phase's
//! displacement thousands of times over.
//!
//! In a sheared box ([`crate::contact::lees_edwards`]) the layers above and below slide along
//! x, so only the shifts within the layer (`k_y = 0`) are fixed. The tree is also checked
//! against the layer above (`k_y = 1`, so a pair touching through the layer below is found
//! from its other body): for each `k_z` and every x image `k_x` whose box can meet the tree's,
//! a box shifted by `L_y` along y and along x by anything from the strain offset at the
//! build plus `k_x L_x` to that plus how far the layer slides until the horizon, which holds
//! the image at every instant of the interval. Pairs are evaluated by the oracle's sheared
//! function. When the layer would slide past more than 64 periods over the interval, every
//! pair is checked instead.
//!
//! # Termination
//!
//! With no event left to happen, Δ would grow for ever. The search is bounded instead:
//!
//! - fewer than two bodies, or no body moving (every pair then has a zero relative velocity
//!   and never approaches): the answer is `W` at once (`None` when nothing moves); in a
//!   sheared box the layers' speed counts as motion (bodies at rest meet images that slide);
//! - otherwise Δ grows at most up to [`FAR_FACTOR`] times the time the fastest body needs to
//!   cross the current extent of all bodies (or for [`MAX_GROWTHS`] steps); if nothing is
//!   found by then, every pair is checked once (O(n²)) and the exact minimum returned, `None`
//!   included. In a walled scene `W` stops the growth long before; the fallback is for open
//!   scenes whose bodies are flying apart. It is also taken if any swept box overflows.
//!
//! The answer is a function of the stored states only, so while no body's change count moves
//! (a repeated query), the last answer is returned without searching.

mod build;
mod options;
mod refit;
mod traverse;
mod tree;
mod validate;
mod walls;

#[cfg(test)]
mod tests;

pub use options::OPTIONS;
pub use validate::InvalidTree;

use super::{finite_event, DebugBox, Finder, FinderError, FinderOptions};
use crate::contact::lees_edwards::toi_bodies_sheared;
use crate::contact::periodic::toi_bodies_periodic;
use crate::event::Event;
use crate::world::toi_bodies_in;
use crate::world::World;
use tree::{children, l1, SweptTree};
use walls::WallCache;

/// Δ never shrinks below this fraction of the first Δ (`FinderOptions::bvh_initial_dt`).
pub const MIN_DT_FRACTION: f64 = 1e-12;

/// Δ stops growing at this many times the time the fastest body needs to cross the extent
/// of all bodies (L1 lengths); beyond it, every pair is checked once.
pub const FAR_FACTOR: f64 = 4.0;

/// At most this many growth steps per query before every pair is checked once.
pub const MAX_GROWTHS: u32 = 256;

/// Work counters of a [`BvhFinder`], for benchmarks and tests.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct BvhStats {
    /// Queries answered by a search (not from the unchanged-state cache).
    pub searches: u64,
    /// Trees built (one per search with at least two moving bodies).
    pub builds: u64,
    /// Refits after Δ grew.
    pub refits: u64,
    /// Body pairs handed to the narrow phase by traversals.
    pub narrow_calls: u64,
    /// Searches that ended by checking every pair (see the module docs, "Termination").
    pub exhaustive: u64,
}

/// The `bvh` finder: the thesis's method, bit-identical to [`AllPairs`](super::AllPairs).
#[derive(Clone, Debug)]
pub struct BvhFinder<const D: usize> {
    grow: f64,
    shrink: f64,
    initial_dt: f64,
    delta: f64,
    tree: SweptTree<D>,
    walls: WallCache,
    last: Option<Option<Event>>,
    stats: BvhStats,
}

/// Refuses options the method cannot run with: `bvh_grow` must be finite and > 1,
/// `bvh_shrink` in (0, 1], `bvh_initial_dt` finite and > 0.
pub fn check_options(o: &FinderOptions) -> Result<(), FinderError> {
    let bad = |option, why: String| Err(FinderError::Option { option, why });
    if !(o.bvh_grow > 1.0 && o.bvh_grow.is_finite()) {
        return bad(
            "bvh_grow",
            format!("{} is not a finite number greater than 1", o.bvh_grow),
        );
    }
    if !(o.bvh_shrink > 0.0 && o.bvh_shrink <= 1.0) {
        return bad("bvh_shrink", format!("{} is outside (0, 1]", o.bvh_shrink));
    }
    if !(o.bvh_initial_dt > 0.0 && o.bvh_initial_dt.is_finite()) {
        return bad(
            "bvh_initial_dt",
            format!("{} is not a finite number greater than 0", o.bvh_initial_dt),
        );
    }
    Ok(())
}

impl<const D: usize> BvhFinder<D> {
    /// A finder with the grow and shrink factors and first Δ of `options`; refuses them as
    /// [`check_options`] says.
    pub fn new(options: &FinderOptions) -> Result<Self, FinderError> {
        check_options(options)?;
        Ok(BvhFinder {
            grow: options.bvh_grow,
            shrink: options.bvh_shrink,
            initial_dt: options.bvh_initial_dt,
            delta: options.bvh_initial_dt,
            tree: SweptTree::default(),
            walls: WallCache::default(),
            last: None,
            stats: BvhStats::default(),
        })
    }

    /// The current time step Δ, seconds: the swept interval the next search starts with.
    #[must_use]
    pub fn delta(&self) -> f64 {
        self.delta
    }

    /// Work counters since [`Finder::init`].
    #[must_use]
    pub fn stats(&self) -> BvhStats {
        self.stats
    }

    /// Checks the hierarchy as the last search (or [`Finder::debug_boxes`]) left it against
    /// `world`, which must not have changed since: shape, boxes enclosing children and swept
    /// bodies, median split. For tests.
    pub fn validate(&self, world: &World<D>) -> Result<(), InvalidTree> {
        self.tree.validate(world)
    }

    /// Builds the tree for the current time and Δ (what a search starts with).
    fn build(&mut self, world: &World<D>) {
        let now = world.now();
        self.tree.build(world, now, now + self.delta);
    }

    /// Algorithm 4 with walls and the termination rule of the module docs; `wall` is the
    /// earliest wall event.
    fn search(&mut self, world: &World<D>, wall: Option<Event>) -> Option<Event> {
        self.stats.searches += 1;
        // Under gravity the stored velocities hold at different times: take them now.
        let now = world.now();
        let mut v_max = match world.gravity() {
            None => world.velocities().map(l1).fold(0.0, f64::max),
            Some(_) => (0..world.len())
                .map(|i| l1(world.stored_velocity_at(i, now)))
                .fold(0.0, f64::max),
        };
        if let Some(bx) = world.shear() {
            // The layers above and below slide past: bodies at rest still meet their images.
            v_max += bx.layer_speed().abs();
        }
        // Under gravity bodies at rest now still fall into each other, and growing ones grow
        // into each other.
        if world.len() < 2
            || (v_max == 0.0 && world.gravity().is_none() && world.growth().is_none())
        {
            return wall;
        }
        self.build(world);
        self.stats.builds += 1;
        let extent = self.tree.extent_now;
        let far = FAR_FACTOR * l1(extent.max - extent.min) / v_max;
        let mut growths = 0;
        let body = loop {
            if !self.tree.finite {
                break self.exhaustive(world);
            }
            let found = self.tree.earliest_body_event(world);
            if found.too_wide {
                break self.exhaustive(world);
            }
            self.stats.narrow_calls += found.narrow_calls;
            if found.best.is_some() {
                break found.best;
            }
            if wall.is_some_and(|w| w.time <= self.tree.horizon) {
                break None; // every body event is later than the wall event
            }
            if self.delta >= far || far.is_nan() || growths >= MAX_GROWTHS {
                break self.exhaustive(world);
            }
            self.delta = (self.delta * self.grow).min(far);
            growths += 1;
            self.stats.refits += 1;
            self.tree.refit(world, now + self.delta);
        };
        self.delta = (self.delta * self.shrink).max(self.initial_dt * MIN_DT_FRACTION);
        Event::earliest(body, wall)
    }

    /// The earliest body–body event over every pair, as the oracle computes it.
    fn exhaustive(&mut self, world: &World<D>) -> Option<Event> {
        self.stats.exhaustive += 1;
        let mut best = None;
        for i in 0..world.len() {
            for j in i + 1..world.len() {
                if !world.collides(i, j) {
                    continue;
                }
                let bodies = world.bodies();
                let t = match (world.periodic(), world.shear()) {
                    (None, _) => toi_bodies_in(world, i, j),
                    (Some(size), None) => {
                        toi_bodies_periodic(&bodies[i], &bodies[j], &size, world.laws())
                    }
                    (Some(_), Some(bx)) => {
                        toi_bodies_sheared(&bodies[i], &bodies[j], &bx, world.laws())
                    }
                };
                if let Some(t) = t {
                    best = Event::earliest(best, Some(Event::body(t, i, j)));
                }
            }
        }
        best
    }
}

impl<const D: usize> Finder<D> for BvhFinder<D> {
    fn name(&self) -> &'static str {
        "bvh"
    }

    fn init(&mut self, _world: &World<D>) -> Result<(), FinderError> {
        self.delta = self.initial_dt;
        self.tree = SweptTree::default();
        self.walls.clear();
        self.last = None;
        self.stats = BvhStats::default();
        Ok(())
    }

    fn update(&mut self, _world: &World<D>, _changed: &[usize]) {
        // Nothing to do: the tree is rebuilt per query, and the wall cache and the answer
        // cache notice changed bodies through their change counts.
    }

    fn next_event(&mut self, world: &World<D>) -> Option<Event> {
        let recomputed = self.walls.refresh(world);
        if recomputed == 0 {
            if let Some(answer) = self.last {
                return answer;
            }
        }
        let answer = finite_event(self.search(world, self.walls.earliest()));
        self.last = Some(answer);
        answer
    }

    /// Every node's box for the current time and Δ, root at depth 0.
    fn debug_boxes(&mut self, world: &World<D>) -> Vec<DebugBox<D>> {
        self.build(world);
        let mut out = Vec::with_capacity(self.tree.nodes.len());
        let mut stack = Vec::new();
        if !self.tree.nodes.is_empty() {
            stack.push((0, 0));
        }
        while let Some((k, depth)) = stack.pop() {
            let node = self.tree.nodes[k];
            out.push(DebugBox {
                aabb: node.aabb,
                depth,
                leaf: node.is_leaf(),
            });
            if !node.is_leaf() {
                let (l, r) = children(k, node.count);
                stack.push((r, depth + 1));
                stack.push((l, depth + 1));
            }
        }
        out
    }
}
