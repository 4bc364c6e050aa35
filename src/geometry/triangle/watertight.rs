//! Watertight ray–triangle test (Woop, Benthin and Wald, JCGT 2013).
//!
//! The triangle is translated to the ray origin, sheared so the ray runs along +z, and the
//! signed 2D edge functions `U, V, W` decide inside/outside. Edges shared by two triangles get
//! exactly opposite edge functions, so a ray through a shared edge or vertex hits at least one of
//! the triangles: no leaks. When an edge function is exactly zero it is recomputed in `f64`, as
//! the paper prescribes, so the sign test is exact for `f32` inputs.

use super::RealKernel;
use crate::geometry::real::{KernelRay, Real, in_interval};

impl RealKernel for Watertight {
    const NAME: &'static str = "watertight";

    #[inline(always)]
    fn on_corners<R: KernelRay>(v: [R::Vec; 3], ray: &R, t_max: R::Scalar) -> Option<R::Scalar> {
        let s = ray.shear();
        let a = v[0] - ray.origin();
        let b = v[1] - ray.origin();
        let c = v[2] - ray.origin();
        let ax = a[s.kx] - s.sx * a[s.kz];
        let ay = a[s.ky] - s.sy * a[s.kz];
        let bx = b[s.kx] - s.sx * b[s.kz];
        let by = b[s.ky] - s.sy * b[s.kz];
        let cx = c[s.kx] - s.sx * c[s.kz];
        let cy = c[s.ky] - s.sy * c[s.kz];
        let [u, v, w] = edge_functions([ax, ay, bx, by, cx, cy]);
        let zero = R::Scalar::ZERO;
        if (u < zero || v < zero || w < zero) && (u > zero || v > zero || w > zero) {
            return None;
        }
        let det = u + v + w;
        if det == zero {
            return None;
        }
        let az = s.sz * a[s.kz];
        let bz = s.sz * b[s.kz];
        let cz = s.sz * c[s.kz];
        let t_scaled = u * az + v * bz + w * cz;
        in_interval(t_scaled / det, ray, t_max)
    }
}

/// The signed 2D edge functions `[U, V, W]` of the sheared corners `[ax, ay, bx, by, cx, cy]`,
/// in their precision; when one is exactly zero all three are recomputed in the widest one
/// (for `f32` corners exact, so the sign is; `f64` corners have nothing wider and get the same
/// values again).
#[inline(always)]
fn edge_functions<S: Real>(sheared: [S; 6]) -> [S; 3] {
    let uvw = plain_edge_functions(sheared);
    if uvw.contains(&S::ZERO) {
        plain_edge_functions(sheared.map(S::widen)).map(S::narrow)
    } else {
        uvw
    }
}

/// [`edge_functions`] without the recomputation.
#[inline(always)]
fn plain_edge_functions<S: Real>([ax, ay, bx, by, cx, cy]: [S; 6]) -> [S; 3] {
    [cx * by - cy * bx, ax * cy - ay * cx, bx * ay - by * ax]
}

/// The watertight kernel of Woop, Benthin and Wald (see the module documentation).
#[derive(Debug, Clone, Copy, Default)]
pub struct Watertight;
