//! The laws that shape motion between events besides each body's velocity: growing radii
//! ([`crate::contact::growth`]) and uniform gravity ([`crate::contact::gravity`]), alone or together
//! ([`crate::contact::falling_growth`]).
//!
//! Every finder passes them to the narrow phase's dispatchers ([`crate::contact::toi_pair`],
//! [`crate::contact::toi_body_wall`], …) as `Option<&Laws<D>>`: `None` in a world with neither,
//! where the dispatchers are the fixed-radius straight-line functions, unchanged.

use crate::geom::Vector;
use crate::motion::GrowthLaw;

/// The laws in force in a world.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Laws<const D: usize> {
    /// Growing radii, if they grow.
    pub growth: Option<GrowthLaw>,
    /// The acceleration of every dynamic body, metres per second squared, if there is
    /// gravity (kinematic bodies do not fall).
    pub gravity: Option<Vector<D>>,
    /// True when the world has kinematic bodies (infinite mass, see
    /// [`crate::BodySpec::kinematic`]): pairs of them, and their pairs with walls, never meet.
    pub kinematic: bool,
    /// True when bodies have collision groups and masks (see [`crate::collision_filter`]):
    /// finders then skip the pairs [`crate::World::collides`] rejects.
    pub filtered: bool,
    /// True when bodies may rest on walls (`settings.rest_speed`, see [`crate::contact::resting`]):
    /// each body then has its own acceleration ([`crate::World::acceleration`]) and never
    /// meets the wall it rests on, so finders take the narrow phase's resting forms
    /// ([`crate::world::toi_pair_resting`], [`crate::world::toi_body_wall_resting`]).
    pub resting: bool,
}

impl<const D: usize> Laws<D> {
    /// No law: fixed radii, straight lines.
    pub const NONE: Laws<D> = Laws {
        growth: None,
        gravity: None,
        kinematic: false,
        filtered: false,
        resting: false,
    };

    /// `Some(self)` when any law is in force, `None` otherwise: what the dispatchers take.
    #[must_use]
    #[inline]
    pub fn in_force(&self) -> Option<&Self> {
        (self.growth.is_some()
            || self.gravity.is_some()
            || self.kinematic
            || self.filtered
            || self.resting)
            .then_some(self)
    }
}
