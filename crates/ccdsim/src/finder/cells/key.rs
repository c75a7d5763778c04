//! Queue keys of the `cells` finder: a body's earliest event or cell crossing.
//!
//! A key packs the total order of [`Event`] into two integers: the time's bits mapped so that
//! unsigned order is [`f64::total_cmp`] order, then a tie-break word holding the class
//! (crossing < body event < wall event) and the indices (a crossing's: its body). Comparing keys is comparing
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

/// An event, crossing or "never", ordered as described in the module docs: by time word,
/// then tie word.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) struct Key {
    /// The time's bits, order-preserving.
    pub time: u64,
    /// Class and indices.
    pub tie: u64,
}

impl Key {
    /// The key as one integer of the same order, time word above tie word: a comparison is
    /// one wide compare, without the branch of a field-by-field one.
    #[inline(always)]
    fn packed(self) -> u128 {
        (u128::from(self.time) << 64) | u128::from(self.tie)
    }
}

impl Ord for Key {
    #[inline(always)]
    fn cmp(&self, other: &Self) -> std::cmp::Ordering {
        self.packed().cmp(&other.packed())
    }
}

impl PartialOrd for Key {
    #[inline(always)]
    fn partial_cmp(&self, other: &Self) -> Option<std::cmp::Ordering> {
        Some(self.cmp(other))
    }

    #[inline(always)]
    fn lt(&self, other: &Self) -> bool {
        self.packed() < other.packed()
    }

    #[inline(always)]
    fn le(&self, other: &Self) -> bool {
        self.packed() <= other.packed()
    }

    #[inline(always)]
    fn gt(&self, other: &Self) -> bool {
        self.packed() > other.packed()
    }

    #[inline(always)]
    fn ge(&self, other: &Self) -> bool {
        self.packed() >= other.packed()
    }
}

/// Maps a time's bits to an unsigned integer with the order of [`f64::total_cmp`].
#[inline]
pub(super) fn ordered(t: f64) -> u64 {
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

    /// A body–body event between bodies `a < b` at the time whose ordered bits are `time`
    /// (see [`ordered`]).
    #[inline]
    pub fn body_bits(time: u64, a: usize, b: usize) -> Key {
        debug_assert!(a < b);
        Key {
            time,
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

    /// A cell crossing of body `i` at `t`.
    #[inline]
    pub fn crossing(t: f64, i: usize) -> Key {
        Key {
            time: ordered(t),
            tie: (CLASS_CROSSING << 62) | i as u64,
        }
    }

    /// True for a crossing key.
    #[inline]
    pub fn is_crossing(self) -> bool {
        self.tie >> 62 == CLASS_CROSSING
    }

    /// The bodies that may hold this key in the queue: the body of a crossing or wall key
    /// (twice), the two bodies of a body–body key.
    #[inline]
    pub fn holders(self) -> (usize, usize) {
        let a = ((self.tie >> 31) & INDEX_MASK) as usize;
        let b = (self.tie & INDEX_MASK) as usize;
        match self.tie >> 62 {
            CLASS_CROSSING => (b, b),
            CLASS_BODY => (a, b),
            _ => (a, a),
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
        assert!(Key::crossing(1.0, 7) < Key::body(1.0, 0, 1));
        assert!(Key::crossing(1.0, 2) < Key::crossing(1.0, 3));
        assert!(Key::crossing(0.5, 3) < Key::crossing(1.0, 2));
        assert!(Key::crossing(1.0, 2).is_crossing() && !Key::wall(1.0, 2, 0).is_crossing());
        assert_eq!(Key::crossing(1.0, 9).holders(), (9, 9));
        assert_eq!(Key::body(1.0, 3, 9).holders(), (3, 9));
        assert_eq!(Key::wall(1.0, 3, 9).holders(), (3, 3));
        assert!(Key::body(f64::INFINITY, 0, 1) < Key::NEVER);
        assert_eq!(Key::body(2.0, 3, 4).partner(4), Some(3));
        assert_eq!(Key::wall(2.0, 3, 4).partner(3), None);
    }
}
