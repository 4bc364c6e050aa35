//! One [`Index`] implementation for obvhs's trees: obvhs builds the tree over our primitive
//! bounds and walks it with its own node test; our kernel decides every hit, in our order.

use super::{ObvhsParams, culling_bound, prim_boxes};
use crate::geometry::Ray;
use crate::index::build_budget::per_primitive;
use crate::index::kit::prim_test;
use crate::index::{BatchIndex, BuildError, HitQuery, Index, IndexInfo, Stats};
use crate::scene::Geometry;
use obvhs::BvhBuildParams;
use obvhs::aabb::Aabb;
use std::time::Duration;

/// One of obvhs's trees (implemented on obvhs's own types), as [`Obvhs`] needs it.
pub trait ObvhsTree: Clone + Send + Sync + 'static {
    /// The registry name, for errors.
    const NAME: &'static str;
    /// The build's peak heap per primitive for the estimate
    /// ([`Index::estimated_build_bytes`]), in bytes, measured with a margin.
    const BUILD_BYTES_PER_PRIM: usize;
    /// Builds the tree over the primitives' boxes (scene order) with obvhs's `params`.
    fn build(boxes: &[Aabb], params: BvhBuildParams, time: &mut Duration) -> Self;
    /// obvhs's own walk, with our counting: hands each visited primitive (its scene id) to
    /// `prim` with the stats and obvhs's ray, whose `tmax` `prim` may lower; `prim` returns
    /// `false` to stop (as far as obvhs's loop allows an exit).
    fn walk<S: Stats>(
        &self,
        ray: &Ray,
        stats: &mut S,
        prim: impl FnMut(u32, &mut S, &mut obvhs::ray::Ray) -> bool,
    );
    /// The tree's size and shape, measured by walking it (for [`Index::info`], after the build
    /// is timed).
    fn shape(&self) -> TreeShape;
}

/// What [`Obvhs::info`] reports of a tree: obvhs keeps no such figures itself.
#[derive(Debug, Clone, Copy)]
pub struct TreeShape {
    pub nodes: usize,
    pub leaves: usize,
    /// Levels of the deepest leaf (root = 1).
    pub depth: usize,
    /// Entries of the tree's primitive-id array (one per primitive: obvhs does not split).
    pub prim_refs: usize,
    /// The tree's arrays: nodes, primitive ids and any extra boxes it keeps.
    pub memory_bytes: usize,
}

/// An obvhs tree as our index: a peer with obvhs's box tests and our triangle test, with its
/// shape measured when asked ([`Index::info`], outside the timed build).
#[derive(Clone)]
pub struct Obvhs<T> {
    tree: T,
}

impl<T: ObvhsTree> Index for Obvhs<T> {
    type Params = ObvhsParams;

    fn build<G: Geometry>(geom: &G, params: &ObvhsParams) -> Result<Self, BuildError> {
        let boxes = prim_boxes(geom, T::NAME)?;
        let params = params.preset.build_params();
        let tree = T::build(&boxes, params, &mut Duration::default());
        Ok(Obvhs { tree })
    }

    /// obvhs's walk, each primitive through our kernel; for the closest hit obvhs's `tmax`
    /// follows the best `t` with [`culling_bound`]'s slack, an any-hit query stops at the first
    /// hit (as far as obvhs's loop allows).
    #[inline]
    fn query<Q: HitQuery, G: Geometry, S: Stats>(&self, g: &G, r: &Ray, s: &mut S) -> Q::Answer {
        let mut found = Q::start(r);
        self.tree.walk(r, s, |prim, s, oray| {
            let over = prim_test::test::<Q, G, S>(&mut found, g, prim, r, s);
            if Q::CLOSEST {
                oray.tmax = culling_bound(Q::reach(&found, r));
            }
            !over
        });
        Q::answer(found)
    }

    fn estimated_build_bytes(prims: usize, _: &ObvhsParams) -> Option<usize> {
        per_primitive(prims, T::BUILD_BYTES_PER_PRIM)
    }

    fn info(&self) -> IndexInfo {
        let TreeShape {
            nodes,
            leaves,
            depth,
            prim_refs,
            memory_bytes,
        } = self.tree.shape();
        IndexInfo {
            nodes,
            leaves,
            depth,
            memory_bytes,
            prim_refs,
            extra: vec![(
                "bytes_per_prim".into(),
                memory_bytes as f64 / prim_refs as f64,
            )],
            ..IndexInfo::default()
        }
    }
}

impl<T: ObvhsTree> BatchIndex for Obvhs<T> {}
