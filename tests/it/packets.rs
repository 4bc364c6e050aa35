//! `run --packets N` changes no hit: `bvh`, `bvh4` and `bvh8` trace packets of 4, 8 and 16
//! neighbouring rays with one shared traversal and an active mask, the other indices ray by ray;
//! every ray gets brute force's closest hit bit for bit and the same any-hit answer, whether the
//! packets are row segments of the batch or screen tiles of an image (`closest_hits_image`).
//! The beam modes (`beams4`, `beams8`, `beams16`: the same packets, `bvh`, `bvh4` and `bvh8`
//! tracing them as beams) are checked on the same rays; `beams.rs` checks them on the bunny.

use crate::common;

use accelbench::camera::ModelKind;
use accelbench::geometry::{Ray, TriangleKernelKind};
use accelbench::harness::verify::compare_closest;
use accelbench::index::{Counters, IndexSpec, TraceMode, build_index, index_names, is_peer};
use accelbench::rays::{CAMERA_SET_SEED, camera_model_rays, primary_rays};
use accelbench::scene::{Scene, generators};
use glam::Vec3;

#[test]
fn packets_of_four_change_no_hit() {
    common::assert_mode_agrees(TraceMode::Packets(4));
}

#[test]
fn packets_of_eight_change_no_hit() {
    common::assert_mode_agrees(TraceMode::Packets(8));
}

#[test]
fn packets_of_sixteen_change_no_hit() {
    common::assert_mode_agrees(TraceMode::Packets(16));
}

#[test]
fn beams_of_sixteen_change_no_hit() {
    common::assert_mode_agrees(TraceMode::Beams(16));
}

/// The packet and beam modes.
const MODES: [TraceMode; 6] = [
    TraceMode::Packets(4),
    TraceMode::Packets(8),
    TraceMode::Packets(16),
    TraceMode::Beams(4),
    TraceMode::Beams(8),
    TraceMode::Beams(16),
];

/// Asserts that every index of ours returns brute force's closest hits (counted and not) and
/// any-hit answers on `rays` over `scene`, traced in packets and beams of 4, 8 and 16: of consecutive
/// rays, and with `width` also from the tiles of an image `width` rays wide.
fn assert_packets_agree(scene: &Scene, rays: &[Ray], width: Option<usize>) {
    let geom = scene.geometry();
    let kernel = TriangleKernelKind::Exact;
    let brute = build_index(&IndexSpec::named("brute"), &geom, kernel).unwrap();
    let mut expected = vec![None; rays.len()];
    brute.closest_hits(rays, &mut expected);
    for name in index_names().into_iter().filter(|n| !is_peer(n)) {
        let index = build_index(&IndexSpec::named(name), &geom, kernel).unwrap();
        let layouts = |m| std::iter::once((m, None)).chain(width.map(|w| (m, Some(w))));
        for (mode, width) in MODES.into_iter().flat_map(layouts) {
            let what = format!("{name} in {mode:?}, image width {width:?}");
            let closest = |got: &mut [_], c: Option<&mut [Counters]>| match width {
                Some(w) => index.closest_hits_image(mode, rays, w, got, c),
                None => index.closest_hits_in(mode, rays, got, c),
            };
            let mut got = vec![None; rays.len()];
            closest(&mut got, None);
            let m = compare_closest(rays, &expected, &got);
            common::assert_no_mismatch(&what, scene, rays.len(), &m);
            let mut counters = vec![Counters::default(); rays.len()];
            closest(&mut got, Some(&mut counters));
            let m = compare_closest(rays, &expected, &got);
            common::assert_no_mismatch(&format!("{what}, counted"), scene, rays.len(), &m);
            let mut any = vec![false; rays.len()];
            match width {
                Some(w) => index.any_hits_image(mode, rays, w, &mut any, None),
                None => index.any_hits_in(mode, rays, &mut any, None),
            }
            let wrong = (0..rays.len())
                .filter(|&i| any[i] != expected[i].is_some())
                .count();
            assert_eq!(wrong, 0, "{what} any-hit on {}: {wrong} wrong", scene.name);
        }
    }
}

/// Scenes with axis-aligned faces (room, flat) and without (soup, stadium, terrain).
fn scenes() -> Vec<Scene> {
    ["room", "flat", "terrain", "stadium", "soup"]
        .iter()
        .map(|n| generators::generate(n, 2000, 5).unwrap())
        .collect()
}

