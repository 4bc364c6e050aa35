//! The ray as both traversals see it: one rule, shared, for "has the ray crossed this plane by
//! parameter `t`", so that both walk the same cells in the same `t` order.
//!
//! The crossing parameter of a plane `x = p` is `T(p) = (p - o.x) * inv.x`, rounded once per
//! operation. For a fixed ray and axis `T` is monotone in `p` (non-decreasing when the direction
//! is positive, non-increasing when negative), and siblings share their split planes bit for bit,
//! so the computed intervals `[T(near), T(far)]` of the cells along an axis tile the `t` line
//! without gaps: every `t` has exactly one cell per axis (the rule below breaks ties toward the
//! side the ray moves into). A cell whose interval rounds to a single value is still visited.
//!
//! Zero direction components (`+0.0` and `-0.0` alike) are treated as positive with an inverse of
//! `+inf`: the ray never crosses a plane on that axis, and a ray lying exactly in a split plane
//! belongs to the upper cell (`T = NaN` reads as "crossed"). Far planes that give `NaN` (the
//! ray lies in the root's upper face) read as "never left".

use super::tree::octant_bit;
use crate::geometry::{Aabb, Ray};
use glam::{BVec3A, Vec3A};

/// Per-ray constants of the octree traversals.
#[derive(Debug, Clone, Copy)]
pub(super) struct AxisRay {
    origin: Vec3A,
    /// `1/dir`, with `+inf` for a zero component of either sign.
    inv: Vec3A,
    /// Axes on which the ray moves toward lower coordinates (`dir < 0`, so not `-0.0`).
    neg: BVec3A,
    /// Octant bits of `neg` (Revelles' `a`): normalized child `c` is physical child `c ^ mask`.
    pub mask: usize,
}

/// Octant index (x = 4, y = 2, z = 1) of a per-axis mask.
#[inline(always)]
pub(super) fn octant_of(b: BVec3A) -> usize {
    let m = b.bitmask() as usize;
    ((m & 1) << 2) | (m & 2) | ((m >> 2) & 1)
}

/// Per-axis mask of an octant index.
#[inline(always)]
pub(super) fn mask_of(c: usize) -> BVec3A {
    BVec3A::new(
        c & octant_bit(0) != 0,
        c & octant_bit(1) != 0,
        c & octant_bit(2) != 0,
    )
}

/// `NaN` replaced by `v`.
#[inline(always)]
fn or_nan(x: Vec3A, v: f32) -> Vec3A {
    Vec3A::select(x.cmpeq(x), x, Vec3A::splat(v))
}

impl AxisRay {
    #[inline(always)]
    pub fn new(ray: &Ray) -> AxisRay {
        let neg = ray.dir.cmplt(Vec3A::ZERO);
        AxisRay {
            origin: ray.origin,
            inv: Vec3A::select(ray.dir.cmpeq(Vec3A::ZERO), Vec3A::INFINITY, ray.inv_dir),
            neg,
            mask: octant_of(neg),
        }
    }

    /// Per-axis crossing parameters `T(p)` of the planes through `p`; `NaN` (the ray lies in
    /// the plane) becomes `nan`.
    #[inline(always)]
    fn crossings(&self, p: Vec3A, nan: f32) -> Vec3A {
        or_nan((p - self.origin) * self.inv, nan)
    }

    /// Per-axis parameters where the ray enters (`t0`) and leaves (`t1`) the slabs of `cell`,
    /// with no `NaN`: the cell's interval on the `t` line is `[max(t0), min(t1)]`.
    #[inline(always)]
    pub fn slabs(&self, cell: &Aabb) -> (Vec3A, Vec3A) {
        let near = Vec3A::select(self.neg, cell.max, cell.min);
        let far = Vec3A::select(self.neg, cell.min, cell.max);
        (
            self.crossings(near, f32::NEG_INFINITY),
            self.crossings(far, f32::INFINITY),
        )
    }

    /// Per-axis parameters where the ray crosses the split planes through `mid` (`-inf` when it
    /// lies in one: it counts as already across).
    #[inline(always)]
    pub fn mid_crossings(&self, mid: Vec3A) -> Vec3A {
        self.crossings(mid, f32::NEG_INFINITY)
    }

    /// The normalized octant (bit set = beyond the split in the ray's direction) the ray is in
    /// at parameter `t`, given the split crossings `tm`: an axis counts as crossed when
    /// `tm <= t`, so a ray exactly on a split plane at `t` goes to the side it moves into.
    #[inline(always)]
    pub fn octant_at(tm: Vec3A, t: f32) -> usize {
        octant_of(tm.cmple(Vec3A::splat(t)))
    }

    /// The physical child of a node split at `mid` that holds the ray at parameter `t`.
    #[inline(always)]
    pub fn child_at(&self, mid: Vec3A, t: f32) -> usize {
        Self::octant_at(self.mid_crossings(mid), t) ^ self.mask
    }

    /// Where the ray leaves `cell` (`min` of the far-slab parameters) and through which axis
    /// (the lowest on ties: edges and corners), and whether it moves to the upper side there.
    #[inline(always)]
    pub fn exit(&self, cell: &Aabb) -> (f32, usize, bool) {
        let (_, t1) = self.slabs(cell);
        let t = t1.min_element();
        let axis = if t1.x == t {
            0
        } else if t1.y == t {
            1
        } else {
            2
        };
        (t, axis, !self.neg.test(axis))
    }
}
