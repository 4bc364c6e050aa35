//! The SIMD registers the slab tests are written over ([`Lanes`]): four `f32` lanes (glam's
//! [`Vec4`], one SSE register), eight ([`F8`], one AVX register, two [`Vec4`] without AVX) or
//! sixteen ([`F16`](super::lanes16::F16), one AVX-512 register, two [`F8`] without AVX-512).
//!
//! Every operation is the same instruction on every lane, with the SSE/AVX rules: `min(a, b)`
//! and `max(a, b)` return `b` when the lanes compare equal (`+0` against `-0`) or either is NaN,
//! comparisons are ordered (false on NaN), no FMA. So one slab routine over `V: Lanes` gives
//! every lane the same bits whichever width runs it (see [`super::slab`]).

use glam::Vec4;
use std::ops::{Mul, Sub};

/// The most lanes a [`Lanes`] register has: the length of the arrays it loads from and stores to.
pub const MAX_LANES: usize = 16;

/// A register of [`Lanes::WIDTH`] `f32` lanes.
pub trait Lanes: Copy + Sub<Output = Self> + Mul<Output = Self> {
    /// Number of lanes.
    const WIDTH: usize;
    /// `x` in every lane.
    fn splat(x: f32) -> Self;
    /// Lanes `0..WIDTH` of `x`.
    fn load(x: &[f32; MAX_LANES]) -> Self;
    /// The lanes, in `0..WIDTH` of the array (the rest are 0).
    fn to_lanes(self) -> [f32; MAX_LANES];
    /// Per lane `min(self, o)`, SSE rule (see the module doc).
    fn min(self, o: Self) -> Self;
    /// Per lane `max(self, o)`, SSE rule.
    fn max(self, o: Self) -> Self;
    /// `fill` in the NaN lanes, the lane itself elsewhere (bit for bit).
    fn nan_to(self, fill: f32) -> Self;
    /// Bit `i` set where lane `i` of `self <= o` (ordered).
    fn le(self, o: Self) -> u32;
    /// Bit `i` set where lane `i` of `self < o` (ordered).
    fn lt(self, o: Self) -> u32;
}

impl Lanes for Vec4 {
    const WIDTH: usize = 4;

    #[inline(always)]
    fn splat(x: f32) -> Self {
        Vec4::splat(x)
    }

    #[inline(always)]
    fn load(x: &[f32; MAX_LANES]) -> Self {
        Vec4::new(x[0], x[1], x[2], x[3])
    }

    #[inline(always)]
    fn to_lanes(self) -> [f32; MAX_LANES] {
        let mut out = [0.0; MAX_LANES];
        self.write_to_slice(&mut out[..4]);
        out
    }

    #[inline(always)]
    fn min(self, o: Self) -> Self {
        Vec4::min(self, o)
    }

    #[inline(always)]
    fn max(self, o: Self) -> Self {
        Vec4::max(self, o)
    }

    #[inline(always)]
    fn nan_to(self, fill: f32) -> Self {
        Vec4::select(self.cmpeq(self), self, Vec4::splat(fill))
    }

    #[inline(always)]
    fn le(self, o: Self) -> u32 {
        self.cmple(o).bitmask()
    }

    #[inline(always)]
    fn lt(self, o: Self) -> u32 {
        self.cmplt(o).bitmask()
    }
}

pub use eight::F8;

/// Eight lanes in one AVX register.
#[cfg(all(target_arch = "x86_64", target_feature = "avx"))]
mod eight {
    use super::{Lanes, MAX_LANES};
    use glam::Vec4;
    use std::arch::x86_64::*;
    use std::ops::{Mul, Sub};

    /// Eight `f32` lanes (AVX).
    #[derive(Debug, Clone, Copy)]
    pub struct F8(__m256);

    impl F8 {
        /// Lanes `0..4` from `v[0]`, `4..8` from `v[1]`.
        #[inline(always)]
        pub fn from_halves(v: &[Vec4; 2]) -> F8 {
            // SAFETY: `[Vec4; 2]` is 8 contiguous f32; AVX is enabled at compile time.
            F8(unsafe { _mm256_loadu_ps(v.as_ptr().cast::<f32>()) })
        }

        /// The eight lanes.
        #[inline(always)]
        pub fn to_array(self) -> [f32; 8] {
            let mut out = [0.0; 8];
            // SAFETY: `out` is 8 contiguous f32; AVX is enabled at compile time.
            unsafe { _mm256_storeu_ps(out.as_mut_ptr(), self.0) };
            out
        }
    }

    // SAFETY (every `unsafe` below): AVX is enabled at compile time (this module's cfg), and
    // the loads and stores go through arrays of at least eight f32.
    impl Sub for F8 {
        type Output = F8;
        #[inline(always)]
        fn sub(self, o: F8) -> F8 {
            F8(unsafe { _mm256_sub_ps(self.0, o.0) })
        }
    }

    impl Mul for F8 {
        type Output = F8;
        #[inline(always)]
        fn mul(self, o: F8) -> F8 {
            F8(unsafe { _mm256_mul_ps(self.0, o.0) })
        }
    }

