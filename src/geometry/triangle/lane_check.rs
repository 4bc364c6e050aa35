//! The scalar kernel's answers for the lanes of a block ([`scalar_lanes`]): what an undecided
//! lane gets, and the reference the lane forms are tested against ([`LaneTally`]).

use super::TriangleKernel;
#[cfg(test)]
use super::lanes::LaneHits;
use super::lanes::TriangleLanes;

/// The scalar kernel's answers for the four lanes (the reference the lane forms are tested
/// against, and what an undecided lane gets).
pub fn scalar_lanes<K: TriangleKernel>(
    lanes: &TriangleLanes,
    ray: &crate::geometry::Ray,
) -> [Option<f32>; 4] {
    std::array::from_fn(|i| K::intersect(&lanes.triangle(i), ray, ray.t_max))
}

/// What the lane-form tests saw: decided hits and misses, lanes left to the scalar kernel, and
/// blocks whose every lane was a decided miss (among them the blocks the lane forms' early exit
/// returns: every lane missed by its signs).
#[cfg(test)]
#[derive(Debug, Default)]
pub struct LaneTally {
    pub hits: usize,
    pub misses: usize,
    pub undecided: usize,
    pub all_missed: usize,
}

#[cfg(test)]
impl LaneTally {
    /// Asserts that every lane `got` decided equals the scalar kernel `K` bit for bit (hit or
    /// miss, and `t`), and counts the outcomes.
    pub fn check<K: TriangleKernel>(
        &mut self,
        got: &LaneHits,
        lanes: &TriangleLanes,
        ray: &crate::geometry::Ray,
    ) {
        self.all_missed += usize::from(got.hit | got.scalar == 0);
        for (i, w) in scalar_lanes::<K>(lanes, ray).iter().enumerate() {
            if got.scalar >> i & 1 == 1 {
                self.undecided += 1;
                continue;
            }
            let g = (got.hit >> i & 1 == 1).then_some(got.t[i]);
            assert_eq!(g.map(f32::to_bits), w.map(f32::to_bits), "lane {i} {ray:?}");
            if g.is_some() {
                self.hits += 1
            } else {
                self.misses += 1
            }
        }
    }

    /// Asserts that the test reached every outcome: over 10,000 hits and misses, over 100
    /// undecided lanes and over 1,000 blocks of misses only.
    pub fn assert_all_outcomes(&self) {
        assert!(
            self.hits > 10_000
                && self.misses > 10_000
                && self.undecided > 100
                && self.all_missed > 1_000,
            "{self:?}"
        );
    }
}
