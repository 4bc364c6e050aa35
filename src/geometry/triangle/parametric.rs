//! The parametric (alpha/beta) test of the course (Shirley's textbook): solve the 3x3 system
//! `a + beta (b - a) + gamma (c - a) = o + t d` by Cramer's rule, then require `beta >= 0`,
//! `gamma >= 0`, `beta + gamma <= 1`. Each unknown is its own determinant ratio (no shared
//! cross products), which makes it the slowest of the four. A hit is kept only when the
//! determinant is certainly nonzero and the ray's point agrees with the barycentric point
//! ([`certainly_nonzero`](crate::geometry::real::certainly_nonzero),
//! [`on_triangle`](crate::geometry::real::on_triangle)): otherwise it is rounding noise.

use super::RealKernel;
use crate::geometry::real::{
    KernelRay, Real, RealVec, certainly_nonzero, in_interval, on_triangle,
};

impl RealKernel for Parametric {
    const NAME: &'static str = "parametric";

    #[inline(always)]
    fn on_corners<R: KernelRay>(v: [R::Vec; 3], ray: &R, t_max: R::Scalar) -> Option<R::Scalar> {
        // Columns: (a - b), (a - c), d; right-hand side: a - o.
        let c2 = ray.dir();
        let c0 = v[0] - v[1];
        let c1 = v[0] - v[2];
        let rhs = v[0] - ray.origin();
        let det = c0.dot(c1.cross(c2));
        if det == R::Scalar::ZERO {
            return None;
        }
        let beta = rhs.dot(c1.cross(c2)) / det;
        if beta < R::Scalar::ZERO {
            return None;
        }
        let gamma = c0.dot(rhs.cross(c2)) / det;
        if gamma < R::Scalar::ZERO || beta + gamma > R::Scalar::ONE {
            return None;
        }
        let t = in_interval(c0.dot(c1.cross(rhs)) / det, ray, t_max)?;
        if !certainly_nonzero(det, c0, c1, c2) {
            return None;
        }
        // `a + beta (b - a) + gamma (c - a)`.
        on_triangle(t, ray, v[0] - c0 * beta - c1 * gamma)
    }
}

/// The parametric kernel: Cramer's rule on the 3x3 system (see the module documentation).
#[derive(Debug, Clone, Copy, Default)]
pub struct Parametric;
