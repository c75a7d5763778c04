//! The hierarchy's storage: a flat array of nodes in pre-order over a permutation of the
//! bodies, and the padded swept box of one body (the only geometric primitive it holds).

use crate::geom::{Aabb, Vector};
use crate::motion::Motion;

/// Padding, relative to a body's radius plus its travel since its reference time, that covers
/// the narrow phase's root-finding error (of order √ε times those lengths; see the module
/// docs of [`super`]). 10⁻⁵ leaves a margin of about a hundred over that bound.
pub(crate) const ROOT_PAD: f64 = 1e-5;

/// Padding, relative to the magnitudes of coordinates and absolute times, that covers the
/// rounding of positions `p + v·(t − t_i)` and of event times `t0 + dt` (of order ε times
/// those magnitudes). 10⁻¹² is several thousand ε.
pub(crate) const ROUND_PAD: f64 = 1e-12;

/// One node of the hierarchy: its box and the bodies below it, `order[start..start + count]`.
///
/// Nodes are stored in pre-order: the left child of node `k` is `k + 1` and holds the first
/// `count / 2` bodies; the right child is `k + 2·(count / 2)` and holds the rest. A leaf
/// (`count == 1`) holds one body. `n` bodies take exactly `2n − 1` nodes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Node<const D: usize> {
    /// Encloses the swept boxes of every body below the node, metres.
    pub aabb: Aabb<D>,
    /// First position in [`SweptTree::order`].
    pub start: u32,
    /// Number of bodies below the node (≥ 1).
    pub count: u32,
}

impl<const D: usize> Node<D> {
    /// True when the node holds a single body.
    #[inline]
    pub fn is_leaf(&self) -> bool {
        self.count == 1
    }
}

/// Index of the left and right children of inner node `k` holding `count` bodies.
#[inline]
pub(crate) fn children(k: usize, count: u32) -> (usize, usize) {
    (k + 1, k + 2 * (count / 2) as usize)
}

/// A balanced bounding-volume hierarchy over the bodies' swept boxes for the time interval
/// `[now, horizon]`, kept in flat arrays and reused from one search to the next.
#[derive(Clone, Debug)]
pub(crate) struct SweptTree<const D: usize> {
    /// The nodes in pre-order; empty when there are no bodies.
    pub nodes: Vec<Node<D>>,
    /// A permutation of the body indices; every node holds a contiguous range of it.
    pub order: Vec<u32>,
    /// Scratch: each body's swept box during a build, by body index.
    pub leaf_boxes: Vec<Aabb<D>>,
    /// Scratch: the bodies with their sort keys during a build.
    pub items: Vec<Item<D>>,
    /// Start of the swept interval, seconds (the world's current time at the build).
    pub now: f64,
    /// End of the swept interval, seconds: `now + Δ`.
    pub horizon: f64,
    /// The horizon at the last build (the median split is only guaranteed for it).
    pub built_horizon: f64,
    /// True when every box is finite (no overflowing position); a search on a tree with
    /// non-finite boxes would be unsound, so the finder falls back to checking every pair.
    pub finite: bool,
    /// The box of all balls at `now` (not swept), metres.
    pub extent_now: Aabb<D>,
    /// In a periodic world, half of the non-zero image shifts (see
    /// [`half_image_shifts`]), set by each build; empty
    /// otherwise.
    pub shifts: Vec<Vector<D>>,
}

impl<const D: usize> Default for SweptTree<D> {
    fn default() -> Self {
        SweptTree {
            nodes: Vec::new(),
            order: Vec::new(),
            leaf_boxes: Vec::new(),
            items: Vec::new(),
            now: 0.0,
            horizon: 0.0,
            built_horizon: 0.0,
            finite: true,
            extent_now: Aabb::EMPTY,
            shifts: Vec::new(),
        }
    }
}

impl<const D: usize> SweptTree<D> {
    /// The body held by leaf `node`.
    #[inline]
    pub fn body(&self, node: &Node<D>) -> usize {
        self.order[node.start as usize] as usize
    }
}

/// Largest absolute component.
#[inline]
fn max_abs<const D: usize>(v: Vector<D>) -> f64 {
    v.0.iter().fold(0.0, |m, x| m.max(x.abs()))
}

/// Sum of absolute components (an upper bound of the Euclidean length).
#[inline]
pub(crate) fn l1<const D: usize>(v: Vector<D>) -> f64 {
    v.0.iter().map(|x| x.abs()).sum()
}

