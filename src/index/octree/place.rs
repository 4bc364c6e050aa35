//! Where a node splits: per axis, the plane that minimises the surface area heuristic (SAH) over
//! a few candidates, and no split at all on an axis where no candidate pays (Havran reports large
//! gains for octrees whose split point is placed by SAH rather than at the middle).
//!
//! Each axis is judged on its own, as a binary split of the node's cell along that axis, and the
//! node then splits all chosen axes at once (2, 4 or 8 children). The candidates are the interior
//! boundaries of [`BINS`] equal bins and two planes just outside the primitives' bounds (a cut
//! of empty space: on a flat or boxy scene the empty side becomes one empty leaf instead of a
//! chain of ever smaller empty octants toward the surface). An axis on which every candidate
//! leaves all primitives on both sides costs more split than unsplit, so it is not split: a
//! thin cell around a plane is split along the plane only.
//!
//! Placement only decides where cells end; which primitives a cell lists is still decided by
//! the conservative overlap test, so exactness does not depend on anything here.

use crate::geometry::Aabb;
use glam::Vec3A;

/// Equal bins per axis whose interior boundaries are split candidates.
pub const BINS: usize = 16;

/// A split must leave each side of the plane at least this many overlap paddings wide (the
/// [`OVERLAP_PAD`](crate::geometry::overlap::OVERLAP_PAD) of the cell's largest coordinate, added
/// on every side before the overlap test): a thinner side would be mostly padding and list
/// nearly the same primitives as the cell, and far from the origin (a scene at 1e7 pads cells by
/// 100 units) such splits would only multiply nodes. So an axis narrower than twice this is
/// never split, which keeps the tree bounded on every scene.
pub const MIN_SIDE_IN_PADS: f32 = 2.0;

/// How far (in paddings) an empty-space cut lies outside the primitives' bounds, so that no
/// primitive's padded overlap reaches the empty side.
const CUT_MARGIN_IN_PADS: f32 = 2.0;

/// SAH cost of one more traversal step, in primitive tests.
const STEP_COST: f64 = 1.0;

/// Where and along which axes a node splits.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Split {
    /// The split point on the split axes; the cell's upper corner on the others (so that the
    /// first child's upper corner is this point).
    pub point: Vec3A,
    /// Octant bits of the split axes (x = 4, y = 2, z = 1); 0: no axis pays, stay a leaf.
    pub axes: usize,
}

/// Surface area of a box with side lengths `d`.
fn area(d: [f64; 3]) -> f64 {
    2.0 * (d[0] * d[1] + d[1] * d[2] + d[2] * d[0])
}

/// The split of `cell` holding primitives with bounds `bounds` (at least one), with overlap
/// padding `pad` (scene units).
pub fn place(cell: &Aabb, bounds: &[Aabb], pad: f32) -> Split {
    let mut split = Split {
        point: cell.max,
        axes: 0,
    };
    for a in 0..3 {
        if let Some(p) = best_plane(cell, bounds, pad, a) {
            split.point[a] = p;
            split.axes |= super::tree::octant_bit(a);
        }
    }
    split
}

