//! Full sweep SAH split: on each axis, primitives sorted by centroid, every split between two
//! consecutive primitives scored by the surface area heuristic (MacDonald and Booth 1990).
//! O(n log n) per node; the slow, high-quality option.

use super::prim_ref::PrimRef;
use crate::geometry::Aabb;

/// Sorts by centroid on `axis`, ties by id (deterministic).
fn sort_on(refs: &mut [PrimRef], axis: usize) {
    refs.sort_unstable_by(|a, b| {
        a.centroid()[axis]
            .total_cmp(&b.centroid()[axis])
            .then(a.id().cmp(&b.id()))
    });
}

/// Finds the cheapest split over all three axes and orders `refs` so that it is at `mid`.
///
/// Returns `(cost, mid)` with both sides non-empty and
/// `cost = area(left) * n_left + area(right) * n_right`, each count rounded up to a multiple of
/// `block` ([`super::params::BuildConfig::sah_block`]); `None` for fewer than 2 primitives.
pub fn split(refs: &mut [PrimRef], block: usize) -> Option<(f32, usize)> {
    let n = refs.len();
    if n < 2 {
        return None;
    }
    // right_cost[i]: area * count of refs[i..].
    let mut right_cost = vec![0.0f32; n];
    let mut best: Option<(f32, usize, usize)> = None;
    for axis in 0..3 {
        sort_on(refs, axis);
        let mut acc = Aabb::EMPTY;
        for i in (1..n).rev() {
            acc = acc.union(refs[i].bounds());
            right_cost[i] = acc.surface_area() * (n - i).next_multiple_of(block) as f32;
        }
        let mut acc = Aabb::EMPTY;
        for i in 1..n {
            acc = acc.union(refs[i - 1].bounds());
            let cost = acc.surface_area() * i.next_multiple_of(block) as f32 + right_cost[i];
            if best.is_none_or(|(c, ..)| cost < c) {
                best = Some((cost, axis, i));
            }
        }
    }
    let (cost, axis, mid) = best?;
    if axis != 2 {
        sort_on(refs, axis);
    }
    Some((cost, mid))
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3A;

    #[test]
    fn finds_the_gap_on_the_right_axis() {
        // Two clusters along y; x and z carry no information (sorting on them orders by id,
        // which here also separates the clusters, at the same cost).
        let mut refs: Vec<PrimRef> = (0..9u32)
            .map(|i| {
                let c = Vec3A::new(0.0, if i < 3 { i as f32 } else { 100.0 + i as f32 }, 0.0);
                PrimRef::new(Aabb::new(c - 0.5, c + 0.5), 8 - i)
            })
            .collect();
        let (_, mid) = split(&mut refs, 1).unwrap();
        let low = |r: &PrimRef| r.centroid().y < 50.0;
        let (l, r) = refs.split_at(mid);
        assert!(l.iter().all(low) && !r.iter().any(low) || !l.iter().any(low) && r.iter().all(low));
    }
}