    impl Lanes for F8 {
        const WIDTH: usize = 8;

        #[inline(always)]
        fn splat(x: f32) -> Self {
            F8(unsafe { _mm256_set1_ps(x) })
        }

        #[inline(always)]
        fn load(x: &[f32; MAX_LANES]) -> Self {
            F8(unsafe { _mm256_loadu_ps(x.as_ptr()) })
        }

        #[inline(always)]
        fn to_lanes(self) -> [f32; MAX_LANES] {
            let mut out = [0.0; MAX_LANES];
            unsafe { _mm256_storeu_ps(out.as_mut_ptr(), self.0) };
            out
        }

        #[inline(always)]
        fn min(self, o: Self) -> Self {
            F8(unsafe { _mm256_min_ps(self.0, o.0) })
        }

        #[inline(always)]
        fn max(self, o: Self) -> Self {
            F8(unsafe { _mm256_max_ps(self.0, o.0) })
        }

        #[inline(always)]
        fn nan_to(self, fill: f32) -> Self {
            unsafe {
                let ok = _mm256_cmp_ps::<_CMP_EQ_OQ>(self.0, self.0);
                F8(_mm256_blendv_ps(_mm256_set1_ps(fill), self.0, ok))
            }
        }

        #[inline(always)]
        fn le(self, o: Self) -> u32 {
            unsafe { _mm256_movemask_ps(_mm256_cmp_ps::<_CMP_LE_OS>(self.0, o.0)) as u32 }
        }

        #[inline(always)]
        fn lt(self, o: Self) -> u32 {
            unsafe { _mm256_movemask_ps(_mm256_cmp_ps::<_CMP_LT_OS>(self.0, o.0)) as u32 }
        }
    }
}

/// Eight lanes as two [`Vec4`] (targets without AVX): each half is [`Vec4`]'s operation.
#[cfg(not(all(target_arch = "x86_64", target_feature = "avx")))]
mod eight {
    use super::{Lanes, MAX_LANES};
    use glam::Vec4;
    use std::ops::{Mul, Sub};

    /// Eight `f32` lanes (two four-lane halves).
    #[derive(Debug, Clone, Copy)]
    pub struct F8([Vec4; 2]);

    impl F8 {
        /// Lanes `0..4` from `v[0]`, `4..8` from `v[1]`.
        #[inline(always)]
        pub fn from_halves(v: &[Vec4; 2]) -> F8 {
            F8(*v)
        }

        /// The eight lanes.
        #[inline(always)]
        pub fn to_array(self) -> [f32; 8] {
            let [a, b, c, d] = self.0[0].to_array();
            let [e, f, g, h] = self.0[1].to_array();
            [a, b, c, d, e, f, g, h]
        }

        #[inline(always)]
        fn map2(self, o: F8, f: impl Fn(Vec4, Vec4) -> Vec4) -> F8 {
            F8([f(self.0[0], o.0[0]), f(self.0[1], o.0[1])])
        }

        #[inline(always)]
        fn mask2(self, o: F8, f: impl Fn(Vec4, Vec4) -> u32) -> u32 {
            f(self.0[0], o.0[0]) | f(self.0[1], o.0[1]) << 4
        }
    }

    impl Sub for F8 {
        type Output = F8;
        #[inline(always)]
        fn sub(self, o: F8) -> F8 {
            self.map2(o, |a, b| a - b)
        }
    }

    impl Mul for F8 {
        type Output = F8;
        #[inline(always)]
        fn mul(self, o: F8) -> F8 {
            self.map2(o, |a, b| a * b)
        }
    }

    impl Lanes for F8 {
        const WIDTH: usize = 8;

        #[inline(always)]
        fn splat(x: f32) -> Self {
            F8([Vec4::splat(x); 2])
        }

        #[inline(always)]
        fn load(x: &[f32; MAX_LANES]) -> Self {
            F8([Vec4::from_slice(&x[..4]), Vec4::from_slice(&x[4..8])])
        }

        #[inline(always)]
        fn to_lanes(self) -> [f32; MAX_LANES] {
            let mut out = [0.0; MAX_LANES];
            self.0[0].write_to_slice(&mut out[..4]);
            self.0[1].write_to_slice(&mut out[4..8]);
            out
        }

        #[inline(always)]
        fn min(self, o: Self) -> Self {
            self.map2(o, Vec4::min)
        }

        #[inline(always)]
        fn max(self, o: Self) -> Self {
            self.map2(o, Vec4::max)
        }

        #[inline(always)]
        fn nan_to(self, fill: f32) -> Self {
            F8(self.0.map(|h| Lanes::nan_to(h, fill)))
        }

        #[inline(always)]
        fn le(self, o: Self) -> u32 {
            self.mask2(o, Lanes::le)
        }

        #[inline(always)]
        fn lt(self, o: Self) -> u32 {
            self.mask2(o, Lanes::lt)
        }
    }
}
