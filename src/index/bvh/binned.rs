//! Binned SAH split (Wald 2007): centroids are binned into `bins` equal buckets per axis, and
//! the `bins - 1` planes between buckets are scored by the surface area heuristic.

use super::params::BINS;
use super::prim_ref::PrimRef;
use crate::geometry::Aabb;
use glam::{BVec3A, Vec3A};

/// Bin slots per axis: the largest accepted bin count, a power of two, so that masking a bin
/// index (always below the bin count) with `SLOTS - 1` proves it in range without changing it.
pub const SLOTS: usize = 64;
const _: () = assert!(SLOTS == *BINS.end() as usize && SLOTS.is_power_of_two());

/// Nodes with at least this many primitives bin into two sets (even and odd primitives), so
/// that consecutive primitives landing in the same bin do not wait on each other; smaller
/// nodes use one set (clearing and merging a second would cost more than it saves).
const TWO_SETS_MIN: usize = 256;

/// One set of bins on the three axes: bin `k` of axis `a` holds `count[a][k]` primitives whose
/// bounds' union is `min[a][k]..max[a][k]`. Only the first `bins` slots of each axis are used.
#[derive(Clone)]
struct BinSet {
    min: [[Vec3A; SLOTS]; 3],
    max: [[Vec3A; SLOTS]; 3],
    count: [[u32; SLOTS]; 3],
}

impl BinSet {
    const EMPTY: BinSet = BinSet {
        min: [[Vec3A::INFINITY; SLOTS]; 3],
        max: [[Vec3A::NEG_INFINITY; SLOTS]; 3],
        count: [[0; SLOTS]; 3],
    };

    /// Empties the first `bins` (at most [`SLOTS`]) bins of every axis.
    fn clear(&mut self, bins: usize) {
        for a in 0..3 {
            self.min[a][..bins].fill(Vec3A::INFINITY);
            self.max[a][..bins].fill(Vec3A::NEG_INFINITY);
            self.count[a][..bins].fill(0);
        }
    }

    /// Adds `r` to bin `k[a]` of each axis `a` (every `k[a]` below the bin count).
    #[inline(always)]
    fn add(&mut self, k: [usize; 3], r: &PrimRef) {
        let (lo, hi) = (r.min(), r.max());
        for (a, k) in k.into_iter().enumerate() {
            let k = k & (SLOTS - 1);
            self.count[a][k] += 1;
            self.min[a][k] = self.min[a][k].min(lo);
            self.max[a][k] = self.max[a][k].max(hi);
        }
    }

    /// Adds `o`'s first `bins` bins into this set's.
    fn merge(&mut self, o: &BinSet, bins: usize) {
        for a in 0..3 {
            for k in 0..bins {
                self.count[a][k] += o.count[a][k];
                self.min[a][k] = self.min[a][k].min(o.min[a][k]);
                self.max[a][k] = self.max[a][k].max(o.max[a][k]);
            }
        }
    }
}

/// Surface area of a non-empty box given by its corners (no emptiness check: callers only
/// score sides that hold primitives).
#[inline(always)]
fn area(min: Vec3A, max: Vec3A) -> f32 {
    let e = max - min;
    2.0 * (e.x * e.y + e.y * e.z + e.z * e.x)
}

/// Scaled centroid offsets `(c - min) * scale`: truncated (and clamped to the last bin) they
/// are the centroid's bins on the three axes. The same function bins and partitions, so the
/// partition matches the counts the cost was computed from. `scale` is finite and 0 on axes
/// without extent (everything in bin 0).
#[inline(always)]
fn offsets(c: Vec3A, min: Vec3A, scale: Vec3A) -> Vec3A {
    (c - min) * scale
}