/// Rays of a 24 x 24 image where, inside every packet, some rays have zero (`+0.0`, `-0.0`)
/// direction components (infinite `inv_dir`, and `0 * inf = NaN` slab products where the
/// origin lies on a box plane: origins are put on the scene box's planes) next to ordinary
/// rays, so packets take the NaN-safe test on mixed finite and non-finite lanes.
fn mixed_finite_rays(scene: &Scene) -> Vec<Ray> {
    let b = scene.ray_set_bounds();
    let (lo, hi) = (Vec3::from(b.min), Vec3::from(b.max));
    let primary = primary_rays(&b, 24, 24).unwrap();
    let mut rays = Vec::new();
    for (i, r) in primary.iter().enumerate() {
        let (o, d) = (Vec3::from(r.origin), Vec3::from(r.dir));
        let axis = i / 3 % 3;
        let ray = match i % 3 {
            0 => *r,
            // The direction with one component zeroed (either sign).
            1 => {
                let mut d2 = d;
                d2[axis] = if i % 2 == 0 { 0.0 } else { -0.0 };
                Ray::infinite(o, d2).unwrap_or(*r)
            }
            // Along a plane of the scene box: origin on it, no motion across it.
            _ => {
                let mut o2 = o.lerp((lo + hi) * 0.5, 0.5);
                o2[axis] = if i % 2 == 0 { lo[axis] } else { hi[axis] };
                let mut d2 = (lo + hi) * 0.5 - o2;
                d2[axis] = 0.0;
                Ray::infinite(o2, d2).unwrap_or(*r)
            }
        };
        rays.push(ray);
    }
    rays
}

#[test]
fn packets_mixing_finite_and_non_finite_rays_change_no_hit() {
    for scene in scenes() {
        let rays = mixed_finite_rays(&scene);
        let non_finite = rays.iter().filter(|r| !r.inv_dir.is_finite()).count();
        assert!(
            non_finite > rays.len() / 2,
            "{non_finite} of {}",
            rays.len()
        );
        assert_packets_agree(&scene, &rays, Some(24));
    }
}

/// Rays of a 20 x 20 image in which some lanes of a packet are idle from the start or soon:
/// every fifth ray turned away from the scene (misses the root box), every seventh cut to a
/// short `t_max` (drops out after the first boxes), every eleventh started beyond the scene
/// (`t_min` past every hit).
fn rays_with_idle_lanes(scene: &Scene) -> Vec<Ray> {
    let b = scene.ray_set_bounds();
    let diagonal = b.extent().length();
    let primary = primary_rays(&b, 20, 20).unwrap();
    let mut rays = Vec::new();
    for (i, r) in primary.iter().enumerate() {
        let (o, d) = (Vec3::from(r.origin), Vec3::from(r.dir));
        let ray = if i % 5 == 0 {
            Ray::infinite(o, -d)
        } else if i % 7 == 0 {
            Ray::new(o, d, 0.0, diagonal * 0.05)
        } else if i % 11 == 0 {
            Ray::new(o, d, diagonal * 100.0, f32::INFINITY)
        } else {
            Ok(*r)
        };
        rays.push(ray.unwrap());
    }
    rays
}

#[test]
fn partial_packets_and_idle_lanes_change_no_hit() {
    for scene in scenes() {
        let rays = rays_with_idle_lanes(&scene);
        assert_packets_agree(&scene, &rays, Some(20));
        // Batches of every length up to two packets of 16 and one more: the last packet of
        // each is partial (lanes past the rays stay idle); as images 5 rays wide, tiles with
        // partial rows and columns.
        for len in 1..=33 {
            let start = 190 - len / 2;
            assert_packets_agree(&scene, &rays[start..start + len], Some(5));
        }
    }
}

/// Images whose sides are not multiples of 4 (tiles cut at the right and bottom borders), as
/// the suite's square camera sets and wider than high: primary rays and the camera models.
#[test]
fn tiles_at_image_borders_change_no_hit() {
    for scene in scenes() {
        let b = scene.ray_set_bounds();
        for (w, h) in [(23, 23), (18, 13), (4, 9)] {
            let rays = primary_rays(&b, w, h).unwrap();
            assert_packets_agree(&scene, &rays, Some(w as usize));
        }
        for kind in [ModelKind::Dof, ModelKind::Motion, ModelKind::Lens] {
            let rays = camera_model_rays(&b, 21, kind, CAMERA_SET_SEED).unwrap();
            assert_packets_agree(&scene, &rays, Some(21));
        }
    }
}

/// Packets whose rays point into all eight octants from inside the scene, some with zero
/// direction components: per packet of 16, lane `k` has the signs of octant `k % 8`, and
/// every third ray one component `+0` or `-0`.
#[test]
fn packets_with_mixed_direction_signs_change_no_hit() {
    for scene in scenes() {
        let b = scene.ray_set_bounds();
        let (lo, hi) = (Vec3::from(b.min), Vec3::from(b.max));
        let mut rays = Vec::new();
        for i in 0..16 * 12 {
            let o = lo.lerp(hi, 0.3 + 0.4 * (i as f32 / 192.0));
            let octant = i % 8;
            let sign = |bit: usize| if octant >> bit & 1 == 1 { -1.0 } else { 1.0 };
            let mut d = Vec3::new(
                sign(0) * (0.3 + (i % 5) as f32 * 0.1),
                sign(1) * (0.5 + (i % 3) as f32 * 0.2),
                sign(2) * (0.2 + (i % 7) as f32 * 0.1),
            );
            if i % 3 == 0 {
                d[i / 3 % 3] = if i % 2 == 0 { 0.0 } else { -0.0 };
            }
            rays.push(Ray::infinite(o, d).unwrap());
        }
        assert_packets_agree(&scene, &rays, Some(12));
    }
}
