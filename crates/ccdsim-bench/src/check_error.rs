//! Why a physics check (rough cooling, shear) could not run: one error for all of them.

use ccdsim::generate::GenerateError;
use ccdsim::sim::SimError;

/// Why a physics check could not run.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum CheckError {
    /// The scene could not be generated.
    #[error(transparent)]
    Generate(#[from] GenerateError),
    /// The simulation could not be set up.
    #[error(transparent)]
    Sim(#[from] SimError),
    /// A parameter is out of range, or the gas stopped colliding.
    #[error("{0}")]
    Param(String),
}
