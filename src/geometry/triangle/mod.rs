//! Triangles and the five ray–triangle kernels.
//!
//! Every kernel is a pure function `(triangle, ray, t_max) -> Option<t>` that reports a hit only
//! for `t` in the closed interval `[ray.t_min, t_max]`. The `t` it computes does not depend on
//! `t_max` (only the acceptance does), so indices that pass a shrinking `t_max` get the same bits
//! as brute force.

pub mod exact;
pub mod lane_check;
pub mod lanes;
mod moller_trumbore;
mod parametric;
mod plane_edges;
mod watertight;

pub use exact::Exact;
pub use moller_trumbore::MollerTrumbore;
pub use parametric::Parametric;
pub use plane_edges::PlaneEdges;
pub use watertight::Watertight;

pub(crate) use super::real::in_interval;

use super::Ray;
use super::real::{KernelRay, RealVec};
pub use super::triangle_shape::Triangle;
use serde::{Deserialize, Serialize};

/// A ray–triangle kernel. Implementors are zero-sized, so the choice is made at compile time and
/// a traversal monomorphized for one kernel pays no dispatch.
pub trait TriangleKernel: Copy + Default + Send + Sync + 'static {
    /// The name used on the command line and in reports.
    const NAME: &'static str;
    /// `Some(t)` when the ray hits the triangle at `t` in `[ray.t_min, t_max]`.
    fn intersect(tri: &Triangle, ray: &Ray, t_max: f32) -> Option<f32>;
    /// The lane form on up to four triangles (contract in [`lanes`]); by default no lane is
    /// decided, so every triangle goes through [`TriangleKernel::intersect`].
    #[inline(always)]
    fn intersect_lanes(_tris: &lanes::TriangleLanes, _ray: &Ray) -> lanes::LaneHits {
        lanes::LaneHits::UNDECIDED
    }
}

/// A triangle kernel written once over the precision ([`crate::geometry::real`]): its `f32`
/// instance is its [`TriangleKernel::intersect`], its `f64` instance the accuracy study's mirror
/// (same formulas, same order of operations, same acceptance tests).
pub trait RealKernel: Copy + Default + Send + Sync + 'static {
    /// The name used on the command line and in reports.
    const NAME: &'static str;
    /// `Some(t)` when the ray hits the triangle with corners `v` at `t` in `[ray.t_min, t_max]`.
    fn on_corners<R: KernelRay>(v: [R::Vec; 3], ray: &R, t_max: R::Scalar) -> Option<R::Scalar>;

    /// The lane form of the `f32` instance ([`TriangleKernel::intersect_lanes`], contract in
    /// [`lanes`]); by default no lane is decided.
    #[inline(always)]
    fn on_lanes(_tris: &lanes::TriangleLanes, _ray: &Ray) -> lanes::LaneHits {
        lanes::LaneHits::UNDECIDED
    }

    /// [`RealKernel::on_corners`] on the corners of `tri`, taken exactly in the ray's precision.
    #[inline(always)]
    fn intersect_in<R: KernelRay>(tri: &Triangle, ray: &R, t_max: R::Scalar) -> Option<R::Scalar> {
        Self::on_corners(tri.v.map(R::Vec::from_f32), ray, t_max)
    }
}

impl<K: RealKernel> TriangleKernel for K {
    const NAME: &'static str = <K as RealKernel>::NAME;
    #[inline]
    fn intersect(tri: &Triangle, ray: &Ray, t_max: f32) -> Option<f32> {
        K::intersect_in(tri, ray, t_max)
    }
    #[inline(always)]
    fn intersect_lanes(tris: &lanes::TriangleLanes, ray: &Ray) -> lanes::LaneHits {
        K::on_lanes(tris, ray)
    }
}

/// The selectable triangle kernels (run-time name of a [`TriangleKernel`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum TriangleKernelKind {
    PlaneEdges,
    Parametric,
    MollerTrumbore,
    Watertight,
    /// The default: exact hit/miss decisions at the watertight kernel's speed (see `exact`).
    #[default]
    Exact,
}

impl TriangleKernelKind {
    pub const ALL: [TriangleKernelKind; 5] = [
        TriangleKernelKind::PlaneEdges,
        TriangleKernelKind::Parametric,
        TriangleKernelKind::MollerTrumbore,
        TriangleKernelKind::Watertight,
        TriangleKernelKind::Exact,
    ];

