//! Plane intersection, then an inside test against the three edge planes (the course's first
//! method): `t = n.(v0 - o) / n.d`, `p = o + t d`, inside when `((v_{i+1} - v_i) x (p - v_i)).n
//! >= 0` for all three edges.

use super::{Ray, Triangle, TriangleKernel, in_interval};

impl TriangleKernel for PlaneEdges {
    const NAME: &'static str = "plane-edges";

    #[inline]
    fn intersect(tri: &Triangle, ray: &Ray, t_max: f32) -> Option<f32> {
        let n = tri.normal_unnormalized();
        let denom = n.dot(ray.dir);
        if denom == 0.0 {
            return None;
        }
        let t = n.dot(tri.v[0] - ray.origin) / denom;
        let t = in_interval(t, ray, t_max)?;
        let p = ray.at(t);
        for i in 0..3 {
            let a = tri.v[i];
            let b = tri.v[(i + 1) % 3];
            if (b - a).cross(p - a).dot(n) < 0.0 {
                return None;
            }
        }
        Some(t)
    }
}

/// The plane-then-edges kernel (see the module documentation).
#[derive(Debug, Clone, Copy, Default)]
pub struct PlaneEdges;
