//! Static walls: segments and one-sided planes, and their geometry (clearance, closed
//! polygons).
//!
//! Kept apart from the scene format so that the narrow phase, the periodic box and the
//! scene's validation can all use walls without importing one another.

use crate::geom::Vector;
use serde::{Deserialize, Serialize};
use std::collections::HashMap;

/// A static wall. Walls never move and have infinite mass.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(untagged)]
pub enum Wall<const D: usize> {
    /// A segment from `a` to `b` (the usual 2D wall). A body can touch it from either side or
    /// at its end points.
    Segment {
        /// First end point.
        a: Vector<D>,
        /// Second end point.
        b: Vector<D>,
    },
    /// A one-sided plane (the usual 3D wall; a line in 2D) through `point`. Bodies live on the
    /// side `normal` points to; the normal need not be of unit length.
    Plane {
        /// Any point of the plane.
        point: Vector<D>,
        /// Direction towards the bodies' side.
        normal: Vector<D>,
    },
}

/// The box bounding the walls' points (segment ends, plane points) as `(lo, hi)`, metres, if
/// it has a positive, finite extent along every axis: the volume of a walled scene.
#[must_use]
pub fn walls_bounds<const D: usize>(walls: &[Wall<D>]) -> Option<(Vector<D>, Vector<D>)> {
    let mut lo = Vector([f64::INFINITY; D]);
    let mut hi = Vector([f64::NEG_INFINITY; D]);
    let mut grow = |p: &Vector<D>| {
        for d in 0..D {
            lo[d] = lo[d].min(p[d]);
            hi[d] = hi[d].max(p[d]);
        }
    };
    for wall in walls {
        match wall {
            Wall::Segment { a, b } => {
                grow(a);
                grow(b);
            }
            Wall::Plane { point, .. } => grow(point),
        }
    }
    (0..D)
        .all(|d| (hi[d] - lo[d]).is_finite() && hi[d] > lo[d])
        .then_some((lo, hi))
}

/// Distance from `p` to the wall (signed for planes: negative behind it).
#[must_use]
pub fn wall_clearance<const D: usize>(wall: &Wall<D>, p: Vector<D>) -> f64 {
    match *wall {
        Wall::Segment { a, b } => {
            let u = b - a;
            let s = ((p - a).dot(u) / u.norm_sq()).clamp(0.0, 1.0);
            (p - (a + u * s)).norm()
        }
        Wall::Plane { point, normal } => (p - point).dot(normal) / normal.norm(),
    }
}

/// Segments both of whose end points are shared with exactly one other segment end, on
/// chains that close: the edges of closed polygons. The inner pieces of an open chain (a
/// shelf drawn in pieces) are no polygon's edges.
pub(crate) fn closed_segments<const D: usize>(walls: &[Wall<D>]) -> Vec<(Vector<D>, Vector<D>)> {
    let mut segs: Vec<(Vector<D>, Vector<D>)> = walls
        .iter()
        .filter_map(|w| match *w {
            Wall::Segment { a, b } => Some((a, b)),
            Wall::Plane { .. } => None,
        })
        .collect();
    let bits = |v: Vector<D>| v.0.map(f64::to_bits);
    let degrees = |segs: &[(Vector<D>, Vector<D>)]| {
        let mut degree: HashMap<[u64; D], usize> = HashMap::new();
        for (a, b) in segs {
            *degree.entry(bits(*a)).or_default() += 1;
            *degree.entry(bits(*b)).or_default() += 1;
        }
        degree
    };
    let degree = degrees(&segs);
    segs.retain(|(a, b)| degree[&bits(*a)] == 2 && degree[&bits(*b)] == 2);
    // Peel open chains from their loose ends until only closed ones are left.
    loop {
        let degree = degrees(&segs);
        let before = segs.len();
        segs.retain(|(a, b)| degree[&bits(*a)] == 2 && degree[&bits(*b)] == 2);
        if segs.len() == before {
            return segs;
        }
    }
}

/// True when the point `(x, y)` lies inside the polygons formed by `segs`, by the even–odd
/// rule.
pub(crate) fn inside_even_odd<const D: usize>(
    segs: &[(Vector<D>, Vector<D>)],
    x: f64,
    y: f64,
) -> bool {
    let mut inside = false;
    for (a, b) in segs {
        let (ax, ay, bx, by) = (a[0], a[1], b[0], b[1]);
        if (ay > y) != (by > y) {
            let cross_x = ax + (y - ay) * (bx - ax) / (by - ay);
            if x < cross_x {
                inside = !inside;
            }
        }
    }
    inside
}

#[cfg(test)]
mod tests {
    use super::*;

    fn seg(a: [f64; 2], b: [f64; 2]) -> Wall<2> {
        Wall::Segment {
            a: Vector(a),
            b: Vector(b),
        }
    }

    #[test]
    fn a_square_is_closed_and_a_shelf_in_pieces_is_not() {
        let square = [
            seg([0.0, 0.0], [1.0, 0.0]),
            seg([1.0, 0.0], [1.0, 1.0]),
            seg([1.0, 1.0], [0.0, 1.0]),
            seg([0.0, 1.0], [0.0, 0.0]),
        ];
        assert_eq!(closed_segments(&square).len(), 4);
        let shelf = [
            seg([0.0, 2.0], [1.0, 2.0]),
            seg([2.0, 2.0], [1.0, 2.0]),
            seg([2.0, 2.0], [3.0, 2.0]),
            seg([3.0, 2.0], [4.0, 2.0]),
        ];
        assert!(closed_segments(&shelf).is_empty());
        let both: Vec<_> = square.iter().chain(&shelf).copied().collect();
        assert_eq!(closed_segments(&both).len(), 4);
    }
}