/// Bins of a centroid on the three axes, in `[0, bins - 1]`; `last` is `bins - 1` on every lane.
#[inline(always)]
fn bins_of(c: Vec3A, min: Vec3A, scale: Vec3A, last: Vec3A) -> [usize; 3] {
    // In [0, bins - 1]: c >= min, and the product is at most bins (times 1 + eps).
    truncate(offsets(c, min, scale).min(last))
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

/// Reusable bin storage, so that no node allocates or clears more bins than it uses (one per
/// build thread).
pub struct Scratch {
    /// Even and odd primitives' bins (the second used only from [`TWO_SETS_MIN`] primitives).
    sets: Box<[BinSet; 2]>,
    sweep: Sweep,
}

impl Default for Scratch {
    fn default() -> Scratch {
        Scratch {
            sets: Box::new([BinSet::EMPTY, BinSet::EMPTY]),
            sweep: Sweep::default(),
        }
    }
}

/// The bins of one axis as the SAH sweep reads them: bin `k` holds references whose bounds'
/// union is `min[k]..max[k]` (`+inf..-inf` when empty); `enter[k]` of them start in it
/// (they go left of every plane above `k`) and `exit[k]` end in it (they go right of every
/// plane up to `k`). For object bins both are the bin's count; a spatial split counts a
/// reference that spans several bins once in its first and once in its last.
pub struct AxisBins<'a> {
    pub min: &'a [Vec3A],
    pub max: &'a [Vec3A],
    pub enter: &'a [u32],
    pub exit: &'a [u32],
    /// The SAH counts each side's references rounded up to a multiple of this
    /// ([`super::params::BuildConfig::sah_block`]).
    pub block: u32,
}

/// A scored plane: between bins `plane - 1` and `plane` of `axis`, with
/// `cost = area(left) * counts[0] + area(right) * counts[1]` (both counts > 0, each rounded up
/// to a multiple of [`AxisBins::block`] in the cost).
#[derive(Debug, Clone, Copy)]
pub struct Plane {
    pub cost: f32,
    pub axis: usize,
    pub plane: usize,
    pub left: Aabb,
    pub right: Aabb,
    pub counts: [u32; 2],
}

/// The SAH sweep's buffer: per plane `k` of the axis being swept, the SAH term
/// `area * count`, the box and the count of bins `k..`.
pub struct Sweep {
    right: Box<[(f32, Aabb, u32); SLOTS]>,
}

impl Default for Sweep {
    fn default() -> Sweep {
        Sweep {
            right: Box::new([(0.0, Aabb::EMPTY); SLOTS].map(|(a, b)| (a, b, 0))),
        }
    }
}

