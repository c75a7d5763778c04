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
    /// How two balls meet ([`BallBallModel::FrictionlessElastic`], pooltool 0.3.3's).
    pub ball_ball: BallBallModel,
    /// How long two balls touch in a collision, seconds (2 × 10⁻⁴: the order of a Hertzian
    /// contact between pool balls, about 4 × 10⁻⁴ s at 1 m/s for phenolic resin of 5.84 GPa and
    /// Poisson's ratio 0.34): balls pressed together by their decelerations part at least
    /// fast enough not to meet again sooner ([`super::ball_impact::part_pressed`]).
    pub contact_time: f64,
}

/// How two balls exchange momentum when they meet (see [`super::ball_impact`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum BallBallModel {
    /// Frictionless and perfectly elastic: the velocities along the line of centres are
    /// exchanged (pooltool 0.3.3's `frictionless_elastic`).
    FrictionlessElastic,
    /// Restitution `e_b` along the line of centres and friction between the balls
    /// (pooltool 0.4's `frictional_inelastic`, after Alciatore).
    FrictionalInelastic {
        /// Coefficient of restitution between the balls, `e_b` (pooltool's 0.95).
        restitution: f64,
        /// Coefficient of friction between the balls.
        friction: BallFriction,
    },
}

impl BallBallModel {
    /// The frictional model with pooltool 0.4's defaults: `e_b` = 0.95 and Alciatore's
    /// friction curve.
    pub const FRICTIONAL: BallBallModel = BallBallModel::FrictionalInelastic {
        restitution: 0.95,
        friction: BallFriction::ALCIATORE,
    };
}

/// The coefficient of friction between two balls' surfaces.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum BallFriction {
    /// The same coefficient at every slip speed (pooltool's `u_b`, 0.05 by default).
    Constant(f64),
    /// `a + b·exp(−c·s)` at slip speed `s` (m/s) of the contact points: the curve D.
    /// Alciatore fitted to measured throw (TP A-14).
    Alciatore {
        /// Limit at high slip speeds.
        a: f64,
        /// Excess at zero slip speed.
        b: f64,
        /// Decay, s/m.
        c: f64,
    },
}

impl BallFriction {
    /// Alciatore's fit, `a = 9.951 × 10⁻³`, `b = 0.108`, `c = 1.088 s/m` (pooltool 0.4's
    /// default).
    pub const ALCIATORE: BallFriction = BallFriction::Alciatore {
        a: 9.951e-3,
        b: 0.108,
        c: 1.088,
    };

    /// The coefficient at the contact points' slip speed `slip` (m/s). (pooltool 0.4.4
    /// evaluates its curve at the slip of the balls' points that face the table's `x` axis
    /// rather than each other; the two agree when the balls meet along `x`.)
    #[must_use]
    pub fn coefficient(&self, slip: f64) -> f64 {
        match *self {
            BallFriction::Constant(mu) => mu,
            BallFriction::Alciatore { a, b, c } => a + b * (-c * slip).exp(),
        }
    }
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
            ball_ball: BallBallModel::FrictionlessElastic,
            contact_time: 2e-4,
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
