//! The textbook priority-queue finder of Sedgewick & Wayne's *Algorithms* (`CollisionSystem`),
//! the baseline the thesis cites and did not implement.
//!
//! Every prediction — each body against every other body and every wall — goes into one
//! binary min-heap. Nothing is ever removed eagerly: an entry remembers the change counts
//! ([`World::change_count`]) of its bodies when it was predicted, and is stale as soon as either
//! body's count moved on. When a body changes, its predictions against all others and all walls
//! are pushed again: O(n) time-of-impact evaluations and O(n log H) heap work per event, and up
//! to O(n²) entries held at once.
//!
//! # Why it is exact
//!
//! A valid entry (both counts current) was computed by the same pure function, with the same
//! argument order (lower index first, like [`all_pairs_next_event`](super::all_pairs_next_event)),
//! on the very stored states the oracle reads now, so its time is the oracle's bit for bit.
//! Every pair whose current time of impact exists has a valid entry: its prediction was pushed
//! the last time either body changed (or at `init`). Stale entries are skipped before the top is
//! returned, and the heap orders entries by [`Event`]'s total order first, so the valid top is
//! the oracle's minimum, ties included.
//!
//! In a periodic world ([`crate::contact::periodic`]) pairs are predicted by the oracle's periodic
//! function [`toi_circle_circle_periodic`](crate::contact::periodic::toi_circle_circle_periodic),
//! and each body's exit from the box is predicted with its walls, named like the oracle names it
//! (wall `walls.len() + face`): it depends on the body's state alone, like a wall event.

use super::{finite_event, Finder, FinderError, FinderMemory};
use crate::contact::lees_edwards::toi_bodies_sheared;
use crate::contact::periodic::{toi_bodies_periodic, toi_box_exit};
use crate::event::{Event, EventKind};
use crate::world::World;
use crate::world::{toi_bodies_in, toi_body_wall_in};
use std::cmp::Reverse;
use std::collections::BinaryHeap;

/// One prediction with the change counts of its bodies at prediction time, packed so that the
/// derived lexicographic order of the fields is [`Event`]'s total order (then the counts): the
/// heap compares two integers instead of a float, an enum and two indices.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
struct Entry {
    /// The time's bits mapped so that unsigned order is `f64::total_cmp`'s order.
    time_key: u64,
    /// `kind << 62 | a << 31 | b` (indices below 2³¹, checked by `init`).
    who: u64,
    /// Change count of body `a` when predicted.
    count_a: u64,
    /// Change count of body `b` (body events only; 0 for wall events).
    count_b: u64,
}

/// Indices must stay below this for [`Entry::who`]'s packing.
const MAX_INDEX: usize = 1 << 31;

impl Entry {
    #[inline]
    fn new(event: Event, count_a: u64, count_b: u64) -> Self {
        let bits = event.time.to_bits();
        let time_key = if bits >> 63 == 1 {
            !bits
        } else {
            bits | 1 << 63
        };
        let who = (event.kind as u64) << 62 | u64::from(event.a) << 31 | u64::from(event.b);
        Entry {
            time_key,
            who,
            count_a,
            count_b,
        }
    }

    #[inline]
    fn event(&self) -> Event {
        let bits = if self.time_key >> 63 == 1 {
            self.time_key & !(1 << 63)
        } else {
            !self.time_key
        };
        let mask = (1 << 31) - 1;
        Event {
            time: f64::from_bits(bits),
            kind: if self.who >> 62 == 0 {
                EventKind::Body
            } else {
                EventKind::Wall
            },
            a: ((self.who >> 31) & mask) as u32,
            b: (self.who & mask) as u32,
        }
    }

    #[inline]
    fn is_current<const D: usize>(&self, world: &World<D>) -> bool {
        let mask = (1 << 31) - 1;
        let a = ((self.who >> 31) & mask) as usize;
        let b = (self.who & mask) as usize;
        world.change_count(a) == self.count_a
            && (self.who >> 62 != 0 || world.change_count(b) == self.count_b)
    }
}

/// Counters of a [`Sedgewick`] finder since its last `init`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct SedgewickStats {
    /// Entries in the queue now (current and stale).
    pub queue_len: usize,
    /// Largest number of entries the queue ever held.
    pub peak_queue_len: usize,
    /// Entries pushed in total.
    pub pushed: u64,
    /// Stale entries discarded from the top.
    pub discarded: u64,
}

