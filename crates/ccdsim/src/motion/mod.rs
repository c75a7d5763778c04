//! How bodies move between events: the motion laws and the settings that choose them.
//!
//! A body's stored state is a [`Motion`] (reference position, velocity and time) and a radius
//! ([`Body`]); the laws in force ([`Laws`]) say how it moves from there: a straight line, a
//! parabola under [`Gravity`] (or a slide's acceleration on a wall it rests on, see
//! [`crate::contact::resting`]), a radius growing by a [`GrowthLaw`], a turn about a segment's end
//! point ([`pivot`]). Moving walls translate ([`WallMotion`]). A billiard ball on the cloth
//! slides, rolls and spins by the laws of [`cloth`], set going by a [`CueStrike`]. This layer knows nothing of
//! contacts, scenes or worlds: the narrow phase ([`crate::contact`]) and everything above it
//! build on it.

mod body;
pub mod cloth;
pub mod cue_strike;
pub mod gravity;
pub mod growth;
mod laws;
pub mod moving_wall;
mod path;
pub mod pivot;
pub mod spin;

pub use body::Body;
pub use cloth::{ClothBall, ClothParams, ClothState};
pub use cue_strike::CueStrike;
pub use gravity::Gravity;
pub use growth::{Growth, GrowthLaw};
pub use laws::Laws;
pub use moving_wall::{start_motions, translated, MovingWall, WallMotion};
pub use path::Path;
pub use spin::Spin;

use crate::geom::Vector;

/// A body's stored linear motion: at time `time` it is at `pos`, moving with `vel`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Motion<const D: usize> {
    /// Reference position, metres.
    pub pos: Vector<D>,
    /// Velocity, metres per second.
    pub vel: Vector<D>,
    /// Time at which `pos` holds, seconds.
    pub time: f64,
}

impl<const D: usize> Motion<D> {
    /// Position at time `t`.
    #[must_use]
    #[inline]
    pub fn at(&self, t: f64) -> Vector<D> {
        self.pos + self.vel * (t - self.time)
    }
}

impl<const D: usize> Motion<D> {
    /// Position at time `t` under the acceleration `g`, metres:
    /// `pos + vel·dt + g·(½·dt²)` with `dt = t − time`.
    #[must_use]
    #[inline]
    pub fn falling_at(&self, t: f64, g: &Vector<D>) -> Vector<D> {
        let dt = t - self.time;
        self.pos + self.vel * dt + *g * (0.5 * dt * dt)
    }

    /// Velocity at time `t` under the acceleration `g`, metres per second: `vel + g·dt`.
    #[must_use]
    #[inline]
    pub fn falling_velocity(&self, t: f64, g: &Vector<D>) -> Vector<D> {
        self.vel + *g * (t - self.time)
    }
}
