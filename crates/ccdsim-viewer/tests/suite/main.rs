//! The viewer's integration tests, one module per topic, in one test binary (one link instead
//! of one per file; run one topic with `cargo test -p ccdsim-viewer --test suite -- <module>::`).

#[path = "../common/mod.rs"]
mod common;

mod ledges;
mod playback;
mod render;
mod resting;
mod server;
