//! Lane-wise triangle tests: up to four triangles in structure-of-arrays form
//! ([`TriangleLanes`]), as SIMD leaves of the wide BVH copy them, and what a kernel's lane
//! form reports about them ([`LaneHits`]).
//!
//! Contract of [`super::TriangleKernel::intersect_lanes`]: for every lane **not** in
//! [`LaneHits::scalar`], the lane's bit in [`LaneHits::hit`] is set exactly when
//! `K::intersect(&lanes.triangle(i), ray, ray.t_max)` is `Some`, and then `t[i]` is that value,
//! bit for bit. Lanes in `scalar` are undecided (for the exact kernel: a sign its static filter
//! could not certify, or a non-finite `t`): the caller runs the scalar kernel on them. A kernel
//! without a lane form leaves every lane undecided, so its leaves cost one scalar call per
//! triangle, as before, but read the triangles from the contiguous block.

use super::Triangle;
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
