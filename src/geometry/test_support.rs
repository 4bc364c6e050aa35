//! Helpers of the geometry unit tests: rays from array literals, a tolerance check on hits and
//! a small deterministic generator.

use super::{Aabb, Ray};
use glam::{Vec3, Vec3A};

/// The ray from `o` along `d` over `[0, +inf]` (panics on an invalid ray: test data).
pub fn ray(o: [f32; 3], d: [f32; 3]) -> Ray {
    Ray::infinite(Vec3::from(o), Vec3::from(d)).unwrap()
}

/// The box `[0, 1]^3`.
pub fn unit_box() -> Aabb {
    Aabb::new(Vec3A::ZERO, Vec3A::ONE)
}

/// A ray and the answer a kernel must give: `(origin, direction, t_max, expected t)`.
pub type RayCase = ([f32; 3], [f32; 3], f32, Option<f32>);

/// `true` when `t` is a hit within `1e-5` of `expected`.
pub fn close(t: Option<f32>, expected: f32) -> bool {
    t.is_some_and(|t| (t - expected).abs() < 1e-5)
}

/// Asserts that `b` spans `min` to `max` within `1e-5` per coordinate.
pub fn assert_bounds_near(b: Aabb, min: [f32; 3], max: [f32; 3]) {
    let off = (b.min - Vec3A::from(min))
        .abs()
        .max((b.max - Vec3A::from(max)).abs());
    assert!(
        off.max_element() < 1e-5,
        "{b:?}, expected {min:?} to {max:?}"
    );
}

/// A deterministic stream of `f32` in `[0, 1)`: the top 24 bits of a 64-bit linear
/// congruential generator (Knuth's MMIX constants) started at `seed`.
pub fn unit_floats(seed: u64) -> impl FnMut() -> f32 {
    let mut s = seed;
    move || {
        s = s
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((s >> 40) as f32) / (1u64 << 24) as f32
    }
}
