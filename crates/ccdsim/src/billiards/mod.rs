//! Pool: balls that slide, roll and spin on the cloth, bounce off cushions and jaws and drop
//! into pockets, played out event by event and exactly.
//!
//! The physics is Leckie & Greenspan's event-based pool simulator ("An event-based pool
//! physics simulator", Advances in Computer Games 2005) with pooltool 0.3.3's models and
//! parameters: the cloth's motion laws ([`crate::motion::cloth`]), the cue's strike
//! ([`crate::motion::cue_strike`]), frictionless elastic ball–ball collisions
//! ([`ball_impact`]), Han's cushion model ([`cushion_impact`]) and pooltool's default table
//! ([`table`]) and racks ([`rack`]). [`Shot`] plays a shot: set the balls down, strike one,
//! run.
//!
//! ```
//! use ccdsim::billiards::{BallParams, PocketTableSpecs, Shot, Table};
//! use ccdsim::motion::CueStrike;
//! use ccdsim::Vector;
//!
//! let table = Table::pool(&PocketTableSpecs::default());
//! let mut shot = Shot::new(table, BallParams::default(), &[
//!     Vector([0.5, 0.5]),   // the cue ball
//!     Vector([0.5, 1.4]),   // an object ball straight up the table
//! ]).unwrap();
//! shot.strike(0, &CueStrike::new(2.0, 90.0)).unwrap();
//! shot.run(10_000).unwrap();
//! assert!(shot.is_still());
//! assert!(shot.events().len() > 3);
//! ```

mod ball_grid;
pub mod ball_impact;
mod box_tree;
mod calendar;
pub mod contact_time;
pub mod cushion_impact;
#[cfg(test)]
mod lattice_boxes;
mod params;
pub mod pool_scene;
pub mod rack;
pub mod run_export;
pub mod run_file;
mod search;
mod shot;
mod shot_event;
pub mod table;

pub use params::{BallBallModel, BallFriction, BallParams};
pub use pool_scene::{PoolBall, PoolBallBall, PoolScene, PoolSceneError, PoolSetup, PoolShot};
pub use rack::{rack, rack_at, Game};
pub use run_export::export_pool_jsonl;
pub use run_file::{
    open_pool_run, record_shot, record_struck, BallAfter, PoolRecord, PoolRunReader, PoolRunWriter,
};
pub use search::PoolFinder;
pub use shot::{Shot, ShotError, TableBall};
pub use shot_event::{ShotEvent, ShotEventKind};
pub use table::{Jaw, LinearCushion, Pocket, PocketTableSpecs, Table};
