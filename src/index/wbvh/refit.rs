//! Refitting the wide BVH to moved primitives ([`crate::index::Index::refit`]): the nodes, the
//! leaves and their order stay; the leaves' triangle copies are refreshed from the geometry and
//! every child box is recomputed bottom up (children follow their parent in the node array, in
//! the collapse's order and in every node layout, so one backward pass sees every child first). The parts that read the scene (the triangle
//! blocks and the leaves' boxes) run in parallel.

use super::node::WideNode;
use crate::geometry::Aabb;
use crate::geometry::triangle::lanes::TriangleBlock;
use crate::index::BuildError;
use crate::index::bvh::refit::leaf_bounds;
use crate::index::kit::box_tree::layout::children_after_parents;
use crate::index::kit::box_tree::leaves::{BLOCK_LANES, LeafStore};
use crate::index::kit::box_tree::node::Child;
use crate::scene::Geometry;
use rayon::prelude::*;

/// Most children of a wide node.
const MAX_WIDTH: usize = 8;

/// Refreshes the triangle copies of `store` from `geom` (a block's padding lanes repeat its
/// first triangle and id, as [`TriangleBlock::new`] pads them).
pub(super) fn refresh_blocks<G: Geometry>(
    geom: &G,
    store: &mut LeafStore,
    index: &str,
) -> Result<(), BuildError> {
    let LeafStore::Blocks(blocks) = store else {
        return Ok(());
    };
    blocks.par_iter_mut().try_for_each(|block| {
        let ids = block.ids;
        let tris = ids.map(|p| geom.block_triangle(p));
        let Some(tris) = tris.into_iter().collect::<Option<Vec<_>>>() else {
            return Err(BuildError::Failed {
                index: index.into(),
                message: "the moved scene is no longer triangles only: rebuild".into(),
            });
        };
        *block = TriangleBlock::new(&tris, &ids);
        Ok(())
    })
}

/// The box of leaf `leaf`'s primitives in `geom`.
fn leaf_box<G: Geometry>(
    geom: &G,
    store: &LeafStore,
    leaf: Child,
    index: &str,
) -> Result<Aabb, BuildError> {
    let (first, count) = (leaf.index as usize, leaf.count as usize);
    match store {
        LeafStore::Ids(ids) => leaf_bounds(geom, ids[first..first + count].iter().copied(), index),
        LeafStore::Blocks(blocks) => {
            // Every block of a leaf is full but the last, whose padding lanes come last.
            let end = first + count.div_ceil(BLOCK_LANES as usize);
            let ids = blocks[first..end].iter().flat_map(|b| b.ids).take(count);
            leaf_bounds(geom, ids, index)
        }
    }
}

/// Recomputes every child box of `nodes` from `geom` (after [`refresh_blocks`]) and returns
/// the root's box.
pub(super) fn refit_nodes<const C: usize, G: Geometry>(
    geom: &G,
    root: Child,
    nodes: &mut [WideNode<C>],
    store: &LeafStore,
    index: &str,
) -> Result<Aabb, BuildError> {
    if root.is_leaf() {
        return leaf_box(geom, store, root, index);
    }
    debug_assert!(
        children_after_parents(nodes),
        "the backward pass needs children last"
    );
    let leaf_boxes: Vec<[Aabb; MAX_WIDTH]> = nodes
        .par_iter()
        .map(|n| {
            let mut boxes = [Aabb::EMPTY; MAX_WIDTH];
            for (i, b) in boxes.iter_mut().enumerate().take(n.width()) {
                if n.child(i).is_leaf() {
                    *b = leaf_box(geom, store, n.child(i), index)?;
                }
            }
            Ok(boxes)
        })
        .collect::<Result<_, BuildError>>()?;
    let mut boxes = vec![Aabb::EMPTY; nodes.len()];
    for i in (0..nodes.len()).rev() {
        let width = nodes[i].width();
        let mut kids = [(Aabb::EMPTY, Child::default()); MAX_WIDTH];
        for (k, kid) in kids.iter_mut().enumerate().take(width) {
            let c = nodes[i].child(k);
            let b = match c.is_leaf() {
                true => leaf_boxes[i][k],
                false => boxes[c.index as usize],
            };
            *kid = (b, c);
        }
        nodes[i] = WideNode::new(&kids[..width]);
        boxes[i] = kids[..width]
            .iter()
            .fold(Aabb::EMPTY, |acc, (b, _)| acc.union(*b));
    }
    Ok(boxes[root.index as usize])
}

/// The SAH cost of the wide tree ([`crate::index::bvh::refit::sah_cost`]).
pub(super) fn sah_cost<const C: usize>(
    root: Child,
    root_bounds: Aabb,
    nodes: &[WideNode<C>],
    cost_ratio: f32,
) -> f64 {
    let children = nodes
        .iter()
        .flat_map(|n| (0..n.width()).map(move |i| (n.child(i), n.child_box(i))));
    crate::index::bvh::refit::sah_cost(root, root_bounds, children, cost_ratio)
}
