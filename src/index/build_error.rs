//! Why an index could not be built ([`BuildError`]), the one error type of every build.

use thiserror::Error;

/// Why an index could not be built.
#[derive(Debug, Error)]
pub enum BuildError {
    #[error("invalid parameters for index '{index}': {message}")]
    Params { index: String, message: String },
    #[error("unknown index '{0}': choose one of {1}")]
    UnknownIndex(String, String),
    #[error("cannot build an index over an empty scene")]
    EmptyScene,
    #[error("index '{index}' cannot be built: {message}")]
    Failed { index: String, message: String },
    /// The index does not handle this scene (a triangle-only peer on a scene with spheres):
    /// the suite skips it with this reason instead of failing.
    #[error("{index} skipped: {reason}")]
    Unsupported { index: String, reason: String },
    /// The build would not fit the memory budget, or outgrew it while building
    /// ([`crate::index::build_budget`]): the suite skips the index with this message, which
    /// says how much, the budget and what to lower.
    #[error("{message}")]
    OverBudget { index: String, message: String },
}
