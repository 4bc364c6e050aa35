//! Finite, capped, arbitrarily oriented right circular cones.

use super::ShapeError;
use super::axial::{AxialRay, AxialSegment, split};
use super::hit_support::{disc_half_extent, first_hit, padded_bounds};
use crate::geometry::{Aabb, Ray};
use glam::Vec3A;

/// The solid cone with its tip at `apex` and a flat circular base of radius `radius` at
/// `apex + axis * height`.
///
/// Invariants: finite `apex`, unit `axis` (from the apex to the base), `height` and `radius`
/// finite and `> 0`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Cone {
    /// Its axis from the apex to the base.
    seg: AxialSegment,
    /// `(radius / height)^2`: the squared slope of the side.
    k2: f32,
    /// Cached [`Self::bounds`] (read on every kernel call by the `Geometry` contract).
    bounds: Aabb,
}

impl Cone {
    /// The cone from its base centre to its apex.
    pub fn new(base: Vec3A, apex: Vec3A, radius: f32) -> Result<Cone, ShapeError> {
        let seg = AxialSegment::new(apex, base, radius, ["cone", "cone radius"])?;
        let k = radius / seg.height;
        // The base disc's bounds grown by the apex.
        let disc = padded_bounds(seg.end(), disc_half_extent(seg.axis, seg.radius));
        Ok(Cone {
            seg,
            k2: k * k,
            bounds: disc.union(padded_bounds(seg.start, Vec3A::ZERO)),
        })
    }

    pub fn apex(&self) -> Vec3A {
        self.seg.start
    }

    pub fn base(&self) -> Vec3A {
        self.seg.end()
    }

    /// The base disc's bounds grown by the apex.
    pub fn bounds(&self) -> Aabb {
        self.bounds
    }

    /// Outward unit normal: the base's when `p` is nearer the base plane than the side, else
    /// the side's, `radial * height - axis * radius` normalized (perpendicular to the line from
    /// the apex to the rim).
    pub fn normal_at(&self, p: Vec3A) -> Vec3A {
        let (z, radial) = split(p - self.seg.start, self.seg.axis);
        let r = radial.length();
        // Distance to the side line in the axial half-plane of p.
        let to_side = (r * self.seg.height - z * self.seg.radius).abs()
            / self.seg.height.hypot(self.seg.radius);
        if (z - self.seg.height).abs() < to_side {
            return self.seg.axis;
        }
        let u = radial.normalize_or_zero();
        (u * self.seg.height - self.seg.axis * self.seg.radius).normalize_or_zero()
    }
}

deref_to_segment!(Cone);

/// The first crossing of the side or the base.
///
/// Side: with `o`, `d` relative to the apex split into axial parts `oz`, `dz` and radial parts
/// `op`, `dp`, the cone is `|op + t dp|^2 = k2 (oz + t dz)^2`, i.e. `a t^2 + 2 b t + c = 0` with
/// `a = |dp|^2 - k2 dz^2`, `b = op.dp - k2 oz dz`, `c = |op|^2 - k2 oz^2`. The discriminant is
/// not formed as `b^2 - a c` (which cancels catastrophically) but by Lagrange's identity as
/// `k2 |oz dp - dz op|^2 - |op x dp|^2`: two squared lengths, the cone's counterpart of the
/// sphere's `r^2 - |l|^2`. The roots are `c/q` and `q/a` with `q = -(b + sign(b) sqrt(disc))`
/// (for `a = 0`, a ray parallel to a side line, `c/q` is the single root). Roots count for
/// `0 <= z <= height` (the other nappe and the part beyond the base are not the solid's).
/// Base: the plane `z = height` within the radius.
#[inline]
pub fn intersect(c: &Cone, ray: &Ray, t_max: f32) -> Option<f32> {
    let r = AxialRay::new(ray, c.seg.start, c.seg.axis);
    let (oz, dz, op, dp) = (r.oz, r.dz, r.op, r.dp);
    let a = dp.dot(dp) - c.k2 * dz * dz;
    let b = op.dot(dp) - c.k2 * oz * dz;
    let cc = op.dot(op) - c.k2 * oz * oz;
    let disc = c.k2 * (dp * oz - op * dz).length_squared() - op.cross(dp).length_squared();
    let (mut s0, mut s1) = (f32::NAN, f32::NAN);
    if disc >= 0.0 {
        let q = -(b + disc.sqrt().copysign(b));
        if q != 0.0 {
            (s0, s1) = (cc / q, q / a);
        } else if a != 0.0 {
            // b == 0 and disc == 0: the double root -b/a = 0.
            (s0, s1) = (0.0, 0.0);
        }
    }
    let sides = [s0, s1].map(|t| r.within_height(t, c.seg.height));
    first_hit(
        [sides[0], sides[1], r.cap(c.seg.height, c.seg.radius)],
        ray,
        t_max,
    )
}

#[cfg(test)]
mod tests {
    use super::super::axial::rim_test;
    use super::*;
    use crate::geometry::test_support::{assert_bounds_near, close, ray};
    use glam::Vec3;

    /// Apex at the origin, base radius 1 at z = 2 (slope 1/2).
    fn up_z() -> Cone {
        Cone::new(Vec3A::new(0.0, 0.0, 2.0), Vec3A::ZERO, 1.0).unwrap()
    }

