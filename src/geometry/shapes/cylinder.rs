//! Finite, capped, arbitrarily oriented circular cylinders.

use super::ShapeError;
use super::axial::{AxialRay, AxialSegment, split};
use super::hit_support::{disc_half_extent, first_hit, padded_bounds};
use crate::geometry::quadratic::ball_roots;
use crate::geometry::{Aabb, Ray};
use glam::Vec3A;

/// The solid cylinder of radius `radius` around the segment `base`–`base + axis * height`,
/// closed by two flat caps.
///
/// Invariants: finite `base`, unit `axis`, `height` and `radius` finite and `> 0`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Cylinder {
    /// Its axis from the base to the top.
    seg: AxialSegment,
    /// Cached [`Self::bounds`] (read on every kernel call by the `Geometry` contract).
    bounds: Aabb,
}

impl Cylinder {
    /// The cylinder between the centres of its two caps.
    pub fn new(base: Vec3A, top: Vec3A, radius: f32) -> Result<Cylinder, ShapeError> {
        let seg = AxialSegment::new(base, top, radius, ["cylinder", "cylinder radius"])?;
        // The union of the two cap discs' bounds.
        let e = disc_half_extent(seg.axis, seg.radius);
        let bounds = padded_bounds(seg.start, e).union(padded_bounds(seg.end(), e));
        Ok(Cylinder { seg, bounds })
    }

    pub fn base(&self) -> Vec3A {
        self.seg.start
    }

    pub fn top(&self) -> Vec3A {
        self.seg.end()
    }

    /// The union of the two cap discs' bounds.
    pub fn bounds(&self) -> Aabb {
        self.bounds
    }

    /// Outward unit normal: the cap's axis direction when `p` is nearer a cap plane than the
    /// side, else the radial direction.
    pub fn normal_at(&self, p: Vec3A) -> Vec3A {
        let (z, radial) = split(p - self.seg.start, self.seg.axis);
        let to_side = (radial.length() - self.seg.radius).abs();
        if z.abs().min((z - self.seg.height).abs()) < to_side {
            if z * 2.0 < self.seg.height {
                -self.seg.axis
            } else {
                self.seg.axis
            }
        } else {
            radial.normalize_or_zero()
        }
    }
}

deref_to_segment!(Cylinder);

/// The first crossing of the side (stable quadratic on the components off the axis, valid for
/// `0 <= z <= height`) or a cap (plane `z = 0` or `z = height`, valid within the radius).
#[inline]
pub fn intersect(c: &Cylinder, ray: &Ray, t_max: f32) -> Option<f32> {
    let r = AxialRay::new(ray, c.seg.start, c.seg.axis);
    let (s0, s1) = ball_roots(r.op, r.dp, c.seg.radius).unwrap_or((f32::NAN, f32::NAN));
    let sides = [s0, s1].map(|t| r.within_height(t, c.seg.height));
    let caps = [0.0, c.seg.height].map(|z| r.cap(z, c.seg.radius));
    first_hit([sides[0], sides[1], caps[0], caps[1]], ray, t_max)
}

#[cfg(test)]
mod tests {
    use super::super::axial::rim_test;
    use super::*;
    use crate::geometry::test_support::{assert_bounds_near, ray};
    use glam::Vec3;

    /// Radius 1 around the x axis from x = 2 to x = 6.
    fn along_x() -> Cylinder {
        Cylinder::new(Vec3A::new(2.0, 0.0, 0.0), Vec3A::new(6.0, 0.0, 0.0), 1.0).unwrap()
    }

    fn hit(c: &Cylinder, o: [f32; 3], d: [f32; 3]) -> Option<f32> {
        intersect(c, &ray(o, d), f32::INFINITY)
    }

