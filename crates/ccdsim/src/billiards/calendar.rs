//! The `sedgewick` finder's event calendar on a pool table: every prediction in a priority
//! queue, stale ones dropped as they surface (Sedgewick's event-driven simulation, as the
//! scenes' `sedgewick` finder keeps it).

use std::cmp::{Ordering, Reverse};
use std::collections::BinaryHeap;

use super::shot_event::{earlier, ShotEvent};

/// A prediction and the versions of its balls when it was made.
#[derive(Clone, Copy, Debug)]
struct Entry {
    event: ShotEvent,
    /// The ball (or lower-numbered ball) and its version.
    a: (u32, u64),
    /// The higher-numbered ball of a meeting and its version.
    b: Option<(u32, u64)>,
}

impl PartialEq for Entry {
    fn eq(&self, o: &Self) -> bool {
        self.cmp(o) == Ordering::Equal
    }
}

impl Eq for Entry {}

impl PartialOrd for Entry {
    fn partial_cmp(&self, o: &Self) -> Option<Ordering> {
        Some(self.cmp(o))
    }
}

impl Ord for Entry {
    /// The shot's order of events ([`earlier`]).
    fn cmp(&self, o: &Self) -> Ordering {
        if earlier(&self.event, &o.event) {
            Ordering::Less
        } else if earlier(&o.event, &self.event) {
            Ordering::Greater
        } else {
            Ordering::Equal
        }
    }
}

/// Every prediction made, earliest first; a prediction is stale once one of its balls has
/// been predicted again.
#[derive(Clone, Debug, Default)]
pub(crate) struct Calendar {
    queue: BinaryHeap<Reverse<Entry>>,
    /// Each ball's version: how many times its predictions were renewed.
    versions: Vec<u64>,
}

impl Calendar {
    /// An empty calendar for `n` balls.
    pub fn new(n: usize) -> Calendar {
        Calendar {
            queue: BinaryHeap::new(),
            versions: vec![0; n],
        }
    }

    /// Makes every prediction of ball `i` stale: its predictions are about to be renewed.
    pub fn renew(&mut self, i: usize) {
        self.versions[i] += 1;
        // Stale entries pile up; once they outnumber the live ones by far, drop them.
        let n = self.versions.len();
        if self.queue.len() > 8 * (n * n + 4 * n) + 64 {
            let versions = &self.versions;
            self.queue.retain(|Reverse(e)| live(versions, e));
        }
    }

    /// Adds the prediction `event` of ball `a` (and `b`, for a meeting), made from their
    /// current states.
    pub fn add(&mut self, event: ShotEvent, a: usize, b: Option<usize>) {
        let v = &self.versions;
        self.queue.push(Reverse(Entry {
            event,
            a: (a as u32, v[a]),
            b: b.map(|b| (b as u32, v[b])),
        }));
    }

    /// The earliest live prediction.
    pub fn first(&mut self) -> Option<ShotEvent> {
        while let Some(Reverse(e)) = self.queue.peek() {
            if live(&self.versions, e) {
                return Some(e.event);
            }
            self.queue.pop();
        }
        None
    }
}

fn live(versions: &[u64], e: &Entry) -> bool {
    versions[e.a.0 as usize] == e.a.1 && e.b.is_none_or(|(b, v)| versions[b as usize] == v)
}
