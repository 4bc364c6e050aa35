//! The kits the structures share, apart from the structures that use them: the box-tree walk,
//! leaves, slab tests and packet walk ([`box_tree`]: `bvh`, `bvh4`, `bvh8`), the near/far
//! partition ([`near_far`]: `kdtree`, `bsp`), the cell walk ([`cell_walk`]: `grid`, `grid2`,
//! `octree`) with its [`mailbox`], and the small pieces every walk uses: a fixed [`stack`],
//! cache hints ([`prefetch`]), one counted primitive test ([`prim_test`]), huge-page arrays
//! ([`huge_pages`]) and the query-writing macro ([`ray_queries`]).

pub mod box_tree;
pub mod cell_walk;
pub mod huge_pages;
pub mod mailbox;
pub mod near_far;
pub mod prefetch;
pub mod prim_test;
pub mod ray_queries;
pub(crate) mod stack;

pub(crate) use ray_queries::ray_queries;
