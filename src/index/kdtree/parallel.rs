//! The top of the kd-tree build: the two children of the nodes of the top levels are built in
//! parallel (`rayon::join`) into separate arrays, joined by shifting their links, so that the
//! tree is the one the sequential [`Builder::node`] makes (tested node for node).

use super::build::{Binning, Builder, Input, LOWER, Split, root_input, too_big};
use super::node::{KdNode, MAX_PAYLOAD};
use crate::geometry::Aabb;
use crate::index::BuildError;
use crate::index::build_budget::ensure_within;
use crate::index::kit::near_far::sweep::MAX_ITEM;
use crate::index::kit::near_far::{Built, SahParams};
use crate::scene::Geometry;

/// Builds the tree over all primitives of `geom` in the cell `root` (their bounds), with
/// classification padding `pad` (world units, > 0).
pub(super) fn build<G: Geometry>(
    geom: &G,
    root: Aabb,
    pad: f32,
    costs: &SahParams,
    binning: Binning,
) -> Result<Built<KdNode>, BuildError> {
    if geom.len() > MAX_ITEM as usize {
        return Err(too_big("primitives"));
    }
    let input = root_input(geom, pad, binning);
    let top = Top {
        geom,
        costs,
        binning,
        pad,
    };
    top.subtree(input, geom.len(), root, 0, PARALLEL)
}

/// Which nodes build their two children in parallel (`rayon::join`): those of the top `levels`
/// levels with at least `min_prims` primitives.
#[derive(Debug, Clone, Copy)]
pub(super) struct Parallel {
    pub levels: u32,
    pub min_prims: usize,
}

/// Up to `2^6` tasks, enough to keep a few cores busy while the sequential subtrees stay large.
const PARALLEL: Parallel = Parallel {
    levels: 6,
    min_prims: 2048,
};

/// What every task of the build shares.
pub(super) struct Top<'a, G: Geometry> {
    pub geom: &'a G,
    pub costs: &'a SahParams,
    pub binning: Binning,
    pub pad: f32,
}

impl<G: Geometry> Clone for Top<'_, G> {
    fn clone(&self) -> Self {
        *self
    }
}

impl<G: Geometry> Copy for Top<'_, G> {}

impl<G: Geometry> Top<'_, G> {
    /// Builds the subtree of `cell` over its `n` references `input` (`depth` of its root),
    /// splitting the work into two `rayon::join` tasks as `par` says. The tree is the one the
    /// sequential [`Builder::node`] makes: the same choices, the same depth-first layout
    /// ([`join_subtrees`] only shifts the links of each part).
    pub fn subtree(
        self,
        input: Input,
        n: usize,
        cell: Aabb,
        depth: u32,
        par: Parallel,
    ) -> Result<Built<KdNode>, BuildError> {
        let mut b = Builder::new(self.geom, self.costs, self.binning, self.pad);
        if par.levels == 0 || n < par.min_prims {
            b.node(input, n, cell, depth)?;
            return Ok(b.into_built());
        }
        let (axis, s, below, above) = match b.split(input, n, cell, depth) {
            Split::Leaf(events) => {
                b.leaf(events, depth)?;
                return Ok(b.into_built());
            }
            Split::Node {
                axis,
                s,
                below,
                above,
            } => (axis, s, below, above),
        };
        drop(b);
        let par = Parallel {
            levels: par.levels - 1,
            ..par
        };
        let part = |(input, n, cell)| self.subtree(input, n, cell, depth + 1, par);
        let (below, above) = rayon::join(|| part(below), || part(above));
        join_subtrees(axis, s, below?, above?)
    }
}

/// The tree of an interior node on `axis` at `s` over its two built subtrees: the node, then
/// the subtree below (links shifted by one node), then the one above (links shifted by the
/// nodes and ids before it).
fn join_subtrees(
    axis: usize,
    s: f32,
    below: Built<KdNode>,
    above: Built<KdNode>,
) -> Result<Built<KdNode>, BuildError> {
    let above_at = 1 + below.nodes.len();
    if (above_at + above.nodes.len()) as u64 > MAX_PAYLOAD as u64 + 1 {
        return Err(too_big("nodes"));
    }
    // The joined arrays are made while both parts are still held.
    let joined = (above_at + above.nodes.len()) * size_of::<KdNode>()
        + (below.ids.len() + above.ids.len()) * size_of::<u32>();
    ensure_within("kdtree", joined, LOWER)?;
    if below.ids.len() + above.ids.len() > u32::MAX as usize {
        return Err(too_big("primitive references"));
    }
    let mut nodes = Vec::with_capacity(above_at + above.nodes.len());
    nodes.push(KdNode::interior(axis, s, above_at as u32));
    nodes.extend(below.nodes.iter().map(|n| n.shifted(1, 0)));
    let (node_shift, id_shift) = (above_at as u32, below.ids.len() as u32);
    nodes.extend(above.nodes.iter().map(|n| n.shifted(node_shift, id_shift)));
    let mut ids = below.ids;
    ids.extend(above.ids);
    Ok(Built {
        nodes,
        ids,
        refs: below.refs + above.refs,
        depth: below.depth.max(above.depth),
        leaves: below.leaves + above.leaves,
        empty_leaves: below.empty_leaves + above.empty_leaves,
        extra: Vec::new(),
    })
}
