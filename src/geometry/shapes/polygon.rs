//! Planar polygons and their two kernels: the convex one (plane, then the course's edge tests on
//! the hit point) and the concave one (plane, then a crossing-number point-in-polygon test).
//!
//! Edge rule of the concave test, which makes two polygons that share an edge agree on either
//! side of it: the polygon is projected along the ray onto the plane through the origin that is
//! perpendicular to it (the watertight triangle test's shear, so `(x, y)` of each vertex depends
//! only on that vertex and the ray), and the ray becomes the point `(0, 0)`. A half-line from
//! it along `+x` is crossed by the edge `{a, b}` when one end has `y <= 0` and the other `y > 0`
//! (half-open in `y`: a vertex on the half-line counts as below it) and the crossing lies at
//! `x > 0`, decided by the sign of `lo.x hi.y - lo.y hi.x` (`lo` the end with `y <= 0`),
//! evaluated in `f64`, where the products of `f32` values are exact, so the sign is exact. The
//! point is inside when the count is odd. The decision for an edge depends only on its two
//! vertices (not their order nor the polygon's plane), so for two polygons sharing an edge the
//! counts of a ray add up to the count of their union plus twice that edge's: a ray through the
//! union away from other edges is inside exactly one of them, also on the shared edge itself.

use super::ShapeError;
use super::hit_support::first_hit;
use crate::geometry::overlap::triangle_overlaps_box;
use crate::geometry::{Aabb, Ray, Triangle};
use glam::{DVec3, Vec3A};

/// A planar polygon with vertices in order (either winding); the last connects to the first.
///
/// Invariants: at least 3 finite vertices, non-zero area, every vertex within `1e-4` of the
/// diagonal (plus rounding) of the plane through the centroid with the Newell normal.
#[derive(Debug, Clone, PartialEq)]
pub struct Polygon {
    verts: Vec<Vec3A>,
    /// Unit Newell normal (right-handed with the winding).
    normal: Vec3A,
    /// Centroid of the vertices, a point on the plane.
    anchor: Vec3A,
    bounds: Aabb,
}

impl Polygon {
    /// A planar polygon (simple or not: the concave kernel uses the even-odd rule).
    pub fn new(vertices: Vec<Vec3A>) -> Result<Polygon, ShapeError> {
        if vertices.len() < 3 {
            return Err(ShapeError::TooFewVertices(vertices.len()));
        }
        if !vertices.iter().all(|v| v.is_finite()) {
            return Err(ShapeError::NonFinite("polygon vertices"));
        }
        let v: Vec<DVec3> = vertices.iter().map(|v| v.as_dvec3()).collect();
        let centroid = v.iter().sum::<DVec3>() / v.len() as f64;
        let n: DVec3 = (0..v.len())
            .map(|i| (v[i] - centroid).cross(v[(i + 1) % v.len()] - centroid))
            .sum();
        let bounds = Aabb::from_points(&vertices);
        let diag = bounds.extent().length() as f64;
        if n.length() <= 1.0e-10 * diag * diag || n.length() == 0.0 {
            return Err(ShapeError::ZeroArea);
        }
        let n = n.normalize();
        let scale = bounds.min.abs().max(bounds.max.abs()).max_element() as f64;
        let tol = 1.0e-4 * diag + 16.0 * f32::EPSILON as f64 * scale;
        for (i, p) in v.iter().enumerate() {
            let off = n.dot(*p - centroid).abs();
            if off > tol {
                return Err(ShapeError::NotPlanar(i, off as f32));
            }
        }
        Ok(Polygon {
            verts: vertices,
            normal: n.as_vec3().into(),
            anchor: centroid.as_vec3().into(),
            bounds,
        })
    }

    /// A planar polygon that must be convex (every turn the same way, one turn in all).
    pub fn convex(vertices: Vec<Vec3A>) -> Result<Polygon, ShapeError> {
        let p = Polygon::new(vertices)?;
        if !p.is_convex() {
            return Err(ShapeError::NotConvex);
        }
        Ok(p)
    }

    pub fn vertices(&self) -> &[Vec3A] {
        &self.verts
    }

    /// Unit plane normal, right-handed with the vertex order.
    pub fn normal(&self) -> Vec3A {
        self.normal
    }

    pub fn bounds(&self) -> Aabb {
        self.bounds
    }

    /// The point on the plane the kernels intersect (the vertices' centroid, rounded).
    pub fn anchor(&self) -> Vec3A {
        self.anchor
    }

    /// `true` when every turn is to the left around the normal (collinear vertices allowed) and
    /// the exterior angles add up to one full turn (a pentagram turns twice).
    pub fn is_convex(&self) -> bool {
        let n = self.normal.as_dvec3();
        let v: Vec<DVec3> = self.verts.iter().map(|v| v.as_dvec3()).collect();
        let len = v.len();
        let mut turning = 0.0;
        for i in 0..len {
            let e0 = v[(i + 1) % len] - v[i];
            let e1 = v[(i + 2) % len] - v[(i + 1) % len];
            let s = e0.cross(e1).dot(n);
            if s < -1.0e-9 * e0.length() * e1.length() {
                return false;
            }
            turning += s.atan2(e0.dot(e1));
        }
        (turning - std::f64::consts::TAU).abs() < 1.0e-3
    }

