//! The float types the ray–triangle and ray–sphere kernels are written over: `f32` (glam's
//! `Vec3A`, the hot path of every index) and `f64` (`DVec3`, the accuracy study's mirrors).
//!
//! A kernel written once over [`KernelRay`] performs, in each precision, the same operations in
//! the same order: every method here is the type's own (`Vec3A::dot` for `f32`, `DVec3::dot` for
//! `f64`), so the `f32` instantiation computes exactly what a kernel written for `Vec3A` computes,
//! bit for bit, and the `f64` one mirrors it line by line.

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

/// Accepts `t` when it lies in `[ray.t_min(), t_max]` (false for NaN).
#[inline(always)]
pub fn in_interval<S: Real>(t: S, ray: &impl KernelRay<Scalar = S>, t_max: S) -> Option<S> {
    (t >= ray.t_min() && t <= t_max).then_some(t)
}

macro_rules! real_types {
    ($($real:ty, $vec:ty, $from_f32:expr);*) => {$(
        impl Real for $real {
            const ZERO: $real = 0.0;
            const ONE: $real = 1.0;
            const INFINITY: $real = <$real>::INFINITY;
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
                <$vec>::cross(self, other)
            }
            #[inline(always)]
            fn length(self) -> $real {
                <$vec>::length(self)
            }
        }
    )*};
}

real_types!(f32, Vec3A, |v| v; f64, DVec3, Vec3A::as_dvec3);
