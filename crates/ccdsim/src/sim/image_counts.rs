//! Per-body periodic image counters: how many whole periods each body's stored position has
//! been shifted by box exits, per axis, so that `stored + k · L` is its unwrapped position.
//!
//! Counts are stored as `i32`, half the memory of `i64` (8 bytes a body in 2D instead of 16):
//! a million-body gas keeps about 190 bytes a body in all, and these counters are the only
//! per-body state the simulation adds to the world and the finder. A body crosses a face far
//! fewer than 2³¹ times in any run a box of that size allows, but a tiny box run for long
//! can get there, so a count that would leave `i32` moves into an exact `i64` carry kept
//! aside: no count is ever lost or wrapped.

use std::collections::HashMap;

/// Image counters of every body slot of a periodic world (none in a world without one).
#[derive(Clone, Debug, Default)]
pub(crate) struct ImageCounts<const D: usize> {
    low: Vec<[i32; D]>,
    /// Whole periods beyond `low`, by slot, for the rare counts that left `i32`.
    carry: HashMap<usize, [i64; D]>,
    /// The world is periodic. Kept apart from `low`: a periodic world may have no body yet.
    counting: bool,
}

impl<const D: usize> ImageCounts<D> {
    /// Counters for `n` slots, all zero, if `periodic`; no counters otherwise.
    pub(crate) fn new(n: usize, periodic: bool) -> Self {
        Self {
            low: if periodic {
                vec![[0; D]; n]
            } else {
                Vec::new()
            },
            carry: HashMap::new(),
            counting: periodic,
        }
    }

    /// True when the world is periodic (the counters exist).
    pub(crate) fn is_counting(&self) -> bool {
        self.counting
    }

    /// Slot `i`'s count, whole periods per axis.
    pub(crate) fn get(&self, i: usize) -> [i64; D] {
        let mut k = self.carry.get(&i).copied().unwrap_or([0; D]);
        for (k, &low) in k.iter_mut().zip(&self.low[i]) {
            *k += i64::from(low);
        }
        k
    }

    /// Sets slot `i`'s count (a teleport or a new body sets zero; a restate its full image).
    pub(crate) fn set(&mut self, i: usize, k: [i64; D]) {
        let low = k.map(|c| i32::try_from(c).ok());
        if low.iter().all(Option::is_some) {
            self.low[i] = low.map(Option::unwrap_or_default);
            self.carry.remove(&i);
        } else {
            self.low[i] = [0; D];
            self.carry.insert(i, k);
        }
    }

    /// Adds `step` (±1) to slot `i`'s count on `axis`: the body left through a face.
    #[inline]
    pub(crate) fn shift(&mut self, i: usize, axis: usize, step: i32) {
        let low = &mut self.low[i][axis];
        match low.checked_add(step) {
            Some(c) => *low = c,
            None => self.spill(i, axis, step),
        }
    }

    /// Adds `periods` to slot `i`'s count on `axis` (a sheared box's exits move bodies along
    /// x by the strain's whole periods, any number of them).
    pub(crate) fn add(&mut self, i: usize, axis: usize, periods: i64) {
        let mut k = self.get(i);
        k[axis] += periods;
        self.set(i, k);
    }

    /// Moves slot `i`'s count on `axis` plus `step` into the carry (it would leave `i32`).
    #[cold]
    #[inline(never)]
    fn spill(&mut self, i: usize, axis: usize, step: i32) {
        let low = std::mem::take(&mut self.low[i][axis]);
        self.carry.entry(i).or_insert([0; D])[axis] += i64::from(low) + i64::from(step);
    }

    /// Makes room for `n` slots, the new ones at zero (counting worlds only).
    pub(crate) fn resize(&mut self, n: usize) {
        if self.is_counting() {
            self.low.resize(n, [0; D]);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_periodic_world_without_bodies_counts_the_ones_added() {
        // A periodic scene may start empty; its first added body once found no counter.
        let mut c = ImageCounts::<2>::new(0, true);
        assert!(c.is_counting());
        c.resize(1);
        c.set(0, [0, 0]);
        c.shift(0, 1, 1);
        assert_eq!(c.get(0), [0, 1]);
    }

    #[test]
    fn counts_are_exact_past_the_range_of_i32() {
        let mut c = ImageCounts::<2>::new(3, true);
        c.set(1, [i64::from(i32::MAX) - 1, -5]);
        for _ in 0..3 {
            c.shift(1, 0, 1);
        }
        c.shift(1, 1, -1);
        assert_eq!(c.get(1), [i64::from(i32::MAX) + 2, -6]);
        for _ in 0..3 {
            c.shift(1, 0, -1);
        }
        assert_eq!(c.get(1), [i64::from(i32::MAX) - 1, -6]);
        c.set(1, [i64::MIN / 2, 7]);
        c.shift(1, 0, -1);
        assert_eq!(c.get(1), [i64::MIN / 2 - 1, 7]);
        c.set(1, [0; 2]);
        assert_eq!(c.get(1), [0, 0]);
        assert_eq!(c.get(0), [0, 0]);
        assert_eq!(c.get(2), [0, 0]);
    }

    #[test]
    fn a_world_without_a_box_counts_nothing() {
        let mut c = ImageCounts::<3>::new(10, false);
        assert!(!c.is_counting());
        c.resize(20);
        assert!(!c.is_counting());
        let mut p = ImageCounts::<3>::new(2, true);
        p.resize(4);
        p.shift(3, 2, -1);
        assert_eq!(p.get(3), [0, 0, -1]);
    }
}
