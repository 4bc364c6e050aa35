//! One primitive tested for a query, counted: the step every index's leaves, cells and brute
//! force share (the kernel through [`Geometry::intersect`], one [`Stats::prim_test`]).

use crate::geometry::Ray;
use crate::index::{HitQuery, Stats};
use crate::scene::Geometry;

/// Tests `prim` against `[ray.t_min, Q::reach(found)]` and hands a hit to
/// [`HitQuery::hit`]; `true` when the walk is over (an any-hit query's first hit).
#[inline(always)]
pub fn test<Q: HitQuery, G: Geometry, S: Stats>(
    found: &mut Q::Found,
    geom: &G,
    prim: u32,
    ray: &Ray,
    stats: &mut S,
) -> bool {
    stats.prim_test();
    match geom.intersect(prim, ray, Q::reach(found, ray)) {
        Some(t) => Q::hit(found, t, prim),
        None => false,
    }
}
