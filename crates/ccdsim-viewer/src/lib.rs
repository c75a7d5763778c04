//! ccdsim-viewer: plays ccdsim run files in the browser and renders them to PNG and GIF.
//!
//! - [`playback`]: a run file opened for playback through a keyframe index, so that runs
//!   larger than memory are streamed and any instant is reached by replaying at most one
//!   keyframe interval of records.
//! - [`pool`]: a pool shot's run file played back for the pool page (table, events, balls
//!   sampled with a marker that turns with each ball's spin).
//! - [`serve`]: an HTTP server on 127.0.0.1 with one embedded page (no internet needed) and a
//!   small binary/JSON API the page streams the run through.
//! - [`render_png`] and [`render_gif`]: headless frames and animations.

#![deny(missing_docs)]
#![forbid(unsafe_code)]

mod assets;
mod error;
pub mod extent;
pub mod keyframes;
pub mod playback;
pub mod pool;
pub mod render;
mod server;
pub mod states;
pub mod wire;

pub use error::ViewerError;
pub use keyframes::KeyframeOptions;
pub use playback::{AnyPlayback, Playback, Snapshot};
pub use pool::PoolPlayback;
pub use render::{render_gif, render_png, ColourBy, GifOptions, RenderOptions, RenderReport};
pub use server::{serve, ServeOptions, StopHandle, ViewerServer, MAX_EVENT_WINDOW};
pub use states::BodyStates;
