//! What the builders see of a primitive: its bounds, its centroid and its id. Nothing else, so
//! one builder serves triangles, spheres and mixed scenes.

use crate::geometry::Aabb;
use glam::Vec3A;

/// A primitive as the builder sees it.
#[derive(Debug, Clone, Copy)]
pub struct PrimRef {
    pub bounds: Aabb,
    pub centroid: Vec3A,
    /// Scene id of the primitive.
    pub id: u32,
}

/// Union of the bounds and of the centroids of `refs`.
pub fn bounds_and_centroids(refs: &[PrimRef]) -> (Aabb, Aabb) {
    refs.iter().fold((Aabb::EMPTY, Aabb::EMPTY), |(b, c), r| {
        (b.union(r.bounds), c.grown(r.centroid))
    })
}
