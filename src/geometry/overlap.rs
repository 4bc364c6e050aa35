//! Conservative primitive–box overlap tests, shared by every spatial subdivision (grid, octree,
//! kd-tree): triangles and spheres are stored in every cell they really touch, never in every
//! cell their bounding box touches, and rounding never leaves a primitive out of a cell it
//! touches. The other shapes (`shapes::Shape::overlaps_box`): boxes and convex polygons exactly
//! too, concave polygons by the fan of triangles from their first vertex (a superset),
//! cylinders, cones and ellipsoids by their bounding boxes only (conservative: they may sit in
//! cells they do not touch, costing kernel tests, never hits).
//!
//! Conservative means: the box is first padded by a few ulps of its largest coordinate
//! ([`OVERLAP_PAD`]), so a primitive that touches the closed cell (even on a face, edge or
//! corner) is always reported, and one that misses it by less than the padding may be reported
//! too (harmless: it is tested and rejected by the kernel).

use super::{Aabb, Sphere, Triangle};
use glam::Vec3A;

/// Relative padding of the cell before an overlap test (in units of its largest coordinate).
pub const OVERLAP_PAD: f32 = 1.0e-5;

/// Separating-axis test of a triangle against a box (Akenine-Möller 2001): the three box axes,
/// the triangle's normal, and the nine edge cross products. Degenerate triangles (zero area)
/// are handled: their zero normal and zero cross products separate nothing, and the remaining
/// axes are exact for a segment or a point.
pub fn triangle_overlaps_box(tri: &Triangle, b: &Aabb) -> bool {
    let b = b.padded(OVERLAP_PAD);
    if !tri.bounds().overlaps(&b) {
        return false;
    }
    let c = b.center();
    let h = b.extent() * 0.5;
    let v = [tri.v[0] - c, tri.v[1] - c, tri.v[2] - c];
    let e = [v[1] - v[0], v[2] - v[1], v[0] - v[2]];
    let separated = |axis: Vec3A| -> bool {
        if axis == Vec3A::ZERO {
            return false;
        }
        let p0 = v[0].dot(axis);
        let p1 = v[1].dot(axis);
        let p2 = v[2].dot(axis);
        let r = h.dot(axis.abs());
        // Pad by the rounding of the dot products (a few ulps of their magnitudes).
        let slack = 8.0
            * f32::EPSILON
            * (r + v[0].abs().dot(axis.abs())
                + v[1].abs().dot(axis.abs())
                + v[2].abs().dot(axis.abs()));
        p0.min(p1).min(p2) > r + slack || p0.max(p1).max(p2) < -r - slack
    };
    for ei in e {
        for a in [Vec3A::X, Vec3A::Y, Vec3A::Z] {
            if separated(a.cross(ei)) {
                return false;
            }
        }
    }
    !separated(e[0].cross(e[1]))
}

/// Sphere–box overlap (Arvo 1990): the squared distance from the centre to the box, compared with
/// `r^2` grown by a relative margin.
pub fn sphere_overlaps_box(s: &Sphere, b: &Aabb) -> bool {
    let b = b.padded(OVERLAP_PAD);
    let closest = s.center.clamp(b.min, b.max);
    let d2 = (s.center - closest).length_squared();
    d2 <= s.radius * s.radius * (1.0 + 1.0e-5)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::test_support::unit_box;

    #[test]
    fn triangle_cases() {
        let inside = Triangle::new(
            Vec3A::splat(0.2),
            Vec3A::new(0.8, 0.2, 0.2),
            Vec3A::new(0.2, 0.8, 0.2),
        );
        assert!(triangle_overlaps_box(&inside, &unit_box()));
        // Big triangle whose plane cuts the box although no vertex is inside.
        let big = Triangle::from_corners([-10.0, -10.0, 0.5], [10.0, -10.0, 0.5], [0.0, 20.0, 0.5]);
        assert!(triangle_overlaps_box(&big, &unit_box()));
        // Bounding boxes overlap, the triangle does not: it passes the corner diagonally.
        let corner = Triangle::from_corners([1.5, -0.5, 0.5], [2.5, 0.5, 0.5], [1.6, 0.9, 0.5]);
        assert!(!triangle_overlaps_box(&corner, &unit_box()));
        let diag = Triangle::from_corners([1.2, -0.5, 0.2], [-0.5, 1.2, 0.2], [2.0, 2.0, 0.2]);
        assert!(!triangle_overlaps_box(
            &diag,
            &Aabb::new(Vec3A::ZERO, Vec3A::splat(0.3))
        ));
        // Touching a face exactly counts (closed boxes).
        let touching = Triangle::from_corners([1.0, 0.2, 0.2], [2.0, 0.2, 0.2], [1.0, 0.8, 0.2]);
        assert!(triangle_overlaps_box(&touching, &unit_box()));
        // Degenerate (a segment through the box).
        let seg = Triangle::new(Vec3A::splat(-1.0), Vec3A::splat(2.0), Vec3A::splat(2.0));
        assert!(triangle_overlaps_box(&seg, &unit_box()));
    }

    #[test]
    fn sphere_cases() {
        let s = Sphere::new(Vec3A::new(2.0, 0.5, 0.5), 1.0);
        assert!(sphere_overlaps_box(&s, &unit_box()));
        let s = Sphere::new(Vec3A::new(1.8, 1.8, 1.8), 1.0);
        assert!(!sphere_overlaps_box(&s, &unit_box()));
    }
}
