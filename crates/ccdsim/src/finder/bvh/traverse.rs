//! "BVH collision check" (thesis Algorithm 3): the self-check of a node and the pair-check of
//! two nodes, ending in the narrow phase on body pairs whose leaf boxes overlap; in a periodic
//! box also the pair-check of the tree against its own images.

use super::tree::{children, SweptTree, ROUND_PAD};
use crate::contact::lees_edwards::{toi_bodies_sheared, ShearedBox};
use crate::contact::periodic::toi_bodies_periodic;
use crate::event::Event;
use crate::geom::{Aabb, Vector};
use crate::world::toi_bodies_in;
use crate::world::World;

/// What one traversal found and how much work it took.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct Traversal {
    /// The earliest body–body event under the total order whose time is at most the tree's
    /// horizon, if any.
    pub best: Option<Event>,
    /// Body pairs handed to the narrow phase.
    pub narrow_calls: u64,
    /// In a sheared box, the layer above slid past more than [`MAX_SHEARED_IMAGES`] periods
    /// over the interval: no search was made (the caller checks every pair instead).
    pub too_wide: bool,
}

/// Most x images of the sheared layer above that one traversal checks the tree against: a
/// longer interval makes the images' swept boxes cover the box many times over, where
/// checking every pair costs less.
const MAX_SHEARED_IMAGES: i64 = 64;

struct Check<'a, const D: usize> {
    tree: &'a SweptTree<D>,
    world: &'a World<D>,
    horizon: f64,
    /// The sides of the periodic box, if the world has one.
    period: Option<Vector<D>>,
    /// The sheared box, if the world is one.
    shear: Option<ShearedBox<D>>,
    out: Traversal,
}

impl<const D: usize> SweptTree<D> {
    /// Runs Algorithm 3 from the root: every body pair whose leaf boxes overlap is given to
    /// [`toi_circle_circle`](crate::contact::narrow::toi_circle_circle), and the earliest resulting
    /// event with time ≤ `horizon` is kept (ties by the event order).
    ///
    /// If the leaf boxes are [`swept_box`](super::tree::swept_box)es for `[now, horizon]`, a
    /// pair whose computed time of impact lies in that interval always reaches the narrow
    /// phase, so `best` is the minimum over *all* pairs with time ≤ `horizon`.
    ///
    /// In a periodic world (`world.periodic()`), pairs are evaluated by the oracle's periodic
    /// narrow phase
    /// [`toi_circle_circle_periodic`](crate::contact::periodic::toi_circle_circle_periodic), and
    /// the tree is also checked against each of its images shifted by [`SweptTree::shifts`] (half
    /// of the non-zero shifts `k·L`, see [`half_image_shifts`](super::tree::half_image_shifts)): a
    /// pair touching through image `k` of its second body has overlapping boxes once that body's
    /// box is shifted by `k·L`, or the first body's by `−k·L`, and one of the two shifts is in the
    /// half.
    pub fn earliest_body_event(&self, world: &World<D>) -> Traversal {
        let mut c = Check {
            tree: self,
            world,
            horizon: self.horizon,
            period: world.periodic(),
            shear: world.shear(),
            out: Traversal::default(),
        };
        if !self.nodes.is_empty() {
            if let Some(bx) = c.shear {
                if self.sheared_images(&bx).is_none() {
                    c.out.too_wide = true;
                    return c.out;
                }
            }
            c.self_check(0);
            if let Some(size) = c.period {
                // Shifting a box by `k·L` rounds by a few ε of `L`; the padding covers
                // thousands of times that (see the module docs of `super`).
                let pad = 4.0 * ROUND_PAD * size.0.iter().fold(0.0f64, |m, &x| m.max(x.abs()));
                for &shift in &self.shifts {
                    // In a sheared box the layers above and below slide: only the shifts
                    // within the layer are fixed.
                    if c.shear.is_none() || shift[1] == 0.0 {
                        c.image_check(0, 0, (shift, shift), pad);
                    }
                }
                if let Some(bx) = c.shear {
                    let pad = pad + 4.0 * ROUND_PAD * (bx.size[0] + self.sweep(&bx).abs());
                    for span in self.sheared_images(&bx).into_iter().flatten() {
                        c.image_check(0, 0, span, pad);
                    }
                }
            }
        }
        c.out
    }

    /// How far the layer above slides along x over the tree's interval, metres.
    fn sweep(&self, bx: &ShearedBox<D>) -> f64 {
        bx.layer_speed() * (self.horizon - self.now)
    }