    pub fn name(self) -> &'static str {
        match self {
            TriangleKernelKind::PlaneEdges => <PlaneEdges as RealKernel>::NAME,
            TriangleKernelKind::Parametric => <Parametric as RealKernel>::NAME,
            TriangleKernelKind::MollerTrumbore => <MollerTrumbore as RealKernel>::NAME,
            TriangleKernelKind::Watertight => <Watertight as RealKernel>::NAME,
            TriangleKernelKind::Exact => Exact::NAME,
        }
    }

    /// Parses a kernel name as printed by [`TriangleKernelKind::name`].
    pub fn parse(s: &str) -> Option<TriangleKernelKind> {
        Self::ALL.into_iter().find(|k| k.name() == s)
    }

    /// Runs the selected kernel (for tools that pick the kernel per call, not for hot loops).
    pub fn intersect(self, tri: &Triangle, ray: &Ray, t_max: f32) -> Option<f32> {
        match self {
            TriangleKernelKind::PlaneEdges => PlaneEdges::intersect(tri, ray, t_max),
            TriangleKernelKind::Parametric => Parametric::intersect(tri, ray, t_max),
            TriangleKernelKind::MollerTrumbore => MollerTrumbore::intersect(tri, ray, t_max),
            TriangleKernelKind::Watertight => Watertight::intersect(tri, ray, t_max),
            TriangleKernelKind::Exact => Exact::intersect(tri, ray, t_max),
        }
    }
}

impl std::fmt::Display for TriangleKernelKind {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::test_support::unit_floats;
    use glam::Vec3;
    use glam::Vec3A;

    fn tri() -> Triangle {
        Triangle::from_corners([0.0, 0.0, 2.0], [4.0, 0.0, 2.0], [0.0, 4.0, 2.0])
    }

    fn all(ray: &Ray) -> [Option<f32>; 5] {
        TriangleKernelKind::ALL.map(|k| k.intersect(&tri(), ray, ray.t_max))
    }

    #[test]
    fn a_triangle_with_two_equal_corners_is_degenerate_and_never_hit() {
        // Found by the property test through the grid: with glam's cross product fused (FMA
        // builds), this segment got the normal (-6e-8, -6e-8, 0) and plane-edges hit it at
        // (0, 1, -0.494), 1.1 away from the segment, in a cell the segment never touches.
        let t = Triangle::from_corners(
            [0.0, 1.0, 0.653_411_15],
            [-0.75, 0.25, -1.823_173],
            [-0.75, 0.25, -1.823_173],
        );
        assert!(t.is_degenerate());
        assert_eq!(t.normal(), Vec3A::ZERO);
        let o = Vec3::new(0.0, 4.0, f32::from_bits(0xbefd_1718));
        let r = Ray::infinite(o, -Vec3::Y).unwrap();
        for k in TriangleKernelKind::ALL {
            assert_eq!(k.intersect(&t, &r, r.t_max), None, "{k}");
        }
    }

    /// The ray of a `.rays` record given as bits (origin, `t_min`, direction, `t_max`).
    fn ray_from_bits(b: [u32; 8]) -> Ray {
        let f = b.map(f32::from_bits);
        let (o, d) = (Vec3::new(f[0], f[1], f[2]), Vec3::new(f[4], f[5], f[6]));
        Ray::new(o, d, f[3], f[7]).unwrap()
    }

    /// Distance from `p` to the segment `[a, b]`, in f64.
    fn distance_to_segment(p: Vec3A, a: Vec3A, b: Vec3A) -> f64 {
        let (p, a, b) = (p.as_dvec3(), a.as_dvec3(), b.as_dvec3());
        let ab = b - a;
        let s = ((p - a).dot(ab) / ab.length_squared()).clamp(0.0, 1.0);
        (a + ab * s - p).length()
    }

    #[test]
    fn zero_area_triangles_in_the_rays_plane_are_never_hit_off_the_triangle() {
        // Found by the property test through the spatial-split BVHs and the grid: rays aimed
        // at a vertex, so the ray lies in the zero-area triangle's line. Moller-Trumbore and
        // parametric divided rounding noise by rounding noise and hit at a random `t`, 0.07 to
        // 2.1 away from the segment. (corners, ray bits)
        #[rustfmt::skip]
        let cases = [
            (
                [[0.5, 0.0, 0.0], [0.75, 0.915_031_4, -1.0], [0.75, 0.915_031_4, -1.0]],
                [
                    0xbfbd_c24c, 0x3f00_0000, 0xbf11_dd99, 0, 0x400e_e126, 0x3ed4_7efe, 0xbedc_44ce,
                    0x7f80_0000,
                ],
            ),
            (
                // Three collinear corners: the third is the midpoint of the first two.
                [
                    [0.461_141_8, 0.75, 1.911_677_6],
                    [-0.5, 1.927_118_9, 0.0],
                    [-0.019_429_103, 1.338_559_4, 0.955_838_8],
                ],
                [
                    0x405a_abfa, 0x3fd0_d13a, 0xbf00_0000, 0x3f8f_9d65, 0xc05b_ea4e, 0xbe95_ed40,
                    0x3fba_58ed, 0x401e_33cf,
                ],
            ),
            (
                // Collinear up to one rounding: its determinant passed `certainly_nonzero`.
                [
                    [0.0, 0.071_558_38, 1.129_651_7],
                    [0.368_695_14, -0.873_586_9, 1.076_438],
                    [0.184_347_57, -0.401_014_27, 1.103_044_7],
                ],
                [
                    0xbf80_0000, 0xc007_c593, 0x3f80_0000, 0x3f82_0f13, 0x3f97_98b4, 0x3fdc_36b6,
                    0x3dd3_0920, 0x4089_080e,
                ],
            ),
        ];
        for ([a, b, c], bits) in cases {
            let t = Triangle::from_corners(a, b, c);
            let r = ray_from_bits(bits);
            for k in TriangleKernelKind::ALL {
                if let Some(hit) = k.intersect(&t, &r, r.t_max) {
                    let p = r.at(hit);
                    let d = distance_to_segment(p, t.v[0], t.v[1]);
                    assert!(d < 1e-5, "{k}: hit at t {hit}, {d} off the triangle");
                }
            }
        }
    }

