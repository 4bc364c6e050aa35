//! Axis-aligned bounding boxes and the conservative, NaN-safe slab test.

use super::float::gamma;
use super::ray::Ray;
use glam::Vec3A;

/// An axis-aligned box `[min, max]` (closed). The empty box has `min = +inf`, `max = -inf`, so
/// that growing it by any point gives that point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Aabb {
    pub min: Vec3A,
    pub max: Vec3A,
}

/// Relative growth of the far slab distance that makes the slab test conservative: the near and
/// far distances each carry at most `gamma(3)` relative error (a subtraction, a reciprocal, a
/// product), so scaling the far one by `1 + 2*gamma(3)` never rejects a box the exact ray hits
/// (Ize 2013; pbrt-v3 section 3.9.2).
pub const SLAB_FAR_SCALE: f32 = 1.0 + 2.0 * gamma(3);

impl Default for Aabb {
    fn default() -> Self {
        Aabb::EMPTY
    }
}

impl Aabb {
    pub const EMPTY: Aabb = Aabb {
        min: Vec3A::INFINITY,
        max: Vec3A::NEG_INFINITY,
    };

    pub fn new(min: Vec3A, max: Vec3A) -> Aabb {
        Aabb { min, max }
    }

    pub fn from_points(points: &[Vec3A]) -> Aabb {
        points.iter().fold(Aabb::EMPTY, |b, &p| b.grown(p))
    }

    #[inline]
    pub fn grown(self, p: Vec3A) -> Aabb {
        Aabb {
            min: self.min.min(p),
            max: self.max.max(p),
        }
    }

    #[inline]
    pub fn union(self, o: Aabb) -> Aabb {
        Aabb {
            min: self.min.min(o.min),
            max: self.max.max(o.max),
        }
    }

    /// The overlap of two boxes (empty when they do not overlap).
    pub fn intersection(self, o: Aabb) -> Aabb {
        Aabb {
            min: self.min.max(o.min),
            max: self.max.min(o.max),
        }
    }

    /// `true` for the empty box (any `min > max`).
    #[inline]
    pub fn is_empty(&self) -> bool {
        self.min.cmpgt(self.max).any()
    }

    #[inline]
    pub fn extent(&self) -> Vec3A {
        self.max - self.min
    }

    #[inline]
    pub fn center(&self) -> Vec3A {
        (self.min + self.max) * 0.5
    }

    /// Surface area (0 for the empty box).
    pub fn surface_area(&self) -> f32 {
        if self.is_empty() {
            return 0.0;
        }
        let e = self.extent();
        2.0 * (e.x * e.y + e.y * e.z + e.z * e.x)
    }

    /// `true` when `p` lies in the closed box.
    #[inline]
    pub fn contains(&self, p: Vec3A) -> bool {
        p.cmpge(self.min).all() && p.cmple(self.max).all()
    }

    /// `true` when the closed boxes share at least one point.
    #[inline]
    pub fn overlaps(&self, o: &Aabb) -> bool {
        self.min.cmple(o.max).all() && o.min.cmple(self.max).all()
    }

    /// Index of the longest axis (ties to the lowest).
    pub fn largest_axis(&self) -> usize {
        let e = self.extent();
        if e.x >= e.y && e.x >= e.z {
            0
        } else if e.y >= e.z {
            1
        } else {
            2
        }
    }

    /// The box grown on every side by `rel` times its largest absolute coordinate (plus the
    /// smallest normal `f32`), so tests against it are conservative against rounding.
    pub fn padded(&self, rel: f32) -> Aabb {
        let scale = self.min.abs().max(self.max.abs()).max_element();
        let pad = Vec3A::splat(scale * rel + f32::MIN_POSITIVE);
        Aabb {
            min: self.min - pad,
            max: self.max + pad,
        }
    }

