//! Acceleration structures behind one trait, and the run-time registry of them.
//!
//! An [`Index`] is built from a [`Geometry`] (bounds, centroids, overlap tests), stores primitive
//! ids, and answers closest-hit and any-hit queries by calling the geometry's shared kernel.
//! Traversal is generic over [`Stats`]: [`NoStats`] for timed runs, [`Counters`] for counting.

pub mod batch;
mod brute;
pub mod bsp;
pub mod bvh;
#[cfg(feature = "embree")]
pub mod embree_peer;
pub mod grid;
pub mod grid2;
pub mod huge_pages;
pub mod kdtree;
pub mod last_hit;
pub mod mailbox;
pub mod near_far;
pub mod obvhs_peer;
pub mod octree;
pub mod prefetch;
pub mod prim_test;
pub mod query;
mod registry;
pub(crate) mod stack;
mod stats;
#[cfg(feature = "tinybvh")]
pub mod tinybvh_peer;
#[cfg(any(feature = "embree", feature = "tinybvh"))]
mod triangle_peer;
pub mod wbvh;

pub use batch::{MAX_PACKET, ModeFamily, TraceMode};
pub use brute::BruteForce;
pub use bsp::Bsp;
pub use bvh::{Bvh, BvhParams};
pub use grid::{Grid, GridParams};
pub use grid2::{Grid2, Grid2Params};
pub use kdtree::KdTree;
pub use obvhs_peer::{ObvhsBvh2, ObvhsCwBvh};
pub use octree::{NeighborOctree, OctreeParams, TopDownOctree};
pub use registry::{
    BoundIndex, IndexSpec, Kind, TraceIndex, build_index, build_index_on, index_names, is_peer,
    parse_params, peer_names,
};
pub use stats::{Counters, NoStats, Stats};
pub use wbvh::{Bvh4, Bvh8};

use crate::geometry::{Hit, Ray};
use crate::scene::Geometry;
use serde::Serialize;
use serde::de::DeserializeOwned;
use std::fmt::Debug;
use std::time::Duration;
use thiserror::Error;

/// Why an index could not be built.
#[derive(Debug, Error)]
pub enum BuildError {
    #[error("invalid parameters for index '{index}': {message}")]
    Params { index: String, message: String },
    #[error("unknown index '{0}': choose one of {1}")]
    UnknownIndex(String, String),
    #[error("cannot build an index over an empty scene")]
    EmptyScene,
    #[error("index '{index}' cannot be built: {message}")]
    Failed { index: String, message: String },
    /// The index does not handle this scene (a triangle-only peer on a scene with spheres):
    /// the suite skips it with this reason instead of failing.
    #[error("{index} skipped: {reason}")]
    Unsupported { index: String, reason: String },
}

/// Size and shape of a built index, for reports.
#[derive(Debug, Clone, Default, Serialize)]
pub struct IndexInfo {
    /// All nodes (or cells), leaves included.
    pub nodes: usize,
    /// Leaves (or non-empty cells).
    pub leaves: usize,
    /// Maximum depth (1 for a flat structure).
    pub depth: usize,
    /// Heap bytes the index owns (nodes, cell arrays, primitive id arrays), excluding the scene.
    pub memory_bytes: usize,
    /// Primitive references stored (an id in a leaf or cell counts once per leaf or cell).
    pub prim_refs: usize,
    /// Build time, measured by the registry around [`Index::build`].
    pub build_time: Duration,
    /// Structure-specific figures (name, value), e.g. `("empty_cells", 0.4)`.
    pub extra: Vec<(String, f64)>,
    /// `true` for peers whose traversal reports nothing to [`Stats`] (Embree, tinybvh): reports
    /// show their tests and steps per ray as missing, not 0.
    pub uncounted: bool,
}

/// An acceleration structure.
///
/// Contract: for every valid ray, [`Index::closest_hit`] returns exactly what [`BruteForce`]
/// returns (same primitive, bit-identical `t`, ties at equal `t` to the lowest primitive id), and
/// [`Index::any_hit`] returns `closest_hit(..).is_some()`. Queries never allocate.
pub trait Index: Sized + Send + Sync + 'static {
    /// Typed build parameters. `Deserialize` with unknown fields rejected, so parameters can
    /// come from the command line (`bvh:leaf_size=4`) and scene files; `Default` is the preset
    /// the suite uses.
    type Params: Default + Clone + Debug + Serialize + DeserializeOwned + Send + Sync;

    /// Builds the index over `geom`. Fails with a clear error on absurd parameters.
    fn build<G: Geometry>(geom: &G, params: &Self::Params) -> Result<Self, BuildError>;

    /// The closest hit in `[ray.t_min, ray.t_max]`.
    fn closest_hit<G: Geometry, S: Stats>(&self, geom: &G, ray: &Ray, stats: &mut S)
    -> Option<Hit>;

    /// Whether any primitive is hit in `[ray.t_min, ray.t_max]` (stops at the first).
    fn any_hit<G: Geometry, S: Stats>(&self, geom: &G, ray: &Ray, stats: &mut S) -> bool;

    /// Size and shape (the registry fills in `build_time`).
    fn info(&self) -> IndexInfo;

    /// Whether the index has a batch technique of its own ([`Index::closest_hits_stream`] is
    /// overridden): the suite then gives it `INDEX+stream` rows. An index without one has no
    /// stream row; the verdict lets its one-at-a-time row stand for it.
    const STREAM: bool = false;

    /// Whether one-query-at-a-time rows of the index measure anything of its own: `false` for
    /// an index that exists only as a batch technique over another index's single rays
    /// (`embree-p16`), which then gets only `+stream` rows.
    const SINGLE: bool = true;

    /// Closest hits of a chunk of consecutive rays of a batch (the harness's parallel work item,
    /// at most 64 rays; image order for camera sets; `out` and `stats` as long as `rays`) with
    /// the index's own batch technique ([`TraceMode::Stream`]). By default
    /// [`Index::closest_hit`] per ray; an index that traces several rays at a time (interleaved
    /// walks in `bvh4`/`bvh8`, Embree's 16-ray packets in `embree-p16`) overrides it and sets
    /// [`Index::STREAM`].
    #[inline]
    fn closest_hits_stream<G: Geometry, S: Stats>(
        &self,
        geom: &G,
        rays: &[Ray],
        out: &mut [Option<Hit>],
        stats: &mut [S],
    ) {
        batch::each_closest(self, geom, rays, out, stats);
    }

    /// Any-hit results of a chunk, as [`Index::closest_hits_stream`].
    #[inline]
    fn any_hits_stream<G: Geometry, S: Stats>(
        &self,
        geom: &G,
        rays: &[Ray],
        out: &mut [bool],
        stats: &mut [S],
    ) {
        batch::each_any(self, geom, rays, out, stats);
    }

    /// Closest hits of a packet of neighbouring rays (at most [`MAX_PACKET`]; `out` and `stats`
    /// as long as `rays`). By default ray by ray; an index with packet traversal overrides it.
    #[inline]
    fn closest_hits_packet<G: Geometry, S: Stats>(
        &self,
        geom: &G,
        rays: &[Ray],
        out: &mut [Option<Hit>],
        stats: &mut [S],
    ) {
        batch::each_closest(self, geom, rays, out, stats);
    }

    /// Any-hit results of a packet, as [`Index::closest_hits_packet`].
    #[inline]
    fn any_hits_packet<G: Geometry, S: Stats>(
        &self,
        geom: &G,
        rays: &[Ray],
        out: &mut [bool],
        stats: &mut [S],
    ) {
        batch::each_any(self, geom, rays, out, stats);
    }
}