/// The SAH-best plane on axis `a`, or `None` when no candidate costs less than leaving the axis
/// unsplit.
fn best_plane(cell: &Aabb, bounds: &[Aabb], pad: f32, a: usize) -> Option<f32> {
    let (lo, hi) = (cell.min[a], cell.max[a]);
    let min_side = MIN_SIDE_IN_PADS * pad;
    let content_lo = bounds
        .iter()
        .map(|b| b.min[a])
        .fold(f32::INFINITY, f32::min);
    let content_hi = bounds
        .iter()
        .map(|b| b.max[a])
        .fold(f32::NEG_INFINITY, f32::max);
    let margin = CUT_MARGIN_IN_PADS * pad;
    let mut cands: Vec<f32> = (1..BINS)
        .map(|i| lo + (hi - lo) * (i as f32 / BINS as f32))
        .chain([content_lo - margin, content_hi + margin])
        .filter(|&p| p - lo >= min_side && hi - p >= min_side)
        .collect();
    if cands.is_empty() {
        return None;
    }
    cands.sort_unstable_by(f32::total_cmp);
    cands.dedup();
    // left[k]: primitives whose padded bounds reach below candidate k (bmin <= p + pad), right[k]
    // above it (bmax >= p - pad); histograms first, then prefix and suffix sums.
    let k = cands.len();
    let mut left = vec![0u32; k + 1];
    let mut right = vec![0u32; k + 1];
    for b in bounds {
        left[cands.partition_point(|&p| p + pad < b.min[a])] += 1;
        right[cands.partition_point(|&p| p - pad <= b.max[a])] += 1;
    }
    for i in 1..=k {
        left[i] += left[i - 1];
    }
    for i in (0..k).rev() {
        right[i] += right[i + 1];
    }
    let ext = cell.extent().to_array().map(f64::from);
    let whole = area(ext);
    if whole <= 0.0 {
        return None;
    }
    let n = bounds.len() as f64;
    let mut best = (n, None);
    for (i, &p) in cands.iter().enumerate() {
        let mut dl = ext;
        let mut dr = ext;
        dl[a] = f64::from(p - lo);
        dr[a] = f64::from(hi - p);
        // Primitives left of candidate i: those counted at 0..=i; right: counted at i+1..
        let (nl, nr) = (f64::from(left[i]), f64::from(right[i + 1]));
        let cost = STEP_COST + (area(dl) * nl + area(dr) * nr) / whole;
        if cost < best.0 {
            best = (cost, Some(p));
        }
    }
    best.1
}

#[cfg(test)]
mod tests {
    use super::*;

    fn boxes(v: &[([f32; 3], [f32; 3])]) -> Vec<Aabb> {
        v.iter()
            .map(|&(a, b)| Aabb::new(Vec3A::from(a), Vec3A::from(b)))
            .collect()
    }

    #[test]
    fn a_plane_in_a_cube_is_cut_off_and_split_along_only() {
        let cell = Aabb::new(Vec3A::splat(-1.0), Vec3A::ONE);
        // 16 x 16 squares tiling the plane y = 0.
        let mut v = Vec::new();
        for i in 0..16 {
            for j in 0..16 {
                let (x, z) = (-1.0 + 0.125 * i as f32, -1.0 + 0.125 * j as f32);
                v.push(([x, 0.0, z], [x + 0.125, 0.0, z + 0.125]));
            }
        }
        let s = place(&cell, &boxes(&v), 1e-5);
        // Split on all three axes: x and z between squares, y just outside the plane.
        assert_eq!(s.axes, 7);
        assert!(s.point.y.abs() > 1e-5 && s.point.y.abs() < 1e-4, "{s:?}");
        // In the thin slab around the plane, y is no longer split.
        let slab = Aabb::new(Vec3A::new(-1.0, -4e-5, -1.0), Vec3A::new(1.0, 4e-5, 1.0));
        let s = place(&slab, &boxes(&v), 1e-5);
        assert_eq!(s.axes, 4 | 1, "{s:?}");
        assert_eq!(s.point.y, slab.max.y);
    }

    #[test]
    fn straddling_primitives_and_narrow_cells_are_not_split() {
        let cell = Aabb::new(Vec3A::ZERO, Vec3A::ONE);
        let all = boxes(&[([0.0; 3], [1.0; 3]); 5]);
        assert_eq!(place(&cell, &all, 1e-5).axes, 0);
        // Two pairs of primitives at opposite corners, in a cell only 3 paddings wide on x.
        let narrow = Aabb::new(Vec3A::ZERO, Vec3A::new(3e-5, 1.0, 1.0));
        let low = ([0.0; 3], [1e-6, 0.1, 0.1]);
        let high = ([2e-5, 0.9, 0.9], [3e-5, 1.0, 1.0]);
        let s = place(&narrow, &boxes(&[low, low, high, high]), 1e-5);
        assert_eq!(s.axes & 4, 0, "{s:?}");
        assert_eq!(s.axes, 2 | 1, "{s:?}");
    }
}