    /// Conservative slab test: the parameter interval `[t_enter, t_exit]` of the ray inside the
    /// box, clipped to `[t_min, t_max]`, or `None` when it is empty.
    ///
    /// Never rejects a box the exact ray meets: the far distances are scaled by
    /// [`SLAB_FAR_SCALE`]. NaN-safe: a zero direction component gives an infinite inverse, and
    /// when the origin lies exactly on that slab's plane (`0 * inf = NaN`) the axis puts no
    /// constraint on `t`, as it should for a closed box. Monotone: for boxes `a` inside `b`,
    /// `b`'s interval contains `a`'s, which is what keeps closest-hit culling exact (see
    /// [`crate::geometry::Hit`]).
    #[inline]
    pub fn ray_interval(&self, ray: &Ray, t_min: f32, t_max: f32) -> Option<(f32, f32)> {
        let t_lo = (self.min - ray.origin) * ray.inv_dir;
        let t_hi = (self.max - ray.origin) * ray.inv_dir;
        // NaN (origin on the slab plane, direction 0 on that axis) means "no constraint".
        let near_lo = Vec3A::select(t_lo.cmpeq(t_lo), t_lo, Vec3A::NEG_INFINITY);
        let near_hi = Vec3A::select(t_hi.cmpeq(t_hi), t_hi, Vec3A::NEG_INFINITY);
        let far_lo = Vec3A::select(t_lo.cmpeq(t_lo), t_lo, Vec3A::INFINITY);
        let far_hi = Vec3A::select(t_hi.cmpeq(t_hi), t_hi, Vec3A::INFINITY);
        let t_near = near_lo.min(near_hi);
        let t_far = far_lo.max(far_hi);
        let far = t_far.min_element();
        // Grow the far distance away from zero on either sign (monotone, keeps infinities).
        let far = far
            * if far >= 0.0 {
                SLAB_FAR_SCALE
            } else {
                2.0 - SLAB_FAR_SCALE
            };
        let enter = t_near.max_element().max(t_min);
        let exit = far.min(t_max);
        if enter <= exit {
            Some((enter, exit))
        } else {
            None
        }
    }

    /// Entry distance of [`Aabb::ray_interval`] (for front-to-back ordering and culling).
    #[inline]
    pub fn ray_entry(&self, ray: &Ray, t_min: f32, t_max: f32) -> Option<f32> {
        self.ray_interval(ray, t_min, t_max).map(|(e, _)| e)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::test_support::{ray, unit_box};

    #[test]
    fn hand_computed_interval() {
        let r = ray([-1.0, 0.5, 0.5], [1.0, 0.0, 0.0]);
        let (e, x) = unit_box().ray_interval(&r, 0.0, f32::INFINITY).unwrap();
        assert_eq!(e, 1.0);
        assert!((2.0..2.0 + 1e-5).contains(&x));
        assert!(unit_box().ray_interval(&r, 0.0, 0.5).is_none());
        let miss = ray([-1.0, 1.5, 0.5], [1.0, 0.0, 0.0]);
        assert!(unit_box().ray_interval(&miss, 0.0, f32::INFINITY).is_none());
    }

    #[test]
    fn ray_in_face_plane_hits_with_either_signed_zero() {
        for z in [0.0f32, 1.0] {
            for dz in [0.0f32, -0.0] {
                for dx in [1.0f32, -1.0] {
                    let o = [if dx > 0.0 { -1.0 } else { 2.0 }, 0.5, z];
                    let r = ray(o, [dx, 0.0, dz]);
                    assert!(
                        unit_box().ray_interval(&r, 0.0, f32::INFINITY).is_some(),
                        "z={z} dz={dz:?} dx={dx}"
                    );
                }
            }
        }
        // Parallel and outside the slab: miss.
        let r = ray([-1.0, 0.5, 1.5], [1.0, 0.0, -0.0]);
        assert!(unit_box().ray_interval(&r, 0.0, f32::INFINITY).is_none());
    }

    #[test]
    fn flat_box_is_hit() {
        let flat = Aabb::new(Vec3A::new(0.0, 0.0, 0.5), Vec3A::new(1.0, 1.0, 0.5));
        let r = ray([0.3, 0.3, 0.0], [0.0, 0.0, 1.0]);
        let (e, x) = flat.ray_interval(&r, 0.0, f32::INFINITY).unwrap();
        assert!(e <= 0.5 && x >= 0.5);
    }

    #[test]
    fn containing_box_interval_contains_inner_interval() {
        let inner = Aabb::new(Vec3A::new(0.2, 0.3, 0.1), Vec3A::new(0.4, 0.9, 0.7));
        let outer = inner.union(unit_box());
        let r = ray([-0.7, -0.3, -0.2], [1.0, 0.9, 0.77]);
        let (ie, ix) = inner.ray_interval(&r, 0.0, f32::INFINITY).unwrap();
        let (oe, ox) = outer.ray_interval(&r, 0.0, f32::INFINITY).unwrap();
        assert!(oe <= ie && ox >= ix);
    }

    #[test]
    fn surface_area_and_empty() {
        assert_eq!(unit_box().surface_area(), 6.0);
        assert!(Aabb::EMPTY.is_empty());
        assert_eq!(Aabb::EMPTY.surface_area(), 0.0);
        assert_eq!(
            Aabb::EMPTY.grown(Vec3A::ONE),
            Aabb::new(Vec3A::ONE, Vec3A::ONE)
        );
    }
}
