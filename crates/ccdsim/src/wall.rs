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
        Wall::Segment { a, b } => away_from_segment(a, b, p).norm(),
        Wall::Plane { point, normal } => (p - point).dot(normal) / normal.norm(),
    }
}

/// [`wall_clearance`] and the unit vector along which the wall pushes a body at `p`: away
/// from a segment's nearest point (zero on the segment), along a plane's normal.
#[must_use]
pub(crate) fn wall_clearance_and_normal<const D: usize>(
    wall: &Wall<D>,
    p: Vector<D>,
) -> (f64, Vector<D>) {
    match *wall {
        Wall::Segment { a, b } => {
            let away = away_from_segment(a, b, p);
            let c = away.norm();
            if c > 0.0 {
                (c, away * (1.0 / c))
            } else {
                (0.0, Vector::default())
            }
        }
        Wall::Plane { point, normal } => {
            let len = normal.norm();
            ((p - point).dot(normal) / len, normal * (1.0 / len))
        }
    }
}

/// `p` less the nearest point of the segment from `a` to `b`.
fn away_from_segment<const D: usize>(a: Vector<D>, b: Vector<D>, p: Vector<D>) -> Vector<D> {
    let u = b - a;
    let s = ((p - a).dot(u) / u.norm_sq()).clamp(0.0, 1.0);
    p - (a + u * s)
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

/// The edges of the table the static walls form (2D), empty when they form none: the edges
/// of the closed polygons ([`closed_segments`]) when one of those polygons encloses every
/// other segment (its midpoint inside, by the even–odd rule) and no wall is a plane. Bodies
/// of a scene with a table lie inside it by the even–odd rule over all these edges (the other
/// polygons are holes in it). Without such a polygon the closed ones are obstacles in an
/// open or plane-bounded scene (bumpers in a pinball cabinet open at its drain, pegs between
/// planes), and no body is outside a table.
pub(crate) fn table_edges<const D: usize>(walls: &[Wall<D>]) -> Vec<(Vector<D>, Vector<D>)> {
    if D != 2 || walls.iter().any(|w| matches!(w, Wall::Plane { .. })) {
        return Vec::new();
    }
    let closed = closed_segments(walls);
    if closed.is_empty() {
        return closed;
    }
    // The closed polygons: edges joined at shared end points (each of degree 2).
    let bits = |v: Vector<D>| v.0.map(f64::to_bits);
    let mut parent: Vec<usize> = (0..closed.len()).collect();
    fn root(parent: &mut [usize], mut k: usize) -> usize {
        while parent[k] != k {
            parent[k] = parent[parent[k]];
            k = parent[k];
        }
        k
    }
    let mut first_at: HashMap<[u64; D], usize> = HashMap::new();
    for (k, (a, b)) in closed.iter().enumerate() {
        for p in [a, b] {
            let j = *first_at.entry(bits(*p)).or_insert(k);
            let (rj, rk) = (root(&mut parent, j), root(&mut parent, k));
            parent[rj] = rk;
        }
    }
    let polygon: Vec<usize> = (0..closed.len()).map(|k| root(&mut parent, k)).collect();
    let segments: Vec<(Vector<D>, Vector<D>)> = walls
        .iter()
        .filter_map(|w| match *w {
            Wall::Segment { a, b } => Some((a, b)),
            Wall::Plane { .. } => None,
        })
        .collect();
    let encloses_the_rest = |p: usize| {
        let edges: Vec<_> = (0..closed.len())
            .filter(|&k| polygon[k] == p)
            .map(|k| closed[k])
            .collect();
        let own = |s: &(Vector<D>, Vector<D>)| {
            edges
                .iter()
                .any(|e| bits(e.0) == bits(s.0) && bits(e.1) == bits(s.1))
        };
        segments.iter().filter(|s| !own(s)).all(|(a, b)| {
            let m = (*a + *b) * 0.5;
            inside_even_odd(&edges, m[0], m[1])
        })
    };
    let mut roots = polygon.clone();
    roots.sort_unstable();
    roots.dedup();
    if roots.into_iter().any(encloses_the_rest) {
        closed
    } else {
        Vec::new()
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
    fn a_table_is_a_closed_polygon_around_every_other_segment() {
        let square = |x: f64, y: f64, s: f64| {
            vec![
                seg([x, y], [x + s, y]),
                seg([x + s, y], [x + s, y + s]),
                seg([x + s, y + s], [x, y + s]),
                seg([x, y + s], [x, y]),
            ]
        };
        // A box with a square obstacle and a shelf inside: the box is the table, the
        // obstacle a hole in it.
        let mut boxed = square(0.0, 0.0, 10.0);
        boxed.extend(square(4.0, 4.0, 1.0));
        boxed.push(seg([1.0, 8.0], [3.0, 8.0]));
        let table = table_edges(&boxed);
        assert_eq!(table.len(), 8);
        assert!(inside_even_odd(&table, 2.0, 2.0));
        assert!(!inside_even_odd(&table, 4.5, 4.5) && !inside_even_odd(&table, 11.0, 2.0));
        // A cabinet open at the bottom with two square bumpers in it: no table.
        let mut cabinet = vec![
            seg([0.0, 0.0], [0.0, 10.0]),
            seg([0.0, 10.0], [10.0, 10.0]),
            seg([10.0, 10.0], [10.0, 0.0]),
        ];
        cabinet.extend(square(2.0, 5.0, 1.0));
        cabinet.extend(square(6.0, 5.0, 1.0));
        assert_eq!(closed_segments(&cabinet).len(), 8);
        assert!(table_edges(&cabinet).is_empty());
        // A polygon alone is a table; between planes it is an obstacle.
        assert_eq!(table_edges(&square(0.0, 0.0, 1.0)).len(), 4);
        let mut between = square(0.0, 0.0, 1.0);
        between.push(Wall::Plane {
            point: Vector([0.0, -5.0]),
            normal: Vector([0.0, 1.0]),
        });
        assert!(table_edges(&between).is_empty());
        // Two boxes side by side: neither encloses the other, no table.
        let mut two = square(0.0, 0.0, 1.0);
        two.extend(square(3.0, 0.0, 1.0));
        assert!(table_edges(&two).is_empty());
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
