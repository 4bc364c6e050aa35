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

/// `struct $name($reg)`, one x86 register of `$width` `f32` lanes, with `Sub`, `Mul` and
/// [`Lanes`] from the intrinsics named (`$sub`, `$mul`, `$splat`, `$load`, `$store`, `$min`,
/// `$max`; `nan_to`, `le` and `lt` as expressions over the raw registers). The AVX [`F8`] and the
/// AVX-512 [`F16`](super::lanes16::F16) are this one code over their own instructions.
///
/// Used only inside a module whose `cfg` enables the instructions named: that is what makes
/// every `unsafe` block it writes sound (the loads and stores go through arrays of
/// [`MAX_LANES`] `f32`, at least `$width`).
#[cfg(all(target_arch = "x86_64", target_feature = "avx"))]
macro_rules! x86_lanes {
    (
        $(#[$doc:meta])*
        $name:ident($reg:ty), $width:literal lanes,
        sub $sub:ident, mul $mul:ident, splat $splat:ident, load $load:ident, store $store:ident,
        min $min:ident, max $max:ident,
        nan_to |$v:ident, $fill:ident| $nan_to:expr,
        le |$la:ident, $lb:ident| $le:expr,
        lt |$ta:ident, $tb:ident| $lt:expr $(,)?
    ) => {
        $(#[$doc])*
        #[derive(Debug, Clone, Copy)]
        pub struct $name($reg);

        impl std::ops::Sub for $name {
            type Output = $name;
            #[inline(always)]
            fn sub(self, o: $name) -> $name {
                $name(unsafe { $sub(self.0, o.0) })
            }
        }

        impl std::ops::Mul for $name {
            type Output = $name;
            #[inline(always)]
            fn mul(self, o: $name) -> $name {
                $name(unsafe { $mul(self.0, o.0) })
            }
        }

        impl Lanes for $name {
            const WIDTH: usize = $width;

            #[inline(always)]
            fn splat(x: f32) -> Self {
                $name(unsafe { $splat(x) })
            }

            #[inline(always)]
            fn load(x: &[f32; MAX_LANES]) -> Self {
                $name(unsafe { $load(x.as_ptr()) })
            }

            #[inline(always)]
            fn to_lanes(self) -> [f32; MAX_LANES] {
                let mut out = [0.0; MAX_LANES];
                unsafe { $store(out.as_mut_ptr(), self.0) };
                out
            }

            #[inline(always)]
            fn min(self, o: Self) -> Self {
                $name(unsafe { $min(self.0, o.0) })
            }

            #[inline(always)]
            fn max(self, o: Self) -> Self {
                $name(unsafe { $max(self.0, o.0) })
            }

            #[inline(always)]
            fn nan_to(self, $fill: f32) -> Self {
                let $v = self.0;
                $name(unsafe { $nan_to })
            }

            #[inline(always)]
            fn le(self, o: Self) -> u32 {
                let ($la, $lb) = (self.0, o.0);
                unsafe { $le }
            }

            #[inline(always)]
            fn lt(self, o: Self) -> u32 {
                let ($ta, $tb) = (self.0, o.0);
                unsafe { $lt }
            }
        }
    };
}
#[cfg(all(target_arch = "x86_64", target_feature = "avx"))]
pub(super) use x86_lanes;

/// [`Halves`]: two registers as one of twice the lanes (targets without AVX-512).
#[cfg(not(all(target_arch = "x86_64", target_feature = "avx512f")))]
mod halves {
    use super::{Lanes, MAX_LANES};
    use std::ops::{Mul, Sub};

    /// Twice `H`'s lanes as two `H` registers, lanes `0..H::WIDTH` in the first:
    /// [`F8`](super::F8) as two [`Vec4`](glam::Vec4) without AVX,
    /// [`F16`](super::super::lanes16::F16) as two `F8` without AVX-512. Every operation is
    /// `H`'s on each half, so every lane has the bits `H` gives it.
    #[derive(Debug, Clone, Copy)]
    pub struct Halves<H>(pub(super) [H; 2]);

    impl<H: Lanes> Halves<H> {
        #[inline(always)]
        fn map2(self, o: Self, f: impl Fn(H, H) -> H) -> Self {
            Halves([f(self.0[0], o.0[0]), f(self.0[1], o.0[1])])
        }

        #[inline(always)]
        fn mask2(self, o: Self, f: impl Fn(H, H) -> u32) -> u32 {
            f(self.0[0], o.0[0]) | f(self.0[1], o.0[1]) << H::WIDTH
        }
    }

    impl<H: Lanes> Sub for Halves<H> {
        type Output = Self;
        #[inline(always)]
        fn sub(self, o: Self) -> Self {
            self.map2(o, |a, b| a - b)
        }
    }

    impl<H: Lanes> Mul for Halves<H> {
        type Output = Self;
        #[inline(always)]
        fn mul(self, o: Self) -> Self {
            self.map2(o, |a, b| a * b)
        }
    }

    impl<H: Lanes> Lanes for Halves<H> {
        const WIDTH: usize = 2 * H::WIDTH;

        #[inline(always)]
        fn splat(x: f32) -> Self {
            Halves([H::splat(x); 2])
        }

        #[inline(always)]
        fn load(x: &[f32; MAX_LANES]) -> Self {
            let mut high = [0.0; MAX_LANES];
            high[..H::WIDTH].copy_from_slice(&x[H::WIDTH..Self::WIDTH]);
            Halves([H::load(x), H::load(&high)])
        }

        #[inline(always)]
        fn to_lanes(self) -> [f32; MAX_LANES] {
            let mut out = self.0[0].to_lanes();
            out[H::WIDTH..Self::WIDTH].copy_from_slice(&self.0[1].to_lanes()[..H::WIDTH]);
            out
        }

        #[inline(always)]
        fn min(self, o: Self) -> Self {
            self.map2(o, H::min)
        }

        #[inline(always)]
        fn max(self, o: Self) -> Self {
            self.map2(o, H::max)
        }

        #[inline(always)]
        fn nan_to(self, fill: f32) -> Self {
            Halves(self.0.map(|h| h.nan_to(fill)))
        }

        #[inline(always)]
        fn le(self, o: Self) -> u32 {
            self.mask2(o, H::le)
        }

        #[inline(always)]
        fn lt(self, o: Self) -> u32 {
            self.mask2(o, H::lt)
        }
    }
}
#[cfg(not(all(target_arch = "x86_64", target_feature = "avx512f")))]
pub use halves::Halves;

pub use eight::F8;

/// Eight lanes in one AVX register.
#[cfg(all(target_arch = "x86_64", target_feature = "avx"))]
mod eight {
    use super::{Lanes, MAX_LANES};
    use glam::Vec4;
    use std::arch::x86_64::*;

    // SAFETY (every `unsafe` the macro writes): AVX is enabled at compile time (this module's
    // cfg).
    super::x86_lanes! {
        /// Eight `f32` lanes (AVX).
        F8(__m256), 8 lanes,
        sub _mm256_sub_ps, mul _mm256_mul_ps, splat _mm256_set1_ps, load _mm256_loadu_ps,
        store _mm256_storeu_ps, min _mm256_min_ps, max _mm256_max_ps,
        nan_to |v, fill| {
            let ok = _mm256_cmp_ps::<_CMP_EQ_OQ>(v, v);
            _mm256_blendv_ps(_mm256_set1_ps(fill), v, ok)
        },
        le |a, b| _mm256_movemask_ps(_mm256_cmp_ps::<_CMP_LE_OS>(a, b)) as u32,
        lt |a, b| _mm256_movemask_ps(_mm256_cmp_ps::<_CMP_LT_OS>(a, b)) as u32,
    }

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
}

/// Eight lanes as two [`Vec4`] (targets without AVX).
#[cfg(not(all(target_arch = "x86_64", target_feature = "avx")))]
mod eight {
    use super::Halves;
    use glam::Vec4;

    /// Eight `f32` lanes (two four-lane halves).
    pub type F8 = Halves<Vec4>;

    impl F8 {
        /// Lanes `0..4` from `v[0]`, `4..8` from `v[1]`.
        #[inline(always)]
        pub fn from_halves(v: &[Vec4; 2]) -> F8 {
            Halves(*v)
        }

        /// The eight lanes.
        #[inline(always)]
        pub fn to_array(self) -> [f32; 8] {
            let [a, b, c, d] = self.0[0].to_array();
            let [e, f, g, h] = self.0[1].to_array();
            [a, b, c, d, e, f, g, h]
        }
    }
}
