//! The wide trees' side of the packet walk shared with the binary BVH
//! ([`crate::index::kit::box_tree::packet`]): one packet slab pass per existing child
//! ([`crate::index::kit::box_tree::packet_slab::hit_box`], every lane exactly its ray's single-ray test
//! of that child), and the walk does the rest.
//!
//! Box tests are counted as the single-ray step counts them, one per child
//! ([`super::node::WideNode::valid`]).

use super::traverse::{STACK, Tree};
use crate::geometry::Aabb;
use crate::index::kit::box_tree::node::Child;
use crate::index::kit::box_tree::packet::PacketTree;

impl<const C: usize> PacketTree<8, STACK> for Tree<'_, C> {
    #[inline(always)]
    fn child_box(&self, node: u32, i: usize) -> Aabb {
        self.nodes[node as usize].child_box(i)
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
