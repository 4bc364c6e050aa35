//! The flattened tree: 64-byte inner nodes that hold both children's boxes, depth-first order.

use crate::geometry::Aabb;
use glam::{Vec3A, Vec4};

/// A reference to a subtree: an inner node, or a leaf stored inline in its parent.
///
/// `count == 0`: the inner node `nodes[index]`. `count > 0`: a leaf of `count` primitives whose
/// ids are `prim_ids[index..index + count]`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Child {
    pub index: u32,
    pub count: u32,
}

impl Child {
    /// A leaf over `prim_ids[first..first + count]` (`count >= 1`).
    pub fn leaf(first: u32, count: u32) -> Child {
        debug_assert!(count > 0);
        Child {
            index: first,
            count,
        }
    }

    /// The inner node `nodes[index]`.
    pub fn inner(index: u32) -> Child {
        Child { index, count: 0 }
    }

    #[inline(always)]
    pub fn is_leaf(self) -> bool {
        self.count != 0
    }
}

/// One inner node: the boxes of its two children `a` (lane 0) and `b` (lane 1) in
/// structure-of-arrays form, so one SIMD pass tests both (see [`super::slab`]), and the
/// children's references. Exactly one cache line.
///
/// Per axis, `x = [a.min.x, b.min.x, a.max.x, b.max.x]` (likewise `y`, `z`): the two halves of
/// each register are the slab planes, so swapping halves pairs every plane with its opposite.
#[derive(Debug, Clone, Copy)]
#[repr(C, align(64))]
pub struct Node {
    pub x: Vec4,
    pub y: Vec4,
    pub z: Vec4,
    pub children: [Child; 2],
}

const _: () = assert!(std::mem::size_of::<Node>() == 64);

impl Node {
    /// A node over children `a` and `b` with boxes `boxes[0]` and `boxes[1]`.
    pub fn new(boxes: [Aabb; 2], children: [Child; 2]) -> Node {
        let [a, b] = boxes;
        let lane = |axis: usize| Vec4::new(a.min[axis], b.min[axis], a.max[axis], b.max[axis]);
        Node {
            x: lane(0),
            y: lane(1),
            z: lane(2),
            children,
        }
    }

    /// The box of child `i` (0 or 1).
    #[inline(always)]
    pub fn child_bounds(&self, i: usize) -> Aabb {
        let (x, y, z) = (self.x.to_array(), self.y.to_array(), self.z.to_array());
        Aabb::new(
            Vec3A::new(x[i], y[i], z[i]),
            Vec3A::new(x[i + 2], y[i + 2], z[i + 2]),
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn child_boxes_and_references_round_trip() {
        let a = Aabb::new(Vec3A::new(-1.0, 2.0, 3.0), Vec3A::new(4.0, 5.0, 6.5));
        let b = Aabb::new(Vec3A::new(-7.0, -2.0, 0.0), Vec3A::new(-6.0, 9.0, 0.25));
        let kids = [Child::leaf(17, 3), Child::inner(u32::MAX)];
        let n = Node::new([a, b], kids);
        assert_eq!((n.child_bounds(0), n.child_bounds(1)), (a, b));
        assert_eq!(n.children, kids);
        assert!(kids[0].is_leaf() && !kids[1].is_leaf());
    }
}
