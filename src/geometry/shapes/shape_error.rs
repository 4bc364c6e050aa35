//! Why a shape could not be built ([`ShapeError`]).

use thiserror::Error;

/// Why a shape could not be built; the message says what to fix.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum ShapeError {
    #[error("{0}: every coordinate must be finite (no NaN or infinity)")]
    NonFinite(&'static str),
    #[error("{0} must be finite and > 0 (got {1})")]
    NotPositive(&'static str, f32),
    #[error("{0}: the two end points coincide; give distinct end points")]
    ZeroLength(&'static str),
    #[error("{0}: the axes must be orthonormal (a rotation, columns = local x, y, z)")]
    NotOrthonormal(&'static str),
    #[error("polygon needs at least 3 vertices (got {0})")]
    TooFewVertices(usize),
    #[error("polygon has zero area (collinear or coincident vertices)")]
    ZeroArea,
    #[error("polygon is not planar: vertex {0} lies {1} off the plane of the others")]
    NotPlanar(usize, f32),
    #[error("polygon is not convex: use a concave polygon (kind \"concave_polygon\") instead")]
    NotConvex,
}
