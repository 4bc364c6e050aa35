//! Möller–Trumbore (1997): Cramer's rule on `o + t d = v0 + u e1 + v e2` with the triple
//! products sharing `p = d x e2` and `q = s x e1`. Fast, not watertight: rays through shared
//! edges can slip between the two triangles. A hit is kept only when the determinant is
//! certainly nonzero and the ray's point agrees with the barycentric point `v0 + u e1 + w e2`
//! ([`certainly_nonzero`](crate::geometry::real::certainly_nonzero),
//! [`on_triangle`](crate::geometry::real::on_triangle)): otherwise it is rounding noise.

use super::RealKernel;
use crate::geometry::real::{
    KernelRay, Real, RealVec, certainly_nonzero, in_interval, on_triangle,
};

impl RealKernel for MollerTrumbore {
    const NAME: &'static str = "moller-trumbore";

    #[inline(always)]
    fn on_corners<R: KernelRay>(v: [R::Vec; 3], ray: &R, t_max: R::Scalar) -> Option<R::Scalar> {
        let e1 = v[1] - v[0];
        let e2 = v[2] - v[0];
        let p = ray.dir().cross(e2);
        let det = e1.dot(p);
        if det == R::Scalar::ZERO {
            return None;
        }
        let inv_det = R::Scalar::ONE / det;
        let s = ray.origin() - v[0];
        let u = s.dot(p) * inv_det;
        if !(R::Scalar::ZERO..=R::Scalar::ONE).contains(&u) {
            return None;
        }
        let q = s.cross(e1);
        let w = ray.dir().dot(q) * inv_det;
        if w < R::Scalar::ZERO || u + w > R::Scalar::ONE {
            return None;
        }
        let t = in_interval(e2.dot(q) * inv_det, ray, t_max)?;
        if !certainly_nonzero(det, e1, ray.dir(), e2) {
            return None;
        }
        on_triangle(t, ray, v[0] + e1 * u + e2 * w)
    }
}

/// The Möller–Trumbore kernel (see the module documentation).
#[derive(Debug, Clone, Copy, Default)]
pub struct MollerTrumbore;
