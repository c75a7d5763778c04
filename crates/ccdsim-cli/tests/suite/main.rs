//! The command-line tool's integration tests, one module per topic, in one test binary (one
//! link instead of one per file; run one topic with
//! `cargo test -p ccdsim-cli --test suite -- <module>::`).

#[path = "../common/mod.rs"]
mod common;

mod architecture_layout;
mod bench_cli;
mod cli;
mod closed_pipe;
mod corrupt_files;
mod drift;
mod gas_and_periodic;
mod golden_runs;
mod hard_inputs;
mod pack;
mod pool;
mod readme_sample;
mod sensors;
mod thermostat;
mod trajectory;
mod view_render;
