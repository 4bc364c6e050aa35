//! Binned SAH split (Wald 2007): centroids are binned into `bins` equal buckets per axis, and
//! the `bins - 1` planes between buckets are scored by the surface area heuristic.

use super::prim_ref::PrimRef;
use crate::geometry::Aabb;
use glam::Vec3A;

#[derive(Clone, Copy)]
struct Bin {
    min: Vec3A,
    max: Vec3A,
    count: u32,
}

const EMPTY_BIN: Bin = Bin {
    min: Vec3A::INFINITY,
    max: Vec3A::NEG_INFINITY,
    count: 0,
};

/// Surface area of a non-empty box given by its corners (no emptiness check: callers only
/// score sides that hold primitives).
#[inline(always)]
fn area(min: Vec3A, max: Vec3A) -> f32 {
    let e = max - min;
    2.0 * (e.x * e.y + e.y * e.z + e.z * e.x)
}

/// Buckets of a centroid on the three axes (the same function bins and partitions, so the
/// partition matches the counts the cost was computed from). `scale` is finite and 0 on axes
/// without extent (everything in bucket 0); `last` is `bins - 1` on every lane.
#[inline(always)]
fn bins_of(c: Vec3A, min: Vec3A, scale: Vec3A, last: Vec3A) -> [usize; 3] {
    // In [0, bins - 1]: c >= min, and the product is at most bins (times 1 + eps).
    let v = ((c - min) * scale).min(last);
    truncate(v)
}

/// Truncates three non-negative lanes below 2^31 to integers (one SSE2 conversion: `as usize`
/// per lane costs saturation checks that dominated the binning loop).
#[cfg(all(target_arch = "x86_64", target_feature = "sse2"))]
#[inline(always)]
fn truncate(v: Vec3A) -> [usize; 3] {
    use std::arch::x86_64::{_mm_cvtsi128_si32, _mm_cvttps_epi32, _mm_shuffle_epi32};
    // SAFETY: the cfg guarantees SSE2, the only requirement of these intrinsics.
    unsafe {
        let i = _mm_cvttps_epi32(v.into());
        [
            _mm_cvtsi128_si32(i) as usize,
            _mm_cvtsi128_si32(_mm_shuffle_epi32::<0b01>(i)) as usize,
            _mm_cvtsi128_si32(_mm_shuffle_epi32::<0b10>(i)) as usize,
        ]
    }
}

#[cfg(not(all(target_arch = "x86_64", target_feature = "sse2")))]
#[inline(always)]
fn truncate(v: Vec3A) -> [usize; 3] {
    [v.x as usize, v.y as usize, v.z as usize]
}

/// Reusable bin storage, so that no node allocates (one per build thread).
#[derive(Default)]
pub struct Scratch {
    grid: Vec<Bin>,
    right_cost: Vec<f32>,
}

/// A chosen split: `refs[..mid]` go left, `refs[mid..]` right (both non-empty), with
/// `cost = area(left) * n_left + area(right) * n_right` and each side's bounds and centroid
/// bounds (so the children need not scan their primitives again).
pub struct Split {
    pub cost: f32,
    pub mid: usize,
    pub left: (Aabb, Aabb),
    pub right: (Aabb, Aabb),
}

