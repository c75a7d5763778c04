//! The contact network of a packing: which bodies touch (within a tolerance), the rattlers,
//! and the mean contact number of the rest.

use crate::contact::periodic::{min_image, wrap_point};
use crate::geom::Vector;
use crate::wall::{wall_clearance, Wall};
use std::collections::HashMap;

/// The contacts of a packing.
#[derive(Clone, Debug, PartialEq)]
pub struct ContactNetwork {
    /// Body pairs `(i, j)`, `i < j`, whose gap is within the tolerance.
    pub pairs: Vec<(usize, usize)>,
    /// Body–wall contacts `(body, wall)` within the tolerance.
    pub walls: Vec<(usize, usize)>,
    /// Rattlers: bodies left with fewer than `D + 1` contacts once every rattler's contacts
    /// are removed, repeatedly (a body held by fewer cannot be locked in place).
    pub rattlers: Vec<usize>,
    /// Mean number of contacts of the bodies that are not rattlers (body and wall contacts
    /// among them); 0 when every body is a rattler. Isostatic packings have `2D`, less
    /// `O(1/N)`.
    pub mean_contacts: f64,
    /// Contacts among the bodies that are not rattlers, wall contacts included.
    pub held_contacts: usize,
    /// The fewest contacts that can hold the bodies that are not rattlers rigid, their
    /// degrees of freedom (Maxwell's count): `D (N' − 1)` for `N'` of them in a periodic box
    /// (D per body less the box's free translation), `D N'` between walls; 0 when every body
    /// is a rattler. A jammed frictionless packing has this many (it is isostatic), or a few
    /// more.
    pub isostatic_contacts: usize,
}

impl ContactNetwork {
    /// Whether the contacts are enough to hold the packing rigid: some body is held and the
    /// held bodies have at least [`ContactNetwork::isostatic_contacts`] contacts. This is the
    /// count a jammed packing needs, not a proof that the network is rigid.
    #[must_use]
    pub fn is_rigid(&self) -> bool {
        self.isostatic_contacts > 0 && self.held_contacts >= self.isostatic_contacts
    }
}

/// The contact network of bodies at `positions` with `radii` (metres): a pair touches when
/// its gap, `|x_j − x_i| − (r_i + r_j)` (nearest images in a periodic box of sides
/// `periodic`), is at most `tolerance · (r_i + r_j)`; a body touches a wall when its clearance
/// less its radius is at most `tolerance · r_i`. Pairs are found on a grid of cells at least
/// one contact distance wide: O(N) at a fixed density.
#[must_use]
pub fn contact_network<const D: usize>(
    positions: &[Vector<D>],
    radii: &[f64],
    walls: &[Wall<D>],
    periodic: Option<Vector<D>>,
    tolerance: f64,
) -> ContactNetwork {
    let n = positions.len();
    let r_max = radii.iter().copied().fold(0.0f64, f64::max);
    let reach = 2.0 * r_max * (1.0 + tolerance);
    let pairs = if n < 2 || reach <= 0.0 {
        Vec::new()
    } else {
        close_pairs(positions, periodic, reach, |i, j, d| {
            let sigma = radii[i] + radii[j];
            d.norm() - sigma <= tolerance * sigma
        })
    };
    let mut wall_contacts = Vec::new();
    for (i, (&p, &r)) in positions.iter().zip(radii).enumerate() {
        for (w, wall) in walls.iter().enumerate() {
            if wall_clearance(wall, p) - r <= tolerance * r {
                wall_contacts.push((i, w));
            }
        }
    }
    let mut count = vec![0usize; n];
    for &(i, j) in &pairs {
        count[i] += 1;
        count[j] += 1;
    }
    for &(i, _) in &wall_contacts {
        count[i] += 1;
    }
    // Peel rattlers: a body with fewer than D + 1 contacts is one, and takes its contacts
    // away from its partners, which may make them rattlers too.
    let mut partners = vec![Vec::new(); n];
    for &(i, j) in &pairs {
        partners[i].push(j);
        partners[j].push(i);
    }
    let mut rattler = vec![false; n];
    let mut stack: Vec<usize> = (0..n).filter(|&i| count[i] < D + 1).collect();
    while let Some(i) = stack.pop() {
        if rattler[i] {
            continue;
        }
        rattler[i] = true;
        for &j in &partners[i] {
            if !rattler[j] {
                count[j] -= 1;
                if count[j] < D + 1 {
                    stack.push(j);
                }
            }
        }
    }
    let held: Vec<usize> = (0..n).filter(|&i| !rattler[i]).collect();
    let mean_contacts = if held.is_empty() {
        0.0
    } else {
        held.iter().map(|&i| count[i]).sum::<usize>() as f64 / held.len() as f64
    };
    let held_contacts = pairs
        .iter()
        .filter(|&&(i, j)| !rattler[i] && !rattler[j])
        .count()
        + wall_contacts.iter().filter(|&&(i, _)| !rattler[i]).count();
    let isostatic_contacts = match (held.len(), periodic) {
        (0, _) => 0,
        (h, Some(_)) => D * (h - 1),
        (h, None) => D * h,
    };
    ContactNetwork {
        held_contacts,
        isostatic_contacts,
        pairs,
        walls: wall_contacts,
        rattlers: (0..n).filter(|&i| rattler[i]).collect(),
        mean_contacts,
    }
}

