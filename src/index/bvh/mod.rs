//! A bounding volume hierarchy: top-down SAH build (binned or full sweep), 64-byte depth-first
//! inner nodes holding both children's boxes, front-to-back closest-hit traversal with early
//! termination, and any-hit.
//!
//! - [`params`]: presets and overrides; `build`: the builder (straight into the node array),
//!   with the SAH split finders in `binned` and `sweep`, and the spatial splits (SBVH, an
//!   option) in `spatial`; `traverse`: the node step; `packet`: the node's side of the packet
//!   walk. The node layout, the slab tests, the traversal loops, the leaves and the packet walk
//!   are the box-tree kit's ([`crate::index::kit::box_tree`]), shared with the wide BVH, and so
//!   are the node orders of the `layout` parameter ([`layout`]: the finished node array
//!   reordered in memory, depth first, van Emde Boas or treelets).
//! - The BVH holds its nodes and the primitive ids in leaf order. The scene's primitives are not
//!   reordered (their ids are the hit contract), so a leaf reads a contiguous run of ids. With
//!   spatial splits an id may occur in several leaves; the hits stay exact (see `spatial`).

mod binned;
mod build;
mod packet;
pub mod params;
mod prim_ref;
pub(crate) mod refit;
mod spatial;
mod sweep;
mod traverse;

pub use build::MAX_DEPTH;
use params::BuildConfig;
pub use params::{BvhParams, Preset, SplitMethod};

use crate::geometry::{Aabb, Ray};
use crate::index::kit::box_tree::node::{Child, Node};
use crate::index::kit::box_tree::{layout, leaves, tree, walk};
use crate::index::kit::huge_pages::huge_page_vec;
use crate::index::{BatchIndex, BuildError, HitQuery, Index, IndexInfo, Stats};
use crate::scene::Geometry;
use prim_ref::PrimRef;
use rayon::prelude::*;

/// The built BVH.
#[derive(Debug, Clone)]
pub struct Bvh {
    root_bounds: Aabb,
    root: Child,
    nodes: Vec<Node>,
    prim_ids: Vec<u32>,
    leaves: usize,
    depth: u32,
    /// Primitives of the scene (with spatial splits, fewer than `prim_ids`).
    prims: usize,
    /// SAH cost of the tree (expected node visits times the cost ratio plus primitive tests,
    /// for a ray that hits the root box), a quality figure for reports; recomputed by a refit.
    sah_cost: f64,
    /// The build's cost of a node visit relative to a primitive test, for the SAH cost.
    cost_ratio: f32,
}

impl Index for Bvh {
    type Params = BvhParams;

    fn build<G: Geometry>(geom: &G, params: &BvhParams) -> Result<Self, BuildError> {
        let mut bvh = Bvh::build_tree(geom, params, 1)?;
        layout::apply(params.layout, &mut bvh.root, &mut bvh.nodes);
        bvh.nodes = huge_page_vec(bvh.nodes);
        bvh.prim_ids = huge_page_vec(bvh.prim_ids);
        Ok(bvh)
    }

    #[inline]
    fn query<Q: HitQuery, G: Geometry, S: Stats>(&self, g: &G, r: &Ray, s: &mut S) -> Q::Answer {
        walk::query::<Q, _, _, _, _>(&self.tree(), g, r, s)
    }

    /// About 200 B per primitive measured (soup, bunny, icosphere), with a margin.
    fn estimated_build_bytes(prims: usize, params: &BvhParams) -> Option<usize> {
        params.estimated_build_bytes(prims, 230)
    }

    const REFIT: bool = true;

    /// Bounds recomputed bottom up ([`refit`]); nodes, leaves and ids kept.
    fn refit<G: Geometry>(&mut self, geom: &G) -> Result<(), BuildError> {
        refit::check_same_count(geom, self.prims, "bvh")?;
        self.root_bounds = refit::refit_nodes(geom, self.root, &mut self.nodes, &self.prim_ids)?;
        self.sah_cost = sah_cost(self.root, self.root_bounds, &self.nodes, self.cost_ratio);
        Ok(())
    }

