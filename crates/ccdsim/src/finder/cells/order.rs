//! The order of the bodies' keys in the event queue: by the Z-order (Morton order) of the
//! cells they are filed in at `init`.
//!
//! After a collision both bodies' keys are set, and both may hold the root's key: the first
//! body's walk stops where its path meets its partner's (the nodes there keep the key the
//! partner still holds, see [`super::tournament::TournamentQueue::set_first_of_pair`]).
//! The bodies of a collision touch, so in an order that keeps neighbours close their paths
//! meet low in the tree and the first walk is short; in index order they mostly meet at
//! the root. The Z-order of cells keeps most neighbours within a few dozen slots, and it is
//! found by sorting one integer per body.

/// Bits per axis a Z-order code may use: `D` of them fit in 32 bits, with a body index of
/// 32 bits below them (2D: 16, 3D: 10).
const fn bits_per_axis(d: usize) -> u32 {
    (32 / d) as u32
}

/// The bodies `0..` in Z-order of their cell coordinates (ties by index), the coordinates
/// reduced to their top bits when a grid has more than `2^(32/D)` cells along some axis
/// (any order is exact; this one only makes walks shorter).
pub(super) fn z_order<const D: usize>(
    coords: impl Iterator<Item = [u32; D]>,
    dims: [usize; D],
) -> Vec<u32> {
    let bits = bits_per_axis(D);
    // Bits needed for the largest coordinate, and how far to shift to keep `bits` of them.
    let need = dims
        .iter()
        .map(|&d| usize::BITS - d.saturating_sub(1).leading_zeros())
        .max()
        .unwrap_or(0);
    let drop = need.saturating_sub(bits);
    let mut codes: Vec<u64> = coords
        .enumerate()
        .map(|(i, k)| (interleave(&k.map(|x| x >> drop), bits) << 32) | i as u64)
        .collect();
    codes.sort_unstable();
    codes.into_iter().map(|c| c as u32).collect()
}

/// The bits `0..bits` of each coordinate interleaved, axis 0 lowest: bit `b` of axis `a` is
/// bit `b·D + a` of the code.
fn interleave<const D: usize>(k: &[u32; D], bits: u32) -> u64 {
    let mut code = 0u64;
    for b in 0..bits {
        for (a, &x) in k.iter().enumerate() {
            code |= u64::from((x >> b) & 1) << (b as usize * D + a);
        }
    }
    code
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn z_order_visits_quadrants_in_turn() {
        // A 4 × 4 grid, one body per cell, bodies in row-major order.
        let coords: Vec<[u32; 2]> = (0..16).map(|c| [c % 4, c / 4]).collect();
        let order = z_order(coords.iter().copied(), [4, 4]);
        assert_eq!(
            order,
            [0, 1, 4, 5, 2, 3, 6, 7, 8, 9, 12, 13, 10, 11, 14, 15]
        );
        // Bodies of one cell keep their index order; every body once.
        let order = z_order([[1u32, 0, 0], [0, 0, 0], [1, 0, 0]].into_iter(), [2, 1, 1]);
        assert_eq!(order, [1, 0, 2]);
        // A grid wider than the bits: the top bits order it.
        let order = z_order(
            [[70_000u32, 0], [1, 0], [69_000, 0]].into_iter(),
            [80_000, 1],
        );
        assert_eq!(order, [1, 2, 0]);
        assert_eq!(interleave(&[0b11u32, 0b01, 0b10], 2), 0b101_011);
    }
}
