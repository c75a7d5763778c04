//! Starting configurations for compression: a dilute random gas with the size distribution
//! the packing should have.

use crate::generate::{gas, GasConfig, GenerateError};
use crate::scene::Scene;

/// The size distribution of a packing; radii are relative to a base radius of 0.5 m.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum SizeMix {
    /// Every radius 0.5 m.
    Monodisperse,
    /// Half the bodies (every other index) of radius 0.5 m, half `ratio` times larger (the
    /// classic 2D glass former is `1.4`).
    Bidisperse(f64),
    /// Radii uniform in `0.5 · [1 − w, 1 + w]` for a width `w` in `(0, 1)`.
    Polydisperse(f64),
}

/// `n` non-overlapping bodies at random positions filling `packing` of a walled or periodic
/// box, with radii of `mix` and Maxwell velocities at `kT = 1` (zero total momentum).
pub fn dilute_start<const D: usize>(
    n: usize,
    packing: f64,
    mix: SizeMix,
    periodic: bool,
    seed: u64,
) -> Result<Scene<D>, GenerateError> {
    let base = GasConfig {
        n,
        packing,
        seed,
        periodic,
        temperature: Some(1.0),
        ..GasConfig::default()
    };
    match mix {
        SizeMix::Monodisperse => gas(&base),
        SizeMix::Polydisperse(w) => {
            if !(w > 0.0 && w < 1.0) {
                return Err(GenerateError::Param {
                    param: "polydisperse",
                    why: format!("the width must lie in (0, 1), not {w}"),
                });
            }
            gas(&GasConfig {
                radius_min: 0.5 * (1.0 - w),
                radius_max: 0.5 * (1.0 + w),
                ..base
            })
        }
        SizeMix::Bidisperse(ratio) => {
            if !(ratio.is_finite() && ratio >= 1.0) {
                return Err(GenerateError::Param {
                    param: "bidisperse",
                    why: format!("the size ratio must be at least 1, not {ratio}"),
                });
            }
            // Place every body at the large radius, at the packing that leaves `packing`
            // once half of them shrink to the small one (shrinking keeps them apart).
            let (small, large): (f64, f64) = (0.5, 0.5 * ratio);
            let d = D as i32;
            let large_share = 2.0 * large.powi(d) / (small.powi(d) + large.powi(d));
            let mut scene = gas(&GasConfig {
                radius_min: large,
                radius_max: large,
                packing: packing * large_share,
                ..base
            })?;
            for b in scene.bodies.iter_mut().step_by(2) {
                b.radius = small;
            }
            Ok(scene)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::packing::packing_fraction;
    use crate::world::World;

    #[test]
    fn mixes_fill_the_asked_fraction() {
        for mix in [
            SizeMix::Monodisperse,
            SizeMix::Bidisperse(1.4),
            SizeMix::Polydisperse(0.2),
        ] {
            let scene = dilute_start::<2>(400, 0.3, mix, true, 3).unwrap();
            let world = World::from_scene(&scene).unwrap();
            let phi = packing_fraction(&world, 0.0).unwrap();
            let tolerance = if matches!(mix, SizeMix::Polydisperse(_)) {
                0.03
            } else {
                1e-9
            };
            assert!((phi - 0.3).abs() < tolerance, "{mix:?}: {phi}");
        }
        let bi = dilute_start::<3>(10, 0.1, SizeMix::Bidisperse(1.4), false, 1).unwrap();
        assert_eq!(bi.bodies[0].radius, 0.5);
        assert_eq!(bi.bodies[1].radius, 0.7);
        assert!(dilute_start::<2>(10, 0.1, SizeMix::Bidisperse(0.5), true, 1).is_err());
        assert!(dilute_start::<2>(10, 0.1, SizeMix::Polydisperse(1.5), true, 1).is_err());
    }
}
