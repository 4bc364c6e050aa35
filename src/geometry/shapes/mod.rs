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
pub mod obb;
pub mod polygon;

pub use axial::AxialSegment;
pub use cone::Cone;
pub use cylinder::Cylinder;
pub use ellipsoid::Ellipsoid;
pub use obb::Obb;
pub use polygon::Polygon;

use super::{Aabb, Ray};
use glam::{Mat3A, Vec3A};
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

/// The smallest finite candidate `>= t_min`, if it is `<= t_max` (NaN never passes).
#[inline(always)]
fn first_hit<const N: usize>(candidates: [f32; N], ray: &Ray, t_max: f32) -> Option<f32> {
    let mut best = f32::INFINITY;
    for t in candidates {
        if t >= ray.t_min && t < best {
            best = t;
        }
    }
    (best.is_finite() && best <= t_max).then_some(best)
}

/// Bounds overlap with the cell padded as in [`crate::geometry::overlap`].
fn bounds_overlap(bounds: &Aabb, cell: &Aabb) -> bool {
    bounds.overlaps(&cell.padded(crate::geometry::overlap::OVERLAP_PAD))
}

/// `center ± half` grown by a few ulps of the largest coordinate, so bounds computed through
/// rounded products still contain the exact surface.
fn padded_bounds(center: Vec3A, half: Vec3A) -> Aabb {
    let pad = 8.0 * f32::EPSILON * (center.abs() + half).max_element() + f32::MIN_POSITIVE;
    let half = half + Vec3A::splat(pad);
    Aabb::new(center - half, center + half)
}

/// Checks the frame of a box or an ellipsoid: a finite `center`, every size finite and `> 0`,
/// orthonormal `axes`; returns the axes renormalized ([`orthonormal`]). `[center, size, axes]`
/// name the three in the error (`["box center", "box half-extent", "box axes"]`).
fn checked_frame(
    center: Vec3A,
    sizes: Vec3A,
    axes: Mat3A,
    [center_name, size_name, axes_name]: [&'static str; 3],
) -> Result<Mat3A, ShapeError> {
    if !center.is_finite() {
        return Err(ShapeError::NonFinite(center_name));
    }
    if let Some(bad) = sizes
        .to_array()
        .into_iter()
        .find(|s| !(s.is_finite() && *s > 0.0))
    {
        return Err(ShapeError::NotPositive(size_name, bad));
    }
    orthonormal(axes_name, axes)
}

/// Checks that the columns of `m` form an orthonormal basis (to `1e-4`), and returns it with
/// its columns renormalized.
fn orthonormal(what: &'static str, m: Mat3A) -> Result<Mat3A, ShapeError> {
    if !m.is_finite() {
        return Err(ShapeError::NonFinite(what));
    }
    let err = (m.transpose() * m - Mat3A::IDENTITY).abs();
    let worst = err.x_axis.max(err.y_axis).max(err.z_axis).max_element();
    if worst > 1.0e-4 {
        return Err(ShapeError::NotOrthonormal(what));
    }
    Ok(Mat3A::from_cols(
        m.x_axis.normalize(),
        m.y_axis.normalize(),
        m.z_axis.normalize(),
    ))
}

/// The half-extents of a disc of radius `r` centred on the origin with unit normal `n`:
/// `r * sqrt(1 - n_i^2)` per axis.
fn disc_half_extent(n: Vec3A, r: f32) -> Vec3A {
    let s = (Vec3A::ONE - n * n).max(Vec3A::ZERO);
    Vec3A::new(s.x.sqrt(), s.y.sqrt(), s.z.sqrt()) * r
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    #[test]
    fn first_hit_picks_smallest_in_range() {
        let r = Ray::new(Vec3::ZERO, Vec3::X, 1.0, 10.0).unwrap();
        assert_eq!(first_hit([5.0, 0.5, 2.0, f32::NAN], &r, 10.0), Some(2.0));
        assert_eq!(first_hit([0.5, 11.0], &r, 10.0), None);
        assert_eq!(first_hit([f32::INFINITY], &r, f32::INFINITY), None);
        // t_max does not change which candidate is chosen, only acceptance.
        assert_eq!(first_hit([3.0, 2.0], &r, 2.5), Some(2.0));
        assert_eq!(first_hit([3.0, 2.0], &r, 1.5), None);
    }

    #[test]
    fn orthonormal_accepts_rotations_only() {
        let r = Mat3A::from_rotation_y(0.3);
        assert!(orthonormal("t", r).is_ok());
        assert_eq!(
            orthonormal("t", Mat3A::from_diagonal(Vec3::new(1.0, 2.0, 1.0))),
            Err(ShapeError::NotOrthonormal("t"))
        );
    }

    #[test]
    fn disc_extent() {
        let e = disc_half_extent(Vec3A::Z, 2.0);
        assert_eq!(e, Vec3A::new(2.0, 2.0, 0.0));
    }
}
