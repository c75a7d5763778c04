//! A uniform grid over a pool table: the `cells` finder's broad phase. Each ball is listed in
//! every cell its swept box covers, each part of the table in every cell its box covers; a
//! ball's contacts are looked for only with what shares a cell with it.

use crate::geom::{Aabb, Vector};

/// The grid: cells of one size over the table's extent, the balls and the table's parts
/// listed in the cells their boxes cover.
#[derive(Clone, Debug)]
pub(crate) struct BallGrid {
    origin: Vector<2>,
    /// Cells per metre.
    inverse_size: f64,
    dims: [usize; 2],
    /// The balls listed in each cell (row-major, `x` fastest).
    balls: Vec<Vec<u32>>,
    /// The table's parts listed in each cell.
    parts: Vec<Vec<u32>>,
    /// Each ball's cells as `[x0, x1, y0, y1]` (inclusive), if it is listed.
    spans: Vec<Option<[usize; 4]>>,
    /// The last query each ball and part was found in, to report it once.
    ball_seen: Vec<u32>,
    part_seen: Vec<u32>,
    query: u32,
}

impl BallGrid {
    /// A grid over `extent` (metres) with cells about `cell` metres wide, `balls` balls not
    /// yet listed, and the table's parts with boxes `parts`.
    pub fn new(extent: Aabb<2>, cell: f64, balls: usize, parts: &[Aabb<2>]) -> BallGrid {
        let size = extent.max - extent.min;
        // Past 4096 cells a side the outer cells just grow: indices are clamped.
        let dims = [0, 1].map(|k| ((size[k] / cell).ceil() as usize).clamp(1, 1 << 12));
        let inverse_size = 1.0 / cell;
        let mut grid = BallGrid {
            origin: extent.min,
            inverse_size,
            dims,
            balls: vec![Vec::new(); dims[0] * dims[1]],
            parts: vec![Vec::new(); dims[0] * dims[1]],
            spans: vec![None; balls],
            ball_seen: vec![0; balls],
            part_seen: vec![0; parts.len()],
            query: 0,
        };
        for (k, b) in parts.iter().enumerate() {
            if let Some(span) = grid.span(b) {
                for cell in cells(span, dims[0]) {
                    grid.parts[cell].push(k as u32);
                }
            }
        }
        grid
    }

    /// The cell index along axis `k` of coordinate `x`: monotone in `x` (a subtraction and a
    /// multiplication by a positive number round monotonically), so two boxes that share a
    /// point share a cell, also where the point lies on a cell face; clamped to the grid,
    /// so the outer cells reach to infinity.
    fn index(&self, x: f64, k: usize) -> usize {
        let c = ((x - self.origin[k]) * self.inverse_size).floor();
        c.clamp(0.0, (self.dims[k] - 1) as f64) as usize
    }

    fn span(&self, b: &Aabb<2>) -> Option<[usize; 4]> {
        if !(b.min[0] <= b.max[0] && b.min[1] <= b.max[1]) {
            return None;
        }
        Some([
            self.index(b.min[0], 0),
            self.index(b.max[0], 0),
            self.index(b.min[1], 1),
            self.index(b.max[1], 1),
        ])
    }

    /// Lists ball `i` in the cells of its new box `b` (none for an empty box) instead of its
    /// old ones.
    pub fn place(&mut self, i: usize, b: &Aabb<2>) {
        let id = i as u32;
        if let Some(old) = self.spans[i].take() {
            for cell in cells(old, self.dims[0]) {
                let list = &mut self.balls[cell];
                if let Some(at) = list.iter().position(|&j| j == id) {
                    list.swap_remove(at);
                }
            }
        }
        if let Some(span) = self.span(b) {
            for cell in cells(span, self.dims[0]) {
                self.balls[cell].push(id);
            }
            self.spans[i] = Some(span);
        }
    }

    /// Appends to `balls` every other ball and to `parts` every part of the table listed in a
    /// cell ball `i` is listed in, each once.
    pub fn near(&mut self, i: usize, balls: &mut Vec<usize>, parts: &mut Vec<usize>) {
        let Some(span) = self.spans[i] else {
            return;
        };
        self.query = self.query.wrapping_add(1);
        if self.query == 0 {
            self.ball_seen.fill(0);
            self.part_seen.fill(0);
            self.query = 1;
        }
        let q = self.query;
        self.ball_seen[i] = q;
        for cell in cells(span, self.dims[0]) {
            for &j in &self.balls[cell] {
                if self.ball_seen[j as usize] != q {
                    self.ball_seen[j as usize] = q;
                    balls.push(j as usize);
                }
            }
            for &k in &self.parts[cell] {
                if self.part_seen[k as usize] != q {
                    self.part_seen[k as usize] = q;
                    parts.push(k as usize);
                }
            }
        }
    }
}

/// The cells of the span `[x0, x1, y0, y1]` on a grid `width` cells wide.
fn cells([x0, x1, y0, y1]: [usize; 4], width: usize) -> impl Iterator<Item = usize> {
    (y0..=y1).flat_map(move |y| (x0..=x1).map(move |x| y * width + x))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::billiards::lattice_boxes::lattice_box;
    use proptest::prelude::*;

    proptest! {
        /// Balls and parts whose boxes overlap a ball's are found, on cell faces too
        /// (integer and half-integer corners on a grid of unit cells).
        #[test]
        fn whatever_overlaps_a_ball_shares_a_cell_with_it(
            balls in prop::collection::vec(((-6i32..6, -6i32..6), 0u8..5), 1..20),
            parts in prop::collection::vec(((-6i32..6, -6i32..6), 0u8..3), 0..10),
            moves in prop::collection::vec((0usize..20, (-6i32..6, -6i32..6), 0u8..5), 0..10),
        ) {
            let to_box = |b: ((i32, i32), u8)| lattice_box(b, 0.5);
            let part_boxes: Vec<Aabb<2>> = parts.iter().map(|&p| to_box((p.0, p.1 + 1))).collect();
            let mut boxes: Vec<Aabb<2>> = balls.iter().map(|&b| to_box(b)).collect();
            let extent = Aabb::of_ball(Vector([0.0, 0.0]), 2.0);
            let mut grid = BallGrid::new(extent, 1.0, boxes.len(), &part_boxes);
            for (i, b) in boxes.iter().enumerate() {
                grid.place(i, b);
            }
            for (i, c, r) in moves {
                let i = i % boxes.len();
                boxes[i] = to_box((c, r));
                grid.place(i, &boxes[i]);
            }
            for i in 0..boxes.len() {
                let (mut near, mut near_parts) = (Vec::new(), Vec::new());
                grid.near(i, &mut near, &mut near_parts);
                for (j, b) in boxes.iter().enumerate() {
                    if j != i && b.overlaps(&boxes[i]) {
                        prop_assert!(near.contains(&j), "ball {} misses ball {}", i, j);
                    }
                }
                for (k, b) in part_boxes.iter().enumerate() {
                    if b.overlaps(&boxes[i]) {
                        prop_assert!(near_parts.contains(&k), "ball {} misses part {}", i, k);
                    }
                }
                let mut once = near.clone();
                once.sort_unstable();
                once.dedup();
                prop_assert_eq!(once.len(), near.len());
                prop_assert!(!near.contains(&i));
            }
        }
    }
}
