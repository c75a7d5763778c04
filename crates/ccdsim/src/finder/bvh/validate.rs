//! Structural and geometric checks of the hierarchy, for tests.

use super::build::along;
use super::tree::{children, is_finite_box, swept_box, Node, SweptTree};
use crate::geom::Aabb;
use crate::world::World;
use std::cmp::Ordering;

/// A broken invariant of the hierarchy, naming the node (pre-order index).
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("BVH node {node}: {why}")]
pub struct InvalidTree {
    /// Index of the offending node in the flat array.
    pub node: usize,
    /// The invariant that fails.
    pub why: String,
}

fn fail<T>(node: usize, why: impl Into<String>) -> Result<T, InvalidTree> {
    Err(InvalidTree {
        node,
        why: why.into(),
    })
}

impl<const D: usize> SweptTree<D> {
    /// Checks, against `world` (unchanged since the last build or refit):
    ///
    /// - the shape: `2n − 1` nodes in pre-order, each holding the range of bodies its parent
    ///   assigns it, and `order` a permutation of the bodies;
    /// - every leaf box equals its body's swept box for `[now, horizon]` and encloses the
    ///   body's ball at `now` and at `horizon` (its swept extent), every inner box encloses
    ///   both children's boxes;
    /// - when the tree has not been refitted since it was built, the median split: along the
    ///   level's axis, no body on the left orders after a body on the right.
    pub fn validate(&self, world: &World<D>) -> Result<(), InvalidTree> {
        let n = world.len();
        if n == 0 {
            return if self.nodes.is_empty() {
                Ok(())
            } else {
                fail(0, "nodes without bodies")
            };
        }
        if self.nodes.len() != 2 * n - 1 {
            return fail(0, format!("{} nodes for {n} bodies", self.nodes.len()));
        }
        let mut seen = vec![false; n];
        for &b in &self.order {
            let b = b as usize;
            if b >= n || std::mem::replace(&mut seen[b], true) {
                return fail(0, format!("order is not a permutation (body {b})"));
            }
        }
        if self.order.len() != n {
            return fail(0, format!("order holds {} of {n} bodies", self.order.len()));
        }
        let boxes: Vec<Aabb<D>> = (0..n)
            .map(|i| {
                swept_box(
                    &world.motion(i),
                    world.radius(i),
                    self.now,
                    self.horizon,
                    world.gravity_of(i).as_ref(),
                )
            })
            .collect();
        self.check_node(world, &boxes, 0, 0, n, 0).map(|_| ())
    }

    /// Checks node `k`, which must hold `count` bodies from `start`, and its subtree; returns
    /// the subtree's node count. `boxes` are the swept boxes recomputed from `world`.
    fn check_node(
        &self,
        world: &World<D>,
        boxes: &[Aabb<D>],
        k: usize,
        start: usize,
        count: usize,
        level: usize,
    ) -> Result<usize, InvalidTree> {
        let Some(node) = self.nodes.get(k) else {
            return fail(k, "missing");
        };
        if (node.start as usize, node.count as usize) != (start, count) {
            return fail(
                k,
                format!(
                    "holds bodies {}+{}, expected {start}+{count}",
                    node.start, node.count
                ),
            );
        }
        if !is_finite_box(&node.aabb) {
            return fail(k, "box is not finite");
        }
        if node.is_leaf() {
            return self.check_leaf(world, boxes, k, node).map(|()| 1);
        }
        let (l, r) = children(k, node.count);
        let half = count / 2;
        let left = self.check_node(world, boxes, l, start, half, level + 1)?;
        if l + left != r {
            return fail(k, "pre-order layout broken");
        }
        let right = self.check_node(world, boxes, r, start + half, count - half, level + 1)?;
        for c in [l, r] {
            if !node.aabb.contains(&self.nodes[c].aabb) {
                return fail(k, format!("box does not enclose child {c}"));
            }
        }
        if self.horizon == self.built_horizon {
            self.check_split(boxes, k, node, level)?;
        }
        Ok(1 + left + right)
    }

    fn check_leaf(
        &self,
        world: &World<D>,
        boxes: &[Aabb<D>],
        k: usize,
        node: &Node<D>,
    ) -> Result<(), InvalidTree> {
        let i = self.body(node);
        let r = world.radius(i);
        if node.aabb != boxes[i] {
            return fail(k, format!("leaf box of body {i} is stale"));
        }
        for t in [self.now, self.horizon] {
            if !node
                .aabb
                .contains(&Aabb::of_ball(world.stored_position_at(i, t), r))
            {
                return fail(k, format!("leaf box misses body {i} at t = {t}"));
            }
        }
        Ok(())
    }

    /// The median split of inner node `k` at `level`, on the recomputed swept boxes (they
    /// equal the build's while the horizon is the build's).
    fn check_split(
        &self,
        boxes: &[Aabb<D>],
        k: usize,
        node: &Node<D>,
        level: usize,
    ) -> Result<(), InvalidTree> {
        let axis = level % D;
        let range = node.start as usize..(node.start + node.count) as usize;
        let half = node.count as usize / 2;
        let (lo, hi) = self.order[range].split_at(half);
        let cmp = |a: &&u32, b: &&u32| along(boxes, axis, **a, **b);
        let (Some(max_lo), Some(min_hi)) = (lo.iter().max_by(cmp), hi.iter().min_by(cmp)) else {
            return fail(k, "empty half");
        };
        if along(boxes, axis, *max_lo, *min_hi) == Ordering::Greater {
            return fail(
                k,
                format!(
                    "body {max_lo} on the left orders after body {min_hi} on the right \
                     along axis {axis}"
                ),
            );
        }
        Ok(())
    }
}
