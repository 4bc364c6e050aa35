//! The kit of the box trees (`bvh`, `bvh4`, `bvh8`): a tree of boxes with leaves of primitive-id
//! runs is a [`tree::Tree`] over its node type implementing [`tree::BoxTree`] (its node step),
//! and gets from here the single-ray loops ([`walk`]), the chunk walks ([`stream`]), the leaves
//! ([`leaves`]), the slab tests ([`slab`] over the registers of [`lanes`] and [`lanes16`]; [`packet_slab`] for a
//! packet of rays), the packet walk ([`packet`]) and the beam walk ([`beam`], with the
//! interval test of [`frustum`]). [`node`] is the two-child node every tree is built as (the
//! binary BVH's layout, which the wide BVH collapses); [`layout`] reorders the nodes of either
//! in memory (the `layout` parameter).

pub(crate) mod beam;
pub(crate) mod frustum;
pub(crate) mod lanes;
pub(crate) mod lanes16;
pub(crate) mod layout;
pub(crate) mod leaves;
pub(crate) mod node;
pub(crate) mod packet;
pub(crate) mod packet_query;
pub(crate) mod packet_slab;
pub(crate) mod slab;
pub(crate) mod stream;
pub(crate) mod tree;
pub(crate) mod walk;