/// The priority-queue finder: one heap of every prediction, invalidated lazily by change counts.
#[derive(Clone, Debug, Default)]
pub struct Sedgewick {
    heap: BinaryHeap<Reverse<Entry>>,
    stats: SedgewickStats,
}

impl Sedgewick {
    /// Bytes taken by one queue entry.
    pub const ENTRY_BYTES: usize = std::mem::size_of::<Reverse<Entry>>();

    /// An empty finder; [`Finder::init`] fills it.
    #[must_use]
    pub fn new() -> Self {
        Self::default()
    }

    /// Queue counters since the last `init`.
    #[must_use]
    pub fn stats(&self) -> SedgewickStats {
        SedgewickStats {
            queue_len: self.heap.len(),
            ..self.stats
        }
    }

    fn push(&mut self, entry: Entry) {
        self.heap.push(Reverse(entry));
        self.stats.pushed += 1;
        self.stats.peak_queue_len = self.stats.peak_queue_len.max(self.heap.len());
    }

    /// Pushes body `i`'s predictions against every body `j` for which `skip(j)` is false, and
    /// against every wall.
    fn predict<const D: usize>(
        &mut self,
        world: &World<D>,
        i: usize,
        skip: impl Fn(usize) -> bool,
    ) {
        let mi = world.motion(i);
        let ci = world.change_count(i);
        let (period, shear) = (world.periodic(), world.shear());
        for j in 0..world.len() {
            if j == i || skip(j) || !world.collides(i, j) {
                continue;
            }
            // The oracle's argument order: lower index first.
            let (a, b) = if i < j { (i, j) } else { (j, i) };
            let t = match (&period, &shear) {
                (None, _) => toi_bodies_in(world, a, b),
                (Some(size), None) => {
                    let bodies = world.bodies();
                    toi_bodies_periodic(&bodies[a], &bodies[b], size, world.laws())
                }
                (Some(_), Some(bx)) => {
                    let bodies = world.bodies();
                    toi_bodies_sheared(&bodies[a], &bodies[b], bx, world.laws())
                }
            };
            if let Some(t) = t {
                self.push(Entry::new(
                    Event::body(t, a, b),
                    world.change_count(a),
                    world.change_count(b),
                ));
            }
        }
        for w in 0..world.walls().len() {
            if let Some(t) = toi_body_wall_in(world, i, w) {
                self.push(Entry::new(Event::wall(t, i, w), ci, 0));
            }
        }
        if let Some((t, face)) = period.and_then(|size| toi_box_exit(&mi, &size)) {
            let exit = world.walls().len() + face;
            self.push(Entry::new(Event::wall(t, i, exit), ci, 0));
        }
    }
}

