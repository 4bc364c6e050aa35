//! What the builders see of a primitive: its bounds and its id. Nothing else, so one builder
//! serves triangles, spheres and mixed scenes. The centroid is the centre of the bounds (what
//! [`crate::scene::Geometry::centroid`] returns).

use crate::geometry::Aabb;
use glam::{BVec4A, Vec3A, Vec4};

/// The `x, y, z` lanes of `v` with `w` zeroed by a bit mask. A `w` lane that holds a small
/// integer's bits is a denormal float, and arithmetic on it (which `Vec3A` does on all four
/// lanes) takes a microcode assist costing about a hundred cycles.
#[inline(always)]
fn xyz(v: Vec4) -> Vec3A {
    Vec3A::from_vec4(Vec4::select(
        BVec4A::new(true, true, true, false),
        v,
        Vec4::ZERO,
    ))
}

/// A primitive as the builder sees it, in 32 bytes (the builder streams these through memory
/// once per tree level): `lo = (min, id bits)`, `hi = (max, unused)`.
#[derive(Debug, Clone, Copy)]
pub struct PrimRef {
    lo: Vec4,
    hi: Vec4,
}

const _: () = assert!(std::mem::size_of::<PrimRef>() == 32);

impl PrimRef {
    pub fn new(bounds: Aabb, id: u32) -> PrimRef {
        PrimRef {
            lo: bounds.min.extend(f32::from_bits(id)),
            hi: bounds.max.extend(0.0),
        }
    }

    /// Scene id of the primitive.
    #[inline(always)]
    pub fn id(&self) -> u32 {
        self.lo.w.to_bits()
    }

    #[inline(always)]
    pub fn min(&self) -> Vec3A {
        xyz(self.lo)
    }

    #[inline(always)]
    pub fn max(&self) -> Vec3A {
        Vec3A::from_vec4(self.hi)
    }

    #[inline(always)]
    pub fn bounds(&self) -> Aabb {
        Aabb::new(self.min(), self.max())
    }

    #[inline(always)]
    pub fn centroid(&self) -> Vec3A {
        (self.min() + self.max()) * 0.5
    }
}

/// Union of the bounds and of the centroids of `refs`.
pub fn bounds_and_centroids(refs: &[PrimRef]) -> (Aabb, Aabb) {
    refs.iter().fold((Aabb::EMPTY, Aabb::EMPTY), |(b, c), r| {
        (b.union(r.bounds()), c.grown(r.centroid()))
    })
}
