//! The BSP node: an arbitrary plane and a child link, 24 bytes, and its near/far step.

use crate::geometry::Ray;
use crate::geometry::float::gamma;
use crate::index::near_far::{CROSSING_REL, SplitNode, Step};
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

/// Error bound factors of the two dot products of a crossing.
const NUM_ERR: f32 = gamma(4);
const DEN_ERR: f32 = gamma(3);

/// What a ray precomputes for its BSP steps: origin and direction and their absolute values
/// (for the error bounds of the dot products).
pub struct BspRay {
    origin: Vec3A,
    dir: Vec3A,
    abs_origin: Vec3A,
    abs_dir: Vec3A,
}

impl SplitNode for BspNode {
    type RayData = BspRay;

    #[inline(always)]
    fn prepare(ray: &Ray) -> BspRay {
        BspRay {
            origin: ray.origin,
            dir: ray.dir,
            abs_origin: ray.origin.abs(),
            abs_dir: ray.dir.abs(),
        }
    }

    /// Crossing of the plane `n . p = offset`: `t = num / den` with `num = offset - n . o` and
    /// `den = n . d`. The computed `num` and `den` are within `e_num = gamma(4) (|n| . |o| +
    /// |offset|)` and `e_den = gamma(3) |n| . |d|` of the exact ones, so the exact crossing is
    /// within `(e_num + |t| e_den) / (|den| - e_den)` of `num / den`; that bound, and the bracket,
    /// are widened by [`CROSSING_REL`] for their own rounding. When `|den| <= e_den` (a ray
    /// parallel or nearly parallel to the plane) both children are visited over the whole
    /// interval, the origin's side first.
    #[inline(always)]
    fn step(&self, at: u32, ray: &BspRay) -> Step {
        if self.link & LEAF_BIT != 0 {
            return Step::Leaf {
                first: self.first,
                count: self.link & MAX_LINK,
            };
        }
        let normal = Vec3A::from(self.normal);
        let (below, above) = (at + 1, self.link);
        let num = self.offset - normal.dot(ray.origin);
        let den = normal.dot(ray.dir);
        let abs_normal = normal.abs();
        let e_num = NUM_ERR * (abs_normal.dot(ray.abs_origin) + self.offset.abs());
        let e_den = DEN_ERR * abs_normal.dot(ray.abs_dir);
        let margin = den.abs() - e_den;
        if margin <= 0.0 {
            let (first, second) = if num >= 0.0 {
                (below, above)
            } else {
                (above, below)
            };
            return Step::Cross {
                first,
                second,
                lo: f32::NEG_INFINITY,
                hi: f32::INFINITY,
            };
        }
        let t = num / den;
        let err =
            (e_num + t.abs() * e_den) / margin * (1.0 + CROSSING_REL) + t.abs() * CROSSING_REL;
        let (first, second) = if den > 0.0 {
            (below, above)
        } else {
            (above, below)
        };
        Step::Cross {
            first,
            second,
            lo: t - err,
            hi: t + err,
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
