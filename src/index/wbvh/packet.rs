//! The wide trees' side of the packet walk shared with the binary BVH
//! ([`crate::index::bvh::packet`]): one ray's test of a node's children is the single-ray
//! step's [`super::node::WideNode::hit`], and the walk does the rest.
//!
//! Box tests are counted as the single-ray step counts them, one per child
//! ([`super::node::WideNode::valid`]).

use super::traverse::{STACK, Tree};
use crate::index::bvh::node::Child;
use crate::index::bvh::packet::PacketTree;
use crate::index::bvh::slab::SlabRay;

impl<const C: usize> PacketTree<8, STACK> for Tree<'_, C> {
    #[inline(always)]
    fn hit<const SAFE: bool>(&self, node: u32, ray: &SlabRay, t_max: f32) -> (u32, [f32; 8]) {
        self.nodes[node as usize].hit::<SAFE>(ray, t_max)
    }

    #[inline(always)]
    fn boxes(&self, node: u32) -> u32 {
        self.nodes[node as usize].valid().count_ones()
    }

    #[inline(always)]
    fn child(&self, node: u32, i: usize) -> Child {
        self.nodes[node as usize].child(i)
    }
}
