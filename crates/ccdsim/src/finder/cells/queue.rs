//! The event queue of the `cells` finder: one entry per body, keyed by the body's earliest
//! event or cell crossing, in an indexed 4-ary min-heap.
//!
//! A key packs the total order of [`Event`] into two integers: the time's bits mapped so that
//! unsigned order is [`f64::total_cmp`] order, then a tie-break word holding the class
//! (crossing < body event < wall event) and the two indices. Comparing keys is comparing
//! events, ties included, and a crossing goes before a real event at the same instant.

use crate::event::{Event, EventKind};

/// "No body" / "no cell".
pub(super) const NONE: u32 = u32::MAX;

/// Largest body or wall index a key can hold.
pub(super) const MAX_INDEX: usize = (1 << 31) - 1;

const CLASS_CROSSING: u64 = 0;
const CLASS_BODY: u64 = 1;
const CLASS_WALL: u64 = 2;
const INDEX_MASK: u64 = (1 << 31) - 1;

/// An event, crossing or "never", ordered as described in the module docs.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub(super) struct Key {
    /// The time's bits, order-preserving.
    pub time: u64,
    /// Class and indices.
    pub tie: u64,
}

/// Maps a time's bits to an unsigned integer with the order of [`f64::total_cmp`].
#[inline]
fn ordered(t: f64) -> u64 {
    let b = t.to_bits();
    if b >> 63 == 1 {
        !b
    } else {
        b | (1 << 63)
    }
}

impl Key {
    /// After everything: no event and no crossing.
    pub const NEVER: Key = Key {
        time: u64::MAX,
        tie: u64::MAX,
    };

    /// A body–body event at `t` between bodies `a < b`.
    #[inline]
    pub fn body(t: f64, a: usize, b: usize) -> Key {
        debug_assert!(a < b);
        Key {
            time: ordered(t),
            tie: (CLASS_BODY << 62) | ((a as u64) << 31) | b as u64,
        }
    }

    /// A body–wall event at `t` between body `a` and wall `w`.
    #[inline]
    pub fn wall(t: f64, a: usize, w: usize) -> Key {
        Key {
            time: ordered(t),
            tie: (CLASS_WALL << 62) | ((a as u64) << 31) | w as u64,
        }
    }

    /// A cell crossing at `t`.
    #[inline]
    pub fn crossing(t: f64) -> Key {
        Key {
            time: ordered(t),
            tie: CLASS_CROSSING,
        }
    }

    /// True for [`Key::NEVER`].
    #[inline]
    pub fn is_never(self) -> bool {
        self == Key::NEVER
    }

    /// The time, seconds.
    #[inline]
    pub fn seconds(self) -> f64 {
        if self.time >> 63 == 1 {
            f64::from_bits(self.time & !(1 << 63))
        } else {
            f64::from_bits(!self.time)
        }
    }

    /// The event of a body or wall key.
    #[inline]
    pub fn event(self) -> Event {
        let a = ((self.tie >> 31) & INDEX_MASK) as u32;
        let b = (self.tie & INDEX_MASK) as u32;
        let kind = if self.tie >> 62 == CLASS_BODY {
            EventKind::Body
        } else {
            EventKind::Wall
        };
        Event {
            time: self.seconds(),
            kind,
            a,
            b,
        }
    }

    /// For a body–body key involving body `i`: the other body.
    #[inline]
    pub fn partner(self, i: usize) -> Option<usize> {
        if self.tie >> 62 != CLASS_BODY {
            return None;
        }
        let a = ((self.tie >> 31) & INDEX_MASK) as usize;
        let b = (self.tie & INDEX_MASK) as usize;
        Some(if a == i { b } else { a })
    }
}

const ARITY: usize = 4;

/// An indexed min-heap holding one key per body.
///
/// The heap stores only each key's time; the tie-break word is asked of the owner (through
/// the `tie` closure of the mutating methods) in the rare case of two equal times, which keeps
/// the heap at 12 bytes per body.
#[derive(Clone, Debug, Default)]
pub(super) struct EventQueue {
    /// Key times by heap slot.
    times: Vec<u64>,
    /// Bodies by heap slot.
    items: Vec<u32>,
    /// Heap slot of each body.
    slot: Vec<u32>,
}

impl EventQueue {
    /// A queue of `n` bodies, all with key [`Key::NEVER`].
    pub fn new(n: usize) -> Self {
        EventQueue {
            times: vec![Key::NEVER.time; n],
            items: (0..n as u32).collect(),
            slot: (0..n as u32).collect(),
        }
    }

    /// Bytes held (payload).
    pub fn bytes(&self) -> usize {
        8 * self.times.capacity() + 4 * (self.items.capacity() + self.slot.capacity())
    }

    /// The time word of body `i`'s key.
    #[inline]
    pub fn time_of(&self, i: usize) -> u64 {
        self.times[self.slot[i] as usize]
    }

    /// The body with the smallest key.
    #[inline]
    pub fn top(&self) -> Option<usize> {
        Some(*self.items.first()? as usize)
    }