impl<const D: usize> Finder<D> for Sedgewick {
    fn name(&self) -> &'static str {
        "sedgewick"
    }

    fn init(&mut self, world: &World<D>) -> Result<(), FinderError> {
        // Box exits are named after the walls, two faces per axis.
        if world.len() > MAX_INDEX || world.walls().len() + 2 * D > MAX_INDEX {
            return Err(FinderError::Unsupported {
                finder: "sedgewick",
                why: "more than 2^31 bodies or walls".into(),
            });
        }
        self.heap = BinaryHeap::new();
        self.stats = SedgewickStats::default();
        for i in 0..world.len() {
            // Pairs (i, j) with j < i were pushed while predicting for j.
            self.predict(world, i, |j| j < i);
        }
        Ok(())
    }

    fn update(&mut self, world: &World<D>, changed: &[usize]) {
        for (k, &c) in changed.iter().enumerate() {
            // A pair of two changed bodies is predicted once, by the first of them.
            let before = &changed[..k];
            if before.contains(&c) {
                continue;
            }
            self.predict(world, c, |j| before.contains(&j));
        }
    }

    fn next_event(&mut self, world: &World<D>) -> Option<Event> {
        while let Some(Reverse(top)) = self.heap.peek() {
            if top.is_current(world) {
                return finite_event(Some(top.event()));
            }
            self.heap.pop();
            self.stats.discarded += 1;
        }
        None
    }

    fn memory(&self) -> Option<FinderMemory> {
        Some(FinderMemory {
            bytes: self.heap.len() * Self::ENTRY_BYTES,
            peak_bytes: self.stats.peak_queue_len * Self::ENTRY_BYTES,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::finder::all_pairs_next_event;
    use crate::generate::{gas, GasConfig};
    use crate::sim::Simulation;

    /// Runs `events` events with the sedgewick finder and checks every one against the oracle
    /// on the same state.
    fn differential<const D: usize>(scene: &crate::Scene<D>, events: u64) -> u64 {
        let mut sim = Simulation::with_finder(scene, Box::new(Sedgewick::new())).unwrap();
        let mut n = 0;
        while n < events {
            let expected = all_pairs_next_event(sim.world());
            let got = sim.peek_event();
            match (expected, got) {
                (Some(e), Some(g)) => {
                    assert_eq!(
                        e.time.to_bits(),
                        g.time.to_bits(),
                        "event {n}: {e:?} vs {g:?}"
                    );
                    assert_eq!((e.kind, e.a, e.b), (g.kind, g.a, g.b), "event {n}");
                }
                (None, None) => break,
                (e, g) => panic!("event {n}: oracle {e:?}, sedgewick {g:?}"),
            }
            sim.step_event();
            n += 1;
        }
        n
    }

    #[test]
    fn matches_oracle_on_a_small_gas() {
        let scene: crate::Scene<2> = gas(&GasConfig {
            n: 40,
            packing: 0.3,
            radius_min: 0.3,
            radius_max: 0.8,
            seed: 3,
            ..GasConfig::default()
        })
        .unwrap();
        assert_eq!(differential(&scene, 3000), 3000);
    }

    #[test]
    fn packing_keeps_the_event_order() {
        let times = [
            -1.5,
            -0.0,
            0.0,
            1e-300,
            0.5,
            0.5000000000000001,
            3.0,
            f64::INFINITY,
        ];
        let mut events = Vec::new();
        for &t in &times {
            events.push(Event::body(t, 0, 1));
            events.push(Event::body(t, 2, 7));
            events.push(Event::body(t, MAX_INDEX - 2, MAX_INDEX - 1));
            events.push(Event::wall(t, 0, 3));
            events.push(Event::wall(t, MAX_INDEX - 1, 0));
        }
        for x in &events {
            let ex = Entry::new(*x, 5, 6);
            let back = ex.event();
            assert_eq!(x.time.to_bits(), back.time.to_bits());
            assert_eq!((x.kind, x.a, x.b), (back.kind, back.a, back.b));
            for y in &events {
                assert_eq!(x.cmp(y), ex.cmp(&Entry::new(*y, 5, 6)), "{x:?} vs {y:?}");
            }
        }
    }

    #[test]
    fn empty_world_has_no_event() {
        let scene = crate::Scene::<3>::default();
        let mut sim = Simulation::with_finder(&scene, Box::new(Sedgewick::new())).unwrap();
        assert!(sim.step_event().is_none());
    }

    #[test]
    fn stale_entries_are_discarded_and_peak_tracked() {
        let scene: crate::Scene<2> = gas(&GasConfig {
            n: 30,
            packing: 0.3,
            seed: 9,
            ..GasConfig::default()
        })
        .unwrap();
        let mut world = World::from_scene(&scene).unwrap();
        let mut f = Sedgewick::new();
        Finder::<2>::init(&mut f, &world).unwrap();
        let first = f.stats();
        assert_eq!(first.queue_len, first.peak_queue_len);
        assert_eq!(first.pushed as usize, first.queue_len);
        for _ in 0..500 {
            let e = f.next_event(&world).unwrap();
            assert_eq!(Some(e), all_pairs_next_event(&world));
            world.set_now(e.time.max(world.now()));
            let (a, b) = (e.a as usize, e.b as usize);
            match e.kind {
                EventKind::Body => {
                    crate::resolve::resolve_body_body(&mut world, a, b, e.time);
                    f.update(&world, &[a, b]);
                }
                EventKind::Wall => {
                    crate::resolve::resolve_body_wall(&mut world, a, b, e.time);
                    f.update(&world, &[a]);
                }
                EventKind::Reset | EventKind::Edit => {
                    panic!("finders never predict resets or edits")
                }
            }
        }
        let s = f.stats();
        assert!(s.discarded > 0, "{s:?}");
        assert!(s.peak_queue_len >= s.queue_len && s.peak_queue_len > first.peak_queue_len);
        assert_eq!(s.pushed, s.discarded + s.queue_len as u64);
        let mem = Finder::<2>::memory(&f).unwrap();
        assert_eq!(mem.peak_bytes, s.peak_queue_len * Sedgewick::ENTRY_BYTES);
    }
}
