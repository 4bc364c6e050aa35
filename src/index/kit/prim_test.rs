//! One primitive tested for a query, counted: the step every index's leaves, cells and brute
//! force share (the kernel through [`Geometry::intersect`], one [`Stats::prim_test`]).

use crate::geometry::{ClosestHit, Ray};
use crate::index::Stats;
use crate::scene::Geometry;

/// Tests `prim` against `[ray.t_min, best t]` and offers a hit to `best`; `true` when it was
/// hit (and offered).
#[inline(always)]
pub fn closest<G: Geometry, S: Stats>(
    best: &mut ClosestHit,
    geom: &G,
    prim: u32,
    ray: &Ray,
    stats: &mut S,
) -> bool {
    stats.prim_test();
    let hit = geom.intersect(prim, ray, best.t());
    if let Some(t) = hit {
        best.offer(t, prim);
    }
    hit.is_some()
}

/// Whether `prim` is hit in `[ray.t_min, ray.t_max]`.
#[inline(always)]
pub fn any<G: Geometry, S: Stats>(geom: &G, prim: u32, ray: &Ray, stats: &mut S) -> bool {
    stats.prim_test();
    geom.intersect(prim, ray, ray.t_max).is_some()
}
