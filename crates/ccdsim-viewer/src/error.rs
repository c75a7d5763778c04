//! Why the viewer or the renderer cannot do what was asked.

use ccdsim::record::RecordError;
use ccdsim::{FinderError, SceneError};

/// Errors of the viewer library; every message names the file, option or value at fault.
#[derive(Debug, thiserror::Error)]
pub enum ViewerError {
    /// The run file cannot be read.
    #[error(transparent)]
    Record(#[from] RecordError),
    /// A file cannot be written or a socket cannot be bound.
    #[error("{what}: {source}")]
    Io {
        /// The file or address.
        what: String,
        /// The error.
        source: std::io::Error,
    },
    /// The server's address cannot be bound (the port is taken, or not allowed).
    #[error("cannot listen on {addr}: {why}")]
    Bind {
        /// The address, `127.0.0.1:PORT`.
        addr: String,
        /// What the system said.
        why: String,
    },
    /// The finder asked for the boxes cannot be made or cannot serve the run's scene.
    #[error(transparent)]
    Finder(#[from] FinderError),
    /// The run's scene cannot be rebuilt into a world.
    #[error(transparent)]
    Scene(#[from] SceneError),
    /// The run file reads but breaks a rule playback relies on (events out of time order).
    #[error("{path}: {why}")]
    BadRun {
        /// The run file.
        path: String,
        /// What is wrong.
        why: String,
    },
    /// An option or request parameter is out of range.
    #[error("{name}: {why}")]
    Param {
        /// The option or parameter.
        name: String,
        /// Why it is refused.
        why: String,
    },
    /// The image could not be encoded.
    #[error("{path}: cannot encode the image: {why}")]
    Encode {
        /// The output file.
        path: String,
        /// What the encoder said.
        why: String,
    },
}

impl ViewerError {
    /// A [`ViewerError::Param`] for `name`.
    pub(crate) fn param(name: &str, why: impl Into<String>) -> Self {
        ViewerError::Param {
            name: name.to_string(),
            why: why.into(),
        }
    }
}
