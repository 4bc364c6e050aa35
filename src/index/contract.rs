//! The [`Index`] trait: what every acceleration structure answers (build, closest hit, any
//! hit, size and shape), and the hit contract it answers by. Tracing several rays at a time is
//! the separate [`crate::index::BatchIndex`].

use crate::geometry::{Hit, Ray};
use crate::index::hit_query::{AnyHit, Closest, HitQuery};
use crate::index::{BuildError, IndexInfo, Stats};
use crate::scene::Geometry;
use serde::Serialize;
use serde::de::DeserializeOwned;
use std::fmt::Debug;

/// An acceleration structure.
///
/// Contract: for every valid ray, [`Index::closest_hit`] returns exactly what [`crate::index::BruteForce`]
/// returns (same primitive, bit-identical `t`, ties at equal `t` to the lowest primitive id), and
/// [`Index::any_hit`] returns `closest_hit(..).is_some()`. Queries never allocate.
pub trait Index: Sized + Send + Sync + 'static {
    /// Typed build parameters. `Deserialize` with unknown fields rejected, so parameters can
    /// come from the command line (`bvh:leaf_size=4`) and scene files; `Default` is the preset
    /// the suite uses.
    type Params: Default + Clone + Debug + Serialize + DeserializeOwned + Send + Sync;

    /// Builds the index over `geom`. Fails with a clear error on absurd parameters.
    fn build<G: Geometry>(geom: &G, params: &Self::Params) -> Result<Self, BuildError>;

    /// The answer to query `Q` for `ray` over `[ray.t_min, ray.t_max]`: one walk written once
    /// for both query kinds ([`HitQuery`]); an index that asks a library picks its call with
    /// [`HitQuery::select`].
    fn query<Q: HitQuery, G: Geometry, S: Stats>(
        &self,
        geom: &G,
        ray: &Ray,
        stats: &mut S,
    ) -> Q::Answer;

    /// The closest hit in `[ray.t_min, ray.t_max]`.
    #[inline]
    fn closest_hit<G: Geometry, S: Stats>(
        &self,
        geom: &G,
        ray: &Ray,
        stats: &mut S,
    ) -> Option<Hit> {
        self.query::<Closest, G, S>(geom, ray, stats)
    }

    /// Whether any primitive is hit in `[ray.t_min, ray.t_max]` (stops at the first).
    #[inline]
    fn any_hit<G: Geometry, S: Stats>(&self, geom: &G, ray: &Ray, stats: &mut S) -> bool {
        self.query::<AnyHit, G, S>(geom, ray, stats)
    }

    /// Size and shape (the registry fills in `build_time`).
    fn info(&self) -> IndexInfo;

    /// An estimate, in bytes, of the heap the build over `prims` primitives holds at its peak
    /// with `params` (the build's own allocations, not the scene's), or `None` where there is
    /// none. [`crate::index::build_index_on`] refuses a build whose estimate would not fit the
    /// memory budget ([`crate::index::build_budget`]). The estimates come from the peaks `info
    /// --indices` measures on the generated soup and icosphere and on the bunny, with a margin,
    /// and `tests/it/memory_checks.rs` checks them against those peaks; structures that scenes of thin,
    /// long primitives make larger than that check the budget while they build too.
    fn estimated_build_bytes(prims: usize, params: &Self::Params) -> Option<usize> {
        let _ = (prims, params);
        None
    }

    /// Why this index cannot be given `ray`, or `None`: outside libraries have input ranges
    /// (Embree takes coordinates up to ±1.844e18); every index of ours takes every valid ray.
    /// The index answers a refused ray as a miss without handing it on, and the suite and
    /// `trace` say how many rays were refused and why ([`crate::index::TraceIndex::refused`]).
    fn refuses(ray: &Ray) -> Option<&'static str> {
        let _ = ray;
        None
    }

    /// Whether the index allocates outside Rust's global allocator (a C or C++ library):
    /// then [`crate::heap_meter`] cannot see its build, and [`Index::info`] gives
    /// `peak_build_bytes` itself, or `None` where nothing measures it.
    const FOREIGN_HEAP: bool = false;

    /// Whether [`Index::refit`] updates the index in place.
    const REFIT: bool = false;

    /// Moves the index to `geom`, the same primitives (same count, same ids) at new positions:
    /// the topology is kept and every bound is recomputed bottom up, so the hit contract holds
    /// on `geom` as after a build (only the tree's quality may fall). Indices without a refit
    /// refuse with [`BuildError::Unsupported`]; callers rebuild them instead.
    fn refit<G: Geometry>(&mut self, geom: &G) -> Result<(), BuildError> {
        let _ = geom;
        Err(BuildError::Unsupported {
            index: std::any::type_name::<Self>().to_owned(),
            reason: "it has no refit; rebuild it".into(),
        })
    }
}
