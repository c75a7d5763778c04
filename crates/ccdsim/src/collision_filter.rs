//! Collision groups and masks: which pairs of bodies collide.
//!
//! Each body belongs to the groups set in its `group` bits and collides with the groups set
//! in its `mask` bits. Two bodies collide only when each belongs to a group the other
//! collides with; otherwise they pass through each other, and every finder, like the
//! all-pairs oracle, never reports their contact. Walls always collide with dynamic bodies.
//!
//! ```
//! use ccdsim::collision_filter::CollisionFilter;
//! let ball = CollisionFilter::DEFAULT; // group 1, collides with everything
//! let ghost = CollisionFilter { group: 2, mask: !1 }; // ignores group 1
//! assert!(ball.collides(&ball));
//! assert!(!ball.collides(&ghost) && !ghost.collides(&ball));
//! assert!(ghost.collides(&ghost));
//! ```

use serde::{Deserialize, Serialize};

/// A body's collision group and mask, bit sets of up to 32 groups.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub struct CollisionFilter {
    /// The groups the body belongs to (bit `k` set: group `k`).
    pub group: u32,
    /// The groups the body collides with.
    pub mask: u32,
}

impl CollisionFilter {
    /// A body's filter unless it sets one: group 1 (bit 0), colliding with every group.
    pub const DEFAULT: CollisionFilter = CollisionFilter {
        group: 1,
        mask: u32::MAX,
    };

    /// The filter of a vacant slot (see [`crate::World::is_vacant`]): it belongs to no group
    /// and collides with none.
    pub const NONE: CollisionFilter = CollisionFilter { group: 0, mask: 0 };

    /// The filter of a body with the given optional `group` and `mask` (each defaulting to
    /// [`CollisionFilter::DEFAULT`]'s).
    #[must_use]
    pub fn of(group: Option<u32>, mask: Option<u32>) -> Self {
        CollisionFilter {
            group: group.unwrap_or(Self::DEFAULT.group),
            mask: mask.unwrap_or(Self::DEFAULT.mask),
        }
    }

    /// True when bodies with filters `self` and `other` collide: each belongs to a group the
    /// other collides with. Symmetric.
    #[must_use]
    #[inline]
    pub fn collides(&self, other: &CollisionFilter) -> bool {
        self.group & other.mask != 0 && other.group & self.mask != 0
    }
}

/// True when bodies `i` and `j` collide under the filters `filters` by body index (an
/// empty slice: every pair collides).
#[must_use]
#[inline(always)]
pub fn pair_collides(filters: &[CollisionFilter], i: usize, j: usize) -> bool {
    filters.is_empty() || filters[i].collides(&filters[j])
}

/// The lane mask of the bodies `quad` (indices into `filters`, non-empty) that collide with
/// body `i`: bit `l` set when `quad[l]` does.
#[must_use]
#[inline(always)]
pub(crate) fn colliding_lanes<const L: usize>(
    filters: &[CollisionFilter],
    i: usize,
    quad: [u32; L],
) -> u32 {
    let mut lanes = 0;
    for (l, &j) in quad.iter().enumerate() {
        lanes |= u32::from(filters[i].collides(&filters[j as usize])) << l;
    }
    lanes
}

impl Default for CollisionFilter {
    fn default() -> Self {
        Self::DEFAULT
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn collides_is_symmetric_and_needs_both_directions() {
        let f = |group, mask| CollisionFilter { group, mask };
        let cases = [
            (f(1, u32::MAX), f(1, u32::MAX), true),
            (f(1, 2), f(2, 1), true),
            (f(1, 2), f(2, 2), false), // the second does not collide with group 1
            (f(0, u32::MAX), f(1, u32::MAX), false), // in no group: collides with no body
            (f(4, 4), f(4, 4), true),
            (f(4, 3), f(4, 3), false),
        ];
        for (a, b, want) in cases {
            assert_eq!(a.collides(&b), want, "{a:?} {b:?}");
            assert_eq!(b.collides(&a), want, "{b:?} {a:?}");
        }
    }

    #[test]
    fn of_fills_defaults() {
        assert_eq!(CollisionFilter::of(None, None), CollisionFilter::DEFAULT);
        assert_eq!(
            CollisionFilter::of(Some(8), None),
            CollisionFilter {
                group: 8,
                mask: u32::MAX
            }
        );
    }
}
