//! "BVH collision check" (thesis Algorithm 3): the self-check of a node and the pair-check of
//! two nodes, ending in the narrow phase on body pairs whose leaf boxes overlap.

use super::tree::{children, SweptTree};
use crate::event::Event;
use crate::narrow::toi_circle_circle;
use crate::world::World;

/// What one traversal found and how much work it took.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct Traversal {
    /// The earliest body–body event under the total order whose time is at most the tree's
    /// horizon, if any.
    pub best: Option<Event>,
    /// Body pairs handed to the narrow phase.
    pub narrow_calls: u64,
}

struct Check<'a, const D: usize> {
    tree: &'a SweptTree<D>,
    world: &'a World<D>,
    horizon: f64,
    out: Traversal,
}

impl<const D: usize> SweptTree<D> {
    /// Runs Algorithm 3 from the root: every body pair whose leaf boxes overlap is given to
    /// [`toi_circle_circle`], and the earliest resulting event with time ≤ `horizon` is kept
    /// (ties by the event order).
    ///
    /// If the leaf boxes are [`swept_box`](super::tree::swept_box)es for `[now, horizon]`, a
    /// pair whose computed time of impact lies in that interval always reaches the narrow
    /// phase, so `best` is the minimum over *all* pairs with time ≤ `horizon`.
    pub fn earliest_body_event(&self, world: &World<D>) -> Traversal {
        let mut c = Check {
            tree: self,
            world,
            horizon: self.horizon,
            out: Traversal::default(),
        };
        if !self.nodes.is_empty() {
            c.self_check(0);
        }
        c.out
    }
}

impl<const D: usize> Check<'_, D> {
    /// Pairs within the subtree of node `k`.
    fn self_check(&mut self, k: usize) {
        let node = self.tree.nodes[k];
        if node.is_leaf() {
            return;
        }
        let (l, r) = children(k, node.count);
        self.pair_check(l, r);
        self.self_check(l);
        self.self_check(r);
    }

    /// Pairs with one body below node `a` and the other below node `b` (disjoint subtrees).
    fn pair_check(&mut self, a: usize, b: usize) {
        let (na, nb) = (self.tree.nodes[a], self.tree.nodes[b]);
        if !na.aabb.overlaps(&nb.aabb) {
            return;
        }
        match (na.is_leaf(), nb.is_leaf()) {
            (true, true) => self.narrow(self.tree.body(&na), self.tree.body(&nb)),
            (true, false) => {
                let (l, r) = children(b, nb.count);
                self.pair_check(a, l);
                self.pair_check(a, r);
            }
            (false, true) => {
                let (l, r) = children(a, na.count);
                self.pair_check(l, b);
                self.pair_check(r, b);
            }
            (false, false) => {
                let (al, ar) = children(a, na.count);
                let (bl, br) = children(b, nb.count);
                self.pair_check(al, bl);
                self.pair_check(al, br);
                self.pair_check(ar, bl);
                self.pair_check(ar, br);
            }
        }
    }

    /// The narrow phase, called exactly as the oracle calls it (lower index first).
    #[inline]
    fn narrow(&mut self, i: usize, j: usize) {
        let (i, j) = if i < j { (i, j) } else { (j, i) };
        self.out.narrow_calls += 1;
        let Some(t) = toi_circle_circle(
            &self.world.motion(i),
            self.world.radius(i),
            &self.world.motion(j),
            self.world.radius(j),
        ) else {
            return;
        };
        if t <= self.horizon {
            self.out.best = Event::earliest(self.out.best, Some(Event::body(t, i, j)));
        }
    }
}
