//! What both PLY encodings read from the body, and the checks they share: vertex positions,
//! triangle corners from faces (fan-triangulated) and strips, and the size a header's counts
//! claim against the bytes there are.

use super::header::{Element, Fail, Problem, malformed};
use crate::scene::corners::{push_polygon, push_strip};
use crate::scene::error::Location;
use glam::Vec3A;

/// The vertices and triangle corners of a PLY body, in file order.
#[derive(Debug, Default)]
pub struct Body {
    pub positions: Vec<Vec3A>,
    pub corners: Vec<[u32; 3]>,
}

/// Refuses an element whose `count` records of at least `min_bytes` each cannot fit in the
/// `left` bytes after `at`: before anything is allocated for it.
pub fn check_fits(e: &Element, min_bytes: u64, left: u64, at: Location) -> Result<(), Fail> {
    let need = e.count.saturating_mul(min_bytes);
    if need > left {
        return malformed(
            at,
            format!(
                "element '{}' declares {} records of at least {min_bytes} bytes ({need} bytes), but the file has only {left} bytes left; the file is truncated or the count (header line {}) is wrong",
                e.name, e.count, e.line
            ),
        );
    }
    Ok(())
}

/// Vertex index `v` (as read) checked against the `vertices` the header declares.
#[inline]
pub fn vertex_index(v: f64, vertices: u64) -> Result<u32, Problem> {
    if v >= 0.0 && v < vertices as f64 {
        Ok(v as u32)
    } else {
        Err(Problem::Malformed(format!(
            "vertex index {v} is out of range: the header declares {vertices} vertices (0 to {}); fix the index or the vertex count",
            vertices as i128 - 1
        )))
    }
}

/// Appends face `poly` (at least 3 vertex indices) fan-triangulated.
pub fn push_face(corners: &mut Vec<[u32; 3]>, poly: &[u32]) -> Result<(), Problem> {
    if poly.len() < 3 {
        return Err(Problem::Malformed(format!(
            "a face needs at least 3 vertices, this one has {}; complete or remove it",
            poly.len()
        )));
    }
    push_polygon(corners, poly);
    Ok(())
}

/// Appends one `tristrips` record: runs of vertex indices separated by -1.
pub fn push_strips(
    corners: &mut Vec<[u32; 3]>,
    items: &[f64],
    vertices: u64,
    run: &mut Vec<u32>,
) -> Result<(), Problem> {
    run.clear();
    for &v in items {
        if v == -1.0 {
            push_strip(corners, run);
            run.clear();
        } else {
            run.push(vertex_index(v, vertices)?);
        }
    }
    push_strip(corners, run);
    Ok(())
}

/// A vertex's coordinates as `f32`: NaN or infinity refused, and a finite `f64` beyond
/// `f32`'s range told apart.
pub fn coordinates(xyz: [f64; 3], vertex: u64) -> Result<Vec3A, Problem> {
    let p = Vec3A::new(xyz[0] as f32, xyz[1] as f32, xyz[2] as f32);
    if p.is_finite() {
        return Ok(p);
    }
    let text = format!("vertex {vertex}: {} {} {}", xyz[0], xyz[1], xyz[2]);
    if xyz.iter().all(|c| c.is_finite()) {
        Err(Problem::Malformed(format!(
            "{text}: a coordinate is beyond the range of f32 (about -3.4e38 to 3.4e38); scale the model down"
        )))
    } else {
        Err(Problem::NonFinite(text))
    }
}
