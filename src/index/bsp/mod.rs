//! A general BSP tree: convex cells split by planes of any orientation (axis planes and the
//! primitives' own planes, autopartition-style), chosen by a cost estimate ([`build`]), and the
//! near/far traversal of [`crate::index::near_far`] with the signed distance to the plane.
//!
//! Crossing of a plane `n . p = offset`: `t = (offset - n . o) / (n . d)`. Both dot products
//! carry rounding error, bounded by `gamma(4)` of the sums of absolute terms; the traversal
//! takes the extreme quotients of the two error intervals (widened by
//! [`CROSSING_REL`]) as the bracket of the exact crossing. When the error interval of `n . d`
//! contains zero (a ray parallel or nearly parallel to the plane) both children are visited over
//! the whole interval, the origin's side first. With the builder's padding (a primitive within
//! `pad` of a plane is on both sides) and the strict skip rule, hits match brute force.
//!
//! Build time (one core, release, default parameters): the Stanford bunny (69,451 triangles)
//! takes about 5.5 s on a loaded 2-core machine (0.84 M nodes, 8.5 references per triangle,
//! 22 MB), about twice the time of box-area costs: every candidate cuts the cell's polyhedron.
//! Even scored by the exact cell areas, the own planes win few splits (0.06% on the bunny, 0.04%
//! on a 20k-triangle icosphere; see `cargo test --release --test bsp -- --nocapture`). The
//! candidate counts, `max_depth` and `leaf_size` cap it (time grows linearly with the number of
//! candidates).

mod build;
mod node;

pub use node::{BspKind, BspNode};

use super::near_far::{
    self, CROSSING_REL, MAX_TREE_DEPTH, NearFarTree, Step, scene_bounds, scene_pad,
};
use super::{BuildError, Index, IndexInfo, Stats};
use crate::geometry::float::gamma;
use crate::geometry::{Aabb, Hit, Ray};
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
    /// Deepest level (root = 0); absent: `8 + 1.3 log2 N`. At most 64.
    pub max_depth: Option<u32>,
    /// Nodes with at most this many primitives become leaves (at least 1).
    pub leaf_size: u32,
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
        }
    }
}

/// A built BSP: 24-byte nodes depth-first (root at 0, the child below a plane right after its
/// parent) and one array of primitive ids that leaves index.
#[derive(Debug, Clone)]
pub struct Bsp {
    nodes: Vec<BspNode>,
    ids: Vec<u32>,
    bounds: Aabb,
    prims: usize,
    depth: usize,
    leaves: usize,
    empty_leaves: usize,
    axis_splits: usize,
}

fn bad(message: String) -> BuildError {
    BuildError::Params {
        index: "bsp".into(),
        message,
    }
}

impl BspParams {
    fn limits(&self, n: usize) -> Result<build::Limits, BuildError> {
        for (name, v) in [
            ("intersect_cost", self.intersect_cost),
            ("traversal_cost", self.traversal_cost),
        ] {
            if !(v.is_finite() && v > 0.0) {
                return Err(bad(format!("{name} must be a finite number > 0, got {v}")));
            }
        }
        if !(0.0..1.0).contains(&self.empty_bonus) {
            return Err(bad(format!(
                "empty_bonus must be in [0, 1), got {}",
                self.empty_bonus
            )));
        }
        let total = 3 * self.axis_candidates as u64 + self.plane_candidates as u64;
        if total > 1024 || (total == 0 && !self.sweep) {
            return Err(bad(format!(
                "3 * axis_candidates + plane_candidates must be in 0..=1024 (at least 1 without \
                 sweep), got {total}"
            )));
        }
        let max_depth = self
            .max_depth
            .unwrap_or_else(|| crate::index::kdtree::default_max_depth(n));
        if max_depth > MAX_TREE_DEPTH {
            return Err(bad(format!(
                "max_depth must be at most {MAX_TREE_DEPTH}, got {max_depth}"
            )));
        }
        if self.leaf_size == 0 {
            return Err(bad("leaf_size must be at least 1".into()));
        }
        Ok(build::Limits {
            intersect: self.intersect_cost,
            traversal: self.traversal_cost,
            empty_bonus: self.empty_bonus,
            sweep: self.sweep,
            axis_candidates: self.axis_candidates,
            plane_candidates: self.plane_candidates,
            max_depth,
            leaf_size: self.leaf_size,
        })
    }
}

