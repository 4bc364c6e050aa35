//! `obvhs-bvh2`: obvhs's binary BVH (PLOC build, reinsertion, leaf collapse) and its stack
//! traversal, with our kernel and our closest-hit order in the leaf callback.

use super::{ObvhsParams, culling_bound, obvhs_ray, prim_boxes};
use crate::geometry::{ClosestHit, Hit, Ray};
use crate::index::{BuildError, Index, IndexInfo, Stats};
use crate::scene::Geometry;
use obvhs::bvh2::{Bvh2, builder::build_bvh2, node::Bvh2Node};
use obvhs::ray::RayHit;
use std::time::Duration;

/// obvhs's `Bvh2` over the scene's primitive bounds.
#[derive(Clone)]
pub struct ObvhsBvh2 {
    bvh: Bvh2,
    depth: usize,
}

impl ObvhsBvh2 {
    /// Runs obvhs's traversal; `leaf` gets the scene ids of each visited leaf and the obvhs ray
    /// (whose `tmax` it may lower) and returns `false` to stop.
    #[inline(always)]
    fn traverse(&self, ray: &Ray, mut leaf: impl FnMut(&[u32], &mut obvhs::ray::Ray) -> bool) {
        let ids = &self.bvh.primitive_indices;
        let mut on_leaf = |node: &Bvh2Node, oray: &mut obvhs::ray::Ray, _: &mut RayHit| {
            let first = node.first_index as usize;
            leaf(&ids[first..first + node.prim_count as usize], oray)
        };
        let oray = obvhs_ray(ray, culling_bound(ray.t_max));
        let mut hit = RayHit::none();
        // As obvhs's own `ray_traverse`: a stack sized by the build's depth.
        obvhs::fast_stack!(u32, (96, 192), self.bvh.max_depth, stack, {
            self.bvh
                .ray_traverse_dynamic(&mut stack, oray, &mut hit, &mut on_leaf)
        });
    }
}

impl Index for ObvhsBvh2 {
    type Params = ObvhsParams;

    fn build<G: Geometry>(geom: &G, params: &ObvhsParams) -> Result<Self, BuildError> {
        let boxes = prim_boxes(geom, "obvhs-bvh2")?;
        let bvh = build_bvh2(
            &boxes,
            params.preset.build_params(),
            &mut Duration::default(),
        );
        let depth = bvh.depth(0);
        Ok(ObvhsBvh2 { bvh, depth })
    }

    #[inline]
    fn closest_hit<G: Geometry, S: Stats>(
        &self,
        geom: &G,
        ray: &Ray,
        stats: &mut S,
    ) -> Option<Hit> {
        let mut best = ClosestHit::new(ray.t_max);
        self.traverse(ray, |ids, oray| {
            stats.node_visit();
            for &prim in ids {
                stats.prim_test();
                if let Some(t) = geom.intersect(prim, ray, best.t()) {
                    best.offer(t, prim);
                    oray.tmax = culling_bound(best.t());
                }
            }
            true
        });
        best.get()
    }

    #[inline]
    fn any_hit<G: Geometry, S: Stats>(&self, geom: &G, ray: &Ray, stats: &mut S) -> bool {
        let mut found = false;
        self.traverse(ray, |ids, _| {
            stats.node_visit();
            found = ids.iter().any(|&prim| {
                stats.prim_test();
                geom.intersect(prim, ray, ray.t_max).is_some()
            });
            !found
        });
        found
    }

    fn info(&self) -> IndexInfo {
        let nodes = self.bvh.nodes.len();
        let prims = self.bvh.primitive_indices.len();
        let memory_bytes = nodes * size_of::<Bvh2Node>() + prims * 4;
        IndexInfo {
            nodes,
            leaves: self.bvh.nodes.iter().filter(|n| n.is_leaf()).count(),
            depth: self.depth,
            memory_bytes,
            prim_refs: prims,
            extra: vec![("bytes_per_prim".into(), memory_bytes as f64 / prims as f64)],
            ..IndexInfo::default()
        }
    }
}