    #[test]
    fn side_caps_inside_and_misses() {
        let c = along_x();
        // Side from above: z = 5 down to the top of the side at z = 1.
        assert_eq!(hit(&c, [4.0, 0.0, 5.0], [0.0, 0.0, -1.0]), Some(4.0));
        assert_eq!(hit(&c, [4.0, 0.0, 5.0], [0.0, 0.0, -2.0]), Some(2.0));
        // Off-centre: y = 0.6 gives z = 0.8, t = 4.2.
        let t = hit(&c, [4.0, 0.6, 5.0], [0.0, 0.0, -1.0]).unwrap();
        assert!((t - 4.2).abs() < 1e-6, "{t}");
        // Caps along the axis, from either end.
        assert_eq!(hit(&c, [0.0, 0.5, 0.0], [1.0, 0.0, 0.0]), Some(2.0));
        assert_eq!(hit(&c, [9.0, 0.5, 0.0], [-1.0, 0.0, 0.0]), Some(3.0));
        // Inside: exits through the side, or through a cap.
        assert_eq!(hit(&c, [4.0, 0.0, 0.0], [0.0, 1.0, 0.0]), Some(1.0));
        assert_eq!(hit(&c, [4.0, 0.0, 0.0], [1.0, 0.0, 0.0]), Some(2.0));
        // Misses: beside, beyond the ends (the infinite cylinder would be hit), behind.
        assert_eq!(hit(&c, [4.0, 1.5, 5.0], [0.0, 0.0, -1.0]), None);
        assert_eq!(hit(&c, [7.0, 0.0, 5.0], [0.0, 0.0, -1.0]), None);
        assert_eq!(hit(&c, [4.0, 0.0, 5.0], [0.0, 0.0, 1.0]), None);
        // Grazing the side (tangent line y = 1): a double root on the surface.
        assert_eq!(hit(&c, [4.0, 1.0, 5.0], [0.0, 0.0, -1.0]), Some(5.0));
        // Through the rim (cap edge) diagonally: x = 2, z = 1 at t = 1.
        let t = hit(&c, [1.0, 0.0, 2.0], [1.0, 0.0, -1.0]).unwrap();
        assert!((t - 1.0).abs() < 1e-6, "{t}");
        // Beyond t_max.
        assert_eq!(
            intersect(&c, &ray([4.0, 0.0, 5.0], [0.0, 0.0, -1.0]), 3.9),
            None
        );
    }

    #[test]
    fn oblique_axis_and_far_away() {
        // Axis along (1,1,1)/sqrt(3); a ray perpendicular to it through the middle.
        let c = Cylinder::new(Vec3A::ZERO, Vec3A::splat(3.0), 0.5).unwrap();
        let mid = Vec3::splat(1.5);
        let d = Vec3::new(1.0, -1.0, 0.0).normalize();
        let t = intersect(&c, &ray((mid - d * 4.0).into(), d.into()), f32::INFINITY).unwrap();
        assert!((t - 3.5).abs() < 1e-5, "{t}");
        // A thin cylinder 1e4 away keeps its digits (stable quadratic).
        let thin = Cylinder::new(
            Vec3A::new(-1.0, 0.0, 1.0e4),
            Vec3A::new(1.0, 0.0, 1.0e4),
            0.01,
        )
        .unwrap();
        let t = hit(&thin, [0.0, 0.0, 0.0], [0.0, 0.0, 1.0]).unwrap();
        assert!((t - 9999.99).abs() <= 1e-3, "{t}");
    }

    /// Rays aimed exactly at points of the rims (where side and cap meet) from outside never
    /// slip through between the side and cap tests: they hit at the rim, `t = 1`.
    #[test]
    fn rims_are_watertight() {
        let c = Cylinder::new(Vec3A::new(0.1, 0.2, 0.3), Vec3A::new(0.7, 1.1, 0.5), 0.35).unwrap();
        let (u, v) = c.seg.axis.any_orthonormal_pair();
        let (b, w) = (c.seg.start.as_dvec3(), c.seg.axis.as_dvec3());
        rim_test::assert_rim_watertight(
            3,
            20000,
            c.bounds(),
            |a, i| {
                let end = if i % 2 == 0 { c.base() } else { c.top() };
                end + (u * a.cos() + v * a.sin()) * c.seg.radius
            },
            |r| intersect(&c, r, f32::INFINITY),
            |p| {
                let z = (p - b).dot(w);
                let radial = (p - b - w * z).length();
                (c.seg.radius as f64 - radial)
                    .min(z)
                    .min(c.seg.height as f64 - z)
            },
        );
    }

    #[test]
    fn bounds_and_normals() {
        let c = along_x();
        assert_bounds_near(c.bounds(), [2.0, -1.0, -1.0], [6.0, 1.0, 1.0]);
        assert_eq!(c.normal_at(Vec3A::new(4.0, 0.0, 1.0)), Vec3A::Z);
        assert_eq!(c.normal_at(Vec3A::new(2.0, 0.3, 0.1)), -Vec3A::X);
        assert_eq!(c.normal_at(Vec3A::new(6.0, 0.3, 0.1)), Vec3A::X);
        assert!(Cylinder::new(Vec3A::ONE, Vec3A::ONE, 1.0).is_err());
        assert!(Cylinder::new(Vec3A::ZERO, Vec3A::ONE, 0.0).is_err());
        assert!(Cylinder::new(Vec3A::ZERO, Vec3A::splat(f32::NAN), 1.0).is_err());
    }
}
