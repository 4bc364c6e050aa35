//! What indices ask of a set of primitives, in two traits: [`Geometry`], the primitive test and
//! the bounds (all a query needs), and [`ShapeQueries`], the rest (overlap, clipping, extents,
//! planes, normals, triangle blocks: what builders, shading and peers ask). A geometry that only
//! changes how primitives are tested (one that counts, records or narrows the kernel's range)
//! implements [`Geometry`] and names what it wraps ([`GeometryWrapper`]); its shape queries are
//! then the wrapped geometry's, by the blanket impl below, with nothing forwarded by hand.

use crate::geometry::triangle::lanes::TriangleBlock;
use crate::geometry::{Aabb, Ray, Triangle};
use glam::Vec3A;

/// A set of primitives with ids `0..len()` in scene order (triangles first, then spheres, then
/// shapes).
///
/// Contract of [`Geometry::intersect`]: the returned `t` is the shared kernel's `t` clamped into
/// the slab interval of the primitive's own bounds ([`Aabb::ray_interval`]), and a kernel hit
/// whose bounds the conservative slab test rejects is a miss. So `t` never lies before the entry
/// of any box that contains the primitive's bounds, which makes "skip a box whose entry is
/// greater than the best `t`" exact. The `t` does not depend on the `t_max` passed in (only its
/// acceptance does): indices that shrink `t_max` get the bits brute force gets. A hit's `t` is
/// finite: a clamped `t` of `+inf` (a distance that overflows `f32`) is a miss, as `+inf` is the
/// protocol's miss distance (`scene/accept.rs`).
pub trait Geometry: ShapeQueries + Clone + Send + Sync + 'static {
    /// Number of primitives.
    fn len(&self) -> usize;
    /// `true` when there are no primitives.
    fn is_empty(&self) -> bool {
        self.len() == 0
    }
    /// Bounds of primitive `prim`.
    fn bounds(&self, prim: u32) -> Aabb;
    /// A representative point (centre of the bounds), for builders.
    fn centroid(&self, prim: u32) -> Vec3A {
        self.bounds(prim).center()
    }
    /// The shared kernel: `Some(t)` for a hit with a finite `t` in `[ray.t_min, t_max]`.
    fn intersect(&self, prim: u32, ray: &Ray, t_max: f32) -> Option<f32>;
    /// [`Geometry::intersect`] on the four lanes of `block`, whose corners are copies of
    /// `block_triangle(block.ids[i])` ([`ShapeQueries::block_triangle`]): bit `i` of the mask
    /// is set and `t[i]` holds the `t` exactly when `intersect(block.ids[i], ray, t_max)` is
    /// `Some(t)`, bit for bit. By default lane by lane through `intersect`.
    #[inline]
    fn intersect_block(&self, block: &TriangleBlock, ray: &Ray, t_max: f32) -> (u32, [f32; 4]) {
        let mut out = (0, [0.0; 4]);
        for (i, &prim) in block.ids.iter().enumerate() {
            if let Some(t) = self.intersect(prim, ray, t_max) {
                out.0 |= 1 << i;
                out.1[i] = t;
            }
        }
        out
    }
}

/// What builders, shading and peers ask of the primitives beyond the test and the bounds.
/// Every [`Geometry`] is one; a [`GeometryWrapper`] gets its wrapped geometry's.
pub trait ShapeQueries {
    /// Conservative overlap of the primitive with a closed box (never a false "no").
    fn overlaps_box(&self, prim: u32, cell: &Aabb) -> bool;
    /// Unit geometric normal at the hit (final hit only).
    fn normal(&self, prim: u32, ray: &Ray, t: f32) -> Vec3A;
    /// Bounds of the part of the primitive inside `cell` (for kd-tree "perfect splits"):
    /// conservative (contains the exact part, rounding included), empty when they do not meet.
    /// By default the overlap of the two boxes; triangles are clipped to the box.
    fn clipped_bounds(&self, prim: u32, cell: &Aabb) -> Aabb
    where
        Self: Geometry,
    {
        self.bounds(prim).intersection(*cell)
    }
    /// The interval `[min, max]` of `dir . p` over the primitive's points (its extent along
    /// `dir`, for classifying it against an arbitrary plane), up to the rounding of a dot
    /// product (callers pad). By default from the corners of its bounds.
    fn extent_along(&self, prim: u32, dir: Vec3A) -> (f32, f32)
    where
        Self: Geometry,
    {
        let b = self.bounds(prim);
        let up = dir.cmpge(Vec3A::ZERO);
        (
            dir.dot(Vec3A::select(up, b.min, b.max)),
            dir.dot(Vec3A::select(up, b.max, b.min)),
        )
    }
    /// The primitive's own plane `(unit normal, offset)`, `normal . p = offset` on it (candidate
    /// planes of autopartition BSPs); `None` for curved or zero-area primitives.
    fn own_plane(&self, _prim: u32) -> Option<(Vec3A, f32)> {
        None
    }
    /// The triangle primitive `prim` is, when this geometry tests it with the kernel's lane
    /// form in [`Geometry::intersect_block`] (triangle-only scenes); `None` otherwise, and
    /// indices then keep leaves of primitive ids.
    fn block_triangle(&self, _prim: u32) -> Option<Triangle> {
        None
    }
    /// All primitives as triangles (ids = positions), when the scene has nothing else: for
    /// outside peers that build their own triangle structures. `None` by default.
    fn triangles_only(&self) -> Option<&[Triangle]> {
        None
    }
}

/// A geometry that changes only how primitives are tested: it implements [`Geometry`] (its
/// test, and `len` and `bounds` of what it wraps) and names the geometry it wraps here; every
/// [`ShapeQueries`] method is then the wrapped geometry's, except the two that hand primitives
/// to a test of their own past the wrapper's [`Geometry::intersect`] (`block_triangle`, for the
/// lane form, and `triangles_only`, for peers): a wrapper offers neither, so every primitive it
/// is built over is tested through it.
pub trait GeometryWrapper {
    /// The wrapped geometry.
    type Inner: Geometry;
    fn inner(&self) -> &Self::Inner;
}

impl<W: GeometryWrapper> ShapeQueries for W {
    #[inline]
    fn overlaps_box(&self, prim: u32, cell: &Aabb) -> bool {
        self.inner().overlaps_box(prim, cell)
    }
    #[inline]
    fn normal(&self, prim: u32, ray: &Ray, t: f32) -> Vec3A {
        self.inner().normal(prim, ray, t)
    }
    #[inline]
    fn clipped_bounds(&self, prim: u32, cell: &Aabb) -> Aabb {
        self.inner().clipped_bounds(prim, cell)
    }
    #[inline]
    fn extent_along(&self, prim: u32, dir: Vec3A) -> (f32, f32) {
        self.inner().extent_along(prim, dir)
    }
    #[inline]
    fn own_plane(&self, prim: u32) -> Option<(Vec3A, f32)> {
        self.inner().own_plane(prim)
    }
}