/// Finds the cheapest binned SAH plane over the three axes and partitions `refs` by it.
///
/// `None` when the centroids coincide on every axis (no plane separates them). `centroids` is
/// the bounds of the centroids of `refs`; `bins` is in `2..=`[`super::params::BINS`]`.end()`.
pub fn split(
    refs: &mut [PrimRef],
    centroids: &Aabb,
    bins: u32,
    scratch: &mut Scratch,
) -> Option<Split> {
    let bins = bins as usize;
    let ext = centroids.extent();
    if refs.len() < 2 || ext.max_element() <= 0.0 {
        return None;
    }
    let scale = Vec3A::splat(bins as f32) / ext;
    let scale = Vec3A::select(
        ext.cmpgt(Vec3A::ZERO) & scale.is_finite_mask(),
        scale,
        Vec3A::ZERO,
    );
    let last = Vec3A::splat((bins - 1) as f32);
    let min = centroids.min;
    // Two sets of bins, for even and odd primitives, so that consecutive primitives landing in
    // the same bin do not wait on each other; merged afterwards. Bins of axis `a` in set `s`
    // are `grid[(2 * a + s) * bins..][..bins]`.
    let grid = &mut scratch.grid;
    grid.clear();
    grid.resize(6 * bins, EMPTY_BIN);
    let mut add = |set: usize, r: &PrimRef| {
        let k = bins_of(r.centroid(), min, scale, last);
        for (a, k) in k.into_iter().enumerate() {
            let b = &mut grid[(2 * a + set) * bins + k];
            b.count += 1;
            b.min = b.min.min(r.min());
            b.max = b.max.max(r.max());
        }
    };
    let mut pairs = refs.chunks_exact(2);
    for p in &mut pairs {
        add(0, &p[0]);
        add(1, &p[1]);
    }
    if let [r] = pairs.remainder() {
        add(0, r);
    }
    for a in 0..3 {
        let (even, odd) = grid[2 * a * bins..(2 * a + 2) * bins].split_at_mut(bins);
        for (e, o) in even.iter_mut().zip(odd.iter()) {
            e.count += o.count;
            e.min = e.min.min(o.min);
            e.max = e.max.max(o.max);
        }
    }
    let n = refs.len() as u32;
    let mut best: Option<(f32, usize, usize)> = None;
    let right_cost = &mut scratch.right_cost;
    right_cost.clear();
    right_cost.resize(bins, 0.0);
    for a in (0..3).filter(|&a| ext[a] > 0.0) {
        let bin = &grid[2 * a * bins..][..bins];
        // right_cost[k]: area * count of bins k..bins (0 while they are empty).
        let (mut lo, mut hi, mut count) = (Vec3A::INFINITY, Vec3A::NEG_INFINITY, 0u32);
        for k in (1..bins).rev() {
            lo = lo.min(bin[k].min);
            hi = hi.max(bin[k].max);
            count += bin[k].count;
            right_cost[k] = if count > 0 {
                area(lo, hi) * count as f32
            } else {
                0.0
            };
        }
        let (mut lo, mut hi, mut count) = (Vec3A::INFINITY, Vec3A::NEG_INFINITY, 0u32);
        for k in 1..bins {
            lo = lo.min(bin[k - 1].min);
            hi = hi.max(bin[k - 1].max);
            count += bin[k - 1].count;
            if count == 0 || count == n {
                continue;
            }
            let cost = area(lo, hi) * count as f32 + right_cost[k];
            if best.is_none_or(|(c, ..)| cost < c) {
                best = Some((cost, a, k));
            }
        }
    }
    let (cost, a, plane) = best?;
    let (mid, left, right) =
        partition(refs, |r| bins_of(r.centroid(), min, scale, last)[a] < plane);
    debug_assert!(mid > 0 && mid < refs.len());
    Some(Split {
        cost,
        mid,
        left,
        right,
    })
}

/// Moves the elements for which `left` holds to the front; returns how many there are and the
/// (bounds, centroid bounds) of each side.
fn partition(
    refs: &mut [PrimRef],
    left: impl Fn(&PrimRef) -> bool,
) -> (usize, (Aabb, Aabb), (Aabb, Aabb)) {
    let mut l = (Aabb::EMPTY, Aabb::EMPTY);
    let mut r = (Aabb::EMPTY, Aabb::EMPTY);
    let mut mid = 0;
    for i in 0..refs.len() {
        let p = refs[i];
        if left(&p) {
            l = (l.0.union(p.bounds()), l.1.grown(p.centroid()));
            refs.swap(i, mid);
            mid += 1;
        } else {
            r = (r.0.union(p.bounds()), r.1.grown(p.centroid()));
        }
    }
    (mid, l, r)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::index::bvh::prim_ref::bounds_and_centroids;

    fn point_ref(id: u32, x: f32) -> PrimRef {
        let c = Vec3A::new(x, 0.0, 0.0);
        PrimRef::new(Aabb::new(c - 0.01, c + 0.01), id)
    }

    #[test]
    fn separates_two_clusters() {
        let mut refs: Vec<PrimRef> = (0..10)
            .map(|i| point_ref(i, if i % 2 == 0 { 0.0 } else { 10.0 } + i as f32 * 0.01))
            .collect();
        let (_, c) = bounds_and_centroids(&refs);
        let sp = split(&mut refs, &c, 8, &mut Scratch::default()).unwrap();
        assert_eq!(sp.mid, 5);
        assert_eq!(sp.left, bounds_and_centroids(&refs[..5]));
        assert_eq!(sp.right, bounds_and_centroids(&refs[5..]));
        assert!(refs[..5].iter().all(|r| r.id() % 2 == 0));
    }

    #[test]
    fn coincident_centroids_have_no_plane() {
        let mut refs: Vec<PrimRef> = (0..4).map(|i| point_ref(i, 1.0)).collect();
        let (_, c) = bounds_and_centroids(&refs);
        assert!(split(&mut refs, &c, 16, &mut Scratch::default()).is_none());
    }
}
