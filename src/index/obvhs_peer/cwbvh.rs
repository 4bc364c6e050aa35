//! `obvhs-cwbvh`: obvhs's compressed wide BVH8 (PLOC build, reinsertion, BVH2 to CWBVH) and its
//! `traverse!` loop with its SIMD node test, with our kernel and our closest-hit order in the
//! primitive step.

use super::{ObvhsParams, culling_bound, obvhs_ray, prim_boxes};
use crate::geometry::{ClosestHit, Hit, Ray};
use crate::index::{BuildError, Index, IndexInfo, Stats};
use crate::scene::Geometry;
use glam::UVec2;
use obvhs::cwbvh::{CwBvh, builder::build_cwbvh, node::CwBvhNode};
use std::time::Duration;

/// obvhs's `CwBvh` over the scene's primitive bounds.
#[derive(Clone)]
pub struct ObvhsCwBvh {
    bvh: CwBvh,
    depth: usize,
    leaves: usize,
}

impl Index for ObvhsCwBvh {
    type Params = ObvhsParams;

    fn build<G: Geometry>(geom: &G, params: &ObvhsParams) -> Result<Self, BuildError> {
        let boxes = prim_boxes(geom, "obvhs-cwbvh")?;
        let bvh = build_cwbvh(
            &boxes,
            params.preset.build_params(),
            &mut Duration::default(),
        );
        let (depth, leaves) = shape(&bvh);
        Ok(ObvhsCwBvh { bvh, depth, leaves })
    }

    #[inline]
    fn closest_hit<G: Geometry, S: Stats>(
        &self,
        geom: &G,
        ray: &Ray,
        stats: &mut S,
    ) -> Option<Hit> {
        let mut best = ClosestHit::new(ray.t_max);
        let mut oray = obvhs_ray(ray, culling_bound(ray.t_max));
        let mut state = self.bvh.new_traversal(oray.direction);
        let mut node: &CwBvhNode;
        let ids = &self.bvh.primitive_indices;
        obvhs::traverse!(
            self.bvh,
            node,
            state,
            {
                stats.node_visit();
                stats.box_tests(node.child_meta.iter().filter(|&&m| m != 0).count() as u32);
                node.intersect_ray(&oray, state.oct_inv4)
            },
            {
                let prim = ids[state.primitive_id as usize];
                stats.prim_test();
                if let Some(t) = geom.intersect(prim, ray, best.t()) {
                    best.offer(t, prim);
                    oray.tmax = culling_bound(best.t());
                }
            }
        );
        best.get()
    }

    #[inline]
    fn any_hit<G: Geometry, S: Stats>(&self, geom: &G, ray: &Ray, stats: &mut S) -> bool {
        let oray = obvhs_ray(ray, culling_bound(ray.t_max));
        let mut state = self.bvh.new_traversal(oray.direction);
        let mut node: &CwBvhNode;
        let ids = &self.bvh.primitive_indices;
        let mut found = false;
        obvhs::traverse!(
            self.bvh,
            node,
            state,
            {
                stats.node_visit();
                stats.box_tests(node.child_meta.iter().filter(|&&m| m != 0).count() as u32);
                node.intersect_ray(&oray, state.oct_inv4)
            },
            {
                stats.prim_test();
                if geom
                    .intersect(ids[state.primitive_id as usize], ray, ray.t_max)
                    .is_some()
                {
                    found = true;
                    break;
                }
            }
        );
        found
    }

    fn info(&self) -> IndexInfo {
        let nodes = self.bvh.nodes.len();
        let prims = self.bvh.primitive_indices.len();
        let exact = self.bvh.exact_node_aabbs.as_ref().map_or(0, |v| v.len());
        let memory_bytes =
            nodes * size_of::<CwBvhNode>() + prims * 4 + exact * size_of::<obvhs::aabb::Aabb>();
        IndexInfo {
            nodes,
            leaves: self.leaves,
            depth: self.depth,
            memory_bytes,
            prim_refs: prims,
            extra: vec![("bytes_per_prim".into(), memory_bytes as f64 / prims as f64)],
            ..IndexInfo::default()
        }
    }
}

/// Levels (root = 1, leaves counted as a level below their node) and leaf children.
fn shape(bvh: &CwBvh) -> (usize, usize) {
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
