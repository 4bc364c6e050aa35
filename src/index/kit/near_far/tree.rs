//! The one index type of the binary space partitions: nodes of a [`Partition`] node type in
//! depth-first order, one id array the leaves index, and the root cell's box. The kd-tree and
//! the BSP differ only in their node type, parameters and builder.

use super::walk::{self, SplitNode};
use super::{MAX_TREE_DEPTH, default_max_depth, scene_bounds, scene_pad};
use crate::geometry::{Aabb, Ray};
use crate::index::build_budget::per_primitive;
use crate::index::kit::huge_pages::huge_page_vec;
use crate::index::{BatchIndex, BuildError, HitQuery, Index, IndexInfo, Stats};
use crate::scene::Geometry;
use serde::Serialize;
use serde::de::DeserializeOwned;
use std::fmt::Debug;

/// A node type together with its parameters and builder.
pub trait Partition: SplitNode {
    /// The index's registry name (for error messages).
    const NAME: &'static str;
    /// The build's peak heap per primitive for the estimate
    /// ([`Index::estimated_build_bytes`]), in bytes: on scenes whose primitives are split into
    /// a few references each (the generated soup and icosphere, the bunny), with a margin.
    const BUILD_BYTES_PER_PRIM: usize;
    /// Typed build parameters (as [`Index::Params`]).
    type Params: Default + Clone + Debug + Serialize + DeserializeOwned + Send + Sync;
    /// Builds the nodes over all primitives of `geom` in the cell `root` (their bounds), with
    /// classification padding `pad` (world units, > 0).
    fn build<G: Geometry>(
        geom: &G,
        params: &Self::Params,
        root: Aabb,
        pad: f32,
    ) -> BuildResult<Self>;
    /// Whether the walk keeps a mailbox (each primitive tested at most once per ray) with
    /// these parameters.
    fn mailbox(params: &Self::Params) -> bool;

    /// A leaf's `(first, count)` (for a one-primitive leaf, `first` is the primitive's id; else
    /// the first slot of its run in the id array), or `None` for an interior node.
    fn leaf(&self) -> Option<(u32, u32)>;
}

/// The [`Partition`] methods of a node type whose parameters have a `mailbox: bool` field and
/// whose `kind()` is an enum `$kind` with a `Leaf { first, count }` variant: the flag, and
/// that variant's range.
macro_rules! leaf_and_mailbox {
    ($kind:ident) => {
        fn mailbox(params: &Self::Params) -> bool {
            params.mailbox
        }

        fn leaf(&self) -> Option<(u32, u32)> {
            match self.kind() {
                $kind::Leaf { first, count } => Some((first, count)),
                $kind::Interior { .. } => None,
            }
        }
    };
}
pub(crate) use leaf_and_mailbox;

/// What [`Partition::build`] returns.
pub type BuildResult<N> = Result<Built<N>, BuildError>;

/// A builder's output: depth-first nodes (the child below a plane right after its parent), the
/// id array of the leaves of more than one primitive, and figures for reports.
pub struct Built<N> {
    pub nodes: Vec<N>,
    pub ids: Vec<u32>,
    /// Primitive references over all leaves (a one-primitive leaf holds its id in the node,
    /// not in `ids`).
    pub refs: usize,
    pub depth: usize,
    pub leaves: usize,
    pub empty_leaves: usize,
    /// Node-type specific figures for [`IndexInfo::extra`].
    pub extra: Vec<(String, f64)>,
}

/// A built binary space partition.
#[derive(Debug, Clone)]
pub struct NearFarIndex<N> {
    nodes: Vec<N>,
    ids: Vec<u32>,
    refs: usize,
    bounds: Aabb,
    prims: usize,
    /// Whether queries keep a mailbox ([`Partition::mailbox`]).
    mailbox: bool,
    depth: usize,
    leaves: usize,
    empty_leaves: usize,
    extra: Vec<(String, f64)>,
}

impl<N> NearFarIndex<N> {
    /// The parts the walk reads.
    fn tree(&self) -> walk::Tree<'_, N> {
        walk::Tree {
            nodes: &self.nodes,
            ids: &self.ids,
            bounds: &self.bounds,
        }
    }

    /// The nodes, depth-first.
    pub fn nodes(&self) -> &[N] {
        &self.nodes
    }

    /// The bounds of the root cell.
    pub fn bounds(&self) -> Aabb {
        self.bounds
    }
}

