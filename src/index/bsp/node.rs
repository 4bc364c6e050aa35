//! The BSP node: an arbitrary plane and a child link, 24 bytes.

use glam::Vec3A;

/// One BSP node. An interior node holds its plane `normal . p = offset` (unit normal); the child
/// below the plane (`normal . p <= offset`) is the next node (depth-first order), the child
/// above is at `link`. A leaf has `LEAF_BIT` set in `link`, the primitive count below it, and
/// its first slot in the id array in `first`.
#[derive(Debug, Clone, Copy, PartialEq)]
#[repr(C)]
pub struct BspNode {
    normal: [f32; 3],
    offset: f32,
    link: u32,
    first: u32,
}

const LEAF_BIT: u32 = 1 << 31;

/// Largest child index or leaf count a node holds.
pub const MAX_LINK: u32 = LEAF_BIT - 1;

/// What a node is.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum BspKind {
    Interior {
        normal: Vec3A,
        offset: f32,
        above: u32,
    },
    Leaf {
        first: u32,
        count: u32,
    },
}

impl BspNode {
    pub fn leaf(first: u32, count: u32) -> BspNode {
        debug_assert!(count <= MAX_LINK);
        BspNode {
            normal: [0.0; 3],
            offset: 0.0,
            link: LEAF_BIT | count,
            first,
        }
    }

    pub fn interior(normal: Vec3A, offset: f32, above: u32) -> BspNode {
        debug_assert!(above <= MAX_LINK);
        BspNode {
            normal: normal.into(),
            offset,
            link: above,
            first: 0,
        }
    }

    #[inline(always)]
    pub fn kind(&self) -> BspKind {
        if self.link & LEAF_BIT != 0 {
            BspKind::Leaf {
                first: self.first,
                count: self.link & MAX_LINK,
            }
        } else {
            BspKind::Interior {
                normal: Vec3A::from(self.normal),
                offset: self.offset,
                above: self.link,
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn round_trip() {
        assert_eq!(std::mem::size_of::<BspNode>(), 24);
        assert_eq!(
            BspNode::leaf(3, 9).kind(),
            BspKind::Leaf { first: 3, count: 9 }
        );
        assert_eq!(
            BspNode::interior(Vec3A::Y, -2.0, 77).kind(),
            BspKind::Interior {
                normal: Vec3A::Y,
                offset: -2.0,
                above: 77
            }
        );
    }
}
