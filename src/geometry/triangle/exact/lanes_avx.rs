//! The exact kernel's lane form on one 256-bit register per quantity (AVX): the four lanes of
//! [`super::lanes::portable`] as four `f64` lanes of `__m256d`, instruction for instruction the
//! same operations in the same order (`sub`, `mul`, `add`, `div`, no fused multiply-add; the
//! rounding to `f32` by `vcvtpd2ps`, round to nearest like `as f32`), and the per-lane decision
//! (filter, signs, finite `t`, interval) as masks instead of branches, with one branch: a block
//! whose every lane is a certified miss returns before `t` is computed. A decided lane's `t` is
//! therefore the portable form's, and so the scalar kernel's, bit for bit; `tests` checks the
//! two forms against each other.
//!
//! NaN: the comparisons are ordered (false on NaN), as Rust's `>`, `<`, `>=`, `<=`, so a NaN
//! edge function fails the filter and its lane goes to the scalar kernel, as in the portable
//! form. `m` (the largest corner coordinate) is a `max` over absolute values: for finite inputs
//! its order does not matter; a NaN coordinate makes two of the three edge functions NaN, so
//! its lane is undecided whatever `m` is.

use super::filter::FILTER;
use crate::geometry::Ray;
use crate::geometry::triangle::lanes::{LaneHits, TriangleLanes};
use std::arch::x86_64::*;

/// `corner - origin` per axis, four lanes in `f64` (as `d64(v) - o`).
#[inline(always)]
unsafe fn rel(t: &TriangleLanes, corner: usize, o: [__m256d; 3]) -> [__m256d; 3] {
    // SAFETY (all functions of this module): AVX is enabled at compile time (the module is
    // compiled only then); the loads read `[f32; 4]` arrays in place.
    unsafe {
        [0, 1, 2].map(|k| {
            let v = _mm256_cvtps_pd(_mm_loadu_ps(t.v[corner][k].as_ptr()));
            _mm256_sub_pd(v, o[k])
        })
    }
}

/// `d x p` per lane, `glam`'s `DVec3::cross` term for term.
#[inline(always)]
unsafe fn cross(d: [__m256d; 3], p: &[__m256d; 3]) -> [__m256d; 3] {
    unsafe {
        let term = |a: usize, b: usize| {
            _mm256_sub_pd(_mm256_mul_pd(d[a], p[b]), _mm256_mul_pd(p[a], d[b]))
        };
        [term(1, 2), term(2, 0), term(0, 1)]
    }
}

/// `p . q` per lane, `glam`'s `DVec3::dot` term for term: `(p0 q0 + p1 q1) + p2 q2`.
#[inline(always)]
unsafe fn dot(p: &[__m256d; 3], q: &[__m256d; 3]) -> __m256d {
    unsafe {
        let xy = _mm256_add_pd(_mm256_mul_pd(p[0], q[0]), _mm256_mul_pd(p[1], q[1]));
        _mm256_add_pd(xy, _mm256_mul_pd(p[2], q[2]))
    }
}

#[inline(always)]
unsafe fn abs(x: __m256d) -> __m256d {
    unsafe { _mm256_andnot_pd(_mm256_set1_pd(-0.0), x) }
}

/// The lane form (see [`super::lanes`] and the module doc).
#[inline(always)]
pub fn intersect_lanes(tris: &TriangleLanes, ray: &Ray) -> LaneHits {
    let o64 = [0, 1, 2].map(|k| ray.origin[k] as f64);
    let d64 = [0, 1, 2].map(|k| ray.dir[k] as f64);
    let d_sum = d64[0].abs() + d64[1].abs() + d64[2].abs();
    let k = ray.shear.kz;
    // SAFETY: AVX is enabled at compile time (the module is compiled only then).
    unsafe {
        let o = o64.map(|x| _mm256_set1_pd(x));
        let d = d64.map(|x| _mm256_set1_pd(x));
        let (a, b, c) = (rel(tris, 0, o), rel(tris, 1, o), rel(tris, 2, o));
        let (da, db, dc) = (cross(d, &a), cross(d, &b), cross(d, &c));
        let u = dot(&db, &c);
        let v = dot(&dc, &a);
        let w = dot(&da, &b);
        let axis = |k: usize| _mm256_max_pd(_mm256_max_pd(abs(a[k]), abs(b[k])), abs(c[k]));
        let m = _mm256_max_pd(axis(0), _mm256_max_pd(axis(1), axis(2)));
        let e = _mm256_mul_pd(_mm256_mul_pd(_mm256_set1_pd(FILTER * d_sum), m), m);
        let gt = |x: __m256d, y: __m256d| _mm256_movemask_pd(_mm256_cmp_pd::<_CMP_GT_OQ>(x, y));
        let zero = _mm256_setzero_pd();
        let certified = gt(abs(u), e) & gt(abs(v), e) & gt(abs(w), e);
        let negative = gt(zero, u) | gt(zero, v) | gt(zero, w);
        let positive = gt(u, zero) | gt(v, zero) | gt(w, zero);
        let same_sign = certified & !(negative & positive);
        // Every lane a certified miss (the common block): no `t` to compute.
        if (same_sign | !certified) & 0b1111 == 0 {
            return LaneHits::MISS;
        }
        let num = _mm256_add_pd(
            _mm256_add_pd(_mm256_mul_pd(u, a[k]), _mm256_mul_pd(v, b[k])),
            _mm256_mul_pd(w, c[k]),
        );
        let den = _mm256_mul_pd(_mm256_add_pd(_mm256_add_pd(u, v), w), d[k]);
        let t = _mm256_cvtpd_ps(_mm256_div_pd(num, den));

        let abs_t = _mm_andnot_ps(_mm_set1_ps(-0.0), t);
        let finite = _mm_movemask_ps(_mm_cmp_ps::<_CMP_LT_OQ>(abs_t, _mm_set1_ps(f32::INFINITY)));
        let in_range = _mm_movemask_ps(_mm_and_ps(
            _mm_cmp_ps::<_CMP_GE_OQ>(t, _mm_set1_ps(ray.t_min)),
            _mm_cmp_ps::<_CMP_LE_OQ>(t, _mm_set1_ps(ray.t_max)),
        ));
        let hit = (same_sign & finite & in_range) as u32;
        let mut out = LaneHits {
            hit,
            scalar: ((!certified | (same_sign & !finite)) & 0b1111) as u32,
            t: [0.0; 4],
        };
        _mm_storeu_ps(
            out.t.as_mut_ptr(),
            _mm_and_ps(t, _mm_castsi128_ps(lane_mask(hit))),
        );
        out
    }
}

/// All bits set in the lanes whose bit is set in `bits` (0..16), zero elsewhere.
#[inline(always)]
unsafe fn lane_mask(bits: u32) -> __m128i {
    unsafe {
        let lanes = _mm_set_epi32(8, 4, 2, 1);
        let set = _mm_and_si128(_mm_set1_epi32(bits as i32), lanes);
        _mm_cmpeq_epi32(set, lanes)
    }
}
