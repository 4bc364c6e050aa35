//! The `f64` ray the triangle and sphere kernels run on to give their `f64` instances, for the
//! precision comparison only.
//!
//! Each kernel is written once over the precision (`geometry::real`); run on a [`Ray64`] it
//! computes on the exact values of the `f32` triangle, sphere and ray with the same formulas,
//! the same order of operations and the same acceptance tests, every value in `f64`. The `f32`
//! instances stay the hot path of every index; these are never used by an index. The one
//! difference that follows: the watertight kernel recomputes an exactly zero edge function in
//! `f64`, exact for `f32` inputs and nothing wider for `f64` ones.

use crate::geometry::real::KernelRay;
use crate::geometry::{Ray, Shear};
use glam::DVec3;

/// A ray in `f64`: the exact values of an `f32` [`Ray`], plus the watertight shear in `f64`.
#[derive(Debug, Clone, Copy)]
pub struct Ray64 {
    pub origin: DVec3,
    pub dir: DVec3,
    pub t_min: f64,
    pub t_max: f64,
    /// The shear on the `f32` ray's axes, computed in `f64`.
    pub shear: Shear<f64>,
}

impl Ray64 {
    /// The same ray in `f64` (same axes for the shear as the `f32` ray).
    pub fn from_ray(r: &Ray) -> Ray64 {
        let dir = r.dir.as_dvec3();
        let s = &r.shear;
        Ray64 {
            origin: r.origin.as_dvec3(),
            dir,
            t_min: r.t_min as f64,
            t_max: r.t_max as f64,
            shear: Shear::with_axes([s.kx, s.ky, s.kz], dir),
        }
    }
}

impl KernelRay for Ray64 {
    type Scalar = f64;
    type Vec = DVec3;
    fn origin(&self) -> DVec3 {
        self.origin
    }
    fn dir(&self) -> DVec3 {
        self.dir
    }
    fn t_min(&self) -> f64 {
        self.t_min
    }
    fn shear(&self) -> &Shear<f64> {
        &self.shear
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::sphere::{intersect_algebraic, intersect_geometric};
    use crate::geometry::triangle::{
        MollerTrumbore, Parametric, PlaneEdges, RealKernel, Watertight,
    };
    use crate::geometry::{Sphere, Triangle, TriangleKernelKind};
    use glam::{Vec3, Vec3A};

    type Mirror = fn(&Triangle, &Ray64, f64) -> Option<f64>;

    /// On easy rays each f64 mirror agrees with its f32 original to f32 precision.
    #[test]
    fn mirrors_agree_with_the_f32_originals() {
        let tri = Triangle::from_corners([0.0, 0.0, 2.0], [4.0, 0.1, 2.5], [0.2, 4.0, 1.5]);
        let s = Sphere::new(Vec3A::new(0.5, 0.7, 6.0), 1.3);
        let f64s: [(TriangleKernelKind, Mirror); 4] = [
            (TriangleKernelKind::PlaneEdges, PlaneEdges::intersect_in),
            (TriangleKernelKind::Parametric, Parametric::intersect_in),
            (
                TriangleKernelKind::MollerTrumbore,
                MollerTrumbore::intersect_in,
            ),
            (TriangleKernelKind::Watertight, Watertight::intersect_in),
        ];
        for (o, d) in [
            ([1.0, 1.0, 0.0], [0.01, 0.02, 1.0]),
            ([3.0, 3.0, 0.0], [0.0, 0.0, 1.0]),
            ([1.0, 1.0, 9.0], [0.1, -0.05, -1.0]),
            ([0.0, 0.0, 0.0], [0.05, 0.1, 1.0]),
        ] {
            let ray = Ray::infinite(Vec3::from(o), Vec3::from(d)).unwrap();
            let r64 = Ray64::from_ray(&ray);
            for (k, f) in f64s {
                let a = k.intersect(&tri, &ray, f32::INFINITY);
                let b = f(&tri, &r64, f64::INFINITY);
                assert_eq!(a.is_some(), b.is_some(), "{k} {o:?}");
                if let (Some(a), Some(b)) = (a, b) {
                    assert!((a as f64 - b).abs() <= 1e-5 * b.abs(), "{k}: {a} vs {b}");
                }
            }
            for (a, b) in [
                (
                    intersect_algebraic(&s, &ray, f32::INFINITY),
                    intersect_algebraic(&s, &r64, f64::INFINITY),
                ),
                (
                    intersect_geometric(&s, &ray, f32::INFINITY),
                    intersect_geometric(&s, &r64, f64::INFINITY),
                ),
            ] {
                assert_eq!(a.is_some(), b.is_some(), "{o:?}");
                if let (Some(a), Some(b)) = (a, b) {
                    assert!((a as f64 - b).abs() <= 1e-5 * b.abs(), "{a} vs {b}");
                }
            }
        }
    }
}
