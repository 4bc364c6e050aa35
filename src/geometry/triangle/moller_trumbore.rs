//! Möller–Trumbore (1997): Cramer's rule on `o + t d = v0 + u e1 + v e2` with the triple
//! products sharing `p = d x e2` and `q = s x e1`. Fast, not watertight: rays through shared
//! edges can slip between the two triangles.

use super::{Ray, Triangle, TriangleKernel, in_interval};

impl TriangleKernel for MollerTrumbore {
    const NAME: &'static str = "moller-trumbore";

    #[inline]
    fn intersect(tri: &Triangle, ray: &Ray, t_max: f32) -> Option<f32> {
        let e1 = tri.v[1] - tri.v[0];
        let e2 = tri.v[2] - tri.v[0];
        let p = ray.dir.cross(e2);
        let det = e1.dot(p);
        if det == 0.0 {
            return None;
        }
        let inv_det = 1.0 / det;
        let s = ray.origin - tri.v[0];
        let u = s.dot(p) * inv_det;
        if !(0.0..=1.0).contains(&u) {
            return None;
        }
        let q = s.cross(e1);
        let v = ray.dir.dot(q) * inv_det;
        if v < 0.0 || u + v > 1.0 {
            return None;
        }
        in_interval(e2.dot(q) * inv_det, ray, t_max)
    }
}

/// The Möller–Trumbore kernel (see the module documentation).
#[derive(Debug, Clone, Copy, Default)]
pub struct MollerTrumbore;
