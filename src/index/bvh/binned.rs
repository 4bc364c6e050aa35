//! Binned SAH split (Wald 2007): centroids are binned into `bins` equal buckets per axis, and
//! the `bins - 1` planes between buckets are scored by the surface area heuristic.

use super::params::BINS;
use super::prim_ref::PrimRef;
use crate::geometry::Aabb;

const MAX_BINS: usize = *BINS.end() as usize;

#[derive(Clone, Copy)]
struct Bin {
    bounds: Aabb,
    count: u32,
}

const EMPTY_BIN: Bin = Bin {
    bounds: Aabb::EMPTY,
    count: 0,
};

/// Bucket of a centroid coordinate `c` (same rounding for binning and partitioning, so the
/// partition matches the counts the cost was computed from).
#[inline(always)]
fn bin_of(c: f32, min: f32, scale: f32, bins: usize) -> usize {
    (((c - min) * scale) as usize).min(bins - 1)
}

/// Finds the cheapest binned SAH plane over the three axes and partitions `refs` by it.
///
/// Returns `(cost, mid)`: `refs[..mid]` is the left side, `refs[mid..]` the right, both
/// non-empty, and `cost = area(left) * n_left + area(right) * n_right`. `None` when the
/// centroids coincide on every axis (no plane separates them). `centroids` is the bounds of
/// the centroids of `refs`; `bins` is in [`BINS`].
pub fn split(refs: &mut [PrimRef], centroids: &Aabb, bins: u32) -> Option<(f32, usize)> {
    let bins = bins as usize;
    debug_assert!((2..=MAX_BINS).contains(&bins));
    let ext = centroids.extent();
    let axes: Vec<usize> = (0..3).filter(|&a| ext[a] > 0.0).collect();
    if axes.is_empty() || refs.len() < 2 {
        return None;
    }
    let scale = ext.recip() * bins as f32;
    // Bins of axis `a` are `grid[a * bins..(a + 1) * bins]`.
    let mut grid = vec![EMPTY_BIN; 3 * bins];
    for r in refs.iter() {
        for &a in &axes {
            let b = &mut grid[a * bins + bin_of(r.centroid[a], centroids.min[a], scale[a], bins)];
            b.count += 1;
            b.bounds = b.bounds.union(r.bounds);
        }
    }
    let n = refs.len() as u32;
    let mut best: Option<(f32, usize, usize)> = None;
    for &a in &axes {
        let bin = &grid[a * bins..(a + 1) * bins];
        // right_cost[k]: area * count of bins k..bins.
        let mut right_cost = [0.0f32; MAX_BINS];
        let (mut acc, mut count) = (Aabb::EMPTY, 0u32);
        for k in (1..bins).rev() {
            acc = acc.union(bin[k].bounds);
            count += bin[k].count;
            right_cost[k] = acc.surface_area() * count as f32;
        }
        let (mut acc, mut count) = (Aabb::EMPTY, 0u32);
        for k in 1..bins {
            acc = acc.union(bin[k - 1].bounds);
            count += bin[k - 1].count;
            if count == 0 || count == n {
                continue;
            }
            let cost = acc.surface_area() * count as f32 + right_cost[k];
            if best.is_none_or(|(c, ..)| cost < c) {
                best = Some((cost, a, k));
            }
        }
    }
    let (cost, a, plane) = best?;
    let (min, s) = (centroids.min[a], scale[a]);
    let mid = partition(refs, |r| bin_of(r.centroid[a], min, s, bins) < plane);
    debug_assert!(mid > 0 && mid < refs.len());
    Some((cost, mid))
}

/// Moves the elements for which `left` holds to the front; returns how many there are.
fn partition(refs: &mut [PrimRef], left: impl Fn(&PrimRef) -> bool) -> usize {
    let mut mid = 0;
    for i in 0..refs.len() {
        if left(&refs[i]) {
            refs.swap(i, mid);
            mid += 1;
        }
    }
    mid
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::index::bvh::prim_ref::bounds_and_centroids;
    use glam::Vec3A;

    fn point_ref(id: u32, x: f32) -> PrimRef {
        let c = Vec3A::new(x, 0.0, 0.0);
        PrimRef {
            bounds: Aabb::new(c - 0.01, c + 0.01),
            centroid: c,
            id,
        }
    }

    #[test]
    fn separates_two_clusters() {
        let mut refs: Vec<PrimRef> = (0..10)
            .map(|i| point_ref(i, if i % 2 == 0 { 0.0 } else { 10.0 } + i as f32 * 0.01))
            .collect();
        let (_, c) = bounds_and_centroids(&refs);
        let (_, mid) = split(&mut refs, &c, 8).unwrap();
        assert_eq!(mid, 5);
        assert!(refs[..5].iter().all(|r| r.id % 2 == 0));
    }

    #[test]
    fn coincident_centroids_have_no_plane() {
        let mut refs: Vec<PrimRef> = (0..4).map(|i| point_ref(i, 1.0)).collect();
        let (_, c) = bounds_and_centroids(&refs);
        assert!(split(&mut refs, &c, 16).is_none());
    }
}
