//! `obvhs-bvh2`: obvhs's binary BVH (PLOC build, reinsertion, leaf collapse) and its stack
//! traversal, with our kernel and our closest-hit order in the leaf callback.

use super::tree::{Obvhs, ObvhsTree, TreeShape};
use super::{culling_bound, obvhs_ray};
use crate::geometry::Ray;
use crate::index::Stats;
use obvhs::BvhBuildParams;
use obvhs::aabb::Aabb;
use obvhs::bvh2::{Bvh2, builder::build_bvh2, node::Bvh2Node};
use obvhs::ray::RayHit;
use std::time::Duration;

/// obvhs's binary BVH over the scene's primitive bounds as an index (`obvhs-bvh2`).
pub type ObvhsBvh2 = Obvhs<Bvh2>;

impl ObvhsTree for Bvh2 {
    const NAME: &'static str = "obvhs-bvh2";
    /// About 290 B measured.
    const BUILD_BYTES_PER_PRIM: usize = 320;

    fn build(boxes: &[Aabb], params: BvhBuildParams, time: &mut Duration) -> Self {
        build_bvh2(boxes, params, time)
    }

    /// obvhs's stack traversal; a visited leaf counts as a node visit (obvhs's inner nodes are
    /// not counted), and `prim` returning `false` ends the walk.
    #[inline(always)]
    fn walk<S: Stats>(
        &self,
        ray: &Ray,
        stats: &mut S,
        mut prim: impl FnMut(u32, &mut S, &mut obvhs::ray::Ray) -> bool,
    ) {
        let ids = &self.primitive_indices;
        let mut on_leaf = |node: &Bvh2Node, oray: &mut obvhs::ray::Ray, _: &mut RayHit| {
            stats.node_visit();
            let first = node.first_index as usize;
            ids[first..first + node.prim_count as usize]
                .iter()
                .all(|&id| prim(id, stats, oray))
        };
        let oray = obvhs_ray(ray, culling_bound(ray.t_max));
        let mut hit = RayHit::none();
        // As obvhs's own `ray_traverse`: a stack sized by the build's depth.
        obvhs::fast_stack!(u32, (96, 192), self.max_depth, stack, {
            self.ray_traverse_dynamic(&mut stack, oray, &mut hit, &mut on_leaf)
        });
    }

    fn shape(&self) -> TreeShape {
        let prims = self.primitive_indices.len();
        TreeShape {
            nodes: self.nodes.len(),
            leaves: self.nodes.iter().filter(|n| n.is_leaf()).count(),
            depth: self.depth(0),
            prim_refs: prims,
            memory_bytes: self.nodes.len() * size_of::<Bvh2Node>() + prims * 4,
        }
    }
}
