//! Floating-point error helpers (pbrt's `gamma(n)` bound on `n` roundings).

/// Unit roundoff of `f32` (half an ulp of 1.0).
pub const MACHINE_EPSILON: f32 = f32::EPSILON * 0.5;

/// `gamma(n) = n*u / (1 - n*u)`: bounds the relative error of `n` successive `f32` roundings
/// (Higham; pbrt-v3 section 3.9).
#[inline]
pub const fn gamma(n: i32) -> f32 {
    let nu = n as f32 * MACHINE_EPSILON;
    nu / (1.0 - nu)
}

/// `true` when every component is finite (not NaN, not infinite).
#[inline]
pub fn all_finite(v: glam::Vec3A) -> bool {
    v.is_finite()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn gamma_is_small_and_increasing() {
        assert!(gamma(1) > 0.0 && gamma(1) < 1e-7);
        assert!(gamma(3) > gamma(2));
        assert!((gamma(3) - 3.0 * MACHINE_EPSILON).abs() < 1e-12);
    }
}
