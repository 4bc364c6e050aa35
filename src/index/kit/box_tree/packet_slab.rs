//! The slab test of one box against every ray of a packet in one SIMD pass (Wald, Slusallek,
//! Benthin and Wagner 2001): lane `k` of every register is ray `k` ([`PacketRays`]: origins,
//! inverse directions and `t_min` in structure-of-arrays form; a per-lane `t_max`), and the
//! box's six planes are splatted. Four rays fill one [`Vec4`](glam::Vec4) (SSE), eight one
//! [`F8`](super::lanes::F8) (AVX), sixteen one [`F16`](super::lanes16::F16) (AVX-512).
//!
//! The pass is [`slab_lanes`], the routine of the single-ray tests, with the roles of the lanes
//! swapped: every lane performs exactly the single-ray test's operations in the same order (the
//! products `(plane - origin) * inv_dir`, the NaN rule, min/max per axis, the far distance
//! widened as `max(far * s, far * (2 - s))`, the clip to `[t_min, t_max]`), so each ray's box
//! decision and entry equal its single-ray ones bit for bit, and culling with them stays exact
//! (see [`super::walk`]). `tests` checks it lane by lane.
//!
//! `SAFE` is chosen once per packet: `true` when any ray needs it (a non-finite `inv_dir`
//! component or `t_min < 0`, [`Ray::fast_slabs`]). The NaN select is the identity on every lane
//! whose products are not NaN, and the far distance's widening on either sign decides as the
//! one-sided one when `t_min >= 0`, so fast rays in a `SAFE` packet get their `SAFE = false`
//! decisions and entries (checked in `tests`).

use super::lanes::{Lanes, MAX_LANES};
use super::slab::{slab_lanes, slab_lanes_by_sign};
use crate::geometry::Ray;

/// A packet's slab constants, lane `k` from ray `k` (lanes past the packet's rays copy ray 0;
/// the walk masks them out).
#[derive(Debug, Clone, Copy)]
pub struct PacketRays<V> {
    origin: [V; 3],
    inv_dir: [V; 3],
    t_min: V,
    /// Whether every ray may take the `SAFE = false` test ([`Ray::fast_slabs`]).
    fast: bool,
    /// Per axis, the plane every ray meets first when the rays agree on it
    /// ([`super::slab::SlabRay::near`]:
    /// the sign bits of their `inv_dir` components are equal on every axis), else `None`.
    near: Option<[usize; 3]>,
}

impl<V: Lanes> PacketRays<V> {
    /// The packet of `rays` (`1..=V::WIDTH` rays).
    #[inline(always)]
    pub fn new(rays: &[Ray]) -> PacketRays<V> {
        assert!(!rays.is_empty() && rays.len() <= V::WIDTH);
        let mut origin = [[0.0; MAX_LANES]; 3];
        let mut inv_dir = [[0.0; MAX_LANES]; 3];
        let mut t_min = [0.0; MAX_LANES];
        for k in 0..V::WIDTH {
            let r = rays.get(k).unwrap_or(&rays[0]);
            for axis in 0..3 {
                origin[axis][k] = r.origin[axis];
                inv_dir[axis][k] = r.inv_dir[axis];
            }
            t_min[k] = r.t_min;
        }
        PacketRays {
            origin: origin.each_ref().map(V::load),
            inv_dir: inv_dir.each_ref().map(V::load),
            t_min: V::load(&t_min),
            fast: rays.iter().all(Ray::fast_slabs),
            near: shared_signs(rays),
        }
    }

    /// Whether the packet may take the `SAFE = false` test.
    #[inline(always)]
    pub fn fast(&self) -> bool {
        self.fast
    }

    /// Per axis, the plane (0: `min`, 1: `max`) every ray of the packet meets first, when they
    /// agree on every axis.
    #[inline(always)]
    pub fn near(&self) -> Option<[usize; 3]> {
        self.near
    }
}

/// Per axis, which plane of a box every one of `rays` meets first
/// ([`super::slab::SlabRay::near`]: the
/// `max` plane where the sign bit of `inv_dir` is set), when they agree on every axis.
#[inline(always)]
fn shared_signs(rays: &[Ray]) -> Option<[usize; 3]> {
    let signs = |r: &Ray| {
        r.inv_dir
            .to_array()
            .map(|x| usize::from(x.is_sign_negative()))
    };
    let first = signs(&rays[0]);
    rays.iter().all(|r| signs(r) == first).then_some(first)
}

