//! The triangles a mesh file holds (OBJ, PLY, glTF), and how the binary loaders build them:
//! indexed positions gathered into triangles, and the bounds of all positions, in parallel;
//! and back, for the writers: triangles welded into indexed vertices.

use crate::geometry::{Aabb, Triangle};
use glam::Vec3A;
use rayon::prelude::*;
use std::collections::HashMap;
use std::path::Path;

/// The extensions (lower case) of the mesh formats a scene can name.
pub const MESH_EXTENSIONS: &[&str] = &["obj", "ply", "gltf", "glb"];

/// Whether `path` ends in one of [`MESH_EXTENSIONS`], in any case.
pub fn is_mesh_path(path: &Path) -> bool {
    path.extension()
        .is_some_and(|e| MESH_EXTENSIONS.iter().any(|m| e.eq_ignore_ascii_case(m)))
}

/// A mesh file's triangles in file order and the bounds of all its vertices (also those no
/// triangle uses: the protocol's ray sets are derived from them).
#[derive(Debug, Clone)]
pub struct TriangleMesh {
    pub triangles: Vec<Triangle>,
    pub vertex_bounds: Aabb,
}

/// Work items below which the parallel loops stay on one thread.
const MIN_PARALLEL: usize = 1 << 14;

/// Appends to `out` one triangle per corner triple (indices into `positions`), in order.
/// Invariant: every corner is below `positions.len()` (the loaders check it, with the
/// location, before calling).
pub fn push_triangles(out: &mut Vec<Triangle>, positions: &[Vec3A], corners: &[[u32; 3]]) {
    let p = |i: u32| positions[i as usize];
    out.par_extend(
        corners
            .par_iter()
            .with_min_len(MIN_PARALLEL)
            .map(|c| Triangle::new(p(c[0]), p(c[1]), p(c[2]))),
    );
}

/// The bounds of `points`.
pub fn bounds_of(points: &[Vec3A]) -> Aabb {
    points
        .par_iter()
        .with_min_len(MIN_PARALLEL)
        .fold(|| Aabb::EMPTY, |b, p| b.grown(*p))
        .reduce(|| Aabb::EMPTY, Aabb::union)
}

/// `triangles` as indexed vertices: corners with identical bits share one vertex (so a welded
/// mesh stays welded), vertices in order of first use, one corner triple per triangle.
pub fn weld(triangles: &[Triangle]) -> (Vec<Vec3A>, Vec<[u32; 3]>) {
    let mut ids: HashMap<[u32; 3], u32> = HashMap::new();
    let mut vertices = Vec::new();
    let faces = triangles
        .iter()
        .map(|t| {
            t.v.map(|v| {
                *ids.entry(v.to_array().map(f32::to_bits))
                    .or_insert_with(|| {
                        vertices.push(v);
                        vertices.len() as u32 - 1
                    })
            })
        })
        .collect();
    (vertices, faces)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn triangles_follow_their_corners_and_bounds_cover_every_point() {
        let p = [Vec3A::ZERO, Vec3A::X, Vec3A::Y, Vec3A::splat(9.0)];
        let mut out = Vec::new();
        push_triangles(&mut out, &p, &[[0, 1, 2], [2, 1, 0]]);
        assert_eq!(
            out,
            [
                Triangle::new(p[0], p[1], p[2]),
                Triangle::new(p[2], p[1], p[0])
            ]
        );
        assert_eq!(bounds_of(&p).max, Vec3A::splat(9.0));
        assert!(is_mesh_path(Path::new("a/b.GLB")) && !is_mesh_path(Path::new("b.toml")));
        let (v, f) = weld(&out);
        assert_eq!((v, f), (p[..3].to_vec(), vec![[0, 1, 2], [2, 1, 0]]));
    }
}
