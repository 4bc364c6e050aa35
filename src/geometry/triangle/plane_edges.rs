//! Plane intersection, then an inside test against the three edge planes (the course's first
//! method): `t = n.(v0 - o) / n.d`, `p = o + t d`, inside when `((v_{i+1} - v_i) x (p - v_i)).n
//! >= 0` for all three edges. A hit is kept only when `n . d` is certainly nonzero and the hit
//! point agrees with the point the three edge values weigh the corners to
//! ([`certainly_nonzero`](crate::geometry::real::certainly_nonzero),
//! [`on_triangle`](crate::geometry::real::on_triangle)): otherwise it is rounding noise.

use super::RealKernel;
use crate::geometry::real::{
    KernelRay, Real, RealVec, certainly_nonzero, in_interval, on_triangle,
};

impl RealKernel for PlaneEdges {
    const NAME: &'static str = "plane-edges";

    #[inline(always)]
    fn on_corners<R: KernelRay>(v: [R::Vec; 3], ray: &R, t_max: R::Scalar) -> Option<R::Scalar> {
        // The normal of `Triangle::normal_unnormalized`.
        let n = (v[1] - v[0]).cross(v[2] - v[0]);
        let denom = n.dot(ray.dir());
        if denom == R::Scalar::ZERO {
            return None;
        }
        let t = n.dot(v[0] - ray.origin()) / denom;
        let t = in_interval(t, ray, t_max)?;
        let p = ray.at(t);
        let mut edge = [R::Scalar::ZERO; 3];
        for i in 0..3 {
            let a = v[i];
            let b = v[(i + 1) % 3];
            edge[i] = (b - a).cross(p - a).dot(n);
            if edge[i] < R::Scalar::ZERO {
                return None;
            }
        }
        if !certainly_nonzero(denom, ray.dir(), v[1] - v[0], v[2] - v[0]) {
            return None;
        }
        // Edge `i` (from corner `i` to `i + 1`) weighs the opposite corner `i + 2`.
        let sum = edge[0] + edge[1] + edge[2];
        if sum == R::Scalar::ZERO {
            // On all three edge lines: a zero-area triangle.
            return None;
        }
        let on_tri = (v[2] * edge[0] + v[0] * edge[1] + v[1] * edge[2]) / sum;
        on_triangle(t, ray, on_tri)
    }
}

/// The plane-then-edges kernel (see the module documentation).
#[derive(Debug, Clone, Copy, Default)]
pub struct PlaneEdges;
