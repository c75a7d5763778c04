//! Trajectory files: frames of a run sampled at fixed times, written in formats that analysis
//! tools read.
//!
//! * [`Frame`]: the bodies at one instant (positions folded into a periodic box with their
//!   image counts, velocities, radii, masses) and the simulation cell.
//! * [`SampleTimes`]: the sample times `t₀ + k·Δt`, computed from `k` (never accumulated, so
//!   the thousandth frame is not off by a thousand roundings).
//! * [`XyzWriter`]: extended XYZ (ASE, OVITO), full `f64` precision.
//! * [`GsdWriter`]: GSD with the HOOMD schema (the `gsd` package, HOOMD-blue, freud, OVITO),
//!   `f32` as the schema prescribes, time in `log/time` as `f64`.
//! * [`TrajectoryWriter`]: either, chosen by [`TrajectoryFormat`] (from the file name).

mod frame;
mod gsd;
mod sample_times;
mod writer;
mod xyz;

pub use frame::{Cell, Frame};
pub use gsd::GsdWriter;
pub use sample_times::SampleTimes;
pub use writer::{TrajectoryFormat, TrajectoryWriter};
pub use xyz::XyzWriter;
