//! The fuzzer's tests, in one test binary: the regression cases and a bounded campaign.

mod campaign;
mod regressions;
