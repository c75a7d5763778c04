//! ccdsim: exact event-driven (continuous-time) simulation of moving circles (2D) and
//! spheres (3D) with static walls.
//!
//! Bodies move in straight lines between events; the next event (a body–body or body–wall
//! contact) is found by a [`Finder`], resolved with an impulse, and the loop goes on. Every
//! finder returns exactly the event the [`AllPairs`] oracle would, so runs with different
//! finders are byte-identical. The scene and run-file formats are documented in the
//! repository's docs/scene-format.md and docs/run-files.md.
//!
//! ```
//! use ccdsim::generate::{rack, RackConfig};
//! use ccdsim::Simulation;
//! let mut sim = Simulation::new(&rack(&RackConfig::default()), "all-pairs").unwrap();
//! let events = sim.run_until(1.0);
//! assert!(events > 10);
//! assert!(sim.stats().max_overlap <= 1e-9);
//! ```

#![deny(missing_docs)]
#![forbid(unsafe_code)]

pub mod billiards;
pub mod collision_filter;
pub mod contact;
pub mod discrete;
pub mod edit;
pub(crate) mod elliptic;
pub(crate) mod event;
pub mod finder;
pub mod generate;
pub mod geom;
pub mod halt;
pub mod histogram;
pub mod motion;
pub(crate) mod moving_wall_tracker;
pub mod observables;
pub mod packing;
pub(crate) mod prefetch;
pub mod record;
pub mod resolution;
pub(crate) mod resolve;
pub mod scene;
pub mod sensor;
pub mod sim;
pub mod thermostat;
pub mod trajectory;
pub mod verify;
pub mod wall;
pub mod world;

pub use collision_filter::CollisionFilter;
pub use event::{Event, EventKind};
pub use finder::{make_finder, AllPairs, Finder, FinderError, FinderOptions, FINDER_NAMES};
pub use geom::{Aabb, Vector};
pub use halt::{Halt, Partner};
pub use histogram::Histogram;
pub use motion::{Body, Gravity, Growth, GrowthLaw, Laws, Motion, MovingWall, Spin, WallMotion};
pub use observables::Observables;
pub use resolution::RESOLUTION_LIMIT;
pub use scene::arrival::Arrival;
pub use scene::{AnyScene, BodySpec, Scene, SceneError, Settings};
pub use sensor::{Sensor, SensorChange, SensorEvent};
pub use sim::{Collision, SimError, Simulation, Stats};
pub use wall::Wall;
pub use world::World;
