//! One module per subcommand.

pub mod export;
pub mod gen;
pub mod run;
pub mod verify;
