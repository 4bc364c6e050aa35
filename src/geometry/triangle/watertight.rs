//! Watertight ray–triangle test (Woop, Benthin and Wald, JCGT 2013).
//!
//! The triangle is translated to the ray origin, sheared so the ray runs along +z, and the
//! signed 2D edge functions `U, V, W` decide inside/outside. Edges shared by two triangles get
//! exactly opposite edge functions, so a ray through a shared edge or vertex hits at least one of
//! the triangles: no leaks. When an edge function is exactly zero it is recomputed in `f64`, as
//! the paper prescribes, so the sign test is exact for `f32` inputs.

use super::{Ray, Triangle, TriangleKernel, in_interval};

impl TriangleKernel for Watertight {
    const NAME: &'static str = "watertight";

    #[inline]
    fn intersect(tri: &Triangle, ray: &Ray, t_max: f32) -> Option<f32> {
        let s = &ray.shear;
        let a = tri.v[0] - ray.origin;
        let b = tri.v[1] - ray.origin;
        let c = tri.v[2] - ray.origin;
        let ax = a[s.kx] - s.sx * a[s.kz];
        let ay = a[s.ky] - s.sy * a[s.kz];
        let bx = b[s.kx] - s.sx * b[s.kz];
        let by = b[s.ky] - s.sy * b[s.kz];
        let cx = c[s.kx] - s.sx * c[s.kz];
        let cy = c[s.ky] - s.sy * c[s.kz];
        let mut u = cx * by - cy * bx;
        let mut v = ax * cy - ay * cx;
        let mut w = bx * ay - by * ax;
        if u == 0.0 || v == 0.0 || w == 0.0 {
            let (ax, ay, bx, by, cx, cy) = (
                ax as f64, ay as f64, bx as f64, by as f64, cx as f64, cy as f64,
            );
            u = (cx * by - cy * bx) as f32;
            v = (ax * cy - ay * cx) as f32;
            w = (bx * ay - by * ax) as f32;
        }
        if (u < 0.0 || v < 0.0 || w < 0.0) && (u > 0.0 || v > 0.0 || w > 0.0) {
            return None;
        }
        let det = u + v + w;
        if det == 0.0 {
            return None;
        }
        let az = s.sz * a[s.kz];
        let bz = s.sz * b[s.kz];
        let cz = s.sz * c[s.kz];
        let t_scaled = u * az + v * bz + w * cz;
        in_interval(t_scaled / det, ray, t_max)
    }
}

/// The watertight kernel of Woop, Benthin and Wald (see the module documentation).
#[derive(Debug, Clone, Copy, Default)]
pub struct Watertight;
