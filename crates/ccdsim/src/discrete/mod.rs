//! Discrete-time simulation, the usual game-engine loop, for comparison with the exact
//! event-driven one (the thesis's §5.3): fixed time steps, overlap tests at the end of each,
//! and a count of the collisions it misses.

mod overlap_tree;
mod stepper;
mod wall_contact;

pub use overlap_tree::OverlapTree;
pub use stepper::{DiscreteStats, DiscreteStepper, StepReport};
pub use wall_contact::{home_side, wall_push_out};