    /// In a sheared box, the images of the layer above (see
    /// [`crate::contact::lees_edwards`]) the tree is checked against, as the least and
    /// greatest shifts of a box over the tree's interval: `(s_x + k·L_x, L_y, k_z·L_z)` with
    /// `s_x` from the strain offset now to the offset at the horizon, for every `k` whose
    /// images can meet the tree's box and `k_z ∈ {−1, 0, 1}`. A pair touching through an
    /// image of the layer below is found from its other body, through the layer above.
    /// `None` when more than [`MAX_SHEARED_IMAGES`] x images would be needed.
    fn sheared_images(&self, bx: &ShearedBox<D>) -> Option<Vec<(Vector<D>, Vector<D>)>> {
        let root = self.nodes[0].aabb;
        let (lx, base, sweep) = (bx.size[0], bx.offset(self.now), self.sweep(bx));
        let (lo, hi) = (sweep.min(0.0), sweep.max(0.0));
        let width = root.max[0] - root.min[0];
        let first = ((-width - base - hi) / lx).floor();
        let last = ((width - base - lo) / lx).ceil();
        // In floats: an unbounded sweep (or a NaN) fails the test instead of overflowing.
        let count = last - first;
        if count.is_nan() || count >= MAX_SHEARED_IMAGES as f64 {
            return None;
        }
        let (first, last) = (first as i64, last as i64);
        let mut out = Vec::new();
        for k in first..=last {
            for kz in if D == 3 { -1..=1 } else { 0..=0 } {
                let mut low = Vector::ZERO;
                low[1] = bx.size[1];
                if D == 3 {
                    low[D - 1] = f64::from(kz) * bx.size[D - 1];
                }
                let mut high = low;
                low[0] = base + k as f64 * lx + lo;
                high[0] = base + k as f64 * lx + hi;
                out.push((low, high));
            }
        }
        Some(out)
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

    /// Pairs with one body below node `a` and the other below node `b` (any two nodes, the
    /// same one included), `b`'s boxes shifted by anything from `shift.0` to `shift.1`
    /// (the same shift but for a sheared layer sliding past) and grown by `pad`.
    fn image_check(&mut self, a: usize, b: usize, shift: (Vector<D>, Vector<D>), pad: f64) {
        let (na, nb) = (self.tree.nodes[a], self.tree.nodes[b]);
        let grow = Vector::splat(pad);
        let moved = Aabb {
            min: nb.aabb.min + shift.0 - grow,
            max: nb.aabb.max + shift.1 + grow,
        };
        if !na.aabb.overlaps(&moved) {
            return;
        }
        match (na.is_leaf(), nb.is_leaf()) {
            (true, true) => {
                let (i, j) = (self.tree.body(&na), self.tree.body(&nb));
                if i != j {
                    self.narrow(i, j);
                }
            }
            (true, false) => {
                let (l, r) = children(b, nb.count);
                self.image_check(a, l, shift, pad);
                self.image_check(a, r, shift, pad);
            }
            (false, true) => {
                let (l, r) = children(a, na.count);
                self.image_check(l, b, shift, pad);
                self.image_check(r, b, shift, pad);
            }
            (false, false) => {
                let (al, ar) = children(a, na.count);
                let (bl, br) = children(b, nb.count);
                self.image_check(al, bl, shift, pad);
                self.image_check(al, br, shift, pad);
                self.image_check(ar, bl, shift, pad);
                self.image_check(ar, br, shift, pad);
            }
        }
    }

    /// The narrow phase, called exactly as the oracle calls it (lower index first; in a
    /// periodic world the earliest contact over the images, as the oracle computes it).
    #[inline]
    fn narrow(&mut self, i: usize, j: usize) {
        let (i, j) = if i < j { (i, j) } else { (j, i) };
        if !self.world.collides(i, j) {
            return;
        }
        self.out.narrow_calls += 1;
        let bodies = self.world.bodies();
        let t = match (&self.period, &self.shear) {
            (None, _) => toi_bodies_in(self.world, i, j),
            (Some(size), None) => {
                toi_bodies_periodic(&bodies[i], &bodies[j], size, self.world.laws())
            }
            (Some(_), Some(bx)) => {
                toi_bodies_sheared(&bodies[i], &bodies[j], bx, self.world.laws())
            }
        };
        let Some(t) = t else {
            return;
        };
        if t <= self.horizon {
            self.out.best = Event::earliest(self.out.best, Some(Event::body(t, i, j)));
        }
    }
}