/// The padded box enclosing a ball of radius `r` moving along `m` at every time in
/// `[now, horizon]`: the box of the ball at both ends (a moving ball's box is the convex hull
/// of those two), grown by the padding that makes rounding unable to separate two bodies
/// whose computed time of impact lies in the interval.
///
/// Under gravity `g` the ball follows a parabola: along each axis its coordinate is extreme
/// at the ends or at the vertex, so the box of the three encloses it; speeds are bounded by
/// the stored speed plus `|g|` times the longest time from the reference time.
#[must_use]
#[inline]
pub(crate) fn swept_box<const D: usize>(
    m: &Motion<D>,
    r: f64,
    now: f64,
    horizon: f64,
    gravity: Option<&Vector<D>>,
) -> Aabb<D> {
    let Some(g) = gravity else {
        return straight_swept_box(m, r, now, horizon);
    };
    let (mut lo, mut hi) = {
        let (p0, p1) = (m.falling_at(now, g), m.falling_at(horizon, g));
        (p0.min(p1), p0.max(p1))
    };
    for d in 0..D {
        if g[d] != 0.0 {
            let vertex = m.time - m.vel[d] / g[d];
            if vertex > now && vertex < horizon {
                let x = m.falling_at(vertex, g)[d];
                lo[d] = lo[d].min(x);
                hi[d] = hi[d].max(x);
            }
        }
    }
    let span = (now - m.time).abs().max((horizon - m.time).abs());
    let speed = l1(m.vel) + l1(*g) * span;
    let pad = ROOT_PAD * (r + speed * span)
        + ROUND_PAD
            * (max_abs(lo).max(max_abs(hi))
                + speed * (m.time.abs() + horizon.abs())
                + l1(*g) * span * span);
    if !(lo.is_finite() && hi.is_finite() && pad.is_finite()) {
        return Aabb {
            min: Vector::splat(f64::NAN),
            max: Vector::splat(f64::NAN),
        };
    }
    let e = Vector::splat(r + pad);
    Aabb {
        min: lo - e,
        max: hi + e,
    }
}

/// [`swept_box`] without gravity.
#[inline]
fn straight_swept_box<const D: usize>(m: &Motion<D>, r: f64, now: f64, horizon: f64) -> Aabb<D> {
    let p0 = m.at(now);
    let p1 = m.at(horizon);
    let speed = l1(m.vel);
    let pad = ROOT_PAD * (r + speed * (horizon - m.time).abs())
        + ROUND_PAD * (max_abs(p0).max(max_abs(p1)) + speed * (m.time.abs() + horizon.abs()));
    if !(p0.is_finite() && p1.is_finite() && pad.is_finite()) {
        // `f64::min` would hide a NaN; make the box visibly non-finite instead.
        return Aabb {
            min: Vector::splat(f64::NAN),
            max: Vector::splat(f64::NAN),
        };
    }
    let e = Vector::splat(r + pad);
    Aabb {
        min: p0.min(p1) - e,
        max: p0.max(p1) + e,
    }
}

/// True when both corners of `b` are finite numbers (false for the box [`swept_box`] returns
/// when a position overflows).
#[inline]
pub(crate) fn is_finite_box<const D: usize>(b: &Aabb<D>) -> bool {
    b.min.is_finite() && b.max.is_finite()
}

/// A body and twice the centre of its swept box, the build's sort key.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Item<const D: usize> {
    pub(super) key: [f64; D],
    pub(super) body: u32,
}

/// Sets `out` to half of the `3^D − 1` non-zero image shifts `k·L`, `k ∈ {−1, 0, 1}^D`:
/// those whose first non-zero component is positive. Each other shift is the negation of one
/// of them.
pub(crate) fn half_image_shifts<const D: usize>(size: &Vector<D>, out: &mut Vec<Vector<D>>) {
    out.clear();
    for code in 0..3usize.pow(D as u32) {
        let mut k = [0i32; D];
        let mut c = code;
        for kd in &mut k {
            *kd = (c % 3) as i32 - 1;
            c /= 3;
        }
        if k.iter().find(|&&x| x != 0).is_some_and(|&x| x > 0) {
            out.push(Vector(std::array::from_fn(|d| f64::from(k[d]) * size[d])));
        }
    }
}
