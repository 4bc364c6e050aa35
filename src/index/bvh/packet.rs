//! The binary tree's side of the packet walk shared with the wide BVHs
//! ([`crate::index::kit::box_tree::packet`]): its two children's boxes and references.

use super::traverse::{STACK, Tree};
use crate::geometry::Aabb;
use crate::index::kit::box_tree::node::Child;
use crate::index::kit::box_tree::packet::PacketTree;

impl PacketTree<2, STACK> for Tree<'_> {
    #[inline(always)]
    fn child_box(&self, node: u32, i: usize) -> Aabb {
        self.nodes[node as usize].child_bounds(i)
    }

    #[inline(always)]
    fn boxes(&self, _node: u32) -> u32 {
        2
    }

    #[inline(always)]
    fn child(&self, node: u32, i: usize) -> Child {
        self.nodes[node as usize].children[i]
    }
}
