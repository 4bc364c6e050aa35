//! The float types the ray–triangle and ray–sphere kernels are written over: `f32` (glam's
//! `Vec3A`, the hot path of every index) and `f64` (`DVec3`, the accuracy study's mirrors).
//!
//! A kernel written once over [`KernelRay`] performs, in each precision, the same operations in
//! the same order: every method here is the type's own (`Vec3A::dot` for `f32`, `DVec3::dot` for
//! `f64`), except the `f32` cross product, which is [`super::float::cross`] (glam's formula, never
//! fused into an FMA). So the `f32` instantiation computes exactly what a kernel written for
//! `Vec3A` with that cross product computes, bit for bit, and the `f64` one mirrors it line by
//! line.

use glam::{DVec3, Vec3A};
use std::ops::{Add, Div, Index, Mul, Neg, Sub};

/// A float scalar: `f32` or `f64`.
pub trait Real:
    Copy
    + PartialOrd
    + From<f32>
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
{
    const ZERO: Self;
    const ONE: Self;
    const INFINITY: Self;
    /// The gap between 1 and the next value (twice the unit roundoff).
    const EPSILON: Self;
    /// The widest precision there is to recompute in (`f64` for both: there the product of two
    /// `f32` values is exact).
    type Wide: Real;
    fn widen(self) -> Self::Wide;
    /// `wide` rounded to this precision.
    fn narrow(wide: Self::Wide) -> Self;
    fn sqrt(self) -> Self;
    /// `self` with the sign of `sign`.
    fn copysign(self, sign: Self) -> Self;
}

/// A 3-vector of [`Real`]s with the operations the kernels use.
pub trait RealVec:
    Copy
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Self::Scalar, Output = Self>
    + Div<Self::Scalar, Output = Self>
    + Index<usize, Output = Self::Scalar>
{
    type Scalar: Real;
    /// The stored `f32` vector, exactly, in this precision.
    fn from_f32(v: Vec3A) -> Self;
    fn dot(self, other: Self) -> Self::Scalar;
    fn cross(self, other: Self) -> Self;
    fn length(self) -> Self::Scalar;
    /// The largest absolute component (the infinity norm).
    fn max_abs(self) -> Self::Scalar;
    /// The absolute value of each component.
    fn abs(self) -> Self;
}

/// What a kernel reads of a ray `origin + t * dir`: `t` in units of `dir`, accepted in
/// `[t_min(), t_max]`; `shear` holds the watertight test's per-ray constants.
pub trait KernelRay {
    type Scalar: Real;
    type Vec: RealVec<Scalar = Self::Scalar>;
    fn origin(&self) -> Self::Vec;
    fn dir(&self) -> Self::Vec;
    fn t_min(&self) -> Self::Scalar;
    fn shear(&self) -> &Shear<Self::Scalar>;

    /// The point at parameter `t`.
    #[inline(always)]
    fn at(&self, t: Self::Scalar) -> Self::Vec {
        self.origin() + self.dir() * t
    }
}

/// Per-ray constants of the watertight triangle test (Woop, Benthin and Wald 2013): the axis
/// `kz` on which the direction is largest, the two others `kx`, `ky` (swapped when `dir[kz] < 0`
/// to keep the winding), and the shear `sx = dir[kx]/dir[kz]`, `sy = dir[ky]/dir[kz]`,
/// `sz = 1/dir[kz]`, in the precision `S` of the kernel (`f32` on the hot path).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Shear<S = f32> {
    pub kx: usize,
    pub ky: usize,
    pub kz: usize,
    pub sx: S,
    pub sy: S,
    pub sz: S,
}

impl<S: Real> Shear<S> {
    /// The shear of `dir` on the axes `[kx, ky, kz]` (chosen by the `f32` ray), computed in the
    /// precision of `dir`.
    pub fn with_axes<V: RealVec<Scalar = S>>([kx, ky, kz]: [usize; 3], dir: V) -> Shear<S> {
        Shear {
            kx,
            ky,
            kz,
            sx: dir[kx] / dir[kz],
            sy: dir[ky] / dir[kz],
            sz: S::ONE / dir[kz],
        }
    }
}

/// Whether the triple product `det`, computed as `a.dot(b.cross(c))` in that order (or as
/// `(b x c) . a`), is certainly nonzero: `|det|` above its rounding-error bound
/// `4 eps |a| . (|b| x+ |c|)`, where `x+` is the cross product with sums for differences
/// (`gamma(6) < 4 eps` bounds the two roundings of the cross product and the three of the dot).
///
/// The kernels that solve a 3x3 system (Moller-Trumbore, parametric, plane-edges) call it on a
/// hit they are about to accept. For a zero-area triangle (two equal or three collinear
/// corners) the true determinant is zero whatever the ray, and the computed one is rounding
/// noise; dividing by it put hits anywhere on the ray, far from the triangle and from every
/// cell, box or clipped piece that holds it, where no spatial index could find them. A sound
/// triangle fails only when `|det|` is within `4 eps` (about `5e-7`) of `|a| . (|b| x+ |c|)`,
/// i.e. for rays within about that angle of its plane.
#[inline(always)]
pub fn certainly_nonzero<V: RealVec>(det: V::Scalar, a: V, b: V, c: V) -> bool {
    let (a, b, c) = (a.abs(), b.abs(), c.abs());
    let sums = [
        b[1] * c[2] + b[2] * c[1],
        b[2] * c[0] + b[0] * c[2],
        b[0] * c[1] + b[1] * c[0],
    ];
    let bound = (a[0] * sums[0] + a[1] * sums[1] + a[2] * sums[2])
        * (V::Scalar::EPSILON * V::Scalar::from(4.0));
    let abs_det = if det < V::Scalar::ZERO { -det } else { det };
    abs_det > bound
}

