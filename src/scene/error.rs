//! Typed scene errors; each message says what to fix.

use std::path::PathBuf;
use thiserror::Error;

/// Where in a mesh file something is wrong: a line of a text file (1-based), a byte offset of
/// a binary file (0-based, from the file's first byte), or a JSON path of a glTF document
/// (`meshes[0].primitives[1]`).
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Location {
    Line(usize),
    Byte(u64),
    Json(String),
}

impl std::fmt::Display for Location {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Location::Line(n) => write!(f, "line {n}"),
            Location::Byte(b) => write!(f, "byte {b}"),
            Location::Json(p) => write!(f, "at {p}"),
        }
    }
}

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
    /// A PLY or glTF file (`format`) that is malformed at `at`.
    #[error("{path} is not a valid {format} file: {at}: {message}")]
    Mesh {
        path: PathBuf,
        format: &'static str,
        at: Location,
        message: String,
    },
    #[error(
        "{path}, {at}: vertex coordinate is NaN or infinite ({text}); fix or remove that vertex"
    )]
    NonFiniteVertex {
        path: PathBuf,
        at: Location,
        text: String,
    },
    #[error("{0} has no primitives: a scene needs at least one triangle, sphere or shape")]
    Empty(String),
    #[error("scene {0}: {1}")]
    Invalid(String, String),
    #[error("{path} is not a valid scene file: {message}")]
    SceneFile { path: PathBuf, message: String },
    #[error(
        "unknown scene '{0}': give a path to an .obj, .ply, .gltf, .glb or .toml file, or one of: {1}"
    )]
    UnknownScene(String, String),
}
