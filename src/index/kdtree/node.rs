//! The compact 8-byte kd-tree node (pbrt's layout) and its near/far step.

use crate::geometry::Ray;
use crate::index::kit::near_far::{AxisRay, SplitNode, Step, axis_step};

/// One kd-tree node in 8 bytes.
///
/// `tag` holds the kind in its low 2 bits (`0..=2`: interior split on that axis, `3`: leaf) and a
/// 30-bit payload above them: the index of the child above the plane for an interior node (the
/// child below is the next node, depth-first order), the primitive count for a leaf.
/// `data` is the split position (the bits of an `f32`), a leaf's first slot in the id array, or
/// for a leaf of one primitive that primitive's id (no id array read on the way to its test).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[repr(C)]
pub struct KdNode {
    tag: u32,
    data: u32,
}

const LEAF: u32 = 3;

/// Largest child index or leaf count the 30-bit payload holds.
pub const MAX_PAYLOAD: u32 = (1 << 30) - 1;

/// What a node is.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum KdKind {
    Interior { axis: usize, split: f32, above: u32 },
    Leaf { first: u32, count: u32 },
}

impl KdNode {
    /// A leaf over ids `first..first + count` of the id array (`count <= MAX_PAYLOAD`), or when
    /// `count == 1` over primitive `first` itself.
    pub fn leaf(first: u32, count: u32) -> KdNode {
        debug_assert!(count <= MAX_PAYLOAD);
        KdNode {
            tag: (count << 2) | LEAF,
            data: first,
        }
    }

    /// An interior node splitting `axis` at `split`; the child below follows it, the child above
    /// is at `above` (`<= MAX_PAYLOAD`).
    pub fn interior(axis: usize, split: f32, above: u32) -> KdNode {
        debug_assert!(axis < 3 && above <= MAX_PAYLOAD);
        KdNode {
            tag: (above << 2) | axis as u32,
            data: split.to_bits(),
        }
    }

    /// The same node in a tree where its subtree starts `nodes` further on and its leaves' ids
    /// `ids` further on (for joining subtrees built apart).
    pub fn shifted(&self, nodes: u32, ids: u32) -> KdNode {
        match self.kind() {
            KdKind::Leaf { first, count: 1 } => KdNode::leaf(first, 1),
            KdKind::Leaf { first, count } => KdNode::leaf(first + ids, count),
            KdKind::Interior { axis, split, above } => KdNode::interior(axis, split, above + nodes),
        }
    }

    #[inline(always)]
    pub fn kind(&self) -> KdKind {
        let payload = self.tag >> 2;
        match self.tag & 3 {
            LEAF => KdKind::Leaf {
                first: self.data,
                count: payload,
            },
            axis => KdKind::Interior {
                axis: axis as usize,
                split: f32::from_bits(self.data),
                above: payload,
            },
        }
    }
}

impl SplitNode for KdNode {
    type RayData = AxisRay;

    #[inline(always)]
    fn prepare(ray: &Ray) -> AxisRay {
        AxisRay::new(ray)
    }

    /// A leaf's range (or its one primitive), or the crossing of the node's plane by [`axis_step`].
    #[inline(always)]
    fn step(&self, at: u32, ray: &AxisRay) -> Step {
        let payload = self.tag >> 2;
        let axis = (self.tag & 3) as usize;
        if axis == LEAF as usize {
            return Step::Leaf {
                first: self.data,
                count: payload,
            };
        }
        axis_step(f32::from_bits(self.data), axis, at + 1, payload, ray)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn eight_bytes_and_round_trip() {
        assert_eq!(std::mem::size_of::<KdNode>(), 8);
        assert_eq!(
            KdNode::leaf(7, MAX_PAYLOAD).kind(),
            KdKind::Leaf {
                first: 7,
                count: MAX_PAYLOAD
            }
        );
        assert_eq!(
            KdNode::interior(2, -0.5, 12345).kind(),
            KdKind::Interior {
                axis: 2,
                split: -0.5,
                above: 12345
            }
        );
    }
}
