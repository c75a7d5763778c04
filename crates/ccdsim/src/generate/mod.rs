//! Scene generators: gases (random or lattice starts, walled or periodic boxes), the
//! billiard rack, the thesis benchmark scene, a peg board under gravity and a Galton board.

mod galton;
mod gas;
mod lattice;
mod pegs;
mod place;
mod rack;
mod thesis;

pub use galton::{galton, galton_duration, GaltonConfig};
pub use gas::{densest_lattice_packing, gas, random_packing_limit, GasConfig};
pub use lattice::Lattice;
pub use pegs::{pegs, PegsConfig};
pub use rack::{rack, RackConfig};
pub use thesis::{thesis, ThesisConfig, THESIS_DURATION, THESIS_TABLE_5_1, THESIS_TABLE_5_2};

use crate::geom::Vector;
use crate::wall::Wall;
use rand::Rng;

/// Why a scene could not be generated.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum GenerateError {
    /// A parameter is out of range.
    #[error("`{param}`: {why}")]
    Param {
        /// The parameter.
        param: &'static str,
        /// Why it is refused.
        why: String,
    },
    /// Random placement failed to fit every body.
    #[error("could not place body {placed} of {n} after {attempts} attempts: the packing is too dense for random placement (start on a lattice: `--lattice`)")]
    Jammed {
        /// Bodies placed.
        placed: usize,
        /// Bodies asked for.
        n: usize,
        /// Attempts made.
        attempts: u64,
    },
}

/// Walls enclosing the box `[0, size]`: four segments in 2D, inward-facing planes otherwise.
#[must_use]
pub fn box_walls<const D: usize>(size: Vector<D>) -> Vec<Wall<D>> {
    if D == 2 {
        let c = [
            [0.0, 0.0],
            [size[0], 0.0],
            [size[0], size[1]],
            [0.0, size[1]],
        ];
        (0..4)
            .map(|k| {
                let (mut a, mut b) = (Vector::<D>::ZERO, Vector::<D>::ZERO);
                a[0] = c[k][0];
                a[1] = c[k][1];
                b[0] = c[(k + 1) % 4][0];
                b[1] = c[(k + 1) % 4][1];
                Wall::Segment { a, b }
            })
            .collect()
    } else {
        let mut walls = Vec::with_capacity(2 * D);
        for k in 0..D {
            let mut n = Vector::<D>::ZERO;
            n[k] = 1.0;
            walls.push(Wall::Plane {
                point: Vector::ZERO,
                normal: n,
            });
            let mut p = Vector::<D>::ZERO;
            p[k] = size[k];
            walls.push(Wall::Plane {
                point: p,
                normal: -n,
            });
        }
        walls
    }
}

/// A uniformly random direction (unit vector).
pub fn random_direction<const D: usize, R: Rng>(rng: &mut R) -> Vector<D> {
    loop {
        let mut v = Vector::<D>::ZERO;
        for k in 0..D {
            v[k] = rng.random_range(-1.0..=1.0);
        }
        let n2 = v.norm_sq();
        if n2 > 1e-6 && n2 <= 1.0 {
            return v * (1.0 / n2.sqrt());
        }
    }
}
