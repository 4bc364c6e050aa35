//! Spheres and the two ray–sphere kernels (algebraic and geometric).
//!
//! Both report the smallest root in `[ray.t_min, t_max]`: the near root, or the far one when the
//! ray starts inside (or the near root lies before `t_min`). Each is written once over the
//! precision ([`crate::geometry::real`]): the `f32` instance is the kernel every index uses, the
//! `f64` instance the accuracy study's mirror.

use super::Aabb;
use super::quadratic::ball_roots;
use super::real::{KernelRay, Real, RealVec};
use glam::Vec3A;

#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sphere {
    pub center: Vec3A,
    pub radius: f32,
}

impl Sphere {
    pub fn new(center: Vec3A, radius: f32) -> Sphere {
        Sphere { center, radius }
    }

    #[inline]
    pub fn bounds(&self) -> Aabb {
        let r = Vec3A::splat(self.radius);
        Aabb {
            min: self.center - r,
            max: self.center + r,
        }
    }

    /// Outward unit normal at a surface point.
    pub fn normal_at(&self, p: Vec3A) -> Vec3A {
        (p - self.center).normalize_or_zero()
    }
}

/// Picks the smaller of two roots that lies in `[t_min, t_max]`.
#[inline(always)]
fn first_root<S: Real>(t0: S, t1: S, ray: &impl KernelRay<Scalar = S>, t_max: S) -> Option<S> {
    let (lo, hi) = if t0 <= t1 { (t0, t1) } else { (t1, t0) };
    if lo >= ray.t_min() && lo <= t_max {
        Some(lo)
    } else if hi >= ray.t_min() && hi <= t_max {
        Some(hi)
    } else {
        None
    }
}

/// Algebraic kernel, numerically stable: the roots of [`ball_roots`] (Haines et al., Ray
/// Tracing Gems ch. 7) for `f = origin - center`.
#[inline]
pub fn intersect_algebraic<R: KernelRay>(
    s: &Sphere,
    ray: &R,
    t_max: R::Scalar,
) -> Option<R::Scalar> {
    let f = ray.origin() - R::Vec::from_f32(s.center);
    let (t0, t1) = ball_roots(f, ray.dir(), R::Scalar::from(s.radius))?;
    first_root(t0, t1, ray, t_max)
}

/// Geometric kernel (the course's `L`, `t_ca`, `d^2`, `t_hc` method) on the normalized direction,
/// converted back to units of `dir`.
#[inline]
pub fn intersect_geometric<R: KernelRay>(
    s: &Sphere,
    ray: &R,
    t_max: R::Scalar,
) -> Option<R::Scalar> {
    let radius = R::Scalar::from(s.radius);
    let len = ray.dir().length();
    let dn = ray.dir() / len;
    let l = R::Vec::from_f32(s.center) - ray.origin();
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
    use crate::geometry::Ray;
    use glam::Vec3;

    type Kernel = fn(&Sphere, &Ray, f32) -> Option<f32>;
    const KERNELS: [(&str, Kernel); 2] = [
        ("algebraic", intersect_algebraic),
        ("geometric", intersect_geometric),
    ];

    fn unit() -> Sphere {
        Sphere::new(Vec3A::new(0.0, 0.0, 5.0), 1.0)
    }

    #[test]
    fn hand_computed_cases() {
        let front = Ray::infinite(Vec3::ZERO, Vec3::Z).unwrap();
        let scaled = Ray::infinite(Vec3::ZERO, Vec3::Z * 2.0).unwrap();
        let inside = Ray::infinite(Vec3::new(0.0, 0.0, 5.0), Vec3::Z).unwrap();
        let behind = Ray::infinite(Vec3::new(0.0, 0.0, 7.0), Vec3::Z).unwrap();
        let miss = Ray::infinite(Vec3::new(0.0, 1.5, 0.0), Vec3::Z).unwrap();
        let offset = Ray::infinite(Vec3::new(0.0, 0.6, 0.0), Vec3::Z).unwrap();
        let short = Ray::new(Vec3::ZERO, Vec3::Z, 0.0, 3.9).unwrap();
        for (name, k) in KERNELS {
            assert_eq!(k(&unit(), &front, f32::INFINITY), Some(4.0), "{name}");
            assert_eq!(k(&unit(), &scaled, f32::INFINITY), Some(2.0), "{name}");
            assert_eq!(k(&unit(), &inside, f32::INFINITY), Some(1.0), "{name}");
            assert_eq!(k(&unit(), &behind, f32::INFINITY), None, "{name}");
            assert_eq!(k(&unit(), &miss, f32::INFINITY), None, "{name}");
            assert_eq!(k(&unit(), &short, 3.9), None, "{name}");
            // y = 0.6: t = 5 - sqrt(1 - 0.36) = 4.2
            let t = k(&unit(), &offset, f32::INFINITY).unwrap();
            assert!((t - 4.2).abs() < 1e-6, "{name}: {t}");
        }
    }

    #[test]
    fn far_away_small_sphere_stays_accurate() {
        // The textbook b^2 - 4ac loses every digit here; the stable forms do not.
        let s = Sphere::new(Vec3A::new(0.0, 0.0, 1.0e4), 0.01);
        let r = Ray::infinite(Vec3::ZERO, Vec3::Z).unwrap();
        for (name, k) in KERNELS {
            let t = k(&s, &r, f32::INFINITY).unwrap();
            assert!((t - 9999.99).abs() <= 1e-3, "{name}: {t}");
        }
    }
}
