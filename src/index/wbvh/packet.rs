//! The wide trees' side of the packet walk shared with the binary BVH
//! ([`crate::index::bvh::packet`]): one ray's test of a node's children is the single-ray
//! step's [`WideNode::hit`], and the walk does the rest.
//!
//! Box tests are counted as the single-ray step counts them, one per child. A node's children
//! fill lanes `0..n`; a lane without a child holds the default reference, which names inner
//! node 0, the root, never anyone's child, so the children are the lanes whose reference is
//! not the default.

use super::node::WideNode;
use super::traverse::{STACK, Tree};
use crate::index::Stats;
use crate::index::bvh::node::Child;
use crate::index::bvh::packet::PacketTree;
use crate::index::bvh::slab::SlabRay;
use crate::index::bvh::walk::Top;

/// Number of children of `node` (see the module doc).
#[inline(always)]
fn width<const C: usize>(node: &WideNode<C>) -> u32 {
    (0..4 * C)
        .map(|i| u32::from(node.child(i) != Child::default()))
        .sum()
}

impl<const C: usize> PacketTree<8, STACK> for Tree<'_, C> {
    #[inline(always)]
    fn top(&self) -> Top<'_> {
        self.top
    }

    #[inline(always)]
    fn hit<const SAFE: bool, S: Stats>(
        &self,
        node: u32,
        ray: &SlabRay,
        t_max: f32,
        stats: &mut S,
    ) -> (u32, [f32; 8]) {
        let node = &self.nodes[node as usize];
        stats.box_tests(width(node));
        node.hit::<SAFE>(ray, t_max)
    }

    #[inline(always)]
    fn child(&self, node: u32, i: usize) -> Child {
        self.nodes[node as usize].child(i)
    }
}

#[cfg(test)]
mod tests {
    use super::width;
    use crate::geometry::triangle::Watertight;
    use crate::index::Index;
    use crate::index::bvh::BvhParams;
    use crate::index::wbvh::{Bvh4, Bvh8, WideBvh};
    use crate::scene::{Triangles, generators};

    /// The children counted from the references are the node's children.
    fn widths_match<const C: usize>(bvh: &WideBvh<C>) {
        let (kids, _) = bvh.shape_histograms();
        let mut ours = vec![0; 4 * C + 1];
        for n in &bvh.nodes {
            ours[width(n) as usize] += 1;
        }
        assert_eq!(ours, kids);
    }

    #[test]
    fn children_counted_from_references_are_the_nodes_children() {
        let scene = generators::generate("soup", 3000, 7).unwrap();
        let geom = Triangles::<Watertight>::new(scene.geometry().triangles);
        widths_match(&Bvh4::build(&geom, &BvhParams::default()).unwrap());
        widths_match(&Bvh8::build(&geom, &BvhParams::default()).unwrap());
    }
}
