//! A bounding volume hierarchy over static boxes, rebuilt every frame, to find overlapping
//! pairs: the broad phase of the discrete-time stepper.

use crate::geom::{Aabb, Vector};

/// Most boxes in one leaf.
const LEAF_SIZE: usize = 4;

#[derive(Clone, Copy, Debug)]
struct Node<const D: usize> {
    aabb: Aabb<D>,
    /// Leaf: first item in `items`; inner node: index of the left child (the right one follows).
    first: u32,
    /// Leaf: number of items (> 0); inner node: 0.
    count: u32,
}

/// A BVH over a fixed set of boxes, built top-down by median splits along the widest axis of
/// the box centres. Rebuilding reuses its buffers.
#[derive(Clone, Debug, Default)]
pub struct OverlapTree<const D: usize> {
    nodes: Vec<Node<D>>,
    items: Vec<u32>,
    boxes: Vec<Aabb<D>>,
    stack: Vec<u32>,
}

impl<const D: usize> OverlapTree<D> {
    /// An empty tree.
    #[must_use]
    pub fn new() -> Self {
        OverlapTree {
            nodes: Vec::new(),
            items: Vec::new(),
            boxes: Vec::new(),
            stack: Vec::new(),
        }
    }

    /// Rebuilds the tree over `boxes` (box `k` is item `k`). O(n log n).
    pub fn build(&mut self, boxes: &[Aabb<D>]) {
        self.boxes.clear();
        self.boxes.extend_from_slice(boxes);
        self.items.clear();
        self.items.extend(0..boxes.len() as u32);
        self.nodes.clear();
        if boxes.is_empty() {
            return;
        }
        self.nodes.push(Node {
            aabb: Aabb::EMPTY,
            first: 0,
            count: 0,
        });
        self.build_node(0, 0, boxes.len());
    }

    fn build_node(&mut self, node: usize, start: usize, end: usize) {
        let mut aabb = Aabb::EMPTY;
        let mut centres = Aabb::EMPTY;
        for &k in &self.items[start..end] {
            let b = self.boxes[k as usize];
            aabb = aabb.union(b);
            let c = b.center();
            centres = centres.union(Aabb { min: c, max: c });
        }
        self.nodes[node].aabb = aabb;
        if end - start <= LEAF_SIZE {
            self.nodes[node].first = start as u32;
            self.nodes[node].count = (end - start) as u32;
            return;
        }
        let extent: Vector<D> = centres.max - centres.min;
        let axis = (0..D)
            .max_by(|&a, &b| extent[a].total_cmp(&extent[b]))
            .unwrap_or(0);
        let mid = start + (end - start) / 2;
        let boxes = &self.boxes;
        self.items[start..end].select_nth_unstable_by(mid - start, |&x, &y| {
            let (cx, cy) = (boxes[x as usize].center(), boxes[y as usize].center());
            cx[axis].total_cmp(&cy[axis]).then(x.cmp(&y))
        });
        let left = self.nodes.len();
        let blank = Node {
            aabb: Aabb::EMPTY,
            first: 0,
            count: 0,
        };
        self.nodes.push(blank);
        self.nodes.push(blank);
        self.nodes[node].first = left as u32;
        self.nodes[node].count = 0;
        self.build_node(left, start, mid);
        self.build_node(left + 1, mid, end);
    }

    /// Number of boxes in the tree.
    #[must_use]
    pub fn len(&self) -> usize {
        self.boxes.len()
    }

