//! The differential fuzzer of ccdsim.
//!
//! ccdsim promises that every finder returns, bit for bit, the event the all-pairs oracle
//! would. This crate hunts for breaks of that promise on the inputs people actually write:
//! it draws adversarial cases ([`genome`]: lattice coordinates, bodies on cell faces,
//! touching, at rest, symmetric, every feature combined, edits between steps), runs each
//! through the oracle and every other finder and mode ([`check`]), compares the run files
//! byte for byte and replays the oracle's through `verify`. A failing case shrinks (proptest)
//! to a small one, which [`campaign`] writes out as a regression case (JSON) that the tests
//! replay forever after.

#![deny(missing_docs)]
#![forbid(unsafe_code)]

pub mod campaign;
pub mod case;
pub mod check;
pub mod features;
pub mod genome;
pub mod pool;
pub mod verdict;

pub use case::{Case, EditOp, Schedule};
pub use check::{check_case, check_case_with, Checked, Failure};
