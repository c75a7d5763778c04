//! "Update Hierarchy" (thesis Algorithm 4): after Δ grows, refit every box leaves-to-root
//! without changing the tree's shape.

use super::tree::{children, is_finite_box, swept_box, SweptTree};
use crate::world::World;

impl<const D: usize> SweptTree<D> {
    /// Moves the end of the swept interval to `horizon` and recomputes every box: each leaf's
    /// from its body's stored motion, each inner node's as the union of its children. Nodes
    /// are in pre-order, so walking them backwards visits children before parents. O(n).
    pub fn refit(&mut self, world: &World<D>, horizon: f64) {
        self.horizon = horizon;
        let mut finite = true;
        for k in (0..self.nodes.len()).rev() {
            let node = self.nodes[k];
            let aabb = if node.is_leaf() {
                let i = self.order[node.start as usize] as usize;
                let b = swept_box(
                    &world.motion(i),
                    world.radius_at(i, horizon),
                    self.now,
                    horizon,
                    world.gravity_of(i).as_ref(),
                );
                finite &= is_finite_box(&b);
                b
            } else {
                let (l, r) = children(k, node.count);
                self.nodes[l].aabb.union(self.nodes[r].aabb)
            };
            self.nodes[k].aabb = aabb;
        }
        self.finite = finite;
    }
}
