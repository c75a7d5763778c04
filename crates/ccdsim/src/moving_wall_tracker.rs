//! Each body's next contact with a moving wall, in a priority queue (see
//! [`crate::world::time_of_impact`]).
//!
//! A body's next contact is the earliest over the moving walls of
//! [`toi_body_moving_wall`]: O(walls) when its motion changes, O(n · walls) when a wall's
//! velocity does. Queue entries of a body recomputed since are stale and skipped; the queue
//! is rebuilt from the live entries when stale ones outnumber them, so it never holds more
//! than about twice as many entries as bodies.

use crate::event::Event;
use crate::world::toi_body_moving_wall;
use crate::world::World;
use std::cmp::Reverse;
use std::collections::BinaryHeap;

/// One body's next moving-wall contact, queued with the body's epoch at the time.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
struct Pending {
    event: Event,
    epoch: u32,
}

/// Every body's next contact with a moving wall.
#[derive(Clone, Debug)]
pub struct MovingWallTracker {
    /// Per body, its next contact (a wall event naming the wall after the static ones).
    next: Vec<Option<Event>>,
    /// Per body, how many times its next contact was recomputed.
    epoch: Vec<u32>,
    queue: BinaryHeap<Reverse<Pending>>,
}

impl MovingWallTracker {
    /// Every body's next contact with `world`'s moving walls.
    #[must_use]
    pub fn new<const D: usize>(world: &World<D>) -> Self {
        let mut tracker = MovingWallTracker {
            next: Vec::new(),
            epoch: Vec::new(),
            queue: BinaryHeap::new(),
        };
        tracker.walls_changed(world);
        tracker
    }

    /// The first contact of body `i` with any moving wall, as an event: the earliest, and the
    /// lowest wall index on a tie.
    fn first_contact<const D: usize>(world: &World<D>, i: usize) -> Option<Event> {
        if world.has_resting() && world.pivot(i).is_some() {
            // Parked while it turns: its contacts are the simulation's pivot events.
            return None;
        }
        let first = world.walls().len();
        (0..world.moving_wall_count())
            .filter_map(|k| {
                toi_body_moving_wall(world, i, k)
                    .filter(|t| t.is_finite())
                    .map(|t| Event::wall(t, i, first + k))
            })
            .min()
    }

    /// Body `i`'s stored motion changed (a collision, an edit, an add or a removal): its next
    /// contact is computed anew. Bodies past the slots known so far are added.
    pub fn body_changed<const D: usize>(&mut self, world: &World<D>, i: usize) {
        if i >= self.next.len() {
            self.next.resize(world.len(), None);
            self.epoch.resize(world.len(), 0);
        }
        self.epoch[i] = self.epoch[i].wrapping_add(1);
        self.next[i] = Self::first_contact(world, i);
        if let Some(event) = self.next[i] {
            self.queue.push(Reverse(Pending {
                event,
                epoch: self.epoch[i],
            }));
        }
        if self.queue.len() > 2 * self.next.len() + 64 {
            self.requeue();
        }
    }

    /// A wall's motion changed, or every body's did: every body's next contact is computed
    /// anew. O(n · walls).
    pub fn walls_changed<const D: usize>(&mut self, world: &World<D>) {
        let n = world.len();
        self.next = (0..n).map(|i| Self::first_contact(world, i)).collect();
        self.epoch.resize(n, 0);
        self.requeue();
    }

    /// Rebuilds the queue from the live entries.
    fn requeue(&mut self) {
        let entries: Vec<Reverse<Pending>> = self
            .next
            .iter()
            .zip(&self.epoch)
            .filter_map(|(e, &epoch)| e.map(|event| Reverse(Pending { event, epoch })))
            .collect();
        self.queue = BinaryHeap::from(entries);
    }

    /// The earliest contact of any body with any moving wall under the events' total order,
    /// if there is one.
    pub fn next_event(&mut self) -> Option<Event> {
        while let Some(&Reverse(p)) = self.queue.peek() {
            let i = p.event.a as usize;
            if p.epoch == self.epoch[i] {
                return Some(p.event);
            }
            self.queue.pop();
        }
        None
    }
}
