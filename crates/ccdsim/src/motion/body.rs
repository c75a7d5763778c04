//! A body's record: what every time of impact reads about it.

use super::Motion;

/// The hot part of one body's state: its stored motion, radius, mass and change count.
///
/// `repr(C)` keeps the fields in this order: the ones every time of impact reads come first.
#[derive(Clone, Copy, Debug, PartialEq)]
#[repr(C)]
pub struct Body<const D: usize> {
    /// Stored motion: reference position (metres), velocity (metres per second) and the
    /// reference time (seconds) at which the position holds.
    pub motion: Motion<D>,
    /// Radius, metres.
    pub radius: f64,
    /// Mass, kilograms.
    pub(crate) mass: f64,
    /// How many times the stored motion has been replaced (see [`crate::World::change_count`]).
    pub(crate) changes: u64,
}

impl<const D: usize> Body<D> {
    /// True for a kinematic body: infinite mass (see [`crate::BodySpec::kinematic`]).
    #[must_use]
    #[inline]
    pub fn is_kinematic(&self) -> bool {
        self.mass == f64::INFINITY
    }
}