    /// Conservative overlap with a closed box: a fan of triangles from the first vertex, each
    /// by the triangle–box separating-axis test. The fan covers every point the even-odd rule
    /// calls inside (its signed windings add up to the polygon's winding number, odd there), so
    /// this is exact for a convex polygon and conservative for a concave one.
    pub fn overlaps_box(&self, cell: &Aabb) -> bool {
        let v = &self.verts;
        (1..v.len() - 1).any(|i| triangle_overlaps_box(&Triangle::new(v[0], v[i], v[i + 1]), cell))
    }

    /// The crossing of the plane (`NaN` or infinite for a ray parallel to it).
    #[inline(always)]
    fn plane_t(&self, ray: &Ray) -> f32 {
        self.normal.dot(self.anchor - ray.origin) / self.normal.dot(ray.dir)
    }
}

/// Convex polygon (the course's "same as triangle"): the plane crossing, then the hit point must
/// lie on the inner side of (or on) every edge: `(b - a) x (p - a) . n >= 0`.
#[inline]
pub fn intersect_convex(p: &Polygon, ray: &Ray, t_max: f32) -> Option<f32> {
    let t = first_hit([p.plane_t(ray)], ray, t_max)?;
    let hit = ray.at(t);
    let v = &p.verts;
    let mut a = v[v.len() - 1];
    for &b in v {
        if (b - a).cross(hit - a).dot(p.normal) < 0.0 {
            return None;
        }
        a = b;
    }
    Some(t)
}

