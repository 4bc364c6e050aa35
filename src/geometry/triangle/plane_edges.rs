//! Plane intersection, then an inside test against the three edge planes (the course's first
//! method): `t = n.(v0 - o) / n.d`, `p = o + t d`, inside when `((v_{i+1} - v_i) x (p - v_i)).n
//! >= 0` for all three edges.

use super::RealKernel;
use crate::geometry::real::{KernelRay, Real, RealVec, in_interval};

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
        for i in 0..3 {
            let a = v[i];
            let b = v[(i + 1) % 3];
            if (b - a).cross(p - a).dot(n) < R::Scalar::ZERO {
                return None;
            }
        }
        Some(t)
    }
}

/// The plane-then-edges kernel (see the module documentation).
#[derive(Debug, Clone, Copy, Default)]
pub struct PlaneEdges;
