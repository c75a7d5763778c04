//! Physical observables of a run, in 2D and 3D.
//!
//! * [`thermodynamic`]: kinetic (and rotational) temperature, collision rate, pressure and the compressibility
//!   factor, from a [`Simulation`](crate::Simulation)'s counters.
//! * [`PairCorrelation`]: the radial distribution function g(r) over frames.
//! * [`mean_square_displacement`] and [`velocity_autocorrelation`]: time correlations over
//!   frames, averaged over every time origin (by FFT, O(F log F) per body and axis).
//! * [`PressureTensor`]: the full pressure tensor from the collision virial and the
//!   time-integrated kinetic tensor, fed with the collisions of a run.
//!
//! * [`EnergyBalance`]: the relative energy drift of a run, as `ccdsim run` and
//!   `ccdsim verify` print it.
//!
//! Units are the scene's, with Boltzmann's constant 1.

mod correlation;
mod energy;
pub(crate) mod pair_correlation;
mod pressure_tensor;
pub mod thermodynamic;

pub use correlation::{mean_square_displacement, velocity_autocorrelation};
pub use energy::EnergyBalance;
pub use pair_correlation::PairCorrelation;
pub use pressure_tensor::PressureTensor;
pub use thermodynamic::{
    observables, rotational_temperature, temperature, world_volume, Observables,
};
