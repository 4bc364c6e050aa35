//! Wide BVHs (`bvh4`, `bvh8`): the binary SAH tree of [`Bvh`] collapsed into nodes of up to 4
//! or 8 children whose boxes are tested together, four per SIMD slab pass, front-to-back
//! closest hit with early termination, and any-hit.
//!
//! - `node`: the node layout and the collapse; `traverse`: the node step of the traversal loop
//!   shared with the binary BVH (`kit::box_tree::walk`).
//! - The parameters are the binary BVH's ([`BvhParams`]): the leaves are its leaves. With its
//!   spatial splits a primitive may be in several leaves (a merged leaf may even name it
//!   twice): every copy returns the same `t` for the same id, so the hits do not change.
//! - Leaves of triangle-only scenes hold copies of their triangles in blocks of four, tested
//!   lane-wise by the kernel's lane form; other scenes' leaves hold primitive ids
//!   ([`LeafStore`], shared with the binary BVH).

mod node;
mod packet;
mod refit;
mod traverse;

use crate::geometry::{Aabb, Ray};
use crate::index::bvh::{Bvh, BvhParams};
use crate::index::kit::box_tree::layout;
use crate::index::kit::box_tree::leaves::{BLOCK_LANES, LeafStore};
use crate::index::kit::box_tree::node::Child;
use crate::index::kit::box_tree::{stream, tree, walk};
use crate::index::kit::huge_pages::huge_page_vec;
use crate::index::{BatchIndex, BuildError, HitQuery, Index, IndexInfo, Stats};
use crate::scene::Geometry;
use node::{WideNode, collapse};

/// A BVH whose nodes hold up to `4 * C` children (`C` = 1 or 2).
#[derive(Debug, Clone)]
pub struct WideBvh<const C: usize> {
    root_bounds: Aabb,
    root: Child,
    nodes: Vec<WideNode<C>>,
    leaf_store: LeafStore,
    /// Primitive ids in the leaves (with spatial splits, more than `prims`).
    prim_refs: usize,
    /// Primitives of the scene.
    prims: usize,
    leaves: usize,
    depth: u32,
    /// SAH cost of the tree ([`refit::sah_cost`]), a quality figure; recomputed by a refit.
    sah_cost: f64,
    /// The build's cost of a node visit relative to a primitive test, for the SAH cost.
    cost_ratio: f32,
}

/// Four children per node.
pub type Bvh4 = WideBvh<1>;
/// Eight children per node.
pub type Bvh8 = WideBvh<2>;

impl<const C: usize> Index for WideBvh<C> {
    type Params = BvhParams;

    fn build<G: Geometry>(geom: &G, params: &BvhParams) -> Result<Self, BuildError> {
        const { assert!(C == 1 || C == 2, "the traversal's buffers hold 8 children") };
        // Triangle-block leaves test four triangles at the cost of one: the SAH counts
        // triangles in blocks of four and the collapse merges subtrees of up to four; id leaves
        // test one primitive at a time: plain counts, the binary tree's leaves.
        let blocks = (0..geom.len() as u32).all(|p| geom.block_triangle(p).is_some());
        let leaf_lanes = if blocks { BLOCK_LANES } else { 1 };
        let binary = Bvh::build_tree(geom, params, leaf_lanes)?;
        let (root_bounds, root, nodes, prim_ids) = binary.parts();
        let tris = LeafStore::block_triangles(geom, prim_ids);
        let mut wide = collapse::<C>(root, nodes, leaf_lanes);
        // Before the leaf store: triangle blocks are stored in the order their leaves are met
        // here, so they follow the node order too.
        layout::apply(params.layout, &mut wide.root, &mut wide.nodes);
        let leaf_refs = wide.nodes.iter_mut().flat_map(|n| {
            let kids = n.width();
            n.children.iter_mut().flatten().take(kids)
        });
        let root_ref = Some(&mut wide.root);
        let leaf_store = LeafStore::new(
            prim_ids.to_vec(),
            tris,
            root_ref
                .into_iter()
                .chain(leaf_refs)
                .filter(|c| c.is_leaf()),
        );
        let cost_ratio = params.config()?.cost_ratio;
        let sah_cost = refit::sah_cost(wide.root, root_bounds, &wide.nodes, cost_ratio);
        Ok(WideBvh {
            root_bounds,
            root: wide.root,
            nodes: huge_page_vec(wide.nodes),
            leaf_store,
            prim_refs: prim_ids.len(),
            prims: geom.len(),
            leaves: wide.leaves,
            depth: wide.depth,
            sah_cost,
            cost_ratio,
        })
    }