    /// Sets body `i`'s key to `key`; `tie(j)` must give the tie word of every other body's key.
    #[inline]
    pub fn set(&mut self, i: usize, key: Key, tie: impl Fn(u32) -> u64) {
        let s = self.slot[i] as usize;
        // Moving up or down is decided against the parent: if the new key is below it, the
        // key goes up (and cannot need to go down); otherwise down.
        if s > 0 {
            let p = (s - 1) / ARITY;
            let pt = self.times[p];
            if key.time < pt || (key.time == pt && key.tie < tie(self.items[p])) {
                self.sift_up(s, key, &tie);
                return;
            }
        }
        self.sift_down(s, key, &tie);
    }

    fn sift_up(&mut self, mut s: usize, key: Key, tie: &impl Fn(u32) -> u64) {
        let item = self.items[s];
        while s > 0 {
            let parent = (s - 1) / ARITY;
            let pt = self.times[parent];
            if pt < key.time || (pt == key.time && tie(self.items[parent]) <= key.tie) {
                break;
            }
            self.times[s] = pt;
            self.items[s] = self.items[parent];
            self.slot[self.items[s] as usize] = s as u32;
            s = parent;
        }
        self.times[s] = key.time;
        self.items[s] = item;
        self.slot[item as usize] = s as u32;
    }

    fn sift_down(&mut self, mut s: usize, key: Key, tie: &impl Fn(u32) -> u64) {
        let n = self.times.len();
        let item = self.items[s];
        loop {
            let first = s * ARITY + 1;
            if first >= n {
                break;
            }
            let last = (first + ARITY).min(n);
            let mut child = first;
            let mut ct = self.times[first];
            for c in first + 1..last {
                let t = self.times[c];
                if t < ct || (t == ct && tie(self.items[c]) < tie(self.items[child])) {
                    child = c;
                    ct = t;
                }
            }
            if key.time < ct || (key.time == ct && key.tie <= tie(self.items[child])) {
                break;
            }
            self.times[s] = ct;
            self.items[s] = self.items[child];
            self.slot[self.items[s] as usize] = s as u32;
            s = child;
        }
        self.times[s] = key.time;
        self.items[s] = item;
        self.slot[item as usize] = s as u32;
    }

    /// Checks the heap order (with the given tie words) and the slot index.
    pub fn validate(&self, tie: impl Fn(u32) -> u64) -> Result<(), String> {
        let key = |s: usize| (self.times[s], tie(self.items[s]));
        for s in 1..self.times.len() {
            if key((s - 1) / ARITY) > key(s) {
                return Err(format!("heap order broken at slot {s}"));
            }
        }
        for (s, &i) in self.items.iter().enumerate() {
            if self.slot[i as usize] as usize != s {
                return Err(format!("slot index of body {i} is wrong"));
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn keys_order_like_events() {
        let events = [
            (Key::body(1.0, 0, 5), Event::body(1.0, 0, 5)),
            (Key::wall(1.0, 0, 0), Event::wall(1.0, 0, 0)),
            (Key::body(1.0, 1, 2), Event::body(1.0, 1, 2)),
            (Key::wall(0.5, 9, 9), Event::wall(0.5, 9, 9)),
            (Key::body(-0.0, 0, 1), Event::body(-0.0, 0, 1)),
            (Key::body(0.0, 0, 1), Event::body(0.0, 0, 1)),
            (Key::body(-3.5, 2, 7), Event::body(-3.5, 2, 7)),
        ];
        for (ka, ea) in events {
            assert_eq!(ka.event(), ea);
            assert_eq!(ka.event().time.to_bits(), ea.time.to_bits());
            for (kb, eb) in events {
                assert_eq!(ka.cmp(&kb), ea.cmp(&eb), "{ea:?} vs {eb:?}");
            }
        }
        assert!(Key::crossing(1.0) < Key::body(1.0, 0, 1));
        assert!(Key::body(f64::INFINITY, 0, 1) < Key::NEVER);
        assert_eq!(Key::body(2.0, 3, 4).partner(4), Some(3));
        assert_eq!(Key::wall(2.0, 3, 4).partner(3), None);
    }

    #[test]
    fn heap_keeps_minimum() {
        // Many equal times, so that the tie words decide.
        let n = 50;
        let mut keys = vec![Key::NEVER; n];
        let mut q = EventQueue::new(n);
        for round in 0..2000u64 {
            let i = (round * 7919 % n as u64) as usize;
            let t = (round * 104_729 % 13) as f64;
            keys[i] = if round % 3 == 0 {
                Key::crossing(t)
            } else {
                Key::body(t, i, n + (round % 5) as usize)
            };
            let snapshot = keys.clone();
            q.set(i, keys[i], |j| snapshot[j as usize].tie);
            q.validate(|j| snapshot[j as usize].tie).unwrap();
            let top = q.top().unwrap();
            assert_eq!(keys[top], *keys.iter().min().unwrap());
        }
    }
}
