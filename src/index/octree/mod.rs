//! Octree over the scene's bounds with two traversals of the same tree: neighbor links
//! ([`Neighbor`], registered as `octree`) and the top-down parametric recursion of Revelles et
//! al. 2000 ([`TopDown`], `octree-topdown`). Both take [`OctreeParams`].
//!
//! A node splits the axes where a split pays, at a point placed by the surface area heuristic
//! (`place.rs`), into 2, 4 or 8 children; on a flat or boxy scene this cuts empty space off in
//! one step instead of a chain of ever smaller empty octants toward the surface.
//!
//! # Why stopping at the current leaf's exit is exact
//!
//! Both traversals visit leaves in increasing order of their interval on the `t` line (see the
//! crossing rule in `axis_ray.rs`): when the leaf with interval `[enter, exit]` is done, every
//! leaf the ray meets at parameters up to `exit` has been visited. A primitive is listed in
//! every leaf its conservative overlap test accepts, and that test pads the cell by
//! [`OVERLAP_PAD`](crate::geometry::overlap::OVERLAP_PAD) of its largest coordinate, so a
//! primitive that touches a leaf, or comes within the padding of it, is stored there.
//!
//! Traversal stops when the best hit so far has `t_best <= exit`. Any primitive that could still
//! win has `t <= t_best` (a smaller `t`, or the same `t` and a lower id): its hit point
//! `ray.at(t)` lies at a parameter `<= exit`, hence in a visited leaf or on its boundary (the
//! cell is closed, so a tie at exactly `exit` is included). The kernel's point lies on the
//! primitive up to rounding, and the computed `exit` and the cell planes differ from the exact
//! ones by rounding only, both far below the overlap padding, so the primitive is stored in a
//! visited leaf and was already tested. Ties at equal `t` therefore resolve to the lowest id as
//! in brute force, and `t` itself is the kernel's own value (the geometry's `t` does not depend
//! on the `t_max` passed in). The stop is `<=`, not `<`, only because of that closedness.
//!
//! The rounding argument needs the ray's origin within roughly a hundred scene sizes of the
//! scene (the padding is 1e-5 of the largest coordinate, `f32` rounding 6e-8 of the distance
//! travelled); the protocol's ray sets and the agreement tests stay well within that.
//!
//! Each primitive is tested at most once per ray through the shared per-thread
//! [`mailbox`](crate::index::kit::mailbox): a primitive rejected once stays rejected, because the
//! best `t` only shrinks.

mod axis_ray;
mod build;
mod neighbor;
mod place;
mod topdown;
mod tree;

#[cfg(test)]
mod tests;

pub use build::{MAX_DEPTH_LIMIT, MAX_NODES, OctreeParams};
pub use neighbor::Neighbor;
pub use place::MIN_SIDE_IN_PADS;
pub use topdown::TopDown;
pub use tree::OctreeTree;

use crate::geometry::Ray;
use crate::index::kit::cell_walk::{CellVisit, CellWalk, cell_walk_index};
use crate::index::{BatchIndex, BuildError, Index, IndexInfo, Stats};
use crate::scene::Geometry;
use std::marker::PhantomData;

/// An order in which a traversal hands the leaves a ray meets to `visit`.
///
/// Contract: leaves come in increasing order of their `t` interval along the ray, starting with
/// the leaf that holds the ray at `enter`, its entry into the root (clipped to `ray.t_min`,
/// computed and counted as one box test by the caller). `visit`
/// returns the current cutoff (the best `t`, or `-inf` to stop at once; `ray.t_max` before the
/// first call); the walk stops after a leaf whose exit parameter is `>=` the cutoff, or when the
/// ray leaves the octree. A leaf whose content box the ray misses within `[t_min, cutoff]` is
/// not handed to `visit` (exact: see `OctreeTree::leaf_prims_within`).
pub trait LeafOrder: Send + Sync + 'static {
    fn for_each_leaf<S: Stats>(
        tree: &OctreeTree,
        ray: &Ray,
        enter: f32,
        stats: &mut S,
        visit: impl FnMut(&[u32], &mut S) -> f32,
    );
}

/// The octree with leaf order `O`.
#[derive(Debug, Clone)]
pub struct Octree<O: LeafOrder> {
    tree: OctreeTree,
    order: PhantomData<O>,
}

/// `octree`: traversal through neighbour links.
pub type NeighborOctree = Octree<Neighbor>;
/// `octree-topdown`: the Revelles et al. top-down traversal.
pub type TopDownOctree = Octree<TopDown>;

impl<O: LeafOrder> Octree<O> {
    /// The tree (cells, for tests that aim rays at cell corners and edges).
    pub fn tree(&self) -> &OctreeTree {
        &self.tree
    }
}

/// The leaves in the traversal's order (exact: see the module documentation).
impl<O: LeafOrder> CellWalk for Octree<O> {
    #[inline(always)]
    fn for_each_cell<S: Stats>(&self, ray: &Ray, stats: &mut S, visit: impl CellVisit<S>) {
        stats.box_tests(1);
        let root = self.tree.root_cell();
        if let Some((enter, _)) = root.ray_interval(ray, ray.t_min, ray.t_max) {
            O::for_each_leaf(&self.tree, ray, enter, stats, visit);
        }
    }
}

impl<O: LeafOrder> Index for Octree<O> {
    type Params = OctreeParams;

    fn build<G: Geometry>(geom: &G, params: &OctreeParams) -> Result<Self, BuildError> {
        Ok(Octree {
            tree: OctreeTree::build(geom, params)?,
            order: PhantomData,
        })
    }

    // The build's peak heap a primitive: about 160 B measured (soup, bunny, icosphere), with a
    // margin; the build checks the budget at every node too.
    cell_walk_index!(175);

    fn info(&self) -> IndexInfo {
        let t = &self.tree;
        let leaves = t.leaves();
        IndexInfo {
            nodes: t.nodes.len(),
            leaves,
            depth: t.max_level + 1,
            memory_bytes: t.memory_bytes(),
            prim_refs: t.prim_ids.len(),
            extra: vec![
                ("empty_leaves".into(), t.empty_leaves() as f64),
                (
                    "empty_leaf_fraction".into(),
                    t.empty_leaves() as f64 / leaves as f64,
                ),
                (
                    "refs_per_prim".into(),
                    t.prim_ids.len() as f64 / t.prim_count as f64,
                ),
            ],
            ..IndexInfo::default()
        }
    }
}

impl<O: LeafOrder> BatchIndex for Octree<O> {}
