//! The binary space partitions (kd-tree, general BSP) share one index type
//! ([`NearFarIndex`], over a node type implementing [`Partition`]) and one near/far traversal
//! ([`walk`]): the ray's parameter interval is cut at each split plane, the child the ray meets
//! first is visited first, the other one is pushed on a fixed stack with its own interval.
//!
//! Conservative bookkeeping keeps the hits identical to brute force:
//! - a node reports the crossing parameter of its split plane as a bracket `[lo, hi]` that
//!   contains the exact crossing; the first child gets `[t0, min(t1, hi)]`, the second
//!   `[max(t0, lo), t1]`, so the two intervals overlap slightly instead of leaving a rounding gap
//!   between them;
//! - a pending node is skipped only when its interval starts *strictly after* the best hit, so
//!   a primitive behind a split plane whose hit ties the best `t` (a lower id may win the tie)
//!   is still tested;
//! - builders put a primitive within a padding distance of a plane on both sides.
//!
//! Each primitive is tested at most once per ray (the shared [`crate::index::kit::mailbox`]).

mod axis;
pub mod sweep;
mod tree;
mod walk;

pub use axis::{AxisRay, axis_step};
pub(crate) use tree::leaf_and_mailbox;
pub use tree::{BuildResult, Built, NearFarIndex, Partition, SahParams};
pub use walk::{SplitNode, Step};

use crate::geometry::Aabb;
use crate::geometry::overlap::OVERLAP_PAD;
use crate::index::BuildError;
use crate::scene::Geometry;

/// Deepest tree the traversal stack supports (builders reject a larger `max_depth`).
pub const MAX_TREE_DEPTH: u32 = 64;

/// Relative half-width of the bracket around a computed axis-plane crossing
/// `(split - origin) * inv_dir`: three roundings need `gamma(3)` (about 1.8e-7); the rest is
/// margin for the kernels' own rounding of `t` near a plane.
pub const CROSSING_REL: f32 = 1.0e-6;

/// The bounds of all primitives, or an error naming the problem (NaN, infinite coordinates).
pub fn scene_bounds<G: Geometry>(geom: &G, index: &str) -> Result<Aabb, BuildError> {
    let b = (0..geom.len() as u32).fold(Aabb::EMPTY, |b, p| b.union(geom.bounds(p)));
    if b.is_empty() || !b.min.is_finite() || !b.max.is_finite() {
        return Err(BuildError::Failed {
            index: index.into(),
            message: format!(
                "the scene bounds {:?}..{:?} are not finite; remove NaN or infinite coordinates",
                b.min, b.max
            ),
        });
    }
    Ok(b)
}

/// Classification padding for a scene with bounds `b`: [`OVERLAP_PAD`] of its largest
/// coordinate, as for every overlap test.
pub fn scene_pad(b: &Aabb) -> f32 {
    b.min.abs().max(b.max.abs()).max_element() * OVERLAP_PAD + f32::MIN_POSITIVE
}

/// The default maximum depth `3 + 1.3 log2 n`, capped at [`MAX_TREE_DEPTH`].
///
/// pbrt's `8 + 1.3 log2 n` lets the SAH (which with one-primitive leaves almost always finds a
/// split cheaper than a leaf) cut empty space and straddling primitives five levels further:
/// on the Stanford bunny 11.4 MB instead of 3.4 MB and 2.7 times the build time, for 2.5 fewer
/// tests but no fewer node steps per ray (33.5 against 30.0 on incoherent rays) and no speed
/// gained; on the stadium, soup and room scenes of 20,000 triangles the extra levels change
/// neither steps nor tests per ray measurably.
pub fn default_max_depth(n: usize) -> u32 {
    let d = 3.0 + 1.3 * (n.max(1) as f64).log2();
    (d.round() as u32).min(MAX_TREE_DEPTH)
}
