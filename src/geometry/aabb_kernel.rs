//! Ray–box kernel for a box *primitive* (exact slabs, no conservative padding): the entry
//! distance, or the exit distance when the ray starts inside.

use super::{Aabb, Ray};
use glam::Vec3A;

/// The first crossing of the box surface in `[ray.t_min, t_max]`.
#[inline]
pub fn intersect_box(b: &Aabb, ray: &Ray, t_max: f32) -> Option<f32> {
    slab_first_hit(b.min, b.max, ray.origin, ray.inv_dir, ray.t_min, t_max)
}

/// The exact slab method on the box `[min, max]` for the ray `origin + t / inv_dir`: the entry
/// distance, or the exit distance when the ray starts inside, if it lies in `[t_min, t_max]`.
/// Shared by [`intersect_box`] and the oriented box (which passes its local-frame ray).
#[inline]
pub(crate) fn slab_first_hit(
    min: Vec3A,
    max: Vec3A,
    origin: Vec3A,
    inv_dir: Vec3A,
    t_min: f32,
    t_max: f32,
) -> Option<f32> {
    let t_lo = (min - origin) * inv_dir;
    let t_hi = (max - origin) * inv_dir;
    // A NaN (origin on a face plane, zero direction on that axis) puts no constraint.
    let near = Vec3A::select(t_lo.cmpeq(t_lo), t_lo, Vec3A::NEG_INFINITY).min(Vec3A::select(
        t_hi.cmpeq(t_hi),
        t_hi,
        Vec3A::NEG_INFINITY,
    ));
    let far = Vec3A::select(t_lo.cmpeq(t_lo), t_lo, Vec3A::INFINITY).max(Vec3A::select(
        t_hi.cmpeq(t_hi),
        t_hi,
        Vec3A::INFINITY,
    ));
    let (enter, exit) = (near.max_element(), far.min_element());
    if enter > exit {
        return None;
    }
    [enter, exit]
        .into_iter()
        .find(|&t| t >= t_min && t <= t_max && t.is_finite())
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    #[test]
    fn hand_computed() {
        let b = Aabb::new(Vec3A::ONE, Vec3A::splat(3.0));
        let r = Ray::infinite(Vec3::new(0.0, 2.0, 2.0), Vec3::X).unwrap();
        assert_eq!(intersect_box(&b, &r, f32::INFINITY), Some(1.0));
        let inside = Ray::infinite(Vec3::splat(2.0), Vec3::new(0.0, 0.0, -0.5)).unwrap();
        assert_eq!(intersect_box(&b, &inside, f32::INFINITY), Some(2.0));
        let miss = Ray::infinite(Vec3::new(0.0, 4.0, 2.0), Vec3::X).unwrap();
        assert_eq!(intersect_box(&b, &miss, f32::INFINITY), None);
        let behind = Ray::infinite(Vec3::new(4.0, 2.0, 2.0), Vec3::X).unwrap();
        assert_eq!(intersect_box(&b, &behind, f32::INFINITY), None);
    }
}
