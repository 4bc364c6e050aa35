//! Typed scene errors; each message says what to fix.

use std::path::PathBuf;
use thiserror::Error;

#[derive(Debug, Error)]
pub enum SceneError {
    #[error("cannot read {path}: {cause}")]
    Io {
        path: PathBuf,
        /// In the message, not a chained source (so `{:#}` prints it once).
        cause: std::io::Error,
    },
    #[error("{path} is not a valid OBJ file: {message}")]
    Obj { path: PathBuf, message: String },
    #[error(
        "{path}, line {line}: vertex coordinate is NaN or infinite ({text}); fix or remove that vertex"
    )]
    NonFiniteVertex {
        path: PathBuf,
        line: usize,
        text: String,
    },
    #[error("{0} has no primitives: a scene needs at least one triangle, sphere or shape")]
    Empty(String),
    #[error("scene {0}: {1}")]
    Invalid(String, String),
    #[error("{path} is not a valid scene file: {message}")]
    SceneFile { path: PathBuf, message: String },
    #[error("unknown scene '{0}': give a path to an .obj or .toml file, or one of: {1}")]
    UnknownScene(String, String),
}