impl Bsp {
    /// Every split plane as `(unit normal, offset)`, depth-first (for tests).
    pub fn split_planes(&self) -> Vec<(Vec3A, f32)> {
        self.nodes
            .iter()
            .filter_map(|n| match n.kind() {
                BspKind::Interior { normal, offset, .. } => Some((normal, offset)),
                BspKind::Leaf { .. } => None,
            })
            .collect()
    }
}

/// Error bound factors of the two dot products of a crossing.
const NUM_ERR: f32 = gamma(4);
const DEN_ERR: f32 = gamma(3);

impl NearFarTree for Bsp {
    #[inline(always)]
    fn root_interval(&self, ray: &Ray) -> Option<(f32, f32)> {
        self.bounds.ray_interval(ray, ray.t_min, ray.t_max)
    }

    #[inline(always)]
    fn step(&self, node: u32, ray: &Ray) -> Step<'_> {
        match self.nodes[node as usize].kind() {
            BspKind::Leaf { first, count } => {
                Step::Leaf(&self.ids[first as usize..(first + count) as usize])
            }
            BspKind::Interior {
                normal,
                offset,
                above,
            } => {
                let below = node + 1;
                let num = offset - normal.dot(ray.origin);
                let den = normal.dot(ray.dir);
                let e_num = NUM_ERR * ((normal * ray.origin).abs().element_sum() + offset.abs());
                let e_den = DEN_ERR * (normal * ray.dir).abs().element_sum();
                if den.abs() <= e_den {
                    // (Nearly) parallel: both children everywhere, the origin's side first.
                    let (first, second) = if num >= 0.0 {
                        (below, above)
                    } else {
                        (above, below)
                    };
                    return Step::Cross {
                        first,
                        second,
                        lo: f32::NEG_INFINITY,
                        hi: f32::INFINITY,
                    };
                }
                let q = [
                    (num - e_num) / (den - e_den),
                    (num - e_num) / (den + e_den),
                    (num + e_num) / (den - e_den),
                    (num + e_num) / (den + e_den),
                ];
                let lo = q[0].min(q[1]).min(q[2]).min(q[3]);
                let hi = q[0].max(q[1]).max(q[2]).max(q[3]);
                let (first, second) = if den > 0.0 {
                    (below, above)
                } else {
                    (above, below)
                };
                Step::Cross {
                    first,
                    second,
                    lo: lo - lo.abs() * CROSSING_REL,
                    hi: hi + hi.abs() * CROSSING_REL,
                }
            }
        }
    }
}

impl Index for Bsp {
    type Params = BspParams;

    fn build<G: Geometry>(geom: &G, params: &BspParams) -> Result<Self, BuildError> {
        if geom.is_empty() {
            return Err(BuildError::EmptyScene);
        }
        let limits = params.limits(geom.len())?;
        let bounds = scene_bounds(geom, "bsp")?;
        let mut built = build::build(geom, bounds, scene_pad(&bounds), &limits)?;
        built.nodes.shrink_to_fit();
        built.ids.shrink_to_fit();
        Ok(Bsp {
            nodes: built.nodes,
            ids: built.ids,
            bounds,
            prims: geom.len(),
            depth: built.depth,
            leaves: built.leaves,
            empty_leaves: built.empty_leaves,
            axis_splits: built.axis_splits,
        })
    }

    #[inline]
    fn closest_hit<G: Geometry, S: Stats>(
        &self,
        geom: &G,
        ray: &Ray,
        stats: &mut S,
    ) -> Option<Hit> {
        near_far::closest_hit(self, geom, ray, stats)
    }

    #[inline]
    fn any_hit<G: Geometry, S: Stats>(&self, geom: &G, ray: &Ray, stats: &mut S) -> bool {
        near_far::any_hit(self, geom, ray, stats)
    }

    fn info(&self) -> IndexInfo {
        let interior = self.nodes.len() - self.leaves;
        IndexInfo {
            nodes: self.nodes.len(),
            leaves: self.leaves,
            depth: self.depth,
            memory_bytes: self.nodes.capacity() * size_of::<BspNode>()
                + self.ids.capacity() * size_of::<u32>(),
            prim_refs: self.ids.len(),
            extra: vec![
                ("empty_leaves".into(), self.empty_leaves as f64),
                (
                    "refs_per_prim".into(),
                    self.ids.len() as f64 / self.prims.max(1) as f64,
                ),
                (
                    "general_plane_fraction".into(),
                    if interior == 0 {
                        0.0
                    } else {
                        (interior - self.axis_splits) as f64 / interior as f64
                    },
                ),
            ],
            ..IndexInfo::default()
        }
    }
}
