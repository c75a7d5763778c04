//! "Construct hierarchy" (thesis §4.5–4.6): top-down, split at the median along an axis that
//! cycles with the level, with a linear-time selection, into a flat balanced array.

use super::tree::{is_finite_box, swept_box, Item, Node, SweptTree};
use crate::geom::Aabb;
use crate::world::World;
use std::cmp::Ordering;

impl<const D: usize> SweptTree<D> {
    /// Rebuilds the hierarchy over every body of `world` for the interval `[now, horizon]`.
    ///
    /// Each body's leaf box is its [`swept_box`]; bodies are ordered by the centres of those
    /// boxes. At level `l` the bodies of a node are split at the median of axis `l mod D`
    /// (`select_nth_unstable_by`, linear time): the first `count / 2` go left, the median and
    /// the rest right. The work is O(n log n) and the tree is balanced, so its depth is
    /// ⌈log₂ n⌉.
    pub fn build(&mut self, world: &World<D>, now: f64, horizon: f64) {
        let n = world.len();
        self.now = now;
        self.horizon = horizon;
        self.built_horizon = horizon;
        match world.periodic() {
            Some(size) => super::tree::half_image_shifts(&size, &mut self.shifts),
            None => self.shifts.clear(),
        }
        self.leaf_boxes.clear();
        self.leaf_boxes.extend((0..n).map(|i| {
            swept_box(
                &world.motion(i),
                world.radius_at(i, horizon),
                now,
                horizon,
                world.gravity_of(i).as_ref(),
            )
        }));
        self.finite = self.leaf_boxes.iter().all(is_finite_box);
        self.extent_now = (0..n).fold(Aabb::EMPTY, |acc, i| {
            acc.union(Aabb::of_ball(
                world.stored_position_at(i, now),
                world.radius_at(i, now),
            ))
        });
        if self.order.len() != n {
            // Otherwise keep the last permutation: the bodies have barely moved since, so the
            // selections below start from nearly partitioned input.
            self.order.clear();
            self.order.extend(0..n as u32);
        }
        self.nodes.clear();
        if n == 0 {
            return;
        }
        let placeholder = Node {
            aabb: Aabb::EMPTY,
            start: 0,
            count: 0,
        };
        self.nodes.resize(2 * n - 1, placeholder);
        // Select on a contiguous copy of the keys: the selections then touch sequential
        // memory instead of chasing body indices into the boxes.
        let boxes = &self.leaf_boxes;
        self.items.clear();
        self.items.extend(self.order.iter().map(|&body| Item {
            key: std::array::from_fn(|axis| key(&boxes[body as usize], axis)),
            body,
        }));
        split(&mut self.nodes, &mut self.items, boxes, 0, 0, 0);
        for (slot, item) in self.order.iter_mut().zip(&self.items) {
            *slot = item.body;
        }
    }
}

/// Twice the centre of `b` along `axis` (the factor ½ does not change the order).
#[inline]
fn key<const D: usize>(b: &Aabb<D>, axis: usize) -> f64 {
    b.min[axis] + b.max[axis]
}

/// Order of two bodies along `axis`: by the centres of their boxes (the build's order; equal
/// centres fall on either side).
#[inline]
pub(crate) fn along<const D: usize>(boxes: &[Aabb<D>], axis: usize, a: u32, b: u32) -> Ordering {
    key(&boxes[a as usize], axis).total_cmp(&key(&boxes[b as usize], axis))
}

/// Builds node `k` over the bodies of `items` (the `items.len()` bodies from position
/// `start` of the order) at tree level `level`; returns the node's box.
fn split<const D: usize>(
    nodes: &mut [Node<D>],
    items: &mut [Item<D>],
    boxes: &[Aabb<D>],
    k: usize,
    start: usize,
    level: usize,
) -> Aabb<D> {
    let count = items.len();
    let aabb = if count == 1 {
        boxes[items[0].body as usize]
    } else {
        let half = count / 2;
        let axis = level % D;
        if count == 2 {
            if items[1].key[axis].total_cmp(&items[0].key[axis]).is_lt() {
                items.swap(0, 1);
            }
        } else {
            items.select_nth_unstable_by(half, |a, b| a.key[axis].total_cmp(&b.key[axis]));
        }
        let (lo, hi) = items.split_at_mut(half);
        let (left, right) = super::tree::children(k, count as u32);
        let a = split(nodes, lo, boxes, left, start, level + 1);
        let b = split(nodes, hi, boxes, right, start + half, level + 1);
        a.union(b)
    };
    nodes[k] = Node {
        aabb,
        start: start as u32,
        count: count as u32,
    };
    aabb
}
