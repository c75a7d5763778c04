//! One module per subcommand.

pub mod bench;
pub mod export;
pub mod finder_args;
pub mod gen;
pub mod pack;
pub mod render;
pub mod run;
mod run_pool;
pub mod verify;
pub mod view;
