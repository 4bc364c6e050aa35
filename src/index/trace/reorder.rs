//! Ray reordering for memory coherence, the `reorder` mode (Pharr, Kolb, Gershbein and Hanrahan
//! 1997; Moon, Byun, Kim, Gibson and Yoon 2010; Garanzha and Loop 2010): a batch's rays are
//! sorted by a coherence key, traced one query at a time in that order by the parallel driver,
//! and their answers (and counters) put back in input order. Rays that start near each other
//! and point the same way then follow each other through the structure, so the nodes and
//! primitives one ray brought into the caches are there for the next.
//!
//! The key ([`coherence_key`]), most significant first: the direction's octant (3 sign bits: rays
//! of one octant visit a tree's children in the same order), the origin's Morton code in the
//! batch's origin box (10 bits per axis: rays from nearby points), then the unit direction's
//! Morton code (7 bits per axis). Camera rays share their origin, so they sort by direction;
//! incoherent rays sort into cells of their origins. Ties keep input order (the sort is by key,
//! then index), so the order is deterministic.
//!
//! The parallel driver ([`super::parallel`]) traces the sorted rays ([`Sorted`]) as in `single`,
//! so the hits are those of `single` bit for bit; only the order differs. The sort, the gather of the rays and
//! the scatter of the answers belong to the mode and are timed with it. The mode holds, per
//! ray, the sorted copy of the ray, its key and index, and its sorted answer and counters
//! ([`BYTES_PER_RAY`]), once per batch, never per ray.

use crate::geometry::Ray;
use crate::index::Counters;
use glam::Vec3A;
use rayon::prelude::*;

/// Bits per axis of the origin's Morton code.
const ORIGIN_BITS: u32 = 10;
/// Bits per axis of the direction's Morton code.
const DIRECTION_BITS: u32 = 7;

/// Bytes the mode holds per ray beside the batch: the sorted ray, its key and index, and its
/// sorted answer and counters (an upper bound, for the memory budget).
pub const BYTES_PER_RAY: usize =
    size_of::<Ray>() + size_of::<(u64, usize)>() + size_of::<Counters>() + 16;

/// The bits of `x` (below 2^21) spread to every third bit.
fn spread3(x: u32) -> u64 {
    let mut x = u64::from(x) & 0x1f_ffff;
    x = (x | x << 32) & 0x1f_0000_0000_ffff;
    x = (x | x << 16) & 0x1f_0000_ff00_00ff;
    x = (x | x << 8) & 0x100f_00f0_0f00_f00f;
    x = (x | x << 4) & 0x10c3_0c30_c30c_30c3;
    (x | x << 2) & 0x1249_2492_4924_9249
}

/// The Morton code of `p` (each component in `[0, 1]`, clamped; NaN counts as 0) with `bits`
/// per axis.
fn morton(p: Vec3A, bits: u32) -> u64 {
    let top = ((1u32 << bits) - 1) as f32;
    let q = |x: f32| (x * top).clamp(0.0, top) as u32;
    spread3(q(p.x)) | spread3(q(p.y)) << 1 | spread3(q(p.z)) << 2
}

/// The coherence key of `ray` (see the module doc), its origin placed in the box `lo` +
/// `[0, 1/inv_extent]`.
pub fn coherence_key(ray: &Ray, lo: Vec3A, inv_extent: Vec3A) -> u64 {
    let d = ray.dir;
    let octant = u64::from(d.x < 0.0) | u64::from(d.y < 0.0) << 1 | u64::from(d.z < 0.0) << 2;
    let origin = morton((ray.origin - lo) * inv_extent, ORIGIN_BITS);
    let unit = d * d.length_recip();
    let direction = morton((unit + 1.0) * 0.5, DIRECTION_BITS);
    octant << (3 * (ORIGIN_BITS + DIRECTION_BITS)) | origin << (3 * DIRECTION_BITS) | direction
}

/// The rays' indices in coherence order (by key, ties by index).
pub fn coherence_order(rays: &[Ray]) -> Vec<(u64, usize)> {
    let (lo, hi) = rays.iter().fold(
        (Vec3A::splat(f32::INFINITY), Vec3A::splat(f32::NEG_INFINITY)),
        |(lo, hi), r| (lo.min(r.origin), hi.max(r.origin)),
    );
    let extent = hi - lo;
    // A flat axis (every origin alike, as for camera rays) gets no bits of the origin's code.
    let inv_extent = Vec3A::select(extent.cmpgt(Vec3A::ZERO), extent.recip(), Vec3A::ZERO);
    let mut order: Vec<(u64, usize)> = rays
        .par_iter()
        .enumerate()
        .map(|(i, r)| (coherence_key(r, lo, inv_extent), i))
        .collect();
    order.par_sort_unstable();
    order
}

/// A batch in coherence order: its rays sorted ([`Sorted::rays`]) and where each came from.
pub struct Sorted {
    /// Each sorted ray's key and its index in the batch.
    order: Vec<(u64, usize)>,
    /// The batch's rays in coherence order.
    pub rays: Vec<Ray>,
}

impl Sorted {
    /// Sorts `rays` ([`coherence_order`]) and gathers them in that order.
    pub fn new(rays: &[Ray]) -> Sorted {
        let order = coherence_order(rays);
        let sorted = order.par_iter().map(|&(_, i)| rays[i]).collect();
        Sorted {
            order,
            rays: sorted,
        }
    }

    /// Puts per-ray values of the sorted rays (`sorted[k]` of `self.rays[k]`) back at their
    /// rays' places in the batch.
    pub fn scatter<T: Copy>(&self, sorted: &[T], out: &mut [T]) {
        for (&(_, i), v) in self.order.iter().zip(sorted) {
            out[i] = *v;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    #[test]
    fn spread_interleaves_every_third_bit() {
        assert_eq!(spread3(0b1011), 0b1_000_001_001);
        assert_eq!(spread3(0x1f_ffff), 0x1249_2492_4924_9249);
        assert_eq!(morton(Vec3A::ONE, 2), 0b111_111);
        assert_eq!(morton(Vec3A::new(1.0, 0.0, 0.0), 1), 0b001);
    }

    /// The order is a permutation, by octant first, then by origin; an origin near `f32::MAX`
    /// gets a key like any other (and makes every other origin's cell the same).
    #[test]
    fn the_order_is_a_permutation_by_octant_then_origin() {
        let r = |o: [f32; 3], d: [f32; 3]| Ray::infinite(Vec3::from(o), Vec3::from(d)).unwrap();
        let order = |rays: &[Ray]| -> Vec<usize> {
            coherence_order(rays).into_iter().map(|p| p.1).collect()
        };
        let mut rays = vec![
            r([9.0, 9.0, 9.0], [1.0, 1.0, 1.0]),
            r([0.0, 0.0, 0.0], [-1.0, 1.0, 1.0]),
            r([0.0, 0.0, 0.0], [1.0, 1.0, 1.0]),
            r([9.0, 0.0, 0.0], [1.0, 2.0, 1.0]),
        ];
        assert_eq!(
            order(&rays),
            [2, 3, 0, 1],
            "origin cells, then the x < 0 octant"
        );
        rays.push(r([3.0e38, -3.0e38, 0.0], [1.0, 1.0, 1e-30]));
        let mut seen = order(&rays);
        assert_eq!(seen.last(), Some(&1), "the x < 0 octant sorts last");
        seen.sort_unstable();
        assert_eq!(seen, (0..rays.len()).collect::<Vec<_>>());
    }
}
