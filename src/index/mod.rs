//! Acceleration structures behind one trait, and the run-time registry of them.
//!
//! An [`Index`] is built from a [`Geometry`](crate::scene::Geometry) (bounds, centroids,
//! overlap tests), stores primitive ids, and answers closest-hit and any-hit queries by calling
//! the geometry's shared kernel. Traversal is generic over [`Stats`]: [`NoStats`] for timed
//! runs, [`Counters`] for counting.
//!
//! The folder by kind: the trait and its types here (`contract`, `hit_query` (the query
//! kinds every walk is generic over), `build_error`, `index_info`, `stats`, and `build_budget`, the memory budget builds are held to); the tracing machinery in [`trace`]; the kits the structures share in [`kit`]; one
//! folder per structure (`brute`, `bvh`, `wbvh`, `grid`, `grid2`, `octree`, `kdtree`, `bsp`, and
//! [`tlas`], the two-level structure over a scene's instances);
//! the outside libraries in [`peers`]; the GPU backend in `gpu` (feature `gpu`); the list of
//! them all in [`registry`].

pub mod brute;
pub mod bsp;
pub mod build_budget;
mod build_error;
pub mod bvh;
mod contract;
#[cfg(feature = "gpu")]
pub mod gpu;
pub mod grid;
pub mod grid2;
pub mod hit_query;
mod index_info;
pub mod kdtree;
pub mod kit;
pub mod octree;
pub mod peers;
pub mod registry;
mod stats;
pub mod tlas;
pub mod trace;
pub mod wbvh;

pub use brute::BruteForce;
pub use bsp::Bsp;
pub use build_error::BuildError;
pub use bvh::{Bvh, BvhParams};
pub use contract::Index;
pub use grid::{Grid, GridParams};
pub use grid2::{Grid2, Grid2Params};
pub use hit_query::{AnyHit, Closest, HitQuery};
pub use index_info::IndexInfo;
pub use kdtree::KdTree;
pub use octree::{NeighborOctree, OctreeParams, TopDownOctree};
pub use peers::{ObvhsBvh2, ObvhsCwBvh};
pub use registry::{
    IndexSpec, Kind, build_index, estimated_build_bytes, index_names, is_peer, kind_of,
    parse_params, peer_names,
};
pub use stats::{Counters, NoStats, Stats};
pub use trace::{
    Answers, BatchIndex, BoundIndex, MAX_PACKET, ModeFamily, OwnRays, TraceIndex, TraceMode,
    build_index_on,
};
pub use wbvh::{Bvh4, Bvh8};
