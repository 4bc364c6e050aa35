//! "Check last hit first" (screen-space coherence): a worker tracing rays in image order keeps
//! the primitive its previous ray hit and tests it before traversing.
//!
//! - Closest hit: when the kept primitive is hit at `t_last`, the index is asked for the
//!   closest hit over `[t_min, t_last]` only, so it culls everything beyond at once. This keeps
//!   brute force's answer bit for bit: brute force's hit `(t*, p*)` has `t* <= t_last`, so it
//!   lies in the narrowed interval (closed, so the kept primitive and every primitive tied with
//!   it at `t_last` are still found, and the lowest id among ties wins as usual). One subtlety:
//!   a kernel rejects a raw `t` beyond the *ray's* `t_max` before [`Geometry::intersect`] clamps
//!   it into the primitive's box, so a primitive whose raw `t` lies just beyond `t_last` but
//!   whose clamped `t` does not would be lost by narrowing the ray itself. The narrowed query
//!   therefore runs over [`KernelRange`], which hands the kernel the original `t_max` and only
//!   accepts `t <= t_last`: every primitive gets exactly the `t` brute force computes.
//! - Any hit (shadow rays): a hit on the kept primitive answers "occluded" at once (the shadow
//!   cache of Haines and Greenberg 1986); otherwise the index is asked as usual, over
//!   [`KernelRange`] too, which notes the primitive whose test succeeded last: the occluder the
//!   any-hit query stopped at, kept for the next ray.

use crate::geometry::triangle::lanes::TriangleBlock;
use crate::geometry::{Aabb, Hit, Ray};
use crate::index::{Index, Stats};
use crate::scene::{Geometry, GeometryWrapper};
use std::sync::atomic::AtomicU32;
use std::sync::atomic::Ordering::Relaxed;

/// [`KernelRange`]'s note before any primitive was reported hit.
const NOT_FOUND: u32 = u32::MAX;

/// A geometry whose kernel sees `kernel_t_max` as the ray's `t_max` whatever the ray passed in
/// says (see the module doc), and which notes the last primitive it reported a hit on;
/// everything else is the inner geometry's ([`GeometryWrapper`]). One per worker (the note is a relaxed atomic only
/// because geometries must be `Sync`; nothing else reads it).
pub struct KernelRange<G> {
    inner: G,
    kernel_t_max: f32,
    found: AtomicU32,
}

impl<G: Geometry> KernelRange<G> {
    /// Wraps a geometry (one clone per batch of rays, not per ray).
    pub fn new(inner: G) -> KernelRange<G> {
        KernelRange {
            inner,
            kernel_t_max: f32::INFINITY,
            found: AtomicU32::new(NOT_FOUND),
        }
    }
}

impl<G> KernelRange<G> {
    /// `ray` with the `t_max` the kernel is to see.
    #[inline(always)]
    fn kernel_ray(&self, ray: &Ray) -> Ray {
        Ray {
            t_max: self.kernel_t_max,
            ..*ray
        }
    }
}

impl<G: Clone> Clone for KernelRange<G> {
    fn clone(&self) -> Self {
        KernelRange {
            inner: self.inner.clone(),
            kernel_t_max: self.kernel_t_max,
            found: AtomicU32::new(self.found.load(Relaxed)),
        }
    }
}

impl<G: Geometry> GeometryWrapper for KernelRange<G> {
    type Inner = G;
    fn inner(&self) -> &G {
        &self.inner
    }
}

