//! `obvhs-cwbvh`: obvhs's compressed wide BVH8 (PLOC build, reinsertion, BVH2 to CWBVH) and its
//! `traverse!` loop with its SIMD node test, with our kernel and our closest-hit order in the
//! primitive step.

use super::tree::{Obvhs, ObvhsTree, TreeShape};
use super::{culling_bound, obvhs_ray};
use crate::geometry::Ray;
use crate::index::Stats;
use glam::UVec2;
use obvhs::BvhBuildParams;
use obvhs::aabb::Aabb;
use obvhs::cwbvh::{CwBvh, builder::build_cwbvh, node::CwBvhNode};
use std::time::Duration;

/// obvhs's compressed wide BVH8 over the scene's primitive bounds as an index (`obvhs-cwbvh`).
pub type ObvhsCwBvh = Obvhs<CwBvh>;

impl ObvhsTree for CwBvh {
    const NAME: &'static str = "obvhs-cwbvh";
    /// About 360 B measured (its binary tree, then the compressed wide one).
    const BUILD_BYTES_PER_PRIM: usize = 400;

    fn build(boxes: &[Aabb], params: BvhBuildParams, time: &mut Duration) -> Self {
        build_cwbvh(boxes, params, time)
    }

    /// obvhs's `traverse!` loop with its SIMD node test. `prim` returning `false` leaves the
    /// current leaf's primitives only: obvhs's loop has no exit from the whole walk.
    #[inline(always)]
    fn walk<S: Stats>(
        &self,
        ray: &Ray,
        stats: &mut S,
        mut prim: impl FnMut(u32, &mut S, &mut obvhs::ray::Ray) -> bool,
    ) {
        let mut oray = obvhs_ray(ray, culling_bound(ray.t_max));
        let mut state = self.new_traversal(oray.direction);
        let mut node: &CwBvhNode;
        let ids = &self.primitive_indices;
        obvhs::traverse!(
            self,
            node,
            state,
            {
                stats.node_visit();
                stats.box_tests(node.child_meta.iter().filter(|&&m| m != 0).count() as u32);
                node.intersect_ray(&oray, state.oct_inv4)
            },
            {
                if !prim(ids[state.primitive_id as usize], stats, &mut oray) {
                    break;
                }
            }
        );
    }

    fn shape(&self) -> TreeShape {
        let (depth, leaves) = depth_and_leaves(self);
        let prims = self.primitive_indices.len();
        let exact = self.exact_node_aabbs.as_ref().map_or(0, |v| v.len());
        TreeShape {
            nodes: self.nodes.len(),
            leaves,
            depth,
            prim_refs: prims,
            memory_bytes: self.nodes.len() * size_of::<CwBvhNode>()
                + prims * 4
                + exact * size_of::<obvhs::aabb::Aabb>(),
        }
    }
}

/// Levels (root = 1, leaves counted as a level below their node) and leaf children.
fn depth_and_leaves(bvh: &CwBvh) -> (usize, usize) {
    if bvh.nodes.is_empty() {
        return (0, 0);
    }
    let parents = bvh.compute_parents();
    let mut leaves = 0;
    let mut depth = 1;
    for (i, node) in bvh.nodes.iter().enumerate() {
        // Walk up to the root (parents[0] == 0).
        let (mut at, mut l) = (i, 1);
        while at != 0 {
            at = parents[at] as usize;
            l += 1;
        }
        for ch in 0..8 {
            if !node.is_child_empty(ch) && node.is_leaf(ch) {
                leaves += 1;
                depth = depth.max(l + 1);
            }
        }
    }
    (depth, leaves)
}