    #[test]
    fn hand_computed_hit_for_every_kernel() {
        // From (1,1,0) along +z the plane z=2 is reached at t=2 (t in units of dir: dir = 0.5 z
        // gives t = 4).
        let r = Ray::infinite(Vec3::new(1.0, 1.0, 0.0), Vec3::Z).unwrap();
        for (k, t) in TriangleKernelKind::ALL.iter().zip(all(&r)) {
            assert_eq!(t, Some(2.0), "{k}");
        }
        let r = Ray::infinite(Vec3::new(1.0, 1.0, 0.0), Vec3::Z * 0.5).unwrap();
        for (k, t) in TriangleKernelKind::ALL.iter().zip(all(&r)) {
            assert_eq!(t, Some(4.0), "{k}");
        }
        // From the other side, both windings hit (no culling).
        let r = Ray::infinite(Vec3::new(1.0, 1.0, 5.0), -Vec3::Z).unwrap();
        for (k, t) in TriangleKernelKind::ALL.iter().zip(all(&r)) {
            assert_eq!(t, Some(3.0), "{k}");
        }
    }

    #[test]
    fn misses_outside_behind_parallel_and_beyond_t_max() {
        let outside = Ray::infinite(Vec3::new(3.0, 3.0, 0.0), Vec3::Z).unwrap();
        let behind = Ray::infinite(Vec3::new(1.0, 1.0, 3.0), Vec3::Z).unwrap();
        let parallel = Ray::infinite(Vec3::new(-1.0, 1.0, 2.0), Vec3::X).unwrap();
        let short = Ray::new(Vec3::new(1.0, 1.0, 0.0), Vec3::Z, 0.0, 1.5).unwrap();
        for r in [outside, behind, parallel, short] {
            for (k, t) in TriangleKernelKind::ALL.iter().zip(all(&r)) {
                assert_eq!(t, None, "{k} {r:?}");
            }
        }
    }

    #[test]
    fn kernels_agree_inside_and_outside() {
        // Deterministic pseudo-random rays clearly inside or clearly outside the triangle.
        let mut next = unit_floats(12345);
        let t = tri();
        for _ in 0..2000 {
            let (b1, b2) = (next(), next());
            let o = Vec3::new(next() * 8.0 - 4.0, next() * 8.0 - 4.0, -3.0);
            let target = t.v[0] + (t.v[1] - t.v[0]) * b1 + (t.v[2] - t.v[0]) * b2;
            let inside = b1 + b2 < 0.98 && b1 > 0.02 && b2 > 0.02;
            let outside = b1 + b2 > 1.02;
            if !inside && !outside {
                continue;
            }
            let r = Ray::infinite(o, Vec3::from(target) - o).unwrap();
            for (k, hit) in TriangleKernelKind::ALL.iter().zip(all(&r)) {
                assert_eq!(hit.is_some(), inside, "{k} b=({b1},{b2})");
                if let Some(t) = hit {
                    assert!((t - 1.0).abs() < 1e-4, "{k}: t={t}");
                }
            }
        }
    }

    #[test]
    fn barycentrics_and_degenerate() {
        let b = tri().barycentrics(Vec3A::new(1.0, 2.0, 2.0));
        assert!((b - Vec3A::new(0.25, 0.25, 0.5)).abs().max_element() < 1e-6);
        let d = Triangle::new(Vec3A::ZERO, Vec3A::X, Vec3A::X * 2.0);
        assert!(d.is_degenerate());
        assert_eq!(d.area(), 0.0);
    }

    #[test]
    fn kernel_names_round_trip() {
        for k in TriangleKernelKind::ALL {
            assert_eq!(TriangleKernelKind::parse(k.name()), Some(k));
        }
        assert_eq!(TriangleKernelKind::parse("nope"), None);
    }
}
