//! The kits the structures share, apart from the structures that use them: the box-tree walk,
//! leaves, slab tests and packet walk ([`box_tree`]: `bvh`, `bvh4`, `bvh8`), the near/far
//! partition ([`near_far`]: `kdtree`, `bsp`), the cell walk ([`cell_walk`]: `grid`, `grid2`,
//! `octree`) with its [`mailbox`], and the small pieces every walk uses: a fixed [`stack`],
//! cache hints ([`prefetch`]), one counted primitive test for either query kind ([`prim_test`])
//! and huge-page arrays ([`huge_pages`]).

pub mod box_tree;
pub mod cell_walk;
pub mod huge_pages;
pub mod mailbox;
pub mod near_far;
pub mod prefetch;
pub mod prim_test;
pub(crate) mod stack;
