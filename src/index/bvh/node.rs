//! The flattened node: 32 bytes, depth-first order (pbrt's `LinearBVHNode`).

use crate::geometry::Aabb;
use glam::{BVec4A, Vec3A, Vec4};

/// One node of the flattened tree.
///
/// Layout: `lo = (min.x, min.y, min.z, offset)` and `hi = (max.x, max.y, max.z, count)`, the two
/// `u32` fields stored as the bits of the `w` lanes, so each half loads as one SIMD register and
/// the box is read without shuffles. `count == 0` marks an inner node: its first child is the
/// next node in the array and `offset` is the index of its second child. `count > 0` marks a
/// leaf of `count` primitives whose ids are `prim_ids[offset..offset + count]`.
#[derive(Debug, Clone, Copy)]
#[repr(C, align(32))]
pub struct Node {
    lo: Vec4,
    hi: Vec4,
}

const _: () = assert!(std::mem::size_of::<Node>() == 32);

/// The `x, y, z` lanes of `v` with `w` zeroed by a bit mask. A `w` lane that holds a small
/// integer's bits is a denormal float, and arithmetic on it (which `Vec3A` does on all four
/// lanes) takes a microcode assist costing about a hundred cycles.
#[inline(always)]
pub fn xyz(v: Vec4) -> Vec3A {
    Vec3A::from_vec4(Vec4::select(
        BVec4A::new(true, true, true, false),
        v,
        Vec4::ZERO,
    ))
}

impl Node {
    /// A leaf over `prim_ids[first..first + count]` (`count >= 1`).
    pub fn leaf(bounds: Aabb, first: u32, count: u32) -> Node {
        debug_assert!(count > 0);
        Node::new(bounds, first, count)
    }

    /// An inner node whose second child is at index `second` (the first is the next node).
    pub fn inner(bounds: Aabb, second: u32) -> Node {
        Node::new(bounds, second, 0)
    }

    fn new(b: Aabb, offset: u32, count: u32) -> Node {
        Node {
            lo: b.min.extend(f32::from_bits(offset)),
            hi: b.max.extend(f32::from_bits(count)),
        }
    }

    /// The node's box.
    #[inline(always)]
    pub fn bounds(&self) -> Aabb {
        Aabb::new(xyz(self.lo), xyz(self.hi))
    }

    /// First primitive slot (leaf) or second child (inner node).
    #[inline(always)]
    pub fn offset(&self) -> u32 {
        self.lo.w.to_bits()
    }

    /// Primitives in the leaf; 0 for an inner node.
    #[inline(always)]
    pub fn count(&self) -> u32 {
        self.hi.w.to_bits()
    }

    #[inline(always)]
    pub fn is_leaf(&self) -> bool {
        self.count() != 0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fields_round_trip_including_nan_bit_patterns() {
        let b = Aabb::new(Vec3A::new(-1.0, 2.0, 3.0), Vec3A::new(4.0, 5.0, 6.5));
        // 0x7fc0_0001 and 0xffff_ffff are NaN bit patterns as f32: they must survive unchanged.
        for (offset, count) in [(0x7fc0_0001, 3), (u32::MAX, 0xffff_ffff), (17, 0)] {
            let n = Node::new(b, offset, count);
            assert_eq!((n.offset(), n.count()), (offset, count));
            assert_eq!(n.bounds(), b);
        }
        assert!(!Node::inner(b, 5).is_leaf());
        assert!(Node::leaf(b, 0, 1).is_leaf());
    }
}
