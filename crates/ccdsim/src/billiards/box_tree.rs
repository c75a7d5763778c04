//! A bounding-volume hierarchy over a handful of boxes, rebuilt whenever they change: the
//! `bvh` finder's broad phase on a pool table (balls' swept boxes, and the table's parts).

use crate::geom::Aabb;

/// One node: the box of every item below it, `order[start..start + count]`. Nodes are in
/// pre-order: the left child of node `k` is `k + 1` and holds the first `count / 2` items,
/// the right child is `k + 2·(count / 2)`.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Node<const D: usize> {
    aabb: Aabb<D>,
    start: u32,
    count: u32,
}

/// A balanced hierarchy over the non-empty boxes of a list, split at the median of the
/// boxes' centres along the widest spread of them.
#[derive(Clone, Debug, Default, PartialEq)]
pub(crate) struct BoxTree<const D: usize> {
    nodes: Vec<Node<D>>,
    order: Vec<u32>,
}

impl<const D: usize> BoxTree<D> {
    /// The hierarchy of `boxes` (indexed as the list); empty boxes
    /// ([`Aabb::EMPTY`]: pocketed balls) are left out.
    pub fn build(&mut self, boxes: &[Aabb<D>]) {
        self.order.clear();
        self.order.extend(
            (0..boxes.len() as u32)
                .filter(|&i| boxes[i as usize].min[0] <= boxes[i as usize].max[0]),
        );
        self.nodes.clear();
        if !self.order.is_empty() {
            let count = self.order.len() as u32;
            self.split(boxes, 0, count);
        }
    }

    fn split(&mut self, boxes: &[Aabb<D>], start: u32, count: u32) {
        let items = &mut self.order[start as usize..(start + count) as usize];
        let aabb = items
            .iter()
            .fold(Aabb::EMPTY, |acc, &i| acc.union(boxes[i as usize]));
        self.nodes.push(Node { aabb, start, count });
        if count == 1 {
            return;
        }
        // Centres clamped to finite values: an unbounded box (a ball that never stops) has
        // no centre, and the split only has to be deterministic, not good, for it.
        let centre = |i: u32, k: usize| {
            let b = &boxes[i as usize];
            (0.5 * b.min[k].max(-f64::MAX) + 0.5 * b.max[k].min(f64::MAX)).clamp(-1e300, 1e300)
        };
        let axis = (0..D)
            .max_by(|&j, &k| {
                let spread = |k: usize| {
                    let (lo, hi) =
                        items
                            .iter()
                            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &i| {
                                let c = centre(i, k);
                                (lo.min(c), hi.max(c))
                            });
                    hi - lo
                };
                spread(j).total_cmp(&spread(k))
            })
            .unwrap_or(0);
        let half = (count / 2) as usize;
        items.select_nth_unstable_by(half, |&i, &j| {
            centre(i, axis).total_cmp(&centre(j, axis)).then(i.cmp(&j))
        });
        self.split(boxes, start, count / 2);
        self.split(boxes, start + count / 2, count - count / 2);
    }

    /// Appends to `out` every item whose box overlaps `query` (closed boxes).
    pub fn overlapping(&self, query: &Aabb<D>, out: &mut Vec<usize>) {
        if self.nodes.is_empty() {
            return;
        }
        let mut stack = [0usize; 64];
        let mut top = 1;
        while top > 0 {
            top -= 1;
            let k = stack[top];
            let node = &self.nodes[k];
            if !node.aabb.overlaps(query) {
                continue;
            }
            if node.count == 1 {
                out.push(self.order[node.start as usize] as usize);
            } else {
                let left = k + 1;
                let right = k + 2 * (node.count / 2) as usize;
                stack[top] = right;
                stack[top + 1] = left;
                top += 2;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::billiards::lattice_boxes::lattice_box;
    use crate::geom::Vector;
    use proptest::prelude::*;

    fn ball(x: f64, y: f64, r: f64) -> Aabb<2> {
        Aabb::of_ball(Vector([x, y]), r)
    }

    proptest! {
        /// The tree finds exactly the boxes a scan over all of them finds.
        #[test]
        fn the_tree_finds_what_a_scan_finds(
            items in prop::collection::vec(((-4i32..4, -4i32..4), 0u8..4), 0..40),
            query in ((-5i32..5, -5i32..5), 0u8..6),
        ) {
            // Integer and half-integer corners: boxes that touch exactly.
            let boxes: Vec<Aabb<2>> = items.iter().map(|&b| lattice_box(b, 1.0)).collect();
            // A query of radius 0 is a point, not empty.
            let q = ball(f64::from(query.0 .0), f64::from(query.0 .1), f64::from(query.1) * 0.5);
            let mut tree = BoxTree::default();
            tree.build(&boxes);
            let mut found = Vec::new();
            tree.overlapping(&q, &mut found);
            found.sort_unstable();
            let scan: Vec<usize> = (0..boxes.len()).filter(|&i| boxes[i].overlaps(&q)).collect();
            prop_assert_eq!(found, scan);
        }
    }

    #[test]
    fn an_unbounded_box_overlaps_everything() {
        let everywhere = Aabb {
            min: Vector::splat(f64::NEG_INFINITY),
            max: Vector::splat(f64::INFINITY),
        };
        let boxes = [ball(0.0, 0.0, 1.0), everywhere, ball(9.0, 9.0, 1.0)];
        let mut tree = BoxTree::default();
        tree.build(&boxes);
        let mut found = Vec::new();
        tree.overlapping(&ball(20.0, 20.0, 1.0), &mut found);
        assert_eq!(found, vec![1]);
    }
}
