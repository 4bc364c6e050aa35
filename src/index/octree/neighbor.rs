//! Neighbor traversal ("trace rays through neighbor cells"): find the leaf holding the ray's
//! entry point, test it, compute where and through which face the ray leaves it, follow that
//! face's rope to the deepest node covering that face, and descend it to the leaf holding the ray at
//! the exit parameter. Edges and corners need no special case: the ray leaves through one of the
//! tied faces, and the descent, which already counts the other tied planes as crossed, lands in
//! the diagonal cell (or, when the neighbour is not split there, in a cell the ray leaves again
//! at the same `t`).
//!
//! Termination: every step crosses a face in the ray's direction and the descent follows the
//! monotone per-axis rule of [`AxisRay`], so a leaf is never entered twice.

use super::LeafOrder;
use super::axis_ray::AxisRay;
use super::tree::{NO_ROPE, OctreeTree, face};
use crate::geometry::Ray;
use crate::index::Stats;

/// Leaf order by neighbour links (ropes, Havran-style, precomputed at build time).
#[derive(Debug, Clone, Copy, Default)]
pub struct Neighbor;

/// The leaf below `node` that holds the ray at parameter `t`.
#[inline(always)]
fn locate<S: Stats>(tree: &OctreeTree, r: &AxisRay, mut node: u32, t: f32, stats: &mut S) -> u32 {
    loop {
        stats.node_visit();
        let n = &tree.nodes[node as usize];
        if n.is_leaf() {
            return node;
        }
        let mid = tree.nodes[n.first as usize].max();
        node = n.child(r.child_at(mid, t));
    }
}

impl LeafOrder for Neighbor {
    #[inline]
    fn for_each_leaf<S: Stats>(
        tree: &OctreeTree,
        ray: &Ray,
        enter: f32,
        stats: &mut S,
        mut visit: impl FnMut(&[u32], &mut S) -> f32,
    ) {
        let r = AxisRay::new(ray);
        let mut t = enter;
        let mut leaf = locate(tree, &r, 0, t, stats);
        let mut cutoff = ray.t_max;
        loop {
            let prims = tree.leaf_prims_within(leaf, ray, cutoff, stats);
            if !prims.is_empty() {
                cutoff = visit(prims, stats);
            }
            let node = &tree.nodes[leaf as usize];
            let (exit, axis, upper) = r.exit(&node.cell());
            if cutoff <= exit {
                return;
            }
            let next = node.ropes[face(axis, upper)];
            if next == NO_ROPE {
                return;
            }
            t = t.max(exit);
            leaf = locate(tree, &r, next, t, stats);
        }
    }
}
