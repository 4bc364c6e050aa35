//! The course's other primitives beside triangles and spheres: oriented box, convex and concave
//! polygons, capped cylinder and cone, ellipsoid. One file per kernel; [`Shape`] dispatches.
//!
//! Every kernel is a pure function `(shape, ray, t_max) -> Option<t>` that reports the first
//! surface crossing with `t` in the closed interval `[ray.t_min, t_max]` (the exit when the ray
//! starts inside a solid). The `t` it computes does not depend on `t_max`, only the acceptance
//! does, so indices that pass a shrinking `t_max` get the bits brute force gets. `t` is in units
//! of `ray.dir` (not normalized).
//!
//! Shapes are built by validating constructors only (fields are private), so a [`Shape`] always
//! has finite data, positive sizes, unit orthonormal frames and planar, non-degenerate polygons.

#[macro_use]
mod axial;
pub mod cone;
pub mod cylinder;
pub mod ellipsoid;
mod hit_support;
pub mod obb;
pub mod polygon;
mod shape_error;

pub use axial::AxialSegment;
pub use cone::Cone;
pub use cylinder::Cylinder;
pub use ellipsoid::Ellipsoid;
pub use obb::Obb;
pub use polygon::Polygon;
pub use shape_error::ShapeError;

use super::{Aabb, Ray};
use glam::Vec3A;
use hit_support::bounds_overlap;

/// One primitive of the kinds in this module.
#[derive(Debug, Clone, PartialEq)]
pub enum Shape {
    /// Oriented box, hit by the slab method in its frame.
    Box(Obb),
    /// Convex polygon: plane, then the course's edge tests on the hit point.
    ConvexPolygon(Polygon),
    /// Any simple (or self-intersecting) planar polygon: plane, then the crossing-number test.
    ConcavePolygon(Polygon),
    Cylinder(Cylinder),
    Cone(Cone),
    Ellipsoid(Ellipsoid),
}

impl Shape {
    /// Short kind name (as in scene files).
    pub fn kind(&self) -> &'static str {
        match self {
            Shape::Box(_) => "box",
            Shape::ConvexPolygon(_) => "convex_polygon",
            Shape::ConcavePolygon(_) => "concave_polygon",
            Shape::Cylinder(_) => "cylinder",
            Shape::Cone(_) => "cone",
            Shape::Ellipsoid(_) => "ellipsoid",
        }
    }

    /// The shared kernel of each kind: the first crossing in `[ray.t_min, t_max]`.
    #[inline]
    pub fn intersect(&self, ray: &Ray, t_max: f32) -> Option<f32> {
        match self {
            Shape::Box(b) => obb::intersect_slabs(b, ray, t_max),
            Shape::ConvexPolygon(p) => polygon::intersect_convex(p, ray, t_max),
            Shape::ConcavePolygon(p) => polygon::intersect_concave(p, ray, t_max),
            Shape::Cylinder(c) => cylinder::intersect(c, ray, t_max),
            Shape::Cone(c) => cone::intersect(c, ray, t_max),
            Shape::Ellipsoid(e) => ellipsoid::intersect(e, ray, t_max),
        }
    }

    /// Bounds that contain the whole surface (padded against the rounding of computed extents).
    #[inline]
    pub fn bounds(&self) -> Aabb {
        match self {
            Shape::Box(b) => b.bounds(),
            Shape::ConvexPolygon(p) | Shape::ConcavePolygon(p) => p.bounds(),
            Shape::Cylinder(c) => c.bounds(),
            Shape::Cone(c) => c.bounds(),
            Shape::Ellipsoid(e) => e.bounds(),
        }
    }

    /// Outward unit normal at a surface point `p` (the polygon's plane normal, in its winding).
    pub fn normal_at(&self, p: Vec3A) -> Vec3A {
        match self {
            Shape::Box(b) => b.normal_at(p),
            Shape::ConvexPolygon(q) | Shape::ConcavePolygon(q) => q.normal(),
            Shape::Cylinder(c) => c.normal_at(p),
            Shape::Cone(c) => c.normal_at(p),
            Shape::Ellipsoid(e) => e.normal_at(p),
        }
    }

    /// Conservative overlap with a closed box (never a false "no"), as exact as is cheap:
    /// - box: separating axes, exact up to the cell padding;
    /// - convex polygon: exact (fan of triangles, each by the triangle–box test); concave
    ///   polygon: that fan, which covers it (a superset);
    /// - cylinder, cone, ellipsoid: their padded bounding boxes against the cell only. A cell that
    ///   meets the bounds but not the solid (near the bounds' corners and edges) holds the shape
    ///   anyway: more kernel tests in those cells, never a lost hit.
    pub fn overlaps_box(&self, cell: &Aabb) -> bool {
        match self {
            Shape::Box(b) => b.overlaps_box(cell),
            Shape::ConvexPolygon(p) | Shape::ConcavePolygon(p) => p.overlaps_box(cell),
            // Curved solids: bounding-box overlap (conservative, cheap; see above).
            Shape::Cylinder(_) | Shape::Cone(_) | Shape::Ellipsoid(_) => {
                bounds_overlap(&self.bounds(), cell)
            }
        }
    }
}
