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

/// The cross product `a x b`, each component `a_i b_j - a_j b_i` rounded as two products and a
/// difference, never fused, so it is the same on every build target.
///
/// glam's `Vec3A::cross` becomes a fused multiply-subtract when the build enables FMA
/// (`target-cpu=native`). That would make a kernel's bits depend on the machine that compiled
/// it, and give `e x e` a rounding residue instead of zero: a zero-area triangle (two equal
/// corners) would get a tiny normal in a random direction and the plane-edges kernel could
/// report a hit far off the triangle, outside every cell and box that holds it.
#[inline(always)]
pub fn cross(a: glam::Vec3A, b: glam::Vec3A) -> glam::Vec3A {
    use glam::Vec3Swizzles;
    (a.zxy() * b - a * b.zxy()).zxy()
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
    fn cross_is_glams_formula_unfused() {
        use glam::Vec3A;
        let (a, b) = (Vec3A::new(1.0, 2.0, 3.0), Vec3A::new(-4.0, 0.5, 2.0));
        assert_eq!(
            cross(a, b),
            Vec3A::new(
                2.0 * 2.0 - 3.0 * 0.5,
                3.0 * -4.0 - 1.0 * 2.0,
                1.0 * 0.5 - 2.0 * -4.0
            )
        );
        // A residue-free `e x e` whatever the build target: the corners of a zero-area triangle
        // from the property test whose fused cross product was (-6e-8, -6e-8, 0).
        let e = Vec3A::new(-0.75, 0.25, -1.823173) - Vec3A::new(0.0, 1.0, 0.65341115);
        assert_eq!(cross(e, e), Vec3A::ZERO);
        let x = Vec3A::new(0.1, 0.7, 0.3);
        let y = x * 3.0;
        for (c, r) in cross(x, y).to_array().into_iter().zip([
            0.7 * y.z - 0.3 * y.y,
            0.3 * y.x - 0.1 * y.z,
            0.1 * y.y - 0.7 * y.x,
        ]) {
            assert_eq!(c.to_bits(), r.to_bits());
        }
    }

    #[test]
    fn gamma_is_small_and_increasing() {
        assert!(gamma(1) > 0.0 && gamma(1) < 1e-7);
        assert!(gamma(3) > gamma(2));
        assert!((gamma(3) - 3.0 * MACHINE_EPSILON).abs() < 1e-12);
    }
}
