//! [`Frustum::misses`] is conservative: whenever it culls a box, every ray of the packet (of
//! those it was asked about) misses the box in its single-ray slab test; checked on random and
//! adversarial packets and boxes. And [`Frustum::ray_hits`] is the single-ray decision.

use super::*;
use crate::index::kit::box_tree::lanes16::F16;
use crate::index::kit::box_tree::packet_slab::PacketRays;
use crate::index::kit::box_tree::slab::tests::Rng;
use glam::Vec3;

/// A uniform float in `[0, 1)`.
fn unit(rng: &mut Rng) -> f32 {
    (rng.next() >> 40) as f32 / (1u64 << 24) as f32
}

/// A direction magnitude: ordinary, tiny (huge inverse) or huge (tiny inverse).
fn magnitude(rng: &mut Rng) -> f32 {
    match rng.next() % 8 {
        0 => 1e-30,
        1 => 1e30,
        2 => 1e-12 * (1.0 + unit(rng)),
        3 => 1.0,
        _ => 0.01 + unit(rng),
    }
}

/// A packet of 1 to 16 fast rays sharing the direction signs `signs`: one origin (a camera),
/// origins a little apart, or anywhere; directions around one or anywhere in the octant.
fn packet(rng: &mut Rng) -> Vec<Ray> {
    let n = 1 + (rng.next() % 16) as usize;
    let signs = Vec3::from_array([0, 1, 2].map(|_| {
        if rng.next().is_multiple_of(2) {
            1.0
        } else {
            -1.0
        }
    }));
    let o0 = Vec3::new(rng.coord(), rng.coord(), rng.coord()) * 2.0;
    let d0 = Vec3::new(magnitude(rng), magnitude(rng), magnitude(rng));
    let (origins, dirs) = (rng.next() % 3, rng.next() % 3);
    let mut rays = Vec::new();
    while rays.len() < n {
        let o = match origins {
            0 => o0,
            1 => o0 + Vec3::new(unit(rng), unit(rng), unit(rng)) * 1e-3,
            _ => Vec3::new(rng.coord(), rng.coord(), rng.coord()) * 2.0,
        };
        let d = match dirs {
            0 => d0,
            1 => d0 * Vec3::new(1.0 + unit(rng) * 0.1, 1.0 + unit(rng) * 0.1, 1.0),
            _ => Vec3::new(magnitude(rng), magnitude(rng), magnitude(rng)),
        };
        let t_min = match rng.next() % 4 {
            0 => unit(rng),
            _ => 0.0,
        };
        if let Ok(r) = Ray::new(o, d * signs, t_min, f32::INFINITY)
            && r.fast_slabs()
        {
            rays.push(r);
        }
    }
    rays
}

/// A box: random, tiny (a point or one ulp wide), flat on some axis, huge (to `±1e30` or
/// `±f32::MAX`), or with a face or an edge exactly through a point of one of `rays` (grazing).
fn aabb(rng: &mut Rng, rays: &[Ray]) -> Aabb {
    let p = Vec3A::new(rng.coord(), rng.coord(), rng.coord()) * 2.0;
    match rng.next() % 6 {
        0 => rng.aabb(),
        1 => {
            let q = if rng.next().is_multiple_of(2) {
                p
            } else {
                Vec3A::from_array(p.to_array().map(f32::next_up))
            };
            Aabb::new(p, q)
        }
        2 => {
            let mut b = rng.aabb();
            let k = (rng.next() % 3) as usize;
            b.max[k] = b.min[k];
            b
        }
        3 => {
            let mut b = rng.aabb();
            let big = [1e30, f32::MAX][(rng.next() % 2) as usize];
            for k in 0..3 {
                match rng.next() % 4 {
                    0 => b.min[k] = -big,
                    1 => b.max[k] = big,
                    _ => {}
                }
            }
            b
        }
        _ => {
            // A point of a ray at some t (rounded as f32 computes it), on a face or an edge.
            let r = rays[(rng.next() % rays.len() as u64) as usize];
            let t = unit(rng) * 4.0;
            let q = r.origin + r.dir * t;
            let lo = q - Vec3A::new(unit(rng), unit(rng), unit(rng)) * 2.0;
            let hi = q + Vec3A::new(unit(rng), unit(rng), unit(rng)) * 2.0;
            let mut b = Aabb::new(lo, hi);
            for k in 0..3 {
                match rng.next() % 3 {
                    0 => b.min[k] = q[k],
                    1 => b.max[k] = q[k],
                    _ => {}
                }
            }
            b
        }
    }
}

/// Each ray's `t_max`: infinite, random, zero, or its own entry into `b` (the tie a closest-hit
/// walk meets when its best `t` equals a box's entry) or just below it.
fn t_maxes(rng: &mut Rng, rays: &[Ray], b: &Aabb) -> Vec<f32> {
    rays.iter()
        .map(|r| {
            let entry = b.ray_entry(r, r.t_min, f32::INFINITY);
            match (rng.next() % 5, entry) {
                (0, _) => f32::INFINITY,
                (1, _) => unit(rng) * 4.0,
                (2, _) => 0.0,
                (3, Some(e)) => e,
                (_, Some(e)) => e.next_down().max(0.0),
                (_, None) => f32::INFINITY,
            }
        })
        .collect()
}

