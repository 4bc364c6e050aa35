//! The compact 8-byte kd-tree node (pbrt's layout) and its near/far step.

use crate::geometry::Ray;
use crate::index::near_far::{CROSSING_REL, SplitNode, Step};

/// One kd-tree node in 8 bytes.
///
/// `tag` holds the kind in its low 2 bits (`0..=2`: interior split on that axis, `3`: leaf) and a
/// 30-bit payload above them: the index of the child above the plane for an interior node (the
/// child below is the next node, depth-first order), the primitive count for a leaf.
/// `data` is the split position (the bits of an `f32`) or the leaf's first slot in the id array.
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
    /// A leaf over ids `first..first + count` of the id array (`count <= MAX_PAYLOAD`).
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

/// What a ray precomputes for its kd steps: origin, direction and inverse direction, padded to
/// four lanes so that an axis index (`0..3`, masked by `& 3`) needs no bounds check.
pub struct KdRay {
    origin: [f32; 4],
    dir: [f32; 4],
    inv_dir: [f32; 4],
}

impl SplitNode for KdNode {
    type RayData = KdRay;

    #[inline(always)]
    fn prepare(ray: &Ray) -> KdRay {
        KdRay {
            origin: ray.origin.extend(0.0).into(),
            dir: ray.dir.extend(0.0).into(),
            inv_dir: ray.inv_dir.extend(0.0).into(),
        }
    }

    /// The crossing of the plane is `(split - origin) * inv_dir`, the formula of
    /// [`crate::geometry::Aabb::ray_interval`], bracketed by [`CROSSING_REL`]; the child the
    /// direction points away from first. A ray parallel to the plane (or one whose crossing is
    /// not finite) is handled by [`parallel_step`].
    #[inline(always)]
    fn step(&self, at: u32, ray: &KdRay) -> Step {
        let payload = self.tag >> 2;
        let axis = (self.tag & 3) as usize;
        if axis == LEAF as usize {
            return Step::Leaf {
                first: self.data,
                count: payload,
            };
        }
        let split = f32::from_bits(self.data);
        let (below, above) = (at + 1, payload);
        let t = (split - ray.origin[axis]) * ray.inv_dir[axis];
        if !t.is_finite() {
            return parallel_step(split, ray.origin[axis], ray.dir[axis], below, above);
        }
        let slack = t.abs() * CROSSING_REL;
        let (first, second) = if ray.inv_dir[axis] < 0.0 {
            (above, below)
        } else {
            (below, above)
        };
        Step::Cross {
            first,
            second,
            lo: t - slack,
            hi: t + slack,
        }
    }
}

/// A ray parallel to the plane at `split` (direction `d == 0`) stays on its origin's side, which
/// is exact, and in the plane it is on both; a crossing that overflows or is `0 * inf` (a
/// subnormal direction) visits both children over the whole interval, the origin's side first.
#[cold]
#[inline(never)]
fn parallel_step(split: f32, o: f32, d: f32, below: u32, above: u32) -> Step {
    let (first, second) = if o < split || (o == split && d > 0.0) {
        (below, above)
    } else {
        (above, below)
    };
    let only_first = d == 0.0 && o != split;
    Step::Cross {
        first,
        second,
        lo: if only_first {
            f32::INFINITY
        } else {
            f32::NEG_INFINITY
        },
        hi: f32::INFINITY,
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
