//! Seeded random scenes: a sphere field, a triangle soup and long thin slivers.

use crate::geometry::{Sphere, Triangle};
use crate::rays::SplitMix64;
use glam::Vec3A;

pub(super) fn point(rng: &mut SplitMix64) -> Vec3A {
    Vec3A::new(
        rng.next_unit() as f32,
        rng.next_unit() as f32,
        rng.next_unit() as f32,
    )
}

pub(super) fn unit_vector(rng: &mut SplitMix64) -> Vec3A {
    let w = 1.0 - 2.0 * rng.next_unit();
    let phi = std::f64::consts::TAU * rng.next_unit();
    let s = (1.0 - w * w).max(0.0).sqrt();
    Vec3A::new((s * phi.cos()) as f32, (s * phi.sin()) as f32, w as f32)
}

/// `n` spheres with centres uniform in the unit cube and radii in `[0.5, 1] * 0.6 / cbrt(n)`
/// (about 10% of the volume filled, some overlapping).
pub fn sphere_field(n: usize, seed: u64) -> Vec<Sphere> {
    let r0 = per_object(0.6, n);
    seeded(n, seed, |rng| {
        let c = point(rng);
        Sphere::new(c, r0 * (0.5 + 0.5 * rng.next_unit() as f32))
    })
}

/// `size / cbrt(n)`: a size that shrinks with the spacing of `n` objects in the unit cube.
pub(super) fn per_object(size: f32, n: usize) -> f32 {
    size / (n.max(1) as f32).cbrt()
}

/// `n` objects made one after another by `make` from one stream seeded with `seed`.
fn seeded<T>(n: usize, seed: u64, mut make: impl FnMut(&mut SplitMix64) -> T) -> Vec<T> {
    let mut rng = SplitMix64::new(seed);
    (0..n).map(|_| make(&mut rng)).collect()
}

/// `n` random triangles in the unit cube, each a random corner plus two random offsets of
/// length up to `1.5 / cbrt(n)`.
pub fn triangle_soup(n: usize, seed: u64) -> Vec<Triangle> {
    let size = per_object(1.5, n);
    seeded(n, seed, |rng| {
        let a = point(rng);
        let b = a + (point(rng) - 0.5) * size;
        let c = a + (point(rng) - 0.5) * size;
        Triangle::new(a, b, c)
    })
}

/// `n` long thin triangles ("slivers"): length about `0.5`, width `1e-4` of that, random
/// position and orientation in the unit cube. Their bounding boxes are huge for their area, the
/// classic bad case for box-based structures.
pub fn slivers(n: usize, seed: u64) -> Vec<Triangle> {
    seeded(n, seed, |rng| {
        let a = point(rng);
        let dir = unit_vector(rng) * 0.5;
        let side = dir.cross(unit_vector(rng)).normalize_or_zero() * 0.5e-4;
        Triangle::new(a, a + dir, a + dir * 0.5 + side)
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn seeded_and_sized() {
        assert_eq!(sphere_field(100, 1), sphere_field(100, 1));
        assert_ne!(sphere_field(100, 1), sphere_field(100, 2));
        assert_eq!(triangle_soup(1000, 3).len(), 1000);
        let s = slivers(50, 4);
        assert!(s.iter().all(|t| t.area() > 0.0 && t.area() < 1e-4));
    }
}
