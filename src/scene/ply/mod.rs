//! PLY meshes (Turk 1994, as Stanford's tools write them): ASCII and binary little- and
//! big-endian bodies, `face` elements of any size (fan-triangulated like OBJ faces) and
//! `tristrips` elements (runs ended by -1), read from the memory-mapped file.
//!
//! A small parser of our own rather than the `ply-rs` crate: ply-rs (last released in 2020)
//! parses every element into a map of named properties, which costs an allocation per vertex
//! and face, and its errors carry no line or byte offset. The format is small; this reader
//! checks each count against the bytes there are before it allocates, names the line (ASCII)
//! or byte offset (binary) of every error, and parses fixed-size records in parallel.

mod ascii;
mod binary;
mod body;
mod header;

use super::error::Location;
use super::triangle_mesh::{TriangleMesh, bounds_of, push_triangles};
use super::{SceneError, mapped::Mapped};
use header::{Encoding, Problem};
use std::path::Path;

/// Loads a PLY file: the triangles of its `face` and `tristrips` elements in file order, and
/// the bounds of every vertex (also unused ones, like OBJ). Vertex coordinates of any numeric
/// type are rounded to the nearest `f32`. Errors name the file, the line or byte offset, what
/// is wrong and what to fix: a bad header, counts that do not match the data, indices out of
/// range, NaN or infinite coordinates, no vertices or no faces.
pub fn load_ply(path: &Path) -> Result<TriangleMesh, SceneError> {
    let map = Mapped::open(path)?;
    let bytes = map.bytes();
    let fail = |(at, p): (Location, Problem)| match p {
        Problem::Malformed(message) => SceneError::Mesh {
            path: path.to_owned(),
            format: "PLY",
            at,
            message,
        },
        Problem::NonFinite(text) => SceneError::NonFiniteVertex {
            path: path.to_owned(),
            at,
            text,
        },
    };
    let h = header::parse(bytes).map_err(fail)?;
    let body = match h.encoding {
        Encoding::Ascii => ascii::read(bytes, &h),
        _ => binary::read(bytes, &h),
    }
    .map_err(fail)?;
    let mut triangles = Vec::new();
    push_triangles(&mut triangles, &body.positions, &body.corners);
    if triangles.is_empty() {
        return Err(SceneError::Empty(format!(
            "{} (found {} vertices and no triangles; a PLY scene needs a 'face' or 'tristrips' element)",
            path.display(),
            body.positions.len()
        )));
    }
    Ok(TriangleMesh {
        triangles,
        vertex_bounds: bounds_of(&body.positions),
    })
}