    fn hit(c: &Cone, o: [f32; 3], d: [f32; 3]) -> Option<f32> {
        intersect(c, &ray(o, d), f32::INFINITY)
    }

    #[test]
    fn side_base_inside_and_misses() {
        let c = up_z();
        // Horizontal ray at z = 1 (radius 0.5 there) from x = -3: t = 2.5.
        assert!(close(hit(&c, [-3.0, 0.0, 1.0], [1.0, 0.0, 0.0]), 2.5));
        assert!(close(hit(&c, [-3.0, 0.0, 1.0], [2.0, 0.0, 0.0]), 1.25));
        // Down the axis from above: the base at z = 2.
        assert!(close(hit(&c, [0.0, 0.0, 5.0], [0.0, 0.0, -1.0]), 3.0));
        // Up the axis from below: the apex at t = 1.
        assert!(close(hit(&c, [0.0, 0.0, -1.0], [0.0, 0.0, 1.0]), 1.0));
        // Inside: out through the side (z = 1, x = 0.5) or the base.
        assert!(close(hit(&c, [0.0, 0.0, 1.0], [1.0, 0.0, 0.0]), 0.5));
        assert!(close(hit(&c, [0.0, 0.0, 1.0], [0.0, 0.0, 1.0]), 1.0));
        // The mirrored nappe below the apex and the region beyond the base are empty.
        assert_eq!(hit(&c, [-3.0, 0.0, -1.0], [1.0, 0.0, 0.0]), None);
        assert_eq!(hit(&c, [-3.0, 0.0, 2.5], [1.0, 0.0, 0.0]), None);
        assert_eq!(hit(&c, [-3.0, 0.0, 1.0], [-1.0, 0.0, 0.0]), None);
        // A ray parallel to a side line (a = 0): from (-1, 0, 0) along (1, 0, 2) it meets the
        // other side line x = -z/2 at z = 1, t = 0.5.
        assert!(close(hit(&c, [-1.0, 0.0, 0.0], [1.0, 0.0, 2.0]), 0.5));
        // Grazing: the line y = 0.5 at z = 1 touches the side at (0, 0.5, 1), a double root.
        assert!(close(hit(&c, [-3.0, 0.5, 1.0], [1.0, 0.0, 0.0]), 3.0));
        // Through the rim: from (2, 0, 3) toward (1, 0, 2), t = 1.
        assert!(close(hit(&c, [2.0, 0.0, 3.0], [-1.0, 0.0, -1.0]), 1.0));
    }

    #[test]
    fn oblique_and_far_away() {
        // Apex (1,1,1), base at the origin with radius 0.5; a ray across the middle.
        let c = Cone::new(Vec3A::ZERO, Vec3A::ONE, 0.5).unwrap();
        let mid = Vec3::splat(0.5);
        let d = Vec3::new(1.0, -1.0, 0.0).normalize();
        // Radius at the middle is 0.25.
        assert!(close(hit(&c, (mid - d * 3.0).into(), d.into()), 2.75));
        // A thin cone 1e4 away.
        let far = Cone::new(
            Vec3A::new(0.0, 0.0, 1.0e4),
            Vec3A::new(0.0, 0.0, 1.0e4 + 1.0),
            0.01,
        )
        .unwrap();
        let t = hit(&far, [0.0, 0.0, 0.0], [0.0, 0.0, 1.0]).unwrap();
        assert!((t - 1.0e4).abs() <= 1e-3, "{t}");
        let t = hit(&far, [-1.0, 0.0, 1.0e4 + 0.5], [1.0, 0.0, 0.0]).unwrap();
        assert!((t - 0.995).abs() <= 2e-3, "{t}");
    }

    /// Rays aimed exactly at points of the base rim from outside never slip between the side
    /// and base tests (unless the exact line only touches the rim).
    #[test]
    fn rim_is_watertight() {
        let c = Cone::new(Vec3A::new(0.1, 0.2, 0.3), Vec3A::new(0.7, 1.1, 0.5), 0.35).unwrap();
        let (u, v) = c.seg.axis.any_orthonormal_pair();
        let (o, w, h, r) = (
            c.seg.start.as_dvec3(),
            c.seg.axis.as_dvec3(),
            c.seg.height as f64,
            c.seg.radius as f64,
        );
        rim_test::assert_rim_watertight(
            5,
            20000,
            c.bounds(),
            |a, _| c.base() + (u * a.cos() + v * a.sin()) * c.seg.radius,
            |ray| intersect(&c, ray, f32::INFINITY),
            |p| {
                let z = (p - o).dot(w);
                let radial = (p - o - w * z).length();
                (r * z / h - radial).min(h - z)
            },
        );
    }

    #[test]
    fn bounds_and_normals() {
        let c = up_z();
        assert_bounds_near(c.bounds(), [-1.0, -1.0, 0.0], [1.0, 1.0, 2.0]);
        assert_eq!(c.normal_at(Vec3A::new(0.2, 0.1, 2.0)), Vec3A::Z);
        let n = c.normal_at(Vec3A::new(0.5, 0.0, 1.0));
        assert!(
            (n - Vec3A::new(2.0, 0.0, -1.0).normalize()).length() < 1e-6,
            "{n:?}"
        );
        assert!(Cone::new(Vec3A::ONE, Vec3A::ONE, 1.0).is_err());
        assert!(Cone::new(Vec3A::ZERO, Vec3A::ONE, -1.0).is_err());
    }
}