impl<N: Partition> NearFarIndex<N> {
    /// Every leaf's `(first, count)` ([`Partition::leaf`]), depth-first.
    pub fn leaves(&self) -> impl Iterator<Item = (u32, u32)> + '_ {
        self.nodes.iter().filter_map(N::leaf)
    }
}

impl<N: Partition> Index for NearFarIndex<N> {
    type Params = N::Params;

    fn build<G: Geometry>(geom: &G, params: &N::Params) -> Result<Self, BuildError> {
        if geom.is_empty() {
            return Err(BuildError::EmptyScene);
        }
        let bounds = scene_bounds(geom, N::NAME)?;
        let built = N::build(geom, params, bounds, scene_pad(&bounds))?;
        Ok(NearFarIndex {
            nodes: huge_page_vec(built.nodes),
            ids: huge_page_vec(built.ids),
            refs: built.refs,
            bounds,
            prims: geom.len(),
            mailbox: N::mailbox(params),
            depth: built.depth,
            leaves: built.leaves,
            empty_leaves: built.empty_leaves,
            extra: built.extra,
        })
    }

    #[inline]
    fn query<Q: HitQuery, G: Geometry, S: Stats>(&self, g: &G, r: &Ray, s: &mut S) -> Q::Answer {
        let tree = self.tree();
        if self.mailbox {
            walk::query::<Q, true, _, _, _>(tree, g, r, s)
        } else {
            walk::query::<Q, false, _, _, _>(tree, g, r, s)
        }
    }

    /// [`Partition::BUILD_BYTES_PER_PRIM`] per primitive; the builds check the budget at every
    /// node too, since primitives split into many references can make them far larger.
    fn estimated_build_bytes(prims: usize, _: &N::Params) -> Option<usize> {
        per_primitive(prims, N::BUILD_BYTES_PER_PRIM)
    }

    fn info(&self) -> IndexInfo {
        let mut extra = vec![
            ("empty_leaves".into(), self.empty_leaves as f64),
            (
                "refs_per_prim".into(),
                self.refs as f64 / self.prims.max(1) as f64,
            ),
        ];
        extra.extend(self.extra.iter().cloned());
        IndexInfo {
            nodes: self.nodes.len(),
            leaves: self.leaves,
            depth: self.depth,
            memory_bytes: self.nodes.capacity() * size_of::<N>()
                + self.ids.capacity() * size_of::<u32>(),
            prim_refs: self.refs,
            extra,
            ..IndexInfo::default()
        }
    }
}

impl<N: Partition> BatchIndex for NearFarIndex<N> {}

/// The SAH weights and limits both partitions take, validated.
#[derive(Debug, Clone, Copy)]
pub struct SahParams {
    /// Cost of one primitive test, relative to `traversal`.
    pub intersect: f32,
    /// Cost of one traversal step.
    pub traversal: f32,
    /// Fraction of the cost saved by a split that leaves a child empty, in `[0, 1)`.
    pub empty_bonus: f32,
    /// Deepest level (root = 0), at most [`MAX_TREE_DEPTH`].
    pub max_depth: u32,
    /// Nodes with at most this many primitives become leaves (at least 1).
    pub leaf_size: u32,
}

impl SahParams {
    /// Checks the user's values for index `index` over `n` primitives (`max_depth` absent: the
    /// [`default_max_depth`]); an error names the parameter, the value and the valid range.
    pub fn validate(
        index: &str,
        (intersect, traversal, empty_bonus): (f32, f32, f32),
        max_depth: Option<u32>,
        leaf_size: u32,
        n: usize,
    ) -> Result<SahParams, BuildError> {
        let bad = |message: String| BuildError::Params {
            index: index.into(),
            message,
        };
        for (name, v) in [("intersect_cost", intersect), ("traversal_cost", traversal)] {
            if !(v.is_finite() && v > 0.0) {
                return Err(bad(format!("{name} must be a finite number > 0, got {v}")));
            }
        }
        if !(0.0..1.0).contains(&empty_bonus) {
            return Err(bad(format!(
                "empty_bonus must be in [0, 1), got {empty_bonus}"
            )));
        }
        let max_depth = max_depth.unwrap_or_else(|| default_max_depth(n));
        if max_depth > MAX_TREE_DEPTH {
            return Err(bad(format!(
                "max_depth must be at most {MAX_TREE_DEPTH}, got {max_depth}"
            )));
        }
        if leaf_size == 0 {
            return Err(bad("leaf_size must be at least 1".into()));
        }
        Ok(SahParams {
            intersect,
            traversal,
            empty_bonus,
            max_depth,
            leaf_size,
        })
    }
}
