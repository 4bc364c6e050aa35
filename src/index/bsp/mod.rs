//! A general BSP tree: convex cells split by planes of any orientation (axis planes and the
//! primitives' own planes, autopartition-style), chosen by a cost estimate ([`build`]), and the
//! near/far traversal of [`crate::index::kit::near_far`] with the signed distance to the plane.
//!
//! Crossing of a plane: see the node's step ([`node`]). With the builder's padding (a primitive
//! within `pad` of a plane is on both sides) and the strict skip rule, hits match brute force.
//!
//! Build time (release, default parameters): the Stanford bunny (69,451 triangles) takes about
//! 2.1 s on a 2-core machine with other work paused (best of three; 7.9 MB; with pbrt's depth
//! limit `8 + 1.3 log2 N` 22 MB and 1.7 times the time), about twice the time of box-area costs:
//! every candidate cuts the cell's polyhedron.
//! Even scored by the exact cell areas, the own planes win few splits (0.06% on the bunny, 0.04%
//! on a 20k-triangle icosphere; see `cargo test --release --test bsp -- --nocapture`). The
//! candidate counts, `max_depth` and `leaf_size` cap it (time grows linearly with the number of
//! candidates).

mod build;
mod node;

pub use node::{BspKind, BspNode};

use crate::geometry::Aabb;
use crate::index::BuildError;
use crate::index::kit::near_far::leaf_and_mailbox;
use crate::index::kit::near_far::{BuildResult, NearFarIndex, Partition, SahParams};
use crate::scene::Geometry;
use glam::Vec3A;
use serde::{Deserialize, Serialize};

/// Build parameters.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct BspParams {
    /// Cost of one primitive test, relative to `traversal_cost`.
    pub intersect_cost: f32,
    /// Cost of one traversal step.
    pub traversal_cost: f32,
    /// Fraction of the cost saved by a split that leaves a child empty, in `[0, 1)`.
    pub empty_bonus: f32,
    /// Find the best axis plane by the kd-tree's full SAH sweep over perfect-split candidates.
    pub sweep: bool,
    /// Further axis-plane candidates per axis and node (at quantiles of the primitives' bounds).
    pub axis_candidates: u32,
    /// Own-plane candidates per node (planes of evenly sampled triangles; 0 gives an axis-only
    /// BSP, `sweep=false` with `axis_candidates=0` a pure autopartition). Build time grows
    /// linearly with `3 * axis_candidates + plane_candidates` (at most 1024; at least 1
    /// without `sweep`).
    pub plane_candidates: u32,
    /// Deepest level (root = 0); absent: `3 + 1.3 log2 N`. At most 64.
    pub max_depth: Option<u32>,
    /// Nodes with at most this many primitives become leaves (at least 1).
    pub leaf_size: u32,
    /// Test each primitive at most once per ray (a per-thread stamp per primitive); without
    /// it a primitive in several leaves the ray visits is tested again (same hits).
    pub mailbox: bool,
}

impl Default for BspParams {
    fn default() -> Self {
        BspParams {
            intersect_cost: 80.0,
            traversal_cost: 1.0,
            empty_bonus: 0.2,
            sweep: true,
            axis_candidates: 0,
            plane_candidates: 12,
            max_depth: None,
            leaf_size: 2,
            mailbox: true,
        }
    }
}

/// A built BSP: 24-byte nodes depth-first (root at 0, the child below a plane right after its
/// parent) and one array of primitive ids that leaves index.
pub type Bsp = NearFarIndex<BspNode>;

impl BspParams {
    fn limits(&self, n: usize) -> Result<build::Limits, BuildError> {
        let sah = SahParams::validate(
            BspNode::NAME,
            (self.intersect_cost, self.traversal_cost, self.empty_bonus),
            self.max_depth,
            self.leaf_size,
            n,
        )?;
        let total = 3 * self.axis_candidates as u64 + self.plane_candidates as u64;
        if total > 1024 || (total == 0 && !self.sweep) {
            return Err(BuildError::Params {
                index: BspNode::NAME.into(),
                message: format!(
                    "3 * axis_candidates + plane_candidates must be in 0..=1024 (at least 1 \
                     without sweep), got {total}"
                ),
            });
        }
        Ok(build::Limits {
            sah,
            sweep: self.sweep,
            axis_candidates: self.axis_candidates,
            plane_candidates: self.plane_candidates,
        })
    }
}

impl Partition for BspNode {
    const NAME: &'static str = "bsp";
    /// About 300 B measured.
    const BUILD_BYTES_PER_PRIM: usize = 330;
    type Params = BspParams;

    fn build<G: Geometry>(geom: &G, params: &BspParams, root: Aabb, pad: f32) -> BuildResult<Self> {
        build::build(geom, root, pad, &params.limits(geom.len())?)
    }

    leaf_and_mailbox!(BspKind);
}

impl Bsp {
    /// Every split plane as `(unit normal, offset)`, depth-first (for tests).
    pub fn split_planes(&self) -> Vec<(Vec3A, f32)> {
        self.nodes()
            .iter()
            .filter_map(|n| match n.kind() {
                BspKind::Interior { normal, offset, .. } => Some((normal, offset)),
                BspKind::Leaf { .. } => None,
            })
            .collect()
    }
}
