//! Benchmark drivers behind `ccdsim bench`: the thesis's Table 5.1 (running time against the
//! number of bodies for every finder), Table 5.2 (the exact simulation against a
//! discrete-time stepper and the collisions it misses) and the gas workload (collisions per
//! second and the equation of state of hard discs and spheres), the rough-sphere cooling
//! check (rotational against translational temperature, against kinetic theory), the shear
//! check (Lees–Edwards viscosity against Enskog's, a granular gas's heat balance) and the pool
//! break (breaks per second, beside pooltool's). They print tables and return data; the
//! command-line tool adds the files and plots.
//!
//! A crate of its own, apart from the library: these drivers time and report, and a program
//! that simulates has no use for them.

#![deny(missing_docs)]
#![forbid(unsafe_code)]

mod budget;
mod check_error;
mod discrete;
mod gas;
mod line_fit;
mod pool_break;
mod rough_cooling;
mod shear;
mod thesis;

pub use budget::{CellStatus, Planner};
pub use check_error::CheckError;
pub use discrete::{run_discrete_bench, DiscreteBenchConfig, DiscreteBenchReport, DiscreteRow};
pub use gas::{
    carnahan_starling_z, enskog_collision_rate, eos_z, gas_bench, henderson_z, standard_error,
    GasBenchConfig, GasBenchError, GasBenchReport,
};
pub use line_fit::{line_fit, LineFit};
pub use pool_break::{pool_break, BreakLayout, BreakReport};
pub use rough_cooling::{
    cooling_coefficients, cooling_decay, default_settle, huthmann_zippelius_ratio,
    ratio_relaxation, rough_cooling, CoolingConfig, CoolingError, CoolingReport, CoolingSample,
};
pub use shear::{
    contact_value, enskog_viscosity, granular_temperature, shear_run, ShearConfig, ShearError,
    ShearReport,
};
pub use thesis::{
    fmt_seconds, run_thesis_bench, run_thesis_once, thesis_row, ThesisBenchConfig,
    ThesisBenchReport, ThesisCell, ThesisRun,
};
