//! The BSP node: an arbitrary plane and a child link, 24 bytes, and its near/far step.

use crate::geometry::Ray;
use crate::geometry::float::gamma;
use crate::index::kit::near_far::{AxisRay, CROSSING_REL, SplitNode, Step, axis_step};
use glam::Vec3A;

/// One BSP node. An interior node holds its plane `normal . p = offset` (unit normal); the child
/// below the plane (`normal . p <= offset`) is the next node (depth-first order), the child
/// above is at `link`; its `first` is the axis (`0..=2`) when the normal is that unit axis (the
/// walk then takes the kd-tree's cheaper step, [`axis_step`]), else [`GENERAL`]. A leaf has
/// `LEAF_BIT` set in `link`, the primitive count below it, and its first slot in the id array in
/// `first`.
#[derive(Debug, Clone, Copy, PartialEq)]
#[repr(C)]
pub struct BspNode {
    normal: [f32; 3],
    offset: f32,
    link: u32,
    first: u32,
}

const LEAF_BIT: u32 = 1 << 31;

/// The `first` of an interior node whose plane is not an axis plane.
const GENERAL: u32 = 3;

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
        let axis = [Vec3A::X, Vec3A::Y, Vec3A::Z]
            .iter()
            .position(|&a| a == normal);
        BspNode {
            normal: normal.into(),
            offset,
            link: above,
            first: axis.map_or(GENERAL, |a| a as u32),
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

/// What a ray precomputes for its BSP steps: the axis steps' data, origin and direction and
/// their absolute values (for the error bounds of the dot products).
pub struct BspRay {
    axis: AxisRay,
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
            axis: AxisRay::new(ray),
            origin: ray.origin,
            dir: ray.dir,
            abs_origin: ray.origin.abs(),
            abs_dir: ray.dir.abs(),
        }
    }

    /// An axis plane crosses by [`axis_step`]. Crossing of a general plane `n . p = offset`:
    /// `t = num / den` with `num = offset - n . o` and
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
        let (below, above) = (at + 1, self.link);
        if self.first != GENERAL {
            return axis_step(self.offset, self.first as usize, below, above, &ray.axis);
        }
        let normal = Vec3A::from(self.normal);
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

    #[test]
    fn axis_planes_step_as_kd_nodes_general_planes_do_not() {
        use crate::index::kdtree::KdNode;
        let ray = Ray::new(
            glam::Vec3::new(0.1, -3.0, 0.4),
            glam::Vec3::new(0.2, 1.0, -0.3),
            0.0,
            9.0,
        )
        .unwrap();
        let parts = Step::crossing;
        let kd = parts(KdNode::interior(1, 2.0, 77).step(5, &KdNode::prepare(&ray)));
        let bsp = parts(BspNode::interior(Vec3A::Y, 2.0, 77).step(5, &BspNode::prepare(&ray)));
        assert_eq!(kd, bsp);
        // A tilted plane through the same crossing takes the general step: its bracket differs
        // but still holds the crossing.
        let n = Vec3A::new(0.0, 1.0, 1e-3).normalize();
        let offset = n.dot(ray.at(5.0));
        let (first, _, lo, hi) =
            parts(BspNode::interior(n, offset, 77).step(5, &BspNode::prepare(&ray)));
        assert!((first, lo < 5.0, hi > 5.0) == (6, true, true) && (lo, hi) != (kd.2, kd.3));
    }
}
