//! The structures that hand a ray's cells to a visitor front to back ([`CellWalk`]: grid,
//! two-level grid, octree) share their closest-hit and any-hit queries here, each primitive
//! tested at most once per ray ([`super::mailbox`]).

use super::mailbox::with_mailbox;
use crate::geometry::Ray;
use crate::index::{HitQuery, Stats};
use crate::scene::Geometry;

/// A structure that hands a ray's cells (grid cells, octree leaves) to a visitor front to back.
///
/// Contract of [`CellWalk::for_each_cell`]: `visit` receives the primitive ids of each cell the
/// ray meets, in increasing order of the cells' `t` intervals, and returns the current cutoff
/// (the best `t`, `ray.t_max` while nothing is found, or `-inf` to stop at once); the walk stops
/// after a cell whose exit parameter is `>=` the cutoff, or when the ray leaves the structure.
/// Every primitive whose hit at `t <= cutoff` could beat the best so far lies in a cell handed
/// over before the walk stops (each implementation documents why). A cell may be left out when
/// none of its primitives can hit within `[t_min, cutoff]`.
pub trait CellWalk {
    fn for_each_cell<S: Stats>(&self, ray: &Ray, stats: &mut S, visit: impl CellVisit<S>);
}

/// The visitor [`CellWalk::for_each_cell`] calls per cell: the cell's primitive ids and the
/// counters in, the cutoff out.
pub trait CellVisit<S>: FnMut(&[u32], &mut S) -> f32 {}

impl<S, F: FnMut(&[u32], &mut S) -> f32> CellVisit<S> for F {}

/// Whether primitive `prim` can hit `ray` within `[ray.t_min, cutoff]`: its bounds' slab test
/// first (one box test, counted), then the shared kernel ([`Geometry::intersect`], one primitive
/// test, counted) only for a ray that meets its bounds.
///
/// Exact: [`Geometry::intersect`] clamps the kernel's `t` into the slab interval of the
/// primitive's own bounds and rejects a hit when that interval is empty, computing the interval
/// with the same [`crate::geometry::Aabb::ray_interval`]; a clamped `t` in `[t_min, cutoff]`
/// therefore lies in the interval clipped to `[t_min, cutoff]`, which is then not empty. So a
/// primitive rejected here is one the kernel would reject too. In a grid cell most primitives
/// are small against the cell and most rays crossing it miss their bounds, so this skips most
/// kernel calls for the price of a slab test.
#[inline(always)]
fn hit_within<G: Geometry, S: Stats>(
    geom: &G,
    prim: u32,
    ray: &Ray,
    cutoff: f32,
    stats: &mut S,
) -> Option<f32> {
    stats.box_tests(1);
    geom.bounds(prim).ray_interval(ray, ray.t_min, cutoff)?;
    stats.prim_test();
    geom.intersect(prim, ray, cutoff)
}

/// The answer to query `Q` along `walk`: each primitive tested at most once (the mailbox),
/// through the shared kernel ([`Geometry::intersect`], after its bounds: [`hit_within`]); a
/// closest hit keeps ties at equal `t` to the lowest id ([`crate::geometry::ClosestHit::offer`]),
/// an any-hit query stops at its first hit (the cutoff `-inf`). A primitive rejected once stays
/// rejected, because the reach only shrinks.
#[inline]
pub fn query_cells<Q: HitQuery, W: CellWalk, G: Geometry, S: Stats>(
    walk: &W,
    geom: &G,
    ray: &Ray,
    stats: &mut S,
) -> Q::Answer {
    with_mailbox(geom.len(), |mb| {
        let mut found = Q::start(ray);
        walk.for_each_cell(ray, stats, |prims, stats| {
            for &prim in prims {
                if mb.first_visit(prim)
                    && let Some(t) = hit_within(geom, prim, ray, Q::reach(&found, ray), stats)
                    && Q::hit(&mut found, t, prim)
                {
                    return f32::NEG_INFINITY;
                }
            }
            Q::reach(&found, ray)
        });
        Q::answer(found)
    })
}

/// The [`crate::index::Index`] methods every [`CellWalk`] structure shares, inside its `impl
/// Index`: `query` is the cell walk's ([`query_cells`]), and the build's peak heap is estimated
/// at `$bytes_per_prim` bytes a primitive ([`crate::index::build_budget::per_primitive`]).
macro_rules! cell_walk_index {
    ($bytes_per_prim:expr) => {
        #[inline]
        fn query<Q, G, S>(&self, g: &G, r: &$crate::geometry::Ray, s: &mut S) -> Q::Answer
        where
            Q: $crate::index::HitQuery,
            G: $crate::scene::Geometry,
            S: $crate::index::Stats,
        {
            $crate::index::kit::cell_walk::query_cells::<Q, _, _, _>(self, g, r, s)
        }

        fn estimated_build_bytes(prims: usize, _: &Self::Params) -> Option<usize> {
            $crate::index::build_budget::per_primitive(prims, $bytes_per_prim)
        }
    };
}
pub(crate) use cell_walk_index;