impl Sweep {
    /// Scores the planes between the bins of `axis` (at most [`SLOTS`]) that send at most
    /// `max_refs` references to the two sides together, and keeps in `best` the first plane
    /// strictly cheaper than it, planes in increasing order.
    pub fn axis(&mut self, axis: usize, bins: &AxisBins, max_refs: u32, best: &mut Option<Plane>) {
        let (lo, hi) = (bins.min, bins.max);
        let n = lo.len().min(SLOTS);
        let right = &mut *self.right;
        let (mut acc, mut c) = (Aabb::EMPTY, 0u32);
        for k in (1..n).rev() {
            acc = Aabb::new(acc.min.min(lo[k]), acc.max.max(hi[k]));
            c += bins.exit[k];
            let term = if c > 0 {
                area(acc.min, acc.max) * c.next_multiple_of(bins.block) as f32
            } else {
                0.0
            };
            right[k] = (term, acc, c);
        }
        let (mut acc, mut c) = (Aabb::EMPTY, 0u32);
        for k in 1..n {
            acc = Aabb::new(acc.min.min(lo[k - 1]), acc.max.max(hi[k - 1]));
            c += bins.enter[k - 1];
            let (term, right_box, rc) = right[k];
            if c == 0 || rc == 0 || c.saturating_add(rc) > max_refs {
                continue;
            }
            let cost = area(acc.min, acc.max) * c.next_multiple_of(bins.block) as f32 + term;
            if best.is_none_or(|b| cost < b.cost) {
                *best = Some(Plane {
                    cost,
                    axis,
                    plane: k,
                    left: acc,
                    right: right_box,
                    counts: [c, rc],
                });
            }
        }
    }
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
/// The chosen plane depends only on the set of primitives, not on their order.
pub fn split(
    refs: &mut [PrimRef],
    centroids: &Aabb,
    bins: u32,
    block: u32,
    scratch: &mut Scratch,
) -> Option<Split> {
    debug_assert!(BINS.contains(&bins));
    let bins = (bins as usize).min(SLOTS);
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
    let key = |r: &PrimRef| bins_of(r.centroid(), min, scale, last);
    let [set, odd] = &mut *scratch.sets;
    set.clear(bins);
    if refs.len() >= TWO_SETS_MIN {
        odd.clear(bins);
        let mut pairs = refs.chunks_exact(2);
        for p in &mut pairs {
            set.add(key(&p[0]), &p[0]);
            odd.add(key(&p[1]), &p[1]);
        }
        if let [r] = pairs.remainder() {
            set.add(key(r), r);
        }
        set.merge(odd, bins);
    } else {
        for r in refs.iter() {
            set.add(key(r), r);
        }
    }
    let mut best = None;
    for a in (0..3).filter(|&a| ext[a] > 0.0) {
        let bins = AxisBins {
            min: &set.min[a][..bins],
            max: &set.max[a][..bins],
            enter: &set.count[a][..bins],
            exit: &set.count[a][..bins],
            block,
        };
        scratch.sweep.axis(a, &bins, u32::MAX, &mut best);
    }
    let Plane {
        cost,
        axis: a,
        plane,
        left,
        right,
        ..
    } = best?;
    let plane = plane as f32;
    // The bin is below `plane` exactly when the unclamped offset is (plane <= bins - 1).
    let (mid, lc, rc) = partition(refs, |r| offsets(r.centroid(), min, scale)[a] < plane);
    debug_assert!(mid > 0 && mid < refs.len());
    Some(Split {
        cost,
        mid,
        left: (left, lc),
        right: (right, rc),
    })
}

/// Moves the elements for which `left` holds to the front, in place; returns how many there are
/// and the centroid bounds of each side.
///
/// Branch free (the side of each element is data dependent and unpredictable): every element
/// is swapped with the first right-side one, which keeps `refs[..mid]` left and
/// `refs[mid..=i]` right, and `mid` advances only past left ones.
fn partition(refs: &mut [PrimRef], left: impl Fn(&PrimRef) -> bool) -> (usize, Aabb, Aabb) {
    let (mut lc, mut rc) = (Aabb::EMPTY, Aabb::EMPTY);
    let mut mid = 0;
    for i in 0..refs.len() {
        let p = refs[i];
        let c = p.centroid();
        let is_left = left(&p);
        let m = BVec3A::splat(is_left);
        lc = Aabb::new(
            Vec3A::select(m, lc.min.min(c), lc.min),
            Vec3A::select(m, lc.max.max(c), lc.max),
        );
        rc = Aabb::new(
            Vec3A::select(m, rc.min, rc.min.min(c)),
            Vec3A::select(m, rc.max, rc.max.max(c)),
        );
        refs.swap(i, mid);
        mid += is_left as usize;
    }
    (mid, lc, rc)
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
        let sp = split(&mut refs, &c, 8, 1, &mut Scratch::default()).unwrap();
        assert_eq!(sp.mid, 5);
        assert_eq!(sp.left, bounds_and_centroids(&refs[..5]));
        assert_eq!(sp.right, bounds_and_centroids(&refs[5..]));
        assert!(refs[..5].iter().all(|r| r.id() % 2 == 0));
    }

    #[test]
    fn coincident_centroids_have_no_plane() {
        let mut refs: Vec<PrimRef> = (0..4).map(|i| point_ref(i, 1.0)).collect();
        let (_, c) = bounds_and_centroids(&refs);
        assert!(split(&mut refs, &c, 16, 1, &mut Scratch::default()).is_none());
    }
}
