//! Refitting the binary BVH to moved primitives ([`crate::index::Index::refit`]): the nodes,
//! the leaves and the primitive ids stay; every child box is recomputed bottom up from the
//! primitives' new bounds.
//!
//! Children follow their parent in the node array (the build is depth first, and every node
//! layout keeps children after their parent: [`crate::index::kit::box_tree::layout`]), so one
//! backward pass sees every child before its parent. The leaves' boxes, the part that reads the scene,
//! are computed in parallel first. With spatial splits a leaf's box becomes its primitives'
//! whole bounds (no longer clipped): larger, still holding every point a ray can hit there, so
//! the hits are unchanged.

use crate::geometry::Aabb;
use crate::index::BuildError;
use crate::index::kit::box_tree::layout::children_after_parents;
use crate::index::kit::box_tree::node::{Child, Node};
use crate::scene::Geometry;
use rayon::prelude::*;

/// The union of the bounds of the primitives `prim_ids` names; an error naming the first
/// primitive whose bounds are not finite.
pub(crate) fn leaf_bounds<G: Geometry>(
    geom: &G,
    prim_ids: impl IntoIterator<Item = u32>,
    index: &str,
) -> Result<Aabb, BuildError> {
    prim_ids.into_iter().try_fold(Aabb::EMPTY, |acc, p| {
        let b = geom.bounds(p);
        match b.min.is_finite() && b.max.is_finite() {
            true => Ok(acc.union(b)),
            false => Err(BuildError::Failed {
                index: index.into(),
                message: format!(
                    "primitive {p} has non-finite bounds {b:?} after moving: remove NaN or \
                     infinite coordinates from the frame"
                ),
            }),
        }
    })
}

/// Refuses a geometry whose primitive count differs from the one the tree was built over.
pub(crate) fn check_same_count<G: Geometry>(
    geom: &G,
    built_over: usize,
    index: &str,
) -> Result<(), BuildError> {
    match geom.len() == built_over {
        true => Ok(()),
        false => Err(BuildError::Failed {
            index: index.into(),
            message: format!(
                "refit needs the primitives it was built over ({built_over}), got {}: rebuild \
                 for a scene whose primitives were added or removed",
                geom.len()
            ),
        }),
    }
}

/// Recomputes the boxes of `nodes` (children after parents, in any layout) and returns the
/// root's box.
pub(super) fn refit_nodes<G: Geometry>(
    geom: &G,
    root: Child,
    nodes: &mut [Node],
    prim_ids: &[u32],
) -> Result<Aabb, BuildError> {
    let leaf = |c: Child| {
        let ids = &prim_ids[c.index as usize..(c.index + c.count) as usize];
        leaf_bounds(geom, ids.iter().copied(), "bvh")
    };
    if root.is_leaf() {
        return leaf(root);
    }
    debug_assert!(
        children_after_parents(nodes),
        "the backward pass needs children last"
    );
    let leaf_boxes: Vec<[Aabb; 2]> = nodes
        .par_iter()
        .map(|n| {
            let [a, b] = n.children.map(|c| match c.is_leaf() {
                true => leaf(c),
                false => Ok(Aabb::EMPTY),
            });
            Ok([a?, b?])
        })
        .collect::<Result<_, BuildError>>()?;
    let mut boxes = vec![Aabb::EMPTY; nodes.len()];
    for i in (0..nodes.len()).rev() {
        let children = nodes[i].children;
        let kids = [0, 1].map(|k| match children[k].is_leaf() {
            true => leaf_boxes[i][k],
            false => boxes[children[k].index as usize],
        });
        nodes[i] = Node::new(kids, children);
        boxes[i] = kids[0].union(kids[1]);
    }
    Ok(boxes[root.index as usize])
}

/// Surface area heuristic cost of a flattened tree relative to its root's area, from every
/// child reference with its box (`children`): inner nodes cost `cost_ratio`, leaves their
/// primitive count, each weighted by its box's area. Shared by the binary and the wide trees.
pub(crate) fn sah_cost(
    root: Child,
    root_bounds: Aabb,
    children: impl Iterator<Item = (Child, Aabb)>,
    cost_ratio: f32,
) -> f64 {
    let area = root_bounds.surface_area() as f64;
    if area <= 0.0 {
        return 0.0;
    }
    let cost = |(c, b): (Child, Aabb)| {
        let per_area = match c.is_leaf() {
            true => c.count as f64,
            false => cost_ratio as f64,
        };
        per_area * b.surface_area() as f64
    };
    (cost((root, root_bounds)) + children.map(cost).sum::<f64>()) / area
}