/// Concave (any planar) polygon: the plane crossing, then the even-odd crossing-number test in
/// the ray's projection with the edge rule of the module documentation.
#[inline]
pub fn intersect_concave(p: &Polygon, ray: &Ray, t_max: f32) -> Option<f32> {
    let t = first_hit([p.plane_t(ray)], ray, t_max)?;
    let s = &ray.shear;
    let project = |v: Vec3A| {
        let q = v - ray.origin;
        (q[s.kx] - s.sx * q[s.kz], q[s.ky] - s.sy * q[s.kz])
    };
    let mut inside = false;
    let mut a = project(p.verts[p.verts.len() - 1]);
    for &v in &p.verts {
        let b = project(v);
        let (lo, hi) = if a.1 <= b.1 { (a, b) } else { (b, a) };
        if lo.1 <= 0.0 && hi.1 > 0.0 {
            let det = lo.0 as f64 * hi.1 as f64 - lo.1 as f64 * hi.0 as f64;
            if det > 0.0 {
                inside = !inside;
            }
        }
        a = b;
    }
    inside.then_some(t)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::test_support::{RayCase, ray, unit_floats};
    use glam::Vec3;

    fn v(x: f32, y: f32) -> Vec3A {
        Vec3A::new(x, y, 2.0)
    }

    /// An L in the plane z = 2: the unit-2 square minus its upper-right unit square.
    fn ell() -> Polygon {
        Polygon::new(vec![
            v(0.0, 0.0),
            v(2.0, 0.0),
            v(2.0, 1.0),
            v(1.0, 1.0),
            v(1.0, 2.0),
            v(0.0, 2.0),
        ])
        .unwrap()
    }

    /// Straight down onto the plane z = 2 from z = 5.
    const DOWN: [f32; 3] = [0.0, 0.0, -1.0];
    const INF: f32 = f32::INFINITY;

    /// `kernel` on `poly` gives exactly the expected answer for each ray
    /// `(origin, direction, t_max, expected)`.
    fn check(kernel: fn(&Polygon, &Ray, f32) -> Option<f32>, poly: &Polygon, cases: &[RayCase]) {
        for &(o, d, t_max, expected) in cases {
            assert_eq!(
                kernel(poly, &ray(o, d), t_max),
                expected,
                "{o:?} along {d:?}"
            );
        }
    }

    #[test]
    fn convex_hand_computed() {
        let sq = Polygon::convex(vec![v(0.0, 0.0), v(2.0, 0.0), v(2.0, 2.0), v(0.0, 2.0)]).unwrap();
        check(
            intersect_convex,
            &sq,
            &[
                ([1.0, 1.0, 5.0], DOWN, INF, Some(3.0)),
                // Both sides, scaled direction, on an edge and a vertex (closed).
                ([1.0, 1.0, 0.0], [0.0, 0.0, 0.5], INF, Some(4.0)),
                ([2.0, 1.0, 5.0], DOWN, INF, Some(3.0)),
                ([0.0, 0.0, 5.0], DOWN, INF, Some(3.0)),
                ([2.5, 1.0, 5.0], DOWN, INF, None),
                ([1.0, 1.0, 5.0], DOWN, 2.5, None),
                // Grazing: a ray in the plane is parallel to it, so a miss.
                ([-1.0, 1.0, 2.0], [1.0, 0.0, 0.0], INF, None),
                // Oblique through the centre: from (0,0,0) toward (1,1,2) reaches it at t = 1.
                ([0.0; 3], [1.0, 1.0, 2.0], INF, Some(1.0)),
            ],
        );
    }

    #[test]
    fn concave_hand_computed() {
        let l = ell();
        check(
            intersect_concave,
            &l,
            &[
                ([0.5, 0.5, 5.0], DOWN, INF, Some(3.0)),
                ([1.5, 0.5, 5.0], DOWN, INF, Some(3.0)),
                ([0.5, 1.5, 5.0], DOWN, INF, Some(3.0)),
                // The notch and outside.
                ([1.5, 1.5, 5.0], DOWN, INF, None),
                ([-0.5, 0.5, 5.0], DOWN, INF, None),
                // The half-line from (0.5, 1.0) passes exactly through the reflex vertex (1, 1)
                // and along the edge y = 1: the half-open rule still counts one crossing.
                ([0.5, 1.0, 5.0], DOWN, INF, Some(3.0)),
                ([-1.0, 0.5, 2.0], [1.0, 0.0, 0.0], INF, None),
            ],
        );
        assert!(Polygon::convex(l.vertices().to_vec()).is_err());
    }

    /// Two polygons sharing the edge (1,0)-(1,1)-(1,2) (a concave one and a convex one, given in
    /// opposite directions): every ray through their union hits exactly one of them, including
    /// rays exactly through the shared edge and its middle vertex, from many directions.
    #[test]
    fn shared_edge_is_claimed_exactly_once() {
        let left = Polygon::new(vec![
            v(0.0, 0.0),
            v(1.0, 0.0),
            v(1.0, 1.0),
            v(1.0, 2.0),
            v(0.0, 2.0),
            v(0.5, 1.0),
        ])
        .unwrap();
        let right = Polygon::new(vec![
            v(1.0, 2.0),
            v(1.0, 1.0),
            v(1.0, 0.0),
            v(2.0, 0.0),
            v(2.0, 2.0),
        ])
        .unwrap();
        let mut next = unit_floats(7);
        let mut checked = 0;
        for i in 0..3000 {
            let target = match i % 3 {
                0 => Vec3::new(1.0, 0.02 + 1.96 * next(), 2.0), // on the shared edge
                1 => Vec3::new(1.0, 1.0, 2.0),                  // its middle vertex
                _ => Vec3::new(1.0 + (next() - 0.5) * 1e-5, 0.1 + 1.8 * next(), 2.0),
            };
            let o = Vec3::new(
                next() * 6.0 - 3.0,
                next() * 6.0 - 3.0,
                if next() < 0.5 { -3.0 } else { 5.0 },
            );
            let r = Ray::infinite(o, target - o).unwrap();
            let a = intersect_concave(&left, &r, f32::INFINITY).is_some();
            let b = intersect_concave(&right, &r, f32::INFINITY).is_some();
            assert!(a != b, "ray {r:?}: left {a}, right {b}");
            checked += 1;
        }
        assert_eq!(checked, 3000);
    }

    #[test]
    fn bad_polygons_are_errors() {
        assert_eq!(
            Polygon::new(vec![v(0.0, 0.0), v(1.0, 0.0)]),
            Err(ShapeError::TooFewVertices(2))
        );
        assert_eq!(
            Polygon::new(vec![v(0.0, 0.0), v(1.0, 0.0), v(2.0, 0.0)]),
            Err(ShapeError::ZeroArea)
        );
        let bent = vec![
            v(0.0, 0.0),
            v(1.0, 0.0),
            Vec3A::new(1.0, 1.0, 2.5),
            v(0.0, 1.0),
        ];
        assert!(matches!(Polygon::new(bent), Err(ShapeError::NotPlanar(..))));
        let nan = vec![v(0.0, 0.0), v(1.0, f32::NAN), v(0.0, 1.0)];
        assert!(matches!(Polygon::new(nan), Err(ShapeError::NonFinite(_))));
        // A pentagram turns left at every vertex but twice around: not convex.
        let star: Vec<Vec3A> = (0..5)
            .map(|i| {
                let a = i as f32 * 4.0 * std::f32::consts::PI / 5.0;
                v(a.cos(), a.sin())
            })
            .collect();
        assert_eq!(Polygon::convex(star), Err(ShapeError::NotConvex));
    }

    #[test]
    fn overlap_normal_bounds() {
        let l = ell();
        assert_eq!(l.normal(), Vec3A::Z);
        assert_eq!(l.bounds(), Aabb::new(v(0.0, 0.0), v(2.0, 2.0)));
        let cell =
            |x: f32, y: f32| Aabb::new(Vec3A::new(x, y, 1.0), Vec3A::new(x + 0.4, y + 0.4, 3.0));
        assert!(l.overlaps_box(&cell(0.2, 0.2)));
        assert!(l.overlaps_box(&cell(1.5, 0.2)));
        assert!(!l.overlaps_box(&cell(0.2, 2.5)));
        assert!(!l.overlaps_box(&Aabb::new(Vec3A::splat(0.5), Vec3A::new(1.0, 1.0, 1.5))));
    }
}
