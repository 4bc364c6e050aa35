//! The wide trees' side of the packet walk shared with the binary BVH
//! ([`crate::index::bvh::packet`]): one packet slab pass per existing child
//! ([`crate::index::bvh::packet_slab::hit_box`], every lane exactly its ray's single-ray test
//! of that child), and the walk does the rest.
//!
//! Box tests are counted as the single-ray step counts them, one per child
//! ([`super::node::WideNode::valid`]).

use super::traverse::{STACK, Tree};
use crate::index::bvh::lanes::Lanes;
use crate::index::bvh::node::Child;
use crate::index::bvh::packet::PacketTree;
use crate::index::bvh::packet_slab::{PacketRays, hit_box};

impl<const C: usize> PacketTree<8, STACK> for Tree<'_, C> {
    #[inline(always)]
    fn hit<const SAFE: bool, V: Lanes>(
        &self,
        node: u32,
        rays: &PacketRays<V>,
        t_max: V,
    ) -> ([u32; 8], [V; 8]) {
        let n = &self.nodes[node as usize];
        let mut masks = [0; 8];
        let mut entries = [t_max; 8];
        for i in 0..n.width() {
            let b = n.child_box(i);
            let (min, max) = ([0, 1, 2].map(|k| b.min[k]), [0, 1, 2].map(|k| b.max[k]));
            (masks[i], entries[i]) = hit_box::<SAFE, V>(min, max, rays, t_max);
        }
        (masks, entries)
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
