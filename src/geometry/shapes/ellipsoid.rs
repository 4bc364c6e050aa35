//! Ellipsoids with arbitrary axes, intersected in the frame where they are the unit sphere.

use super::ShapeError;
use super::hit_support::{checked_frame, first_hit, padded_bounds};
use crate::geometry::quadratic::ball_roots;
use crate::geometry::{Aabb, Ray};
use glam::{Mat3A, Vec3A};

/// The solid `{center + axes * l : |l / radii| <= 1}`.
///
/// Invariants: finite centre, radii finite and `> 0`, `axes` orthonormal (columns are the
/// directions of the three radii).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ellipsoid {
    center: Vec3A,
    radii: Vec3A,
    axes: Mat3A,
    /// `diag(1 / radii) * axes^T`: world offsets to the unit-sphere frame.
    to_unit: Mat3A,
    /// Cached [`Self::bounds`] (read on every kernel call by the `Geometry` contract).
    bounds: Aabb,
}

impl Ellipsoid {
    pub fn new(center: Vec3A, radii: Vec3A, axes: Mat3A) -> Result<Ellipsoid, ShapeError> {
        let names = ["ellipsoid center", "ellipsoid radius", "ellipsoid axes"];
        let axes = checked_frame(center, radii, axes, names)?;
        let inv = Vec3A::ONE / radii;
        let to_unit = Mat3A::from_cols(axes.row(0) * inv, axes.row(1) * inv, axes.row(2) * inv);
        // Half-extent `sqrt(sum_j (axes_ij radii_j)^2)` on world axis `i`.
        let m = Mat3A::from_cols(
            axes.x_axis * radii.x,
            axes.y_axis * radii.y,
            axes.z_axis * radii.z,
        );
        let half = Vec3A::new(m.row(0).length(), m.row(1).length(), m.row(2).length());
        Ok(Ellipsoid {
            center,
            radii,
            axes,
            to_unit,
            bounds: padded_bounds(center, half),
        })
    }

    pub fn center(&self) -> Vec3A {
        self.center
    }

    pub fn radii(&self) -> Vec3A {
        self.radii
    }

    pub fn axes(&self) -> Mat3A {
        self.axes
    }

    /// Tight bounds: half-extent `sqrt(sum_j (axes_ij radii_j)^2)` on world axis `i`.
    pub fn bounds(&self) -> Aabb {
        self.bounds
    }

    /// Outward unit normal, the gradient `axes * (l / radii^2)` of the implicit function.
    pub fn normal_at(&self, p: Vec3A) -> Vec3A {
        let l = self.axes.transpose() * (p - self.center);
        (self.axes * (l / (self.radii * self.radii))).normalize_or_zero()
    }
}

/// The ray mapped into the unit-sphere frame (a linear map, so `t` is unchanged), then the
/// stable sphere quadratic; the exit when the ray starts inside.
#[inline]
pub fn intersect(e: &Ellipsoid, ray: &Ray, t_max: f32) -> Option<f32> {
    let f = e.to_unit * (ray.origin - e.center);
    let d = e.to_unit * ray.dir;
    let (t0, t1) = ball_roots(f, d, 1.0)?;
    first_hit([t0, t1], ray, t_max)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::test_support::{assert_bounds_near, close, ray};

    /// Radii (3, 1, 0.5) along world (y, -x, z) after a 90 degree turn about z, centred at
    /// (0, 0, 5): it spans |x| <= 1, |y| <= 3, |z - 5| <= 0.5.
    fn turned() -> Ellipsoid {
        Ellipsoid::new(
            Vec3A::new(0.0, 0.0, 5.0),
            Vec3A::new(3.0, 1.0, 0.5),
            Mat3A::from_rotation_z(std::f32::consts::FRAC_PI_2),
        )
        .unwrap()
    }

    fn hit(e: &Ellipsoid, o: [f32; 3], d: [f32; 3]) -> Option<f32> {
        intersect(e, &ray(o, d), f32::INFINITY)
    }

    #[test]
    fn hand_computed_cases() {
        let e = turned();
        assert!(close(hit(&e, [0.0, 0.0, 0.0], [0.0, 0.0, 1.0]), 4.5));
        assert!(close(hit(&e, [0.0, 0.0, 0.0], [0.0, 0.0, 2.0]), 2.25));
        assert!(close(hit(&e, [-5.0, 0.0, 5.0], [1.0, 0.0, 0.0]), 4.0));
        assert!(close(hit(&e, [0.0, -5.0, 5.0], [0.0, 1.0, 0.0]), 2.0));
        // Inside: the exit.
        assert!(close(hit(&e, [0.0, 0.0, 5.0], [0.0, 1.0, 0.0]), 3.0));
        // Misses and behind.
        assert_eq!(hit(&e, [1.5, 0.0, 0.0], [0.0, 0.0, 1.0]), None);
        assert_eq!(hit(&e, [0.0, 0.0, 6.0], [0.0, 0.0, 1.0]), None);
        // Grazing the tip y = 3 along x: tangent at t = 5.
        assert!(close(hit(&e, [-5.0, 3.0, 5.0], [1.0, 0.0, 0.0]), 5.0));
        // Off-axis: at y = 1.8 (0.6 of the radius) the half-width in x is 0.8.
        assert!(close(hit(&e, [-5.0, 1.8, 5.0], [1.0, 0.0, 0.0]), 4.2));
    }

    #[test]
    fn bounds_and_normals() {
        let e = turned();
        assert_bounds_near(e.bounds(), [-1.0, -3.0, 4.5], [1.0, 3.0, 5.5]);
        assert!((e.normal_at(Vec3A::new(0.0, 3.0, 5.0)) - Vec3A::Y).length() < 1e-6);
        assert!((e.normal_at(Vec3A::new(0.0, 0.0, 4.5)) + Vec3A::Z).length() < 1e-6);
        assert!(Ellipsoid::new(Vec3A::ZERO, Vec3A::new(1.0, 0.0, 1.0), Mat3A::IDENTITY).is_err());
    }
}
