//! Binned SAH for the kd-tree's large nodes (Shevtsov, Soupikov & Kapustin 2007; Havran 2000
//! §4.4): instead of every face of every primitive's clipped bounds, the candidates are the
//! `bins - 1` planes that cut the cell into `bins` equal slabs per axis, and the references are
//! counted per slab in one pass. The build keeps no event lists for such nodes (only the
//! references and their clipped bounds) and sorts nothing; it switches to the exact sweep over
//! sorted events ([`crate::index::kit::near_far::sweep::best_split_sorted`]) where a node has few references.
//!
//! The plane chosen is the cheapest bin boundary, not the cheapest perfect split: a tree with
//! binned upper levels differs from the exact-SAH tree there (the trees below the switch are
//! chosen exactly, each over its own cell).

use crate::geometry::Aabb;
use crate::index::kit::near_far::sweep::{PlaneCost, Ref, Weights};

/// Largest accepted bin count.
pub const MAX_BINS: u32 = 1024;

/// Per-slab counts, reused between nodes: `starts[k]` references whose padded bounds start in
/// slab `k`, `ends[k]` that end there.
#[derive(Debug, Default)]
pub(super) struct Bins {
    starts: Vec<u32>,
    ends: Vec<u32>,
}

impl Bins {
    /// The cheapest of the `bins - 1` inner slab boundaries per axis of `cell` as `(axis,
    /// position)`, when its SAH cost is below a leaf's (`intersect * refs.len()`); ties go to
    /// the lower axis, then the lower position. `bins >= 2`.
    ///
    /// A reference counts below a plane when its bounds grown by `pad` start before it and
    /// above when they end after it, the builders' classification. Counted by slab, a bound
    /// within rounding of a boundary may be counted in the neighbouring slab: that changes the
    /// estimate, never where the reference then goes.
    pub fn best_split(
        &mut self,
        refs: &[Ref],
        cell: &Aabb,
        pad: f32,
        w: &Weights,
        bins: usize,
    ) -> Option<(usize, f32)> {
        let area = cell.surface_area();
        if area <= 0.0 || !area.is_finite() {
            return None;
        }
        let n = refs.len();
        let mut best = None;
        let mut best_cost = w.intersect * n as f32;
        for axis in 0..3 {
            let Some(plane) = PlaneCost::new(cell, axis, area, w) else {
                continue;
            };
            let (lo, hi) = (cell.min[axis], cell.max[axis]);
            let scale = bins as f32 / (hi - lo);
            // `as` saturates (and maps NaN to 0), the clamp keeps the last slab closed.
            let slab = |x: f32| (((x - lo) * scale) as usize).min(bins - 1);
            self.starts.clear();
            self.starts.resize(bins, 0);
            self.ends.clear();
            self.ends.resize(bins, 0);
            for r in refs {
                self.starts[slab(r.b.min[axis] - pad)] += 1;
                self.ends[slab(r.b.max[axis] + pad)] += 1;
            }
            let (mut n_below, mut n_above) = (0usize, n);
            for k in 1..bins {
                n_below += self.starts[k - 1] as usize;
                n_above -= self.ends[k - 1] as usize;
                let s = lo + (hi - lo) * (k as f32 / bins as f32);
                if let Some(cost) = plane.cost(s, n_below, n_above)
                    && cost < best_cost
                {
                    best_cost = cost;
                    best = Some((axis, s));
                }
            }
        }
        best
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3A;

    fn weights() -> Weights {
        Weights {
            intersect: 80.0,
            traversal: 1.0,
            empty_bonus: 0.2,
        }
    }

    /// A box `x..x + 0.9` by `0..1` by `0..1`.
    fn box_at(x: f32) -> Ref {
        Ref {
            prim: 0,
            b: Aabb::new(Vec3A::new(x, 0.0, 0.0), Vec3A::new(x + 0.9, 1.0, 1.0)),
        }
    }

    #[test]
    fn separates_two_clusters_at_the_boundary_between_them() {
        // Four boxes in x 0..2 and four in x 6..8, in a cell 0..8 x 0..1 x 0..1: the
        // boundaries at 2..6 separate them at equal cost; the lowest (2) wins the tie.
        let refs: Vec<Ref> = [0.0, 0.5, 1.0, 1.0, 6.0, 6.5, 7.0, 7.0]
            .map(box_at)
            .to_vec();
        let cell = Aabb::new(Vec3A::ZERO, Vec3A::new(8.0, 1.0, 1.0));
        let got = Bins::default().best_split(&refs, &cell, 0.0, &weights(), 8);
        assert_eq!(got, Some((0, 2.0)));
    }

    #[test]
    fn no_split_of_a_cell_without_volume_or_cheaper_plane() {
        let refs = vec![box_at(0.0)];
        let flat = Aabb::new(Vec3A::ZERO, Vec3A::new(1.0, 0.0, 0.0));
        let mut bins = Bins::default();
        assert_eq!(bins.best_split(&refs, &flat, 0.0, &weights(), 4), None);
        // One box filling its cell: every plane keeps it on both sides.
        let full = Aabb::new(Vec3A::ZERO, Vec3A::ONE);
        let refs = vec![Ref { prim: 0, b: full }];
        assert_eq!(bins.best_split(&refs, &full, 0.0, &weights(), 4), None);
    }
}
