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

use super::{Finder, FinderError, FinderMemory};
use crate::event::{Event, EventKind};
use crate::narrow::{toi_circle_circle, toi_circle_wall};
use crate::world::World;
use std::cmp::{Ordering, Reverse};
use std::collections::BinaryHeap;

/// One prediction with the change counts of its bodies at prediction time.
#[derive(Clone, Copy, Debug)]
struct Entry {
    event: Event,
    /// Change count of body `event.a` when predicted.
    count_a: u64,
    /// Change count of body `event.b` (body events only; 0 for wall events).
    count_b: u64,
}

impl Entry {
    fn is_current<const D: usize>(&self, world: &World<D>) -> bool {
        let e = &self.event;
        world.change_count(e.a as usize) == self.count_a
            && (e.kind == EventKind::Wall || world.change_count(e.b as usize) == self.count_b)
    }
}

// Ordered by the event first, so the heap's minimum among current entries is the oracle's
// event; the counts only make the order total.
impl Ord for Entry {
    fn cmp(&self, o: &Self) -> Ordering {
        self.event
            .cmp(&o.event)
            .then(self.count_a.cmp(&o.count_a))
            .then(self.count_b.cmp(&o.count_b))
    }
}
impl PartialOrd for Entry {
    fn partial_cmp(&self, o: &Self) -> Option<Ordering> {
        Some(self.cmp(o))
    }
}
impl PartialEq for Entry {
    fn eq(&self, o: &Self) -> bool {
        self.cmp(o) == Ordering::Equal
    }
}
impl Eq for Entry {}

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
        let radii = world.radii();
        let mi = world.motion(i);
        let ci = world.change_count(i);
        for j in 0..world.len() {
            if j == i || skip(j) {
                continue;
            }
            // The oracle's argument order: lower index first.
            let (a, b) = if i < j { (i, j) } else { (j, i) };
            let (ma, mb) = if i < j {
                (mi, world.motion(j))
            } else {
                (world.motion(j), mi)
            };
            if let Some(t) = toi_circle_circle(&ma, radii[a], &mb, radii[b]) {
                self.push(Entry {
                    event: Event::body(t, a, b),
                    count_a: world.change_count(a),
                    count_b: world.change_count(b),
                });
            }
        }
        for (w, wall) in world.walls().iter().enumerate() {
            if let Some(t) = toi_circle_wall(&mi, radii[i], wall) {
                self.push(Entry {
                    event: Event::wall(t, i, w),
                    count_a: ci,
                    count_b: 0,
                });
            }
        }
    }
}

impl<const D: usize> Finder<D> for Sedgewick {
    fn name(&self) -> &'static str {
        "sedgewick"
    }

    fn init(&mut self, world: &World<D>) -> Result<(), FinderError> {
        if world.len() > u32::MAX as usize || world.walls().len() > u32::MAX as usize {
            return Err(FinderError::Unsupported {
                finder: "sedgewick",
                why: "more than 2^32 bodies or walls".into(),
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
                return Some(top.event);
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