impl<G: Geometry> Geometry for KernelRange<G> {
    fn len(&self) -> usize {
        self.inner.len()
    }
    fn bounds(&self, prim: u32) -> Aabb {
        self.inner.bounds(prim)
    }
    #[inline(always)]
    fn intersect(&self, prim: u32, ray: &Ray, t_max: f32) -> Option<f32> {
        let t = self.inner.intersect(prim, &self.kernel_ray(ray), t_max);
        if t.is_some() {
            self.found.store(prim, Relaxed);
        }
        t
    }
    /// The inner geometry's lane form with the kernel's ray, so wide leaves keep their
    /// one-pass test; notes the last hit lane, as the lane-by-lane default would.
    #[inline(always)]
    fn intersect_block(&self, block: &TriangleBlock, ray: &Ray, t_max: f32) -> (u32, [f32; 4]) {
        let (mask, t) = self
            .inner
            .intersect_block(block, &self.kernel_ray(ray), t_max);
        if mask != 0 {
            let last = 31 - mask.leading_zeros();
            self.found.store(block.ids[last as usize], Relaxed);
        }
        (mask, t)
    }
}

/// The closest hit of `ray`, testing `*last` (the previous ray's hit primitive) first; updates
/// `*last` to this ray's hit primitive (`None` on a miss).
#[inline]
pub fn closest_hit<I: Index, G: Geometry, S: Stats>(
    index: &I,
    range: &mut KernelRange<G>,
    ray: &Ray,
    last: &mut Option<u32>,
    stats: &mut S,
) -> Option<Hit> {
    let hit = match last.and_then(|p| {
        stats.prim_test();
        range.inner.intersect(p, ray, ray.t_max)
    }) {
        Some(t_last) => {
            range.kernel_t_max = ray.t_max;
            let mut narrowed = *ray;
            narrowed.t_max = t_last;
            index.closest_hit(&*range, &narrowed, stats)
        }
        None => index.closest_hit(&range.inner, ray, stats),
    };
    *last = hit.map(|h| h.prim);
    hit
}

/// Whether `ray` hits anything, answering at once when `*last` (the primitive that last
/// occluded a ray of this worker) is hit; updates `*last` to the occluder found, if any.
#[inline]
pub fn any_hit<I: Index, G: Geometry, S: Stats>(
    index: &I,
    range: &mut KernelRange<G>,
    ray: &Ray,
    last: &mut Option<u32>,
    stats: &mut S,
) -> bool {
    if let Some(p) = *last {
        stats.prim_test();
        if range.inner.intersect(p, ray, ray.t_max).is_some() {
            return true;
        }
    }
    range.kernel_t_max = ray.t_max;
    range.found.store(NOT_FOUND, Relaxed);
    let occluded = index.any_hit(&*range, ray, stats);
    // An outside peer decides with its own triangle test, so it may report an occluder it never
    // asked this geometry about: then nothing is kept.
    *last = match range.found.load(Relaxed) {
        NOT_FOUND => None,
        found => occluded.then_some(found),
    };
    occluded
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Triangle;
    use crate::geometry::triangle::Exact;
    use crate::index::{BuildError, HitQuery, IndexInfo, NoStats};
    use crate::scene::Triangles;
    use glam::{Vec3, Vec3A};

    /// A peer that answers "occluded" with a test of its own, never asking the geometry.
    struct OwnTest;

    impl Index for OwnTest {
        type Params = ();
        fn build<G: Geometry>(_: &G, _: &()) -> Result<Self, BuildError> {
            Ok(OwnTest)
        }
        fn query<Q: HitQuery, G: Geometry, S: Stats>(
            &self,
            _: &G,
            _: &Ray,
            _: &mut S,
        ) -> Q::Answer {
            Q::select(|| None, || true)
        }
        fn info(&self) -> IndexInfo {
            IndexInfo::default()
        }
    }

    #[test]
    fn an_occluder_the_geometry_never_saw_is_not_kept() {
        let tri = Triangle::new(Vec3A::X, Vec3A::Y, Vec3A::Z);
        let mut range = KernelRange::new(Triangles::<Exact>::new(vec![tri].into()));
        let ray = Ray::new(Vec3::ZERO, Vec3::NEG_ONE, 0.0, f32::INFINITY).unwrap();
        let mut last = None;
        for _ in 0..2 {
            assert!(any_hit(&OwnTest, &mut range, &ray, &mut last, &mut NoStats));
            assert_eq!(last, None);
        }
    }
}
