//! The balls' physical parameters: what the cloth, the cushions and the cue need to know.

use crate::motion::ClothParams;

/// A pool ball and how it meets the cloth, the cushions and the cue (SI units). The default
/// is pooltool 0.3.3's generic pool ball (`BallParams()`) struck by its default cue.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BallParams {
    /// Radius and the cloth's friction coefficients (see [`ClothParams`]).
    pub cloth: ClothParams,
    /// Mass, kg (0.170097).
    pub mass: f64,
    /// Coefficient of restitution against a cushion, `e_c` (0.85).
    pub cushion_restitution: f64,
    /// Coefficient of friction against a cushion, `f_c` (0.2).
    pub cushion_friction: f64,
    /// Mass of the cue, kg (0.567).
    pub cue_mass: f64,
    /// Whether the cue's tip offsets are halved, as pooltool does by default ("throttled
    /// english", see [`crate::motion::cue_strike`]).
    pub throttle_english: bool,
}

impl Default for BallParams {
    fn default() -> Self {
        BallParams {
            cloth: ClothParams::default(),
            mass: 0.170097,
            cushion_restitution: 0.85,
            cushion_friction: 0.2,
            cue_mass: 0.567,
            throttle_english: true,
        }
    }
}

impl BallParams {
    /// The ball's radius, metres.
    #[must_use]
    pub fn radius(&self) -> f64 {
        self.cloth.radius
    }
}
