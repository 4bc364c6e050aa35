//! What both PLY encodings read from the body, and the checks they share: vertex positions,
//! triangle corners from faces (fan-triangulated) and strips, and the size a header's counts
//! claim against the bytes there are.

use super::header::{Element, Fail, Problem, Role, malformed};
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

/// One reader's index list of the current face or strip record (`items`, as read), and the
/// indices checked.
#[derive(Debug, Default)]
pub struct IndexList {
    pub items: Vec<f64>,
    poly: Vec<u32>,
}

impl IndexList {
    /// Appends the triangles of the record just read, of an element with `role`: a face
    /// (at least 3 vertices) fan-triangulated, or strips (runs separated by -1); each index
    /// checked against the `vertices` the header declares.
    pub fn push(
        &mut self,
        role: Role,
        vertices: u64,
        corners: &mut Vec<[u32; 3]>,
    ) -> Result<(), Problem> {
        let strips = match role {
            Role::Faces(_) => false,
            Role::Strips(_) => true,
            _ => return Ok(()),
        };
        self.poly.clear();
        for &v in &self.items {
            if strips && v == -1.0 {
                push_strip(corners, &self.poly);
                self.poly.clear();
            } else {
                self.poly.push(vertex_index(v, vertices)?);
            }
        }
        if strips {
            push_strip(corners, &self.poly);
        } else if self.poly.len() < 3 {
            return Err(Problem::Malformed(format!(
                "a face needs at least 3 vertices, this one has {}; complete or remove it",
                self.poly.len()
            )));
        } else {
            push_polygon(corners, &self.poly);
        }
        Ok(())
    }
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