    fn info(&self) -> IndexInfo {
        let memory_bytes =
            size_of::<Aabb>() + self.nodes.len() * size_of::<Node>() + self.prim_ids.len() * 4;
        IndexInfo {
            nodes: self.nodes.len() + self.leaves,
            leaves: self.leaves,
            depth: self.depth as usize,
            memory_bytes,
            prim_refs: self.prim_ids.len(),
            extra: vec![
                (
                    "bytes_per_prim".into(),
                    memory_bytes as f64 / self.prims as f64,
                ),
                ("sah_cost".into(), self.sah_cost),
            ],
            ..IndexInfo::default()
        }
    }
}

impl BatchIndex for Bvh {
    crate::index::kit::box_tree::packet::tree_packets!();
    crate::index::kit::box_tree::beam::tree_beams!();
}

impl Bvh {
    /// The tree in ordinary memory: what [`Index::build`] builds before it moves the arrays to
    /// huge pages ([`huge_page_vec`]), and what the wide BVH collapses (it keeps only its own
    /// arrays). The SAH counts primitives in blocks of `sah_block` (see
    /// [`params::BuildConfig::sah_block`]; 1 for `bvh`).
    pub(crate) fn build_tree<G: Geometry>(
        geom: &G,
        params: &BvhParams,
        sah_block: u32,
    ) -> Result<Bvh, BuildError> {
        let cfg = BuildConfig {
            sah_block,
            ..params.config()?
        };
        if geom.is_empty() {
            return Err(BuildError::EmptyScene);
        }
        let failed = |message: String| BuildError::Failed {
            index: "bvh".into(),
            message,
        };
        let len = u32::try_from(geom.len())
            .map_err(|_| failed(format!("{} primitives exceed u32 ids", geom.len())))?;
        let refs: Vec<PrimRef> = (0..len)
            .into_par_iter()
            .map(|id| PrimRef::new(geom.bounds(id), id))
            .collect();
        if let Some(bad) = refs
            .iter()
            .find(|r| !(r.min().is_finite() && r.max().is_finite()))
        {
            return Err(failed(format!(
                "primitive {} has non-finite bounds {:?}: remove NaN or infinite coordinates",
                bad.id(),
                bad.bounds()
            )));
        }
        let clip: &dyn spatial::Clip = geom;
        let built = build::build(refs, &cfg, cfg.spatial_splits.then_some(clip));
        let sah_cost = sah_cost(built.root, built.root_bounds, &built.nodes, cfg.cost_ratio);
        Ok(Bvh {
            root_bounds: built.root_bounds,
            root: built.root,
            nodes: built.nodes,
            prim_ids: built.prim_ids,
            leaves: built.leaves,
            depth: built.depth,
            prims: geom.len(),
            sah_cost,
            cost_ratio: cfg.cost_ratio,
        })
    }

    /// The root's box and reference, the inner nodes and the primitive ids in leaf order (for
    /// the wide BVH, which collapses this tree).
    pub(crate) fn parts(&self) -> (Aabb, Child, &[Node], &[u32]) {
        (self.root_bounds, self.root, &self.nodes, &self.prim_ids)
    }

    #[inline(always)]
    fn tree(&self) -> traverse::Tree<'_> {
        traverse::Tree {
            top: tree::Top {
                root_bounds: &self.root_bounds,
                root: self.root,
                leaves: leaves::Leaves::Ids(&self.prim_ids),
            },
            nodes: &self.nodes,
        }
    }
}

/// The SAH cost of the binary tree ([`refit::sah_cost`]).
fn sah_cost(root: Child, root_bounds: Aabb, nodes: &[Node], cost_ratio: f32) -> f64 {
    let children = nodes
        .iter()
        .flat_map(|n| (0..2).map(move |i| (n.children[i], n.child_bounds(i))));
    refit::sah_cost(root, root_bounds, children, cost_ratio)
}