    #[inline]
    fn query<Q: HitQuery, G: Geometry, S: Stats>(&self, g: &G, r: &Ray, s: &mut S) -> Q::Answer {
        walk::query::<Q, _, _, _, _>(&self.tree(), g, r, s)
    }

    const REFIT: bool = true;

    /// Triangle copies refreshed, bounds recomputed bottom up ([`refit`]); nodes and leaves
    /// kept.
    fn refit<G: Geometry>(&mut self, geom: &G) -> Result<(), BuildError> {
        let name = if C == 1 { "bvh4" } else { "bvh8" };
        crate::index::bvh::refit::check_same_count(geom, self.prims, name)?;
        refit::refresh_blocks(geom, &mut self.leaf_store, name)?;
        self.root_bounds =
            refit::refit_nodes(geom, self.root, &mut self.nodes, &self.leaf_store, name)?;
        self.sah_cost = refit::sah_cost(self.root, self.root_bounds, &self.nodes, self.cost_ratio);
        Ok(())
    }

    /// About 300 B per primitive measured (the binary tree, then the wide copy and leaf
    /// blocks; soup, bunny, icosphere), with a margin.
    fn estimated_build_bytes(prims: usize, params: &BvhParams) -> Option<usize> {
        params.estimated_build_bytes(prims, 330)
    }

    fn info(&self) -> IndexInfo {
        let memory_bytes = size_of::<Aabb>()
            + self.nodes.len() * size_of::<WideNode<C>>()
            + self.leaf_store.bytes();
        let children: usize = self.nodes.iter().map(WideNode::width).sum();
        IndexInfo {
            nodes: self.nodes.len() + self.leaves,
            leaves: self.leaves,
            depth: self.depth as usize,
            memory_bytes,
            prim_refs: self.prim_refs,
            extra: vec![
                (
                    "bytes_per_prim".into(),
                    memory_bytes as f64 / self.prims as f64,
                ),
                ("leaf_blocks".into(), self.leaf_store.blocks() as f64),
                (
                    "children_per_node".into(),
                    children as f64 / self.nodes.len().max(1) as f64,
                ),
                ("sah_cost".into(), self.sah_cost),
            ],
            ..IndexInfo::default()
        }
    }
}

impl<const C: usize> BatchIndex for WideBvh<C> {
    crate::index::kit::box_tree::packet::tree_packets!();
    crate::index::kit::box_tree::beam::tree_beams!();

    const STREAM: bool = true;

    /// Several walks at a time: chunks of camera-like rays in lockstep pairs of neighbours,
    /// other chunks three walks at a time, each refilled as it finishes ([`stream::coherent`],
    /// [`stream::closest_hits_lockstep`], [`stream::closest_hits_interleaved`]).
    fn closest_hits_stream<G: Geometry, S: Stats>(
        &self,
        geom: &G,
        rays: &[crate::geometry::Ray],
        out: &mut [Option<crate::geometry::Hit>],
        stats: &mut [S],
    ) {
        match stream::coherent(rays) {
            true => stream::closest_hits_lockstep(&self.tree(), geom, rays, out, stats),
            false => stream::closest_hits_interleaved(&self.tree(), geom, rays, out, stats),
        }
    }
}

impl<const C: usize> WideBvh<C> {
    #[inline(always)]
    fn tree(&self) -> traverse::Tree<'_, C> {
        traverse::Tree {
            top: tree::Top {
                root_bounds: &self.root_bounds,
                root: self.root,
                leaves: self.leaf_store.leaves(),
            },
            nodes: &self.nodes,
        }
    }

    /// How many nodes have each number of children (index = children) and how many leaves have
    /// each number of primitives (index = primitives, capped at the last slot), for tests.
    pub fn shape_histograms(&self) -> (Vec<usize>, Vec<usize>) {
        let mut kids = vec![0; 4 * C + 1];
        let mut leaf_sizes = vec![0; 65];
        let mut leaf = |c: Child| leaf_sizes[(c.count as usize).min(64)] += 1;
        if self.root.is_leaf() {
            leaf(self.root);
        }
        for n in &self.nodes {
            kids[n.width()] += 1;
            for i in 0..n.width() {
                let c = n.child(i);
                if c.is_leaf() {
                    leaf(c);
                }
            }
        }
        (kids, leaf_sizes)
    }
}

#[cfg(test)]
#[path = "layout_tests.rs"]
mod layout_tests;
