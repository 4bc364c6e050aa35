//! The parametric (alpha/beta) test of the course (Shirley's textbook): solve the 3x3 system
//! `a + beta (b - a) + gamma (c - a) = o + t d` by Cramer's rule, then require `beta >= 0`,
//! `gamma >= 0`, `beta + gamma <= 1`. Each unknown is its own determinant ratio (no shared
//! cross products), which makes it the slowest of the four.

use super::{Ray, Triangle, TriangleKernel, in_interval};

impl TriangleKernel for Parametric {
    const NAME: &'static str = "parametric";

    #[inline]
    fn intersect(tri: &Triangle, ray: &Ray, t_max: f32) -> Option<f32> {
        // Columns: (a - b), (a - c), d; right-hand side: a - o.
        let c2 = ray.dir;
        let c0 = tri.v[0] - tri.v[1];
        let c1 = tri.v[0] - tri.v[2];
        let rhs = tri.v[0] - ray.origin;
        let det = c0.dot(c1.cross(c2));
        if det == 0.0 {
            return None;
        }
        let beta = rhs.dot(c1.cross(c2)) / det;
        if beta < 0.0 {
            return None;
        }
        let gamma = c0.dot(rhs.cross(c2)) / det;
        if gamma < 0.0 || beta + gamma > 1.0 {
            return None;
        }
        in_interval(c0.dot(c1.cross(rhs)) / det, ray, t_max)
    }
}

/// The parametric kernel: Cramer's rule on the 3x3 system (see the module documentation).
#[derive(Debug, Clone, Copy, Default)]
pub struct Parametric;
