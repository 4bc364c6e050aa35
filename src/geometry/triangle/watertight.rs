//! Watertight ray–triangle test (Woop, Benthin and Wald, JCGT 2013).
//!
//! The triangle is translated to the ray origin, sheared so the ray runs along +z, and the
//! signed 2D edge functions `U, V, W` decide inside/outside. Edges shared by two triangles get
//! exactly opposite edge functions, so a ray through a shared edge or vertex hits at least one of
//! the triangles: no leaks. When an edge function is exactly zero it is recomputed in `f64`, as
//! the paper prescribes, so the sign test is exact for `f32` inputs.
//!
//! The lane form ([`RealKernel::on_lanes`]) runs the `f32` instance on four triangles at once:
//! each lane of [`Vec4`] does the scalar kernel's `f32` operations in the same order (IEEE
//! `sub`, `mul`, `add`, `div`; Rust never fuses them into a multiply-add), so a decided lane's
//! `t` is the scalar kernel's bit for bit. A lane with an edge function exactly zero, which
//! the scalar kernel recomputes in `f64`, is left to the scalar kernel. A block whose every
//! lane has mixed signs and no zero (a decided miss) returns before `t` is computed.

use super::RealKernel;
use super::lanes::{LaneHits, TriangleLanes};
use crate::geometry::Ray;
use crate::geometry::real::{KernelRay, Real, in_interval};
use glam::Vec4;

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

    #[inline(always)]
    fn on_lanes(tris: &TriangleLanes, ray: &Ray) -> LaneHits {
        let s = &ray.shear;
        let o = ray.origin;
        let rel = |c: usize| [0, 1, 2].map(|k| Vec4::from_array(tris.v[c][k]) - Vec4::splat(o[k]));
        let (a, b, c) = (rel(0), rel(1), rel(2));
        let (sx, sy, sz) = (Vec4::splat(s.sx), Vec4::splat(s.sy), Vec4::splat(s.sz));
        let sheared = |p: &[Vec4; 3]| (p[s.kx] - sx * p[s.kz], p[s.ky] - sy * p[s.kz]);
        let ((ax, ay), (bx, by), (cx, cy)) = (sheared(&a), sheared(&b), sheared(&c));
        let [u, v, w] = plain_edge_functions([ax, ay, bx, by, cx, cy]);
        let zero = Vec4::ZERO;
        let any =
            |f: fn(Vec4, Vec4) -> glam::BVec4A| (f(u, zero) | f(v, zero) | f(w, zero)).bitmask();
        let undecided = any(Vec4::cmpeq);
        let mixed = any(Vec4::cmplt) & any(Vec4::cmpgt);
        // Every lane a decided miss (the common block): no `t` to compute.
        if (!mixed | undecided) & 0b1111 == 0 {
            return LaneHits::MISS;
        }
        let det = u + v + w;
        let t_scaled = u * (sz * a[s.kz]) + v * (sz * b[s.kz]) + w * (sz * c[s.kz]);
        let t = t_scaled / det;
        let in_range = t.cmpge(Vec4::splat(ray.t_min)) & t.cmple(Vec4::splat(ray.t_max));
        LaneHits {
            hit: (in_range & det.cmpne(zero)).bitmask() & !mixed & !undecided,
            scalar: undecided,
            t: t.to_array(),
        }
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
fn plain_edge_functions<S>([ax, ay, bx, by, cx, cy]: [S; 6]) -> [S; 3]
where
    S: Copy + std::ops::Mul<Output = S> + std::ops::Sub<Output = S>,
{
    [cx * by - cy * bx, ax * cy - ay * cx, bx * ay - by * ax]
}

/// The watertight kernel of Woop, Benthin and Wald (see the module documentation).
#[derive(Debug, Clone, Copy, Default)]
pub struct Watertight;

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Triangle;
    use crate::geometry::triangle::lane_check::{check_decided_lanes, ray_origin, ray_target};
    use glam::{Vec3, Vec3A};

    /// Decided lanes equal the scalar kernel bit for bit on random triangles at several scales,
    /// with rays aimed inside them, at their corners and edge midpoints (edge functions exactly
    /// zero: lanes left to the scalar kernel), beside them, from inside their plane, and with
    /// `t` intervals that cut hits off; hits, misses, undecided lanes and blocks of misses
    /// only all occur.
    #[test]
    fn decided_lanes_equal_the_scalar_kernel() {
        let aim = |point: &mut dyn FnMut(f32) -> Vec3A, tris: &[Triangle; 4], scale, round| {
            let o = ray_origin(point, tris, scale, round);
            let target = ray_target(tris, round, round % 3);
            let (t_min, t_max) = [(0.0, f32::INFINITY), (-1.0, 1.5), (0.5, 0.9)][round % 3];
            Ray::new(o.into(), Vec3::from(target - o), t_min, t_max).ok()
        };
        let seed = 0x05ee_d0f1_a7e5;
        check_decided_lanes::<Watertight>(seed, &[1.0, 1e3, 1e-3, 1e6], aim, Watertight::on_lanes);
    }
}