/// The box with corners `min` and `max` against every lane's ray over `[t_min, t_max]` (lane
/// `k` of `t_max` for ray `k`): bit `k` of the mask is set when ray `k` hits, lane `k` of the
/// vector is its entry (meaningful where hit).
#[inline(always)]
pub fn hit_box<const SAFE: bool, V: Lanes>(
    min: [f32; 3],
    max: [f32; 3],
    rays: &PacketRays<V>,
    t_max: V,
) -> (u32, V) {
    slab_lanes::<SAFE, V>(
        min.map(V::splat),
        max.map(V::splat),
        rays.origin,
        rays.inv_dir,
        rays.t_min,
        t_max,
    )
}

/// [`hit_box`] for a packet whose rays agree on their direction signs (`near`:
/// [`PacketRays::near`]): each axis's plane the rays meet first and the other one, as the
/// single-ray tests of the wide nodes read them ([`super::slab::hit_near_far`]): the same
/// decisions and entries as [`hit_box`], lane by lane (see [`super::slab`]).
#[inline(always)]
pub fn hit_box_by_sign<const SAFE: bool, V: Lanes>(
    min: [f32; 3],
    max: [f32; 3],
    near: [usize; 3],
    rays: &PacketRays<V>,
    t_max: V,
) -> (u32, V) {
    let planes = [min, max];
    let plane = |k: usize, side: usize| V::splat(planes[(near[k] ^ side) & 1][k]);
    slab_lanes_by_sign::<SAFE, V>(
        [plane(0, 0), plane(1, 0), plane(2, 0)],
        [plane(0, 1), plane(1, 1), plane(2, 1)],
        rays.origin,
        rays.inv_dir,
        rays.t_min,
        t_max,
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Aabb;
    use crate::index::kit::box_tree::lanes::F8;
    use crate::index::kit::box_tree::lanes16::F16;
    use crate::index::kit::box_tree::slab::tests::Rng;
    use crate::index::kit::box_tree::slab::tests::near_far_lanes;
    use crate::index::kit::box_tree::slab::{SlabRay, hit_near_far};
    use glam::{Vec3, Vec4};

    /// The wide nodes' single-ray test of `b`: its decision and entry.
    fn single<const SAFE: bool>(b: &Aabb, ray: &Ray, t_max: f32) -> Option<u32> {
        let sr = SlabRay::new(ray);
        let (near, far) = near_far_lanes::<Vec4>(&[*b], &sr);
        let (mask, enter) = hit_near_far::<SAFE, Vec4>(near, far, &sr, t_max);
        (mask & 1 == 1).then_some(enter.x.to_bits())
    }

    /// A random ray (degenerate often: zero, negative-zero and denormal direction components,
    /// origins on the boxes' planes) and a `t_max` (infinite or random); with `signs`, its
    /// direction components take those signs.
    fn ray(rng: &mut Rng, signs: Option<Vec3>) -> (Ray, f32) {
        loop {
            let o = Vec3::new(rng.coord(), rng.coord(), rng.coord());
            let d = Vec3::new(rng.dir(), rng.dir(), rng.dir());
            let d = signs.map_or(d, |s| d.abs().copysign(s));
            let t_min = match rng.next() % 3 {
                0 => rng.coord().min(0.0),
                _ => rng.coord().abs(),
            };
            if let Ok(r) = Ray::new(o, d, t_min, f32::INFINITY) {
                let t_max = match rng.next() % 3 {
                    0 => f32::INFINITY,
                    1 => 0.0,
                    _ => rng.coord().abs() * 3.0,
                };
                return (r, t_max);
            }
        }
    }

    /// Packets of `V::WIDTH` random rays (some packets all fast, some mixed; some with the
    /// same direction signs on every ray) against random boxes: every lane's decision and
    /// entry bits equal its single-ray test's, and its scalar test's entry by value; fast lanes
    /// of `SAFE` packets equal their `SAFE = false` results; packets whose rays agree on their
    /// signs get the same from [`hit_box_by_sign`].
    fn packet_equals_single_ray_tests<V: Lanes>(seed: u64) {
        let mut rng = Rng(seed);
        let (mut hits, mut mixed, mut fast_lanes, mut by_sign) = (0, 0, 0, 0);
        for _ in 0..40_000 {
            let b = rng.aabb();
            let mut rays = Vec::new();
            let all_fast = rng.next().is_multiple_of(2);
            let signs = rng
                .next()
                .is_multiple_of(3)
                .then(|| ray(&mut rng, None).0.dir.into());
            while rays.len() < V::WIDTH {
                let (r, t) = ray(&mut rng, signs);
                if !all_fast || r.fast_slabs() {
                    rays.push((r, t));
                }
            }
            let only: Vec<Ray> = rays.iter().map(|p| p.0).collect();
            let packet = PacketRays::<V>::new(&only);
            let mut t_max = [0.0; MAX_LANES];
            for (k, (_, t)) in rays.iter().enumerate() {
                t_max[k] = *t;
            }
            let t_max = V::load(&t_max);
            let (b_min, b_max) = (b.min.to_array(), b.max.to_array());
            let (safe_mask, safe_enter) = hit_box::<true, V>(b_min, b_max, &packet, t_max);
            let fast = packet
                .fast()
                .then(|| hit_box::<false, V>(b_min, b_max, &packet, t_max));
            let lane = |(mask, enter): (u32, V), k: usize| {
                (mask >> k & 1 == 1).then_some(enter.to_lanes()[k].to_bits())
            };
            let sign_results = packet.near().map(|near| {
                by_sign += 1;
                let safe = hit_box_by_sign::<true, V>(b_min, b_max, near, &packet, t_max);
                let fast = packet
                    .fast()
                    .then(|| hit_box_by_sign::<false, V>(b_min, b_max, near, &packet, t_max));
                (safe, fast)
            });
            for (k, (r, t)) in rays.iter().enumerate() {
                let want = single::<true>(&b, r, *t);
                assert_eq!(
                    lane((safe_mask, safe_enter), k),
                    want,
                    "lane {k} {r:?} {b:?}"
                );
                let scalar = b.ray_entry(r, r.t_min, *t);
                assert_eq!(want.map(f32::from_bits), scalar, "{r:?} {b:?}");
                if r.fast_slabs() {
                    fast_lanes += 1;
                    assert_eq!(single::<false>(&b, r, *t), want, "{r:?} {b:?}");
                }
                if let Some(f) = fast {
                    assert_eq!(lane(f, k), want, "lane {k} (fast) {r:?} {b:?}");
                }
                if let Some((safe, fast)) = sign_results {
                    assert_eq!(lane(safe, k), want, "lane {k} (by sign) {r:?} {b:?}");
                    if let Some(f) = fast {
                        assert_eq!(lane(f, k), want, "lane {k} (by sign, fast) {r:?} {b:?}");
                    }
                }
                hits += usize::from(want.is_some());
            }
            mixed += usize::from(!packet.fast());
        }
        let lanes = 40_000 * V::WIDTH;
        assert!(hits > lanes / 100 && mixed > 5_000 && fast_lanes > lanes / 2);
        assert!(by_sign > 10_000, "{by_sign}");
    }

    #[test]
    fn four_ray_packets_equal_the_single_ray_test_lane_by_lane() {
        packet_equals_single_ray_tests::<Vec4>(0x5851_f42d_4c95_7f2d);
    }

    #[test]
    fn eight_ray_packets_equal_the_single_ray_test_lane_by_lane() {
        packet_equals_single_ray_tests::<F8>(0x1405_7b7e_f767_814f);
    }

    #[test]
    fn sixteen_ray_packets_equal_the_single_ray_test_lane_by_lane() {
        packet_equals_single_ray_tests::<F16>(0x2b99_2ddf_a232_49d6);
    }

    /// Rays along a face or an edge of the box with zero direction components (`0 * inf = NaN`
    /// on that axis) in a packet with ordinary rays (of 8 and of 16 rays): the `SAFE` pass hits
    /// the box on every lane, as the scalar test does.
    fn face_plane_rays_hit_in_a_mixed_packet<V: Lanes>() {
        let unit = Aabb::new(Vec3::ZERO.into(), Vec3::ONE.into());
        let mut rays = Vec::new();
        for x in [0.0f32, 1.0] {
            for z in [0.0f32, 1.0] {
                for dz in [0.0f32, -0.0] {
                    let (o, d) = (Vec3::new(-1.0, 0.5, z), Vec3::new(1.0, 0.0, dz));
                    rays.push(Ray::infinite(o, d).unwrap());
                    let (o, d) = (Vec3::new(x, -1.0, z), Vec3::new(dz, 1.0, 0.0));
                    rays.push(Ray::infinite(o, d).unwrap());
                }
            }
        }
        rays.truncate(V::WIDTH);
        rays[V::WIDTH - 1] =
            Ray::infinite(Vec3::new(-1.0, 0.25, 0.75), Vec3::new(1.0, 0.1, 0.2)).unwrap();
        let packet = PacketRays::<V>::new(&rays);
        assert!(!packet.fast());
        let inf = V::splat(f32::INFINITY);
        let (mask, enter) = hit_box::<true, V>([0.0; 3], [1.0; 3], &packet, inf);
        assert_eq!(mask, (1 << V::WIDTH) - 1);
        for (k, r) in rays.iter().enumerate() {
            assert_eq!(
                Some(enter.to_lanes()[k]),
                unit.ray_entry(r, 0.0, f32::INFINITY)
            );
        }
    }

    #[test]
    fn rays_in_a_face_plane_hit_in_a_mixed_packet() {
        face_plane_rays_hit_in_a_mixed_packet::<F8>();
        face_plane_rays_hit_in_a_mixed_packet::<F16>();
    }
}
