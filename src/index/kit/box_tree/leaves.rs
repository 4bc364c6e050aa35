//! What the leaves of a box tree hold, and their tests for the shared traversal loop
//! ([`super::walk`]).
//!
//! - [`LeafStore::Ids`]: a leaf `Child { index, count }` is the run `prim_ids[index..index +
//!   count]`, each primitive tested through [`Geometry::intersect`] in id-list order.
//! - [`LeafStore::Blocks`] (triangle-only geometries, see [`Geometry::block_triangle`]): the
//!   leaf's triangles are copied into `count.div_ceil(4)` consecutive [`TriangleBlock`]s
//!   starting at `index`, each tested in one lane-wise pass ([`Geometry::intersect_block`], the
//!   same hits and `t` bits as `intersect` per primitive). A leaf reads one contiguous block of
//!   memory instead of following ids into the scene.
//!
//! Either way every hit is handed to the query ([`HitQuery::hit`]); a closest-hit record keeps
//! the smallest `t` and at equal `t` the lowest id, so the order of the tests within a leaf does
//! not matter.

use super::node::Child;
use crate::geometry::triangle::lanes::TriangleBlock;
use crate::geometry::{Ray, Triangle};
use crate::index::kit::huge_pages::huge_page_vec;
use crate::index::kit::prim_test;
use crate::index::{HitQuery, Stats};
use crate::scene::Geometry;

/// Triangles per [`TriangleBlock`]: a leaf of up to this many costs one lane-wise test.
pub const BLOCK_LANES: u32 = 4;

/// The leaves' contents, owned by the tree.
#[derive(Debug, Clone)]
pub enum LeafStore {
    Ids(Vec<u32>),
    Blocks(Vec<TriangleBlock>),
}

/// The leaves' contents as the traversal reads them.
#[derive(Debug, Clone, Copy)]
pub enum Leaves<'a> {
    Ids(&'a [u32]),
    Blocks(&'a [TriangleBlock]),
}

impl LeafStore {
    /// The triangles `prim_ids` name, in that order, when the geometry offers every one as a
    /// block triangle ([`Geometry::block_triangle`]): the leaves can then be blocks.
    pub fn block_triangles<G: Geometry>(geom: &G, prim_ids: &[u32]) -> Option<Vec<Triangle>> {
        prim_ids.iter().map(|&p| geom.block_triangle(p)).collect()
    }

    /// Triangle blocks when `tris` (from [`LeafStore::block_triangles`]) is `Some`, else the
    /// ids, either on huge pages ([`huge_page_vec`]). `leaves` are every leaf reference of the
    /// tree over `prim_ids`; with blocks their `index` is rewritten to the leaf's first block.
    pub fn new<'c>(
        prim_ids: Vec<u32>,
        tris: Option<Vec<Triangle>>,
        leaves: impl IntoIterator<Item = &'c mut Child>,
    ) -> LeafStore {
        let Some(tris) = tris else {
            return LeafStore::Ids(huge_page_vec(prim_ids));
        };
        let mut blocks = Vec::with_capacity(prim_ids.len().div_ceil(BLOCK_LANES as usize));
        for leaf in leaves {
            let range = leaf.index as usize..(leaf.index + leaf.count) as usize;
            leaf.index = blocks.len() as u32;
            for (t, ids) in tris[range.clone()]
                .chunks(BLOCK_LANES as usize)
                .zip(prim_ids[range].chunks(BLOCK_LANES as usize))
            {
                blocks.push(TriangleBlock::new(t, ids));
            }
        }
        LeafStore::Blocks(huge_page_vec(blocks))
    }

    pub fn leaves(&self) -> Leaves<'_> {
        match self {
            LeafStore::Ids(ids) => Leaves::Ids(ids),
            LeafStore::Blocks(blocks) => Leaves::Blocks(blocks),
        }
    }

    /// Number of triangle blocks (0 for id leaves).
    pub fn blocks(&self) -> usize {
        match self {
            LeafStore::Ids(_) => 0,
            LeafStore::Blocks(blocks) => blocks.len(),
        }
    }

    /// Bytes held.
    pub fn bytes(&self) -> usize {
        match self {
            LeafStore::Ids(ids) => size_of_val(&ids[..]),
            LeafStore::Blocks(blocks) => size_of_val(&blocks[..]),
        }
    }
}

impl Leaves<'_> {
    /// Prefetches the start of `leaf`'s contents (its first triangle block, or its ids).
    #[inline(always)]
    pub fn prefetch(self, leaf: Child) {
        match self {
            Leaves::Ids(ids) => crate::index::kit::prefetch::prefetch(
                ids.as_ptr().wrapping_add(leaf.index as usize),
            ),
            Leaves::Blocks(b) => {
                crate::index::kit::prefetch::prefetch(b.as_ptr().wrapping_add(leaf.index as usize))
            }
        }
    }

    /// Tests the leaf's primitives against `[ray.t_min, Q::reach]`, handing every hit to
    /// `found` ([`HitQuery::hit`]); `true` when the walk is over (an any-hit query's first
    /// hit).
    #[inline(always)]
    pub fn query<Q: HitQuery, G: Geometry, S: Stats>(
        self,
        leaf: Child,
        geom: &G,
        ray: &Ray,
        found: &mut Q::Found,
        stats: &mut S,
    ) -> bool {
        let (first, count) = (leaf.index as usize, leaf.count as usize);
        match self {
            Leaves::Ids(ids) => {
                for &prim in &ids[first..first + count] {
                    if prim_test::test::<Q, G, S>(found, geom, prim, ray, stats) {
                        return true;
                    }
                }
            }
            Leaves::Blocks(blocks) => {
                (0..count).for_each(|_| stats.prim_test());
                for block in &blocks[first..first + count.div_ceil(BLOCK_LANES as usize)] {
                    let (mut hit, t) = geom.intersect_block(block, ray, Q::reach(found, ray));
                    while hit != 0 {
                        let i = hit.trailing_zeros() as usize;
                        hit &= hit - 1;
                        if Q::hit(found, t[i], block.ids[i]) {
                            return true;
                        }
                    }
                }
            }
        }
        false
    }
}
