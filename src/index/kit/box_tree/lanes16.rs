//! Sixteen `f32` lanes ([`F16`]): one AVX-512 register where the target has `avx512f`
//! (`.cargo/config.toml` builds for the native CPU), two [`F8`](super::lanes::F8) elsewhere.
//!
//! The AVX-512 operations follow the same rules as the SSE and AVX ones of [`super::lanes`]:
//! `vminps`/`vmaxps` return the second operand when the lanes compare equal or either is NaN,
//! the comparisons are ordered (false on NaN) and nothing is fused, so every lane of an [`F16`]
//! computes the bits its lane of a [`Vec4`](glam::Vec4) or an `F8` computes.

pub use sixteen::F16;

/// Sixteen lanes in one AVX-512 register.
#[cfg(all(target_arch = "x86_64", target_feature = "avx512f"))]
mod sixteen {
    use super::super::lanes::{Lanes, MAX_LANES};
    use std::arch::x86_64::*;
    use std::ops::{Mul, Sub};

    /// Sixteen `f32` lanes (AVX-512).
    #[derive(Debug, Clone, Copy)]
    pub struct F16(__m512);

    // SAFETY (every `unsafe` below): AVX-512F is enabled at compile time (this module's cfg),
    // and the loads and stores go through arrays of exactly sixteen f32.
    impl Sub for F16 {
        type Output = F16;
        #[inline(always)]
        fn sub(self, o: F16) -> F16 {
            F16(unsafe { _mm512_sub_ps(self.0, o.0) })
        }
    }

    impl Mul for F16 {
        type Output = F16;
        #[inline(always)]
        fn mul(self, o: F16) -> F16 {
            F16(unsafe { _mm512_mul_ps(self.0, o.0) })
        }
    }

    impl Lanes for F16 {
        const WIDTH: usize = 16;

        #[inline(always)]
        fn splat(x: f32) -> Self {
            F16(unsafe { _mm512_set1_ps(x) })
        }

        #[inline(always)]
        fn load(x: &[f32; MAX_LANES]) -> Self {
            F16(unsafe { _mm512_loadu_ps(x.as_ptr()) })
        }

        #[inline(always)]
        fn to_lanes(self) -> [f32; MAX_LANES] {
            let mut out = [0.0; MAX_LANES];
            unsafe { _mm512_storeu_ps(out.as_mut_ptr(), self.0) };
            out
        }

        #[inline(always)]
        fn min(self, o: Self) -> Self {
            F16(unsafe { _mm512_min_ps(self.0, o.0) })
        }

        #[inline(always)]
        fn max(self, o: Self) -> Self {
            F16(unsafe { _mm512_max_ps(self.0, o.0) })
        }

        #[inline(always)]
        fn nan_to(self, fill: f32) -> Self {
            unsafe {
                let ok = _mm512_cmp_ps_mask::<_CMP_EQ_OQ>(self.0, self.0);
                // Lanes of `ok` take `self`, the others `fill`.
                F16(_mm512_mask_blend_ps(ok, _mm512_set1_ps(fill), self.0))
            }
        }

        #[inline(always)]
        fn le(self, o: Self) -> u32 {
            u32::from(unsafe { _mm512_cmp_ps_mask::<_CMP_LE_OS>(self.0, o.0) })
        }

        #[inline(always)]
        fn lt(self, o: Self) -> u32 {
            u32::from(unsafe { _mm512_cmp_ps_mask::<_CMP_LT_OS>(self.0, o.0) })
        }
    }
}

/// Sixteen lanes as two [`F8`] (targets without AVX-512): each half is `F8`'s operation.
#[cfg(not(all(target_arch = "x86_64", target_feature = "avx512f")))]
mod sixteen {
    use super::super::lanes::{F8, Lanes, MAX_LANES};
    use std::ops::{Mul, Sub};

    /// Sixteen `f32` lanes (two eight-lane halves).
    #[derive(Debug, Clone, Copy)]
    pub struct F16([F8; 2]);

    impl F16 {
        #[inline(always)]
        fn map2(self, o: F16, f: impl Fn(F8, F8) -> F8) -> F16 {
            F16([f(self.0[0], o.0[0]), f(self.0[1], o.0[1])])
        }

        #[inline(always)]
        fn mask2(self, o: F16, f: impl Fn(F8, F8) -> u32) -> u32 {
            f(self.0[0], o.0[0]) | f(self.0[1], o.0[1]) << 8
        }
    }

    impl Sub for F16 {
        type Output = F16;
        #[inline(always)]
        fn sub(self, o: F16) -> F16 {
            self.map2(o, |a, b| a - b)
        }
    }

    impl Mul for F16 {
        type Output = F16;
        #[inline(always)]
        fn mul(self, o: F16) -> F16 {
            self.map2(o, |a, b| a * b)
        }
    }

    impl Lanes for F16 {
        const WIDTH: usize = 16;

        #[inline(always)]
        fn splat(x: f32) -> Self {
            F16([F8::splat(x); 2])
        }

        #[inline(always)]
        fn load(x: &[f32; MAX_LANES]) -> Self {
            let mut high = [0.0; MAX_LANES];
            high[..8].copy_from_slice(&x[8..]);
            F16([F8::load(x), F8::load(&high)])
        }

        #[inline(always)]
        fn to_lanes(self) -> [f32; MAX_LANES] {
            let mut out = self.0[0].to_lanes();
            out[8..].copy_from_slice(&self.0[1].to_lanes()[..8]);
            out
        }

        #[inline(always)]
        fn min(self, o: Self) -> Self {
            self.map2(o, Lanes::min)
        }

        #[inline(always)]
        fn max(self, o: Self) -> Self {
            self.map2(o, Lanes::max)
        }

        #[inline(always)]
        fn nan_to(self, fill: f32) -> Self {
            F16(self.0.map(|h| h.nan_to(fill)))
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
