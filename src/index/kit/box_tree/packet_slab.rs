//! The slab test of one box against every ray of a packet in one SIMD pass (Wald, Slusallek,
//! Benthin and Wagner 2001): lane `k` of every register is ray `k` ([`PacketRays`]: origins,
//! inverse directions and `t_min` in structure-of-arrays form; a per-lane `t_max`), and the
//! box's six planes are splatted. Four rays fill one [`Vec4`](glam::Vec4) (SSE), eight one
//! [`F8`](super::lanes::F8) (AVX).
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

use super::lanes::Lanes;
use super::slab::slab_lanes;
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
}

impl<V: Lanes> PacketRays<V> {
    /// The packet of `rays` (`1..=V::WIDTH` rays).
    #[inline(always)]
    pub fn new(rays: &[Ray]) -> PacketRays<V> {
        assert!(!rays.is_empty() && rays.len() <= V::WIDTH);
        let lanes = |f: &dyn Fn(&Ray) -> f32| {
            let mut a = [0.0; 8];
            for (k, x) in a.iter_mut().enumerate().take(V::WIDTH) {
                *x = f(rays.get(k).unwrap_or(&rays[0]));
            }
            V::load(&a)
        };
        PacketRays {
            origin: [0, 1, 2].map(|i| lanes(&|r| r.origin[i])),
            inv_dir: [0, 1, 2].map(|i| lanes(&|r| r.inv_dir[i])),
            t_min: lanes(&|r| r.t_min),
            fast: rays.iter().all(Ray::fast_slabs),
        }
    }

    /// Whether the packet may take the `SAFE = false` test.
    #[inline(always)]
    pub fn fast(&self) -> bool {
        self.fast
    }
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Aabb;
    use crate::index::kit::box_tree::lanes::F8;
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
    /// origins on the boxes' planes) and a `t_max` (infinite or random).
    fn ray(rng: &mut Rng) -> (Ray, f32) {
        loop {
            let o = Vec3::new(rng.coord(), rng.coord(), rng.coord());
            let d = Vec3::new(rng.dir(), rng.dir(), rng.dir());
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

    /// Packets of `V::WIDTH` random rays (some packets all fast, some mixed) against random
    /// boxes: every lane's decision and entry bits equal its single-ray test's, and its scalar
    /// test's entry by value; fast lanes of `SAFE` packets equal their `SAFE = false` results.
    fn packet_equals_single_ray_tests<V: Lanes>(seed: u64) {
        let mut rng = Rng(seed);
        let (mut hits, mut mixed, mut fast_lanes) = (0, 0, 0);
        for _ in 0..40_000 {
            let b = rng.aabb();
            let mut rays = Vec::new();
            let all_fast = rng.next().is_multiple_of(2);
            while rays.len() < V::WIDTH {
                let (r, t) = ray(&mut rng);
                if !all_fast || r.fast_slabs() {
                    rays.push((r, t));
                }
            }
            let only: Vec<Ray> = rays.iter().map(|p| p.0).collect();
            let packet = PacketRays::<V>::new(&only);
            let mut t_max = [0.0; 8];
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
                hits += usize::from(want.is_some());
            }
            mixed += usize::from(!packet.fast());
        }
        let lanes = 40_000 * V::WIDTH;
        assert!(hits > lanes / 100 && mixed > 5_000 && fast_lanes > lanes / 2);
    }

    #[test]
    fn four_ray_packets_equal_the_single_ray_test_lane_by_lane() {
        packet_equals_single_ray_tests::<Vec4>(0x5851_f42d_4c95_7f2d);
    }

    #[test]
    fn eight_ray_packets_equal_the_single_ray_test_lane_by_lane() {
        packet_equals_single_ray_tests::<F8>(0x1405_7b7e_f767_814f);
    }

    /// Rays along a face of the box with zero direction components (`0 * inf = NaN` on that
    /// axis) in a packet with ordinary rays: the `SAFE` pass hits the box on every lane, as
    /// the scalar test does.
    #[test]
    fn rays_in_a_face_plane_hit_in_a_mixed_packet() {
        let unit = Aabb::new(Vec3::ZERO.into(), Vec3::ONE.into());
        let mut rays = Vec::new();
        for z in [0.0f32, 1.0] {
            for dz in [0.0f32, -0.0] {
                rays.push(Ray::infinite(Vec3::new(-1.0, 0.5, z), Vec3::new(1.0, 0.0, dz)).unwrap());
                rays.push(Ray::infinite(Vec3::new(0.5, -1.0, z), Vec3::new(0.1, 1.0, dz)).unwrap());
            }
        }
        rays[7] = Ray::infinite(Vec3::new(-1.0, 0.25, 0.75), Vec3::new(1.0, 0.1, 0.2)).unwrap();
        let packet = PacketRays::<F8>::new(&rays);
        assert!(!packet.fast());
        let inf = F8::splat(f32::INFINITY);
        let (mask, enter) = hit_box::<true, F8>([0.0; 3], [1.0; 3], &packet, inf);
        assert_eq!(mask, 0xff);
        for (k, r) in rays.iter().enumerate() {
            assert_eq!(
                Some(enter.to_lanes()[k]),
                unit.ray_entry(r, 0.0, f32::INFINITY)
            );
        }
    }
}