#[test]
fn a_culled_box_is_missed_by_every_ray_asked_about() {
    let mut rng = Rng(0x2545_f491_4f6c_dd1d);
    let (mut culled, mut sharp, mut hit_boxes, mut subsets) = (0, 0, 0, 0);
    for _ in 0..300_000 {
        let rays = packet(&mut rng);
        let f = Frustum::new(&rays).expect("fast rays sharing their signs");
        let b = aabb(&mut rng, &rays);
        let t_max = t_maxes(&mut rng, &rays, &b);
        let hits: Vec<bool> = (0..rays.len())
            .map(|k| b.ray_entry(&rays[k], rays[k].t_min, t_max[k]).is_some())
            .collect();
        for (k, r) in rays.iter().enumerate() {
            assert_eq!(
                f.ray_hits(&b, r, t_max[k]),
                hits[k],
                "{r:?} {b:?} {}",
                t_max[k]
            );
        }
        // All the rays, then a random subset (the walk asks about the active rays only).
        let all = (1u32 << rays.len()) - 1;
        let subset = (rng.next() as u32 & all).max(1);
        for asked in [all, subset] {
            let lanes = || (0..rays.len()).filter(move |k| asked >> k & 1 == 1);
            let tm = lanes().map(|k| t_max[k]).fold(f32::NEG_INFINITY, f32::max);
            let any_hit = lanes().any(|k| hits[k]);
            if f.misses(&b, tm) {
                culled += 1;
                assert!(
                    !any_hit,
                    "culled a box a ray hits: {rays:?} {b:?} {t_max:?}"
                );
            } else if any_hit {
                hit_boxes += 1;
                // A bound one ulp tighter (later entry) would have culled a box a ray hits:
                // the cases where a rounding in the wrong direction would be caught.
                let (enter, exit) = f.bounds(&b, tm);
                sharp += usize::from(enter.next_up() > exit);
            }
            subsets += usize::from(asked != all);
        }
    }
    assert!(culled > 50_000, "{culled}");
    assert!(hit_boxes > 50_000, "{hit_boxes}");
    assert!(sharp > 1_000, "{sharp}");
    assert!(subsets > 200_000, "{subsets}");
}

/// A camera's 4 x 4 tile: boxes beside its view are culled, a box in front of it is not.
#[test]
fn a_tile_culls_boxes_beside_its_view() {
    let o = Vec3::new(0.0, 0.0, -5.0);
    let rays: Vec<Ray> = (0..16)
        .map(|i| {
            let (x, y) = ((i % 4) as f32 * 0.01, (i / 4) as f32 * 0.01);
            Ray::infinite(o, Vec3::new(x + 0.001, y + 0.001, 1.0)).unwrap()
        })
        .collect();
    let f = Frustum::new(&rays).unwrap();
    let b = |lo: [f32; 3], hi: [f32; 3]| Aabb::new(Vec3A::from(lo), Vec3A::from(hi));
    assert!(f.misses(&b([1.0, 1.0, 0.0], [2.0, 2.0, 1.0]), f32::INFINITY));
    assert!(f.misses(&b([-1.0, -1.0, -9.0], [1.0, 1.0, -6.0]), f32::INFINITY));
    assert!(!f.misses(&b([-1.0, -1.0, 0.0], [1.0, 1.0, 1.0]), f32::INFINITY));
    // In front, but beyond every ray's best hit so far.
    assert!(f.misses(&b([-1.0, -1.0, 0.0], [1.0, 1.0, 1.0]), 4.0));
}

/// Packets the beam cannot take: rays of different signs, a zero direction component (infinite
/// inverse), `t_min < 0`; the signs it reads agree with the packet walk's.
#[test]
fn only_fast_packets_of_one_octant_get_a_frustum() {
    let o = Vec3::ZERO;
    let ray = |d: [f32; 3], t_min: f32| Ray::new(o, Vec3::from(d), t_min, f32::INFINITY).unwrap();
    let a = ray([1.0, -1.0, 0.5], 0.0);
    assert!(Frustum::new(&[a, ray([1.0, 1.0, 0.5], 0.0)]).is_none());
    assert!(Frustum::new(&[a, ray([1.0, -1.0, 0.0], 0.0)]).is_none());
    assert!(Frustum::new(&[a, ray([1.0, -1.0, -0.0], 0.0)]).is_none());
    assert!(Frustum::new(&[a, ray([1.0, -1.0, 0.5], -1.0)]).is_none());
    let rays = [a, ray([2.0, -0.5, 0.25], 0.0)];
    let f = Frustum::new(&rays).unwrap();
    assert_eq!(f.near(), [0, 1, 0]);
    assert_eq!(Some(f.near()), PacketRays::<F16>::new(&rays).near());
}
