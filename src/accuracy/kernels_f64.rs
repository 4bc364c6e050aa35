//! `f64` versions of every ray–primitive kernel, for the precision comparison only.
//!
//! Each function mirrors its `f32` original in `crate::geometry` line by line (same formulas,
//! same order of operations, same acceptance tests), with every value in `f64`. The `f32`
//! kernels stay the hot path of every index; these are never used by an index. The one
//! deliberate difference: the watertight kernel's fallback for an exactly zero edge function
//! recomputes in `f64` in the original and has nothing wider to fall back to here.

use crate::geometry::{Ray, Sphere, Triangle};
use glam::DVec3;

/// A ray in `f64`: the exact values of an `f32` [`Ray`], plus the watertight shear in `f64`.
#[derive(Debug, Clone, Copy)]
pub struct Ray64 {
    pub origin: DVec3,
    pub dir: DVec3,
    pub t_min: f64,
    pub t_max: f64,
    pub(super) kx: usize,
    pub(super) ky: usize,
    pub(super) kz: usize,
    pub(super) sx: f64,
    pub(super) sy: f64,
    pub(super) sz: f64,
}

impl Ray64 {
    /// The same ray in `f64` (same axes for the shear as the `f32` ray).
    pub fn from_ray(r: &Ray) -> Ray64 {
        let dir = glam::Vec3::from(r.dir).as_dvec3();
        let s = &r.shear;
        Ray64 {
            origin: glam::Vec3::from(r.origin).as_dvec3(),
            dir,
            t_min: r.t_min as f64,
            t_max: r.t_max as f64,
            kx: s.kx,
            ky: s.ky,
            kz: s.kz,
            sx: dir[s.kx] / dir[s.kz],
            sy: dir[s.ky] / dir[s.kz],
            sz: 1.0 / dir[s.kz],
        }
    }

    fn at(&self, t: f64) -> DVec3 {
        self.origin + self.dir * t
    }
}

fn corners(tri: &Triangle) -> [DVec3; 3] {
    tri.v.map(|v| glam::Vec3::from(v).as_dvec3())
}

fn in_interval(t: f64, ray: &Ray64, t_max: f64) -> Option<f64> {
    (t >= ray.t_min && t <= t_max).then_some(t)
}

/// Mirrors `geometry::triangle::PlaneEdges`.
pub fn plane_edges(tri: &Triangle, ray: &Ray64, t_max: f64) -> Option<f64> {
    let v = corners(tri);
    let n = (v[1] - v[0]).cross(v[2] - v[0]);
    let denom = n.dot(ray.dir);
    if denom == 0.0 {
        return None;
    }
    let t = n.dot(v[0] - ray.origin) / denom;
    let t = in_interval(t, ray, t_max)?;
    let p = ray.at(t);
    for i in 0..3 {
        let a = v[i];
        let b = v[(i + 1) % 3];
        if (b - a).cross(p - a).dot(n) < 0.0 {
            return None;
        }
    }
    Some(t)
}

