//! Lane-wise triangle tests: up to four triangles in structure-of-arrays form
//! ([`TriangleLanes`]), as SIMD leaves of the wide BVH copy them, and what a kernel's lane
//! form reports about them ([`LaneHits`]).
//!
//! Contract of [`TriangleKernel::intersect_lanes`]: for every lane **not** in
//! [`LaneHits::scalar`], the lane's bit in [`LaneHits::hit`] is set exactly when
//! `K::intersect(&lanes.triangle(i), ray, ray.t_max)` is `Some`, and then `t[i]` is that value,
//! bit for bit. Lanes in `scalar` are undecided (for the exact kernel: a sign its static filter
//! could not certify, or a non-finite `t`): the caller runs the scalar kernel on them. A kernel
//! without a lane form leaves every lane undecided, so its leaves cost one scalar call per
//! triangle, as before, but read the triangles from the contiguous block.

use super::{Triangle, TriangleKernel};
use glam::Vec3A;

/// Up to four triangles: `v[corner][axis][lane]`. Blocks of fewer triangles repeat their
/// first triangle in the unused lanes (a repeated test returns the same answer, so it changes
/// no closest or any hit).
#[derive(Debug, Clone, Copy, PartialEq)]
#[repr(C, align(16))]
pub struct TriangleLanes {
    pub v: [[[f32; 4]; 3]; 3],
}

impl TriangleLanes {
    /// The block of `tris` (1 to 4 triangles), unused lanes filled with `tris[0]`.
    pub fn new(tris: &[Triangle]) -> TriangleLanes {
        assert!((1..=4).contains(&tris.len()), "{} triangles", tris.len());
        let lane = |i: usize| tris.get(i).unwrap_or(&tris[0]);
        let v = std::array::from_fn(|corner| {
            std::array::from_fn(|axis| std::array::from_fn(|i| lane(i).v[corner][axis]))
        });
        TriangleLanes { v }
    }

    /// The triangle in lane `lane` (0..4).
    #[inline(always)]
    pub fn triangle(&self, lane: usize) -> Triangle {
        let corner = |c: usize| {
            let p = &self.v[c];
            Vec3A::new(p[0][lane], p[1][lane], p[2][lane])
        };
        Triangle::new(corner(0), corner(1), corner(2))
    }
}

/// What a lane form decided (see the module doc): bit `i` of `hit` for a hit in lane `i` at
/// `t[i]`, bit `i` of `scalar` for a lane left to the scalar kernel.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LaneHits {
    pub hit: u32,
    pub scalar: u32,
    pub t: [f32; 4],
}

impl LaneHits {
    /// Nothing decided: every lane to the scalar kernel.
    pub const UNDECIDED: LaneHits = LaneHits {
        hit: 0,
        scalar: 0b1111,
        t: [0.0; 4],
    };

    /// Every lane decided: a miss. Lane forms return it as soon as their signs show that no
    /// lane can hit, before they compute any `t`.
    pub const MISS: LaneHits = LaneHits {
        hit: 0,
        scalar: 0,
        t: [0.0; 4],
    };
}

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

/// Up to four scene triangles copied into a leaf ([`TriangleLanes`]) with their primitive
/// ids; unused lanes repeat lane 0's triangle and id. 160 bytes, aligned to 32 so that a block
/// in an array spans three cache lines, never four.
#[derive(Debug, Clone, Copy, PartialEq)]
#[repr(C, align(32))]
pub struct TriangleBlock {
    pub tris: TriangleLanes,
    pub ids: [u32; 4],
}

const _: () = assert!(size_of::<TriangleBlock>() == 160);

impl TriangleBlock {
    /// The block of `tris` (1 to 4) with ids `ids` (as many).
    pub fn new(tris: &[Triangle], ids: &[u32]) -> TriangleBlock {
        assert_eq!(tris.len(), ids.len());
        TriangleBlock {
            tris: TriangleLanes::new(tris),
            ids: std::array::from_fn(|i| *ids.get(i).unwrap_or(&ids[0])),
        }
    }
}
