//! The reference the kernels are measured against: exact hit/miss decisions for triangles (the
//! exact signs of the three edge functions, by Shewchuk's adaptive `orient3d` from the `robust`
//! crate) and double-double (about 106-bit) parameters `t` for triangles and spheres.
//!
//! The reference answers for the exact ray of the `f32` inputs (origin, direction) against the
//! exact primitive of the `f32` inputs, over the closed interval `[0, +inf]`.

use super::dd::{Dd, DdVec3, two_sum};
use crate::geometry::{Ray, Sphere, Triangle};
use glam::Vec3A;
use robust::{Coord3D, orient3d};

/// The reference answer for one ray against one primitive.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Reference {
    /// The exact ray meets the primitive at this `t` (double-double, rounded to `f64`).
    Hit(f64),
    Miss,
    /// The exact decision could not be certified (a coordinate difference not exact in `f64`,
    /// or a sphere tangent closer than double-double can resolve); such rays are left out of the
    /// rates and counted.
    Unverifiable,
}

fn c3(v: [f64; 3]) -> Coord3D<f64> {
    Coord3D {
        x: v[0],
        y: v[1],
        z: v[2],
    }
}

/// `p - o` per component in `f64`, or `None` when a difference is not exact (magnitudes more
/// than `2^29` apart).
fn exact_diff(p: Vec3A, o: Vec3A) -> Option<[f64; 3]> {
    let mut out = [0.0; 3];
    for k in 0..3 {
        let (s, e) = two_sum(p[k] as f64, -(o[k] as f64));
        if e != 0.0 {
            return None;
        }
        out[k] = s;
    }
    Some(out)
}

/// Exact sign of `det[x; y; z]` (rows), i.e. `x . (y x z)`.
fn det_sign(x: [f64; 3], y: [f64; 3], z: [f64; 3]) -> i32 {
    let d = orient3d(c3(x), c3(y), c3(z), c3([0.0; 3]));
    (d > 0.0) as i32 - (d < 0.0) as i32
}

/// Exact classification of `ray` (over `[0, +inf]`) against a triangle, two-sided.
///
/// With `A, B, C` the corners relative to the origin and `d` the direction, the edge functions
/// are `U = d.(B x C)`, `V = d.(C x A)`, `W = d.(A x B)`; the ray's line meets the triangle iff
/// they share a sign and are not all zero (a ray in the triangle's plane is a miss, as in every
/// kernel). `t = det[A; B; C] / (U + V + W)`, so its sign is exact too.
pub fn triangle(tri: &Triangle, ray: &Ray) -> Reference {
    let o = ray.origin;
    let d = [ray.dir.x as f64, ray.dir.y as f64, ray.dir.z as f64];
    let (Some(a), Some(b), Some(c)) = (
        exact_diff(tri.v[0], o),
        exact_diff(tri.v[1], o),
        exact_diff(tri.v[2], o),
    ) else {
        return Reference::Unverifiable;
    };
    let u = det_sign(d, b, c);
    let v = det_sign(d, c, a);
    let w = det_sign(d, a, b);
    let side = if u >= 0 && v >= 0 && w >= 0 {
        1
    } else if u <= 0 && v <= 0 && w <= 0 {
        -1
    } else {
        return Reference::Miss;
    };
    if u == 0 && v == 0 && w == 0 {
        return Reference::Miss;
    }
    // sign(U + V + W) is `side` (all share it, not all zero); sign(t) = sign(det[A;B;C]) * side.
    if det_sign(a, b, c) * side < 0 {
        return Reference::Miss;
    }
    Reference::Hit(triangle_t(tri, ray))
}

/// The plane parameter `t = n.(v0 - o) / n.d` in double-double (`n = (v1 - v0) x (v2 - v0)`).
fn triangle_t(tri: &Triangle, ray: &Ray) -> f64 {
    let e1 = DdVec3::diff(tri.v[1], tri.v[0]);
    let e2 = DdVec3::diff(tri.v[2], tri.v[0]);
    let n = e1.cross(e2);
    let num = n.dot(DdVec3::diff(tri.v[0], ray.origin));
    let den = n.dot(DdVec3::from_f32(ray.dir));
    (num / den).to_f64()
}

