//! Top-down parametric traversal (Revelles, Ureña and Lastra 2000, "An efficient parametric
//! algorithm for octree traversal"): recursion from the root, visiting the children a ray meets
//! in ray order, using only the slab parameters `t0`, `t1` of each node and `tm` of its splits.
//!
//! Differences from the paper, all in the direction of robustness: `tm` is computed from the
//! stored split plane rather than as `(t0 + t1) / 2`, so it agrees bit for bit with the neighbor
//! traversal's rule; zero direction components need no mirroring (see [`AxisRay`]); the first
//! child is the one holding the ray at `max(entry, t_start)`, so rays that start inside the
//! octree skip the children behind them; and the next-child step is derived from the exit axis
//! ([`next_child`]) instead of the paper's table, whose published version has the X and Z
//! columns swapped (see the erratum; the unit test checks the corrected table).

use super::LeafOrder;
use super::axis_ray::{AxisRay, mask_of};
use super::tree::{OctreeTree, octant_bit};
use crate::geometry::Ray;
use crate::index::Stats;
use glam::Vec3A;

/// Leaf order by the top-down parametric recursion of Revelles et al.
#[derive(Debug, Clone, Copy, Default)]
pub struct TopDown;

/// The normalized child the ray enters after leaving child `c` through its far face on `axis`,
/// or `None` when that face is the parent's (the ray leaves the parent).
#[inline(always)]
pub(super) fn next_child(c: usize, axis: usize) -> Option<usize> {
    let bit = octant_bit(axis);
    (c & bit == 0).then_some(c | bit)
}

/// The ray as given, its axis form, and the cutoff so far (the last value `visit` returned,
/// initially `t_max`).
struct Walk<'a> {
    ray: &'a Ray,
    r: AxisRay,
    cutoff: f32,
}

/// Walks the subtree `node` whose slab parameters are `t0`, `t1`; returns `true` to stop.
fn descend<S: Stats>(
    tree: &OctreeTree,
    w: &mut Walk<'_>,
    node: u32,
    (t0, t1): (Vec3A, Vec3A),
    t_start: f32,
    stats: &mut S,
    visit: &mut impl FnMut(&[u32], &mut S) -> f32,
) -> bool {
    let exit = t1.min_element();
    if exit < t_start {
        return false;
    }
    stats.node_visit();
    let n = &tree.nodes[node as usize];
    if n.is_leaf() {
        let prims = tree.leaf_prims_within(node, w.ray, w.cutoff, stats);
        if !prims.is_empty() {
            w.cutoff = visit(prims, stats);
        }
        return w.cutoff <= exit;
    }
    // An unsplit axis reads as split at the cell's near face: the ray is beyond it from the
    // start (its octant bit is set), the children's slabs on that axis are the node's, and
    // crossing the far face leaves the node.
    let split = mask_of(n.split as usize);
    let tm = Vec3A::select(
        split,
        w.r.mid_crossings(tree.nodes[n.first as usize].max()),
        t0,
    );
    let mut c = AxisRay::octant_at(tm, t0.max_element().max(t_start));
    loop {
        let upper = mask_of(c);
        let ct0 = Vec3A::select(upper, tm, t0);
        let ct1 = Vec3A::select(upper, t1, tm);
        let child = n.child(c ^ w.r.mask);
        if descend(tree, w, child, (ct0, ct1), t_start, stats, visit) {
            return true;
        }
        // Leave through the lowest tied axis that stays inside this node (visiting cells of
        // zero length at edges and corners rather than skipping them).
        let t = ct1.min_element();
        match (0..3)
            .filter(|&a| ct1[a] == t)
            .find_map(|a| next_child(c, a))
        {
            Some(next) => c = next,
            None => return false,
        }
    }
}

impl LeafOrder for TopDown {
    #[inline]
    fn for_each_leaf<S: Stats>(
        tree: &OctreeTree,
        ray: &Ray,
        enter: f32,
        stats: &mut S,
        mut visit: impl FnMut(&[u32], &mut S) -> f32,
    ) {
        let r = AxisRay::new(ray);
        let mut w = Walk {
            ray,
            r,
            cutoff: ray.t_max,
        };
        let slabs = r.slabs(&tree.root_cell());
        descend(tree, &mut w, 0, slabs, enter, stats, &mut visit);
    }
}