/// Every pair `(i, j)`, `i < j`, within `reach` of each other for which `keep(i, j, x_j −
/// x_i)` holds (nearest images in a periodic box), sorted.
pub(crate) fn close_pairs<const D: usize>(
    positions: &[Vector<D>],
    periodic: Option<Vector<D>>,
    reach: f64,
    keep: impl Fn(usize, usize, Vector<D>) -> bool,
) -> Vec<(usize, usize)> {
    // Cells per axis: a periodic axis is cut into whole cells at least `reach` wide.
    let per_axis: Option<[i64; D]> =
        periodic.map(|size| std::array::from_fn(|d| ((size[d] / reach).floor() as i64).max(1)));
    let cell_of = |p: Vector<D>| -> [i64; D] {
        match (periodic, per_axis) {
            (Some(size), Some(m)) => {
                let p = wrap_point(p, &size);
                std::array::from_fn(|d| ((p[d] / size[d] * m[d] as f64) as i64).clamp(0, m[d] - 1))
            }
            _ => std::array::from_fn(|d| (p[d] / reach).floor() as i64),
        }
    };
    let mut cells: HashMap<[i64; D], Vec<usize>> = HashMap::new();
    for (i, &p) in positions.iter().enumerate() {
        cells.entry(cell_of(p)).or_default().push(i);
    }
    let mut out = Vec::new();
    let offsets = 3usize.pow(D as u32);
    for (i, &p) in positions.iter().enumerate() {
        let home = cell_of(p);
        let mut seen: Vec<[i64; D]> = Vec::with_capacity(offsets);
        for code in 0..offsets {
            let mut c = home;
            let mut rest = code;
            for d in 0..D {
                c[d] += (rest % 3) as i64 - 1;
                rest /= 3;
                if let Some(m) = per_axis {
                    c[d] = c[d].rem_euclid(m[d]);
                }
            }
            // A periodic axis of fewer than three cells reaches a cell twice.
            if seen.contains(&c) {
                continue;
            }
            seen.push(c);
            let Some(bodies) = cells.get(&c) else {
                continue;
            };
            for &j in bodies {
                if j <= i {
                    continue;
                }
                let d = match periodic {
                    Some(size) => min_image(positions[j] - p, &size),
                    None => positions[j] - p,
                };
                if d.norm() <= reach && keep(i, j, d) {
                    out.push((i, j));
                }
            }
        }
    }
    out.sort_unstable();
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_square_of_four_touching_discs_in_a_periodic_box() {
        // Four unit discs on a 2 × 2 square lattice in a 4 × 4 box: each touches four others
        // (two directly, two through the box), so none is a rattler.
        let p = [[1.0, 1.0], [3.0, 1.0], [1.0, 3.0], [3.0, 3.0]].map(Vector);
        let net = contact_network(&p, &[1.0; 4], &[], Some(Vector([4.0, 4.0])), 1e-9);
        assert_eq!(net.pairs, vec![(0, 1), (0, 2), (1, 3), (2, 3)]);
        // Each pair touches twice (both ways round the box) but counts once: two contacts
        // per disc, fewer than D + 1 = 3, so all rattle.
        assert_eq!(net.rattlers, vec![0, 1, 2, 3]);
        assert_eq!(net.mean_contacts, 0.0);
    }

    #[test]
    fn a_triangle_held_by_walls_and_a_loose_disc() {
        // Three unit discs touching each other in a channel: the lower two touch the floor
        // and a side wall each, the upper one the ceiling; a fourth is far from everything.
        let h = 3f64.sqrt();
        let p = [[1.0, 1.0], [3.0, 1.0], [2.0, 1.0 + h], [8.0, 5.0]].map(Vector);
        let walls = [
            Wall::Segment {
                a: Vector([0.0, 0.0]),
                b: Vector([10.0, 0.0]),
            },
            Wall::Segment {
                a: Vector([0.0, 2.0 + h]),
                b: Vector([10.0, 2.0 + h]),
            },
            Wall::Segment {
                a: Vector([0.0, 0.0]),
                b: Vector([0.0, 10.0]),
            },
            Wall::Segment {
                a: Vector([4.0, 0.0]),
                b: Vector([4.0, 2.0 + h]),
            },
        ];
        let net = contact_network(&p, &[1.0; 4], &walls, None, 1e-9);
        assert_eq!(net.pairs, vec![(0, 1), (0, 2), (1, 2)]);
        assert_eq!(net.walls.len(), 5, "{:?}", net.walls);
        assert_eq!(net.rattlers, vec![3]);
        // Bodies 0 and 1: two discs and two walls each; body 2: two discs and the ceiling.
        assert!((net.mean_contacts - 11.0 / 3.0).abs() < 1e-15);
    }

    #[test]
    fn the_tolerance_decides_near_contacts() {
        let p = [[0.0, 0.0], [2.0 + 1e-6, 0.0]].map(Vector);
        assert!(contact_network(&p, &[1.0; 2], &[], None, 1e-9)
            .pairs
            .is_empty());
        assert_eq!(
            contact_network(&p, &[1.0; 2], &[], None, 1e-5).pairs,
            vec![(0, 1)]
        );
    }
}