/// Reference for a sphere in double-double: with `f = o - c`, `a = d.d`, `b = f.d`, the scaled
/// discriminant `D = a r^2 - |d x f|^2` (Lagrange's identity, no cancellation between `b^2` and
/// `a c`) decides hit or miss; the roots are `q/a` and `c/q` with `q = -(b + sign(b) sqrt(D))`.
/// Returns the smaller root `>= 0`. A tangent within `1e-28` relative is [`Reference::Unverifiable`].
pub fn sphere(s: &Sphere, ray: &Ray) -> Reference {
    let f = DdVec3::diff(ray.origin, s.center);
    let d = DdVec3::from_f32(ray.dir);
    let r = Dd::new(s.radius as f64);
    let a = d.dot(d);
    let b = f.dot(d);
    let dxf = d.cross(f);
    let ar2 = a * r * r;
    let cross2 = dxf.dot(dxf);
    let disc = ar2 - cross2;
    if disc.abs().to_f64() <= 1e-28 * (ar2.to_f64() + cross2.to_f64()) {
        return Reference::Unverifiable;
    }
    if disc.signum() < 0 {
        return Reference::Miss;
    }
    let root = disc.sqrt();
    let q = if b.signum() >= 0 {
        -(b + root)
    } else {
        root - b
    };
    let c = f.dot(f) - r * r;
    if q.signum() == 0 {
        return Reference::Hit(0.0);
    }
    let (t0, t1) = ((q / a).to_f64(), (c / q).to_f64());
    let (lo, hi) = if t0 <= t1 { (t0, t1) } else { (t1, t0) };
    if lo >= 0.0 {
        Reference::Hit(lo)
    } else if hi >= 0.0 {
        Reference::Hit(hi)
    } else {
        Reference::Miss
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    fn tri() -> Triangle {
        Triangle::from_corners([0.0, 0.0, 2.0], [4.0, 0.0, 2.0], [0.0, 4.0, 2.0])
    }

    #[test]
    fn hand_computed_triangle_cases() {
        let r = |o: [f32; 3], d: [f32; 3]| Ray::infinite(Vec3::from(o), Vec3::from(d)).unwrap();
        assert_eq!(
            triangle(&tri(), &r([1.0, 1.0, 0.0], [0.0, 0.0, 0.5])),
            Reference::Hit(4.0)
        );
        assert_eq!(
            triangle(&tri(), &r([1.0, 1.0, 5.0], [0.0, 0.0, -1.0])),
            Reference::Hit(3.0)
        );
        assert_eq!(
            triangle(&tri(), &r([1.0, 1.0, 3.0], [0.0, 0.0, 1.0])),
            Reference::Miss
        );
        assert_eq!(
            triangle(&tri(), &r([3.0, 3.0, 0.0], [0.0, 0.0, 1.0])),
            Reference::Miss
        );
        // Exactly through the hypotenuse and a vertex: hits (closed triangle).
        assert_eq!(
            triangle(&tri(), &r([2.0, 2.0, 0.0], [0.0, 0.0, 1.0])),
            Reference::Hit(2.0)
        );
        assert_eq!(
            triangle(&tri(), &r([4.0, 0.0, 0.0], [0.0, 0.0, 1.0])),
            Reference::Hit(2.0)
        );
        // Just outside the hypotenuse by one ulp: an exact miss that f32 kernels may call a hit.
        let x = f32::from_bits(2.0f32.to_bits() + 1);
        assert_eq!(
            triangle(&tri(), &r([x, 2.0, 0.0], [0.0, 0.0, 1.0])),
            Reference::Miss
        );
        // In the plane: miss.
        assert_eq!(
            triangle(&tri(), &r([-1.0, 1.0, 2.0], [1.0, 0.0, 0.0])),
            Reference::Miss
        );
    }

    #[test]
    fn hand_computed_sphere_cases() {
        let s = Sphere::new(Vec3A::new(0.0, 0.0, 5.0), 1.0);
        let r = |o: [f32; 3]| Ray::infinite(Vec3::from(o), Vec3::Z).unwrap();
        assert_eq!(sphere(&s, &r([0.0, 0.0, 0.0])), Reference::Hit(4.0));
        assert_eq!(sphere(&s, &r([0.0, 0.0, 5.0])), Reference::Hit(1.0));
        assert_eq!(sphere(&s, &r([0.0, 0.0, 7.0])), Reference::Miss);
        assert_eq!(sphere(&s, &r([0.0, 1.5, 0.0])), Reference::Miss);
        // Exactly tangent: cannot be certified either way.
        assert_eq!(sphere(&s, &r([0.0, 1.0, 0.0])), Reference::Unverifiable);
        let Reference::Hit(t) = sphere(&s, &r([0.0, 0.6, 0.0])) else {
            panic!()
        };
        let exact = 5.0 - (1.0 - (0.6f32 as f64).powi(2)).sqrt();
        assert!((t - exact).abs() < 1e-15, "{t} vs {exact}");
    }
}