/// Largest disagreement [`on_triangle`] accepts between a kernel's two hit points, relative to
/// the magnitude of the coordinates involved (2^-8). Chosen by measurement, not derived: the
/// noise hits the property test found on triangles collinear up to one rounding were off by
/// 1.5% and more; sound hits lose out only at grazing angles near the origin (the accuracy
/// study's quick run, grazing family at offset 0: 31 of 995 Moller-Trumbore hits went to a
/// neighbouring triangle, against 4 without the check; 83 at 2^-10; none at offsets 1e3 and
/// beyond).
pub const HIT_AGREEMENT: f32 = 1.0 / 256.0;

/// Keeps a hit at `t` of a kernel that solves for the hit (Moller-Trumbore, parametric,
/// plane-edges) only when the ray's point `origin + t dir` lies within [`HIT_AGREEMENT`] of the
/// kernel's own point on the triangle `on_tri` (a convex combination of the corners): a
/// backstop behind [`certainly_nonzero`] for triangles whose determinant is barely above its
/// rounding bound (three corners collinear up to one rounding). An infinite point (`t` or
/// `on_tri` overflowed) rejects too.
#[inline(always)]
pub fn on_triangle<R: KernelRay>(t: R::Scalar, ray: &R, on_tri: R::Vec) -> Option<R::Scalar> {
    let on_ray = ray.at(t);
    let scale = ray.origin().max_abs() + on_ray.max_abs() + on_tri.max_abs();
    let tolerance = scale * R::Scalar::from(HIT_AGREEMENT);
    (tolerance < R::Scalar::INFINITY && (on_ray - on_tri).max_abs() <= tolerance).then_some(t)
}

/// Accepts `t` when it lies in `[ray.t_min(), t_max]` (false for NaN).
#[inline(always)]
pub fn in_interval<S: Real>(t: S, ray: &impl KernelRay<Scalar = S>, t_max: S) -> Option<S> {
    (t >= ray.t_min() && t <= t_max).then_some(t)
}

macro_rules! real_types {
    ($($real:ty, $vec:ty, $from_f32:expr, $cross:expr);*) => {$(
        impl Real for $real {
            const ZERO: $real = 0.0;
            const ONE: $real = 1.0;
            const INFINITY: $real = <$real>::INFINITY;
            const EPSILON: $real = <$real>::EPSILON;
            type Wide = f64;
            #[inline(always)]
            fn widen(self) -> f64 {
                self as f64
            }
            #[inline(always)]
            fn narrow(wide: f64) -> $real {
                wide as $real
            }
            #[inline(always)]
            fn sqrt(self) -> $real {
                <$real>::sqrt(self)
            }
            #[inline(always)]
            fn copysign(self, sign: $real) -> $real {
                <$real>::copysign(self, sign)
            }
        }

        impl RealVec for $vec {
            type Scalar = $real;
            #[inline(always)]
            fn from_f32(v: Vec3A) -> $vec {
                $from_f32(v)
            }
            #[inline(always)]
            fn dot(self, other: $vec) -> $real {
                <$vec>::dot(self, other)
            }
            #[inline(always)]
            fn cross(self, other: $vec) -> $vec {
                $cross(self, other)
            }
            #[inline(always)]
            fn length(self) -> $real {
                <$vec>::length(self)
            }
            #[inline(always)]
            fn max_abs(self) -> $real {
                <$vec>::abs(self).max_element()
            }
            #[inline(always)]
            fn abs(self) -> $vec {
                <$vec>::abs(self)
            }
        }
    )*};
}

// `f32` crosses unfused on every target (`float::cross`); `DVec3::cross` never fuses.
real_types!(f32, Vec3A, |v| v, super::float::cross; f64, DVec3, Vec3A::as_dvec3, DVec3::cross);

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_repeated_vector_makes_the_triple_product_uncertain_in_both_precisions() {
        let e = Vec3A::new(-0.75, 0.25, -1.823_173) - Vec3A::new(0.0, 1.0, 0.653_411_15);
        let d = Vec3A::new(0.3, -1.0, 0.7);
        // Whatever the computed `det` is (rounding noise), it is within the bound.
        let det = e.dot(d.cross(e));
        assert!(!certainly_nonzero(det, e, d, e));
        let (e64, d64) = (e.as_dvec3(), d.as_dvec3());
        assert!(!certainly_nonzero(e64.dot(d64.cross(e64)), e64, d64, e64));
        // A well-conditioned triple product, and one 1e-6 from its plane, are certain.
        let (x, y) = (Vec3A::X, Vec3A::Y);
        assert!(certainly_nonzero(x.dot(y.cross(Vec3A::Z)), x, y, Vec3A::Z));
        let grazing = Vec3A::new(0.0, 1.0, 1e-6);
        assert!(certainly_nonzero(
            x.dot(grazing.cross(x + y)),
            x,
            grazing,
            x + y
        ));
        // An exact zero is never certain.
        assert!(!certainly_nonzero(0.0f32, x, y, Vec3A::Z));
    }
}