    /// True when the tree holds no box.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.boxes.is_empty()
    }

    /// Appends to `out` every pair `(i, j)`, `i < j`, of overlapping boxes (closed boxes:
    /// touching counts), sorted.
    pub fn overlapping_pairs(&mut self, out: &mut Vec<(u32, u32)>) {
        let from = out.len();
        for i in 0..self.boxes.len() {
            let q = self.boxes[i];
            self.stack.clear();
            if !self.nodes.is_empty() {
                self.stack.push(0);
            }
            while let Some(k) = self.stack.pop() {
                let node = self.nodes[k as usize];
                if !node.aabb.overlaps(&q) {
                    continue;
                }
                if node.count == 0 {
                    self.stack.push(node.first);
                    self.stack.push(node.first + 1);
                    continue;
                }
                let items = &self.items[node.first as usize..(node.first + node.count) as usize];
                for &j in items {
                    if j as usize > i && self.boxes[j as usize].overlaps(&q) {
                        out.push((i as u32, j));
                    }
                }
            }
        }
        out[from..].sort_unstable();
    }

    /// Checks the tree's invariants (every node's box holds its children's or items' boxes,
    /// every item appears in exactly one leaf); for tests.
    pub fn validate(&self) -> Result<(), String> {
        if self.boxes.is_empty() {
            return Ok(());
        }
        let mut seen = vec![false; self.boxes.len()];
        let mut stack = vec![0usize];
        while let Some(k) = stack.pop() {
            let node = &self.nodes[k];
            if node.count == 0 {
                for c in [node.first as usize, node.first as usize + 1] {
                    if !node.aabb.contains(&self.nodes[c].aabb) {
                        return Err(format!("node {k} does not hold child {c}"));
                    }
                    stack.push(c);
                }
            } else {
                for &j in &self.items[node.first as usize..(node.first + node.count) as usize] {
                    if !node.aabb.contains(&self.boxes[j as usize]) {
                        return Err(format!("leaf {k} does not hold box {j}"));
                    }
                    if std::mem::replace(&mut seen[j as usize], true) {
                        return Err(format!("box {j} is in two leaves"));
                    }
                }
            }
        }
        match seen.iter().position(|&s| !s) {
            Some(j) => Err(format!("box {j} is in no leaf")),
            None => Ok(()),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    fn random_boxes<const D: usize>(n: usize, seed: u64) -> Vec<Aabb<D>> {
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        (0..n)
            .map(|_| {
                let mut c = Vector::<D>::ZERO;
                for k in 0..D {
                    c[k] = rng.random_range(0.0..30.0);
                }
                Aabb::of_ball(c, rng.random_range(0.1..2.0))
            })
            .collect()
    }

    fn brute_force<const D: usize>(boxes: &[Aabb<D>]) -> Vec<(u32, u32)> {
        let mut out = Vec::new();
        for i in 0..boxes.len() {
            for j in i + 1..boxes.len() {
                if boxes[i].overlaps(&boxes[j]) {
                    out.push((i as u32, j as u32));
                }
            }
        }
        out
    }

    #[test]
    fn finds_exactly_the_overlapping_pairs() {
        let mut tree = OverlapTree::new();
        for (n, seed) in [(0, 1), (1, 1), (5, 2), (300, 3), (1000, 4)] {
            let boxes = random_boxes::<2>(n, seed);
            tree.build(&boxes);
            tree.validate().unwrap();
            let mut pairs = Vec::new();
            tree.overlapping_pairs(&mut pairs);
            assert_eq!(pairs, brute_force(&boxes), "n = {n}");
        }
        let boxes = random_boxes::<3>(500, 5);
        let mut tree = OverlapTree::new();
        tree.build(&boxes);
        tree.validate().unwrap();
        let mut pairs = Vec::new();
        tree.overlapping_pairs(&mut pairs);
        assert_eq!(pairs, brute_force(&boxes));
        assert!(!pairs.is_empty());
    }

    #[test]
    fn identical_boxes_all_pair_up() {
        let boxes = vec![Aabb::of_ball(Vector([1.0, 1.0]), 1.0); 9];
        let mut tree = OverlapTree::new();
        tree.build(&boxes);
        tree.validate().unwrap();
        let mut pairs = Vec::new();
        tree.overlapping_pairs(&mut pairs);
        assert_eq!(pairs.len(), 36);
    }
}
