//! The library's integration, property and differential tests, one module per topic, in one
//! test binary (one link instead of one per file; run one topic with
//! `cargo test -p ccdsim --test suite -- <module>::`).

mod replay;

mod analytic;
mod billiards_vs_pooltool;
mod body_slots;
mod cells_vs_oracle;
mod cloth_vs_pooltool;
mod discrete_misses;
mod edits;
mod examples;
mod filters;
mod finder_suite;
mod frictional_vs_pooltool;
mod gravity;
mod growth;
mod hard_inputs;
mod jamming;
mod kinematic;
mod layers;
mod ledges;
mod long_runs;
mod moving_walls;
mod narrow_properties;
mod pool_runs;
mod pooltool_issues;
mod reference_json;
mod resting;
mod restitution;
mod rods;
mod rough;
mod run_files;
mod sensors;
mod thermostat;
mod thesis_scene;
mod trajectory;
mod verify_gravity;
mod verify_grid;