/// Mirrors `geometry::triangle::Parametric`.
pub fn parametric(tri: &Triangle, ray: &Ray64, t_max: f64) -> Option<f64> {
    let v = corners(tri);
    let c0 = v[0] - v[1];
    let c1 = v[0] - v[2];
    let c2 = ray.dir;
    let rhs = v[0] - ray.origin;
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

/// Mirrors `geometry::triangle::MollerTrumbore`.
pub fn moller_trumbore(tri: &Triangle, ray: &Ray64, t_max: f64) -> Option<f64> {
    let v = corners(tri);
    let e1 = v[1] - v[0];
    let e2 = v[2] - v[0];
    let p = ray.dir.cross(e2);
    let det = e1.dot(p);
    if det == 0.0 {
        return None;
    }
    let inv_det = 1.0 / det;
    let s = ray.origin - v[0];
    let u = s.dot(p) * inv_det;
    if !(0.0..=1.0).contains(&u) {
        return None;
    }
    let q = s.cross(e1);
    let w = ray.dir.dot(q) * inv_det;
    if w < 0.0 || u + w > 1.0 {
        return None;
    }
    in_interval(e2.dot(q) * inv_det, ray, t_max)
}

/// Mirrors `geometry::triangle::Watertight` (without the wider fallback, see the module doc).
pub fn watertight(tri: &Triangle, ray: &Ray64, t_max: f64) -> Option<f64> {
    let v = corners(tri);
    let (kx, ky, kz) = (ray.kx, ray.ky, ray.kz);
    let a = v[0] - ray.origin;
    let b = v[1] - ray.origin;
    let c = v[2] - ray.origin;
    let ax = a[kx] - ray.sx * a[kz];
    let ay = a[ky] - ray.sy * a[kz];
    let bx = b[kx] - ray.sx * b[kz];
    let by = b[ky] - ray.sy * b[kz];
    let cx = c[kx] - ray.sx * c[kz];
    let cy = c[ky] - ray.sy * c[kz];
    let u = cx * by - cy * bx;
    let v = ax * cy - ay * cx;
    let w = bx * ay - by * ax;
    if (u < 0.0 || v < 0.0 || w < 0.0) && (u > 0.0 || v > 0.0 || w > 0.0) {
        return None;
    }
    let det = u + v + w;
    if det == 0.0 {
        return None;
    }
    let az = ray.sz * a[kz];
    let bz = ray.sz * b[kz];
    let cz = ray.sz * c[kz];
    let t_scaled = u * az + v * bz + w * cz;
    in_interval(t_scaled / det, ray, t_max)
}

/// Mirrors `geometry::sphere`'s `first_root`.
fn first_root(t0: f64, t1: f64, ray: &Ray64, t_max: f64) -> Option<f64> {
    let (lo, hi) = if t0 <= t1 { (t0, t1) } else { (t1, t0) };
    if lo >= ray.t_min && lo <= t_max {
        Some(lo)
    } else if hi >= ray.t_min && hi <= t_max {
        Some(hi)
    } else {
        None
    }
}

/// Mirrors `geometry::sphere::intersect_algebraic`.
pub fn sphere_algebraic(s: &Sphere, ray: &Ray64, t_max: f64) -> Option<f64> {
    let center = glam::Vec3::from(s.center).as_dvec3();
    let radius = s.radius as f64;
    let f = ray.origin - center;
    let a = ray.dir.dot(ray.dir);
    let b = f.dot(ray.dir);
    let c = f.dot(f) - radius * radius;
    let l = f - ray.dir * (b / a);
    let disc = radius * radius - l.dot(l);
    if disc < 0.0 {
        return None;
    }
    let root = (a * disc).sqrt();
    let q = -(b + root.copysign(b));
    if q == 0.0 {
        return first_root(0.0, 0.0, ray, t_max);
    }
    first_root(c / q, q / a, ray, t_max)
}

/// Mirrors `geometry::sphere::intersect_geometric`.
pub fn sphere_geometric(s: &Sphere, ray: &Ray64, t_max: f64) -> Option<f64> {
    let center = glam::Vec3::from(s.center).as_dvec3();
    let radius = s.radius as f64;
    let len = ray.dir.length();
    let dn = ray.dir / len;
    let l = center - ray.origin;
    let t_ca = l.dot(dn);
    let d2 = l.dot(l) - t_ca * t_ca;
    let r2 = radius * radius;
    if d2 > r2 {
        return None;
    }
    let t_hc = (r2 - d2).sqrt();
    first_root((t_ca - t_hc) / len, (t_ca + t_hc) / len, ray, t_max)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::TriangleKernelKind;
    use crate::geometry::sphere::{intersect_algebraic, intersect_geometric};
    use glam::{Vec3, Vec3A};

    type Mirror = fn(&Triangle, &Ray64, f64) -> Option<f64>;

    /// On easy rays each f64 mirror agrees with its f32 original to f32 precision.
    #[test]
    fn mirrors_agree_with_the_f32_originals() {
        let tri = Triangle::from_corners([0.0, 0.0, 2.0], [4.0, 0.1, 2.5], [0.2, 4.0, 1.5]);
        let s = Sphere::new(Vec3A::new(0.5, 0.7, 6.0), 1.3);
        let f64s: [(TriangleKernelKind, Mirror); 4] = [
            (TriangleKernelKind::PlaneEdges, plane_edges),
            (TriangleKernelKind::Parametric, parametric),
            (TriangleKernelKind::MollerTrumbore, moller_trumbore),
            (TriangleKernelKind::Watertight, watertight),
        ];
        for (o, d) in [
            ([1.0, 1.0, 0.0], [0.01, 0.02, 1.0]),
            ([3.0, 3.0, 0.0], [0.0, 0.0, 1.0]),
            ([1.0, 1.0, 9.0], [0.1, -0.05, -1.0]),
            ([0.0, 0.0, 0.0], [0.05, 0.1, 1.0]),
        ] {
            let ray = Ray::infinite(Vec3::from(o), Vec3::from(d)).unwrap();
            let r64 = Ray64::from_ray(&ray);
            for (k, f) in f64s {
                let a = k.intersect(&tri, &ray, f32::INFINITY);
                let b = f(&tri, &r64, f64::INFINITY);
                assert_eq!(a.is_some(), b.is_some(), "{k} {o:?}");
                if let (Some(a), Some(b)) = (a, b) {
                    assert!((a as f64 - b).abs() <= 1e-5 * b.abs(), "{k}: {a} vs {b}");
                }
            }
            for (a, b) in [
                (
                    intersect_algebraic(&s, &ray, f32::INFINITY),
                    sphere_algebraic(&s, &r64, f64::INFINITY),
                ),
                (
                    intersect_geometric(&s, &ray, f32::INFINITY),
                    sphere_geometric(&s, &r64, f64::INFINITY),
                ),
            ] {
                assert_eq!(a.is_some(), b.is_some(), "{o:?}");
                if let (Some(a), Some(b)) = (a, b) {
                    assert!((a as f64 - b).abs() <= 1e-5 * b.abs(), "{a} vs {b}");
                }
            }
        }
    }
}
