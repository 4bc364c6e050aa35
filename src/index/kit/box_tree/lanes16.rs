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
    use super::super::lanes::{Lanes, MAX_LANES, x86_lanes};
    use std::arch::x86_64::*;

    // SAFETY (every `unsafe` the macro writes): AVX-512F is enabled at compile time (this
    // module's cfg), and the loads and stores go through arrays of exactly sixteen f32.
    x86_lanes! {
        /// Sixteen `f32` lanes (AVX-512).
        F16(__m512), 16 lanes,
        sub _mm512_sub_ps, mul _mm512_mul_ps, splat _mm512_set1_ps, load _mm512_loadu_ps,
        store _mm512_storeu_ps, min _mm512_min_ps, max _mm512_max_ps,
        nan_to |v, fill| {
            let ok = _mm512_cmp_ps_mask::<_CMP_EQ_OQ>(v, v);
            // Lanes of `ok` take `v`, the others `fill`.
            _mm512_mask_blend_ps(ok, _mm512_set1_ps(fill), v)
        },
        le |a, b| u32::from(_mm512_cmp_ps_mask::<_CMP_LE_OS>(a, b)),
        lt |a, b| u32::from(_mm512_cmp_ps_mask::<_CMP_LT_OS>(a, b)),
    }
}

/// Sixteen lanes as two [`F8`](super::super::lanes::F8) (targets without AVX-512).
#[cfg(not(all(target_arch = "x86_64", target_feature = "avx512f")))]
mod sixteen {
    use super::super::lanes::{F8, Halves};

    /// Sixteen `f32` lanes (two eight-lane halves).
    pub type F16 = Halves<F8>;
}
