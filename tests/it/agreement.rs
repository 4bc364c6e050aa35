//! The hit contract, one test body for every registered index: each of our indices returns
//! brute force's closest hit (same primitive, bit-identical `t`, ties to the lowest id) and
//! the matching any-hit answer, on the generated agreement scenes with every triangle kernel
//! and on the bunny's protocol rays. Peers ([`is_peer`]) go through the same body, but their
//! mismatches are printed (`--nocapture`), not failed; `tests/it/obvhs_peer.rs` classifies them.
//! A new index is covered by its registry line alone. The stress cases run over the registry
//! in `tests/it/stress.rs`; index-specific parameters and structure invariants stay in the index's
//! own test file.

use crate::common;

use accelbench::geometry::{Ray, TriangleKernelKind};
use accelbench::harness::verify::compare_indices;
use accelbench::index::{BuildError, IndexSpec, build_index, index_names, is_peer};
use accelbench::scene::Scene;

/// Rays per agreement scene (the most any index's own test used before).
const RAYS_PER_SCENE: usize = 1500;

/// Every registered index except brute force itself, against brute force on `scene`'s rays.
fn assert_every_index_agrees(scene: &Scene, kernel: TriangleKernelKind, rays: &[Ray]) {
    let geom = scene.geometry();
    let brute = build_index(&IndexSpec::named("brute"), &geom, kernel).unwrap();
    for name in index_names().into_iter().filter(|n| *n != "brute") {
        let index = match build_index(&IndexSpec::named(name), &geom, kernel) {
            Ok(index) => index,
            // Peers trace triangle scenes only and say so (the suite reports the skip).
            Err(BuildError::Unsupported { .. }) if is_peer(name) => continue,
            Err(e) => panic!("{name} on {}: {e}", scene.name),
        };
        let m = compare_indices(brute.as_ref(), index.as_ref(), rays);
        if is_peer(name) {
            if !m.is_empty() {
                eprintln!(
                    "peer {name} ({kernel}) on {}: {} of {} mismatch",
                    scene.name,
                    m.len(),
                    rays.len()
                );
            }
            continue;
        }
        common::assert_no_mismatch(&format!("{name} ({kernel})"), scene, rays.len(), &m);
    }
}

#[test]
fn every_index_agrees_on_the_generated_scenes_with_every_kernel() {
    for scene in common::agreement_scenes() {
        let rays = common::agreement_rays(&scene, RAYS_PER_SCENE);
        for kernel in TriangleKernelKind::ALL {
            assert_every_index_agrees(&scene, kernel, &rays);
        }
    }
}

#[test]
fn every_index_agrees_on_the_bunny_protocol_rays() {
    let Some(bunny) = common::bunny() else { return };
    let mut rays = common::bunny_protocol_sample(&bunny);
    rays.extend(common::agreement_rays(&bunny, 2000));
    assert_every_index_agrees(&bunny, TriangleKernelKind::Watertight, &rays);
}

/// A hit has a finite `t`: a ray from (0.5, 0.5, -2) with a denormal direction toward the unit
/// quad at z = 0 meets it at about 2e40, beyond `f32`'s range, so the kernel's `t` rounds to
/// `+inf`, the protocol's miss distance. Brute force and every index report a miss there (and
/// `any_hit` false), and still hit with the same quad along ordinary directions.
#[test]
fn a_distance_beyond_f32_is_a_miss_for_every_index() {
    let p = |x: f32, y: f32| glam::Vec3A::new(x, y, 0.0);
    let quad = vec![
        accelbench::geometry::Triangle::new(p(0.0, 0.0), p(1.0, 0.0), p(1.0, 1.0)),
        accelbench::geometry::Triangle::new(p(0.0, 0.0), p(1.0, 1.0), p(0.0, 1.0)),
    ];
    let scene = Scene::from_triangles("quad", quad);
    let origin = glam::Vec3::new(0.5, 0.5, -2.0);
    let far: Vec<Ray> = [
        [1e-45, 1e-44, 1e-40],
        [0.0, 0.0, 1e-40],
        [1e-41, -1e-41, 1e-39],
    ]
    .into_iter()
    .map(|d| Ray::infinite(origin, glam::Vec3::from_array(d)).unwrap())
    .collect();
    let near = [[0.0, 0.0, 1.0], [0.01, -0.02, 1.0], [0.0, 0.0, 1e-30]].map(|d| {
        Ray::infinite(glam::Vec3::new(0.3, 0.6, -2.0), glam::Vec3::from_array(d)).unwrap()
    });
    for kernel in TriangleKernelKind::ALL {
        let brute = build_index(&IndexSpec::named("brute"), &scene.geometry(), kernel).unwrap();
        for ray in &far {
            assert_eq!(brute.closest_hit(ray), None, "{kernel}: {ray:?}");
            assert!(!brute.any_hit(ray), "{kernel}: {ray:?}");
        }
        for ray in &near {
            let t = brute.closest_hit(ray).map(|h| h.t);
            assert!(
                t.is_some_and(f32::is_finite),
                "{kernel}: {ray:?} gave {t:?}"
            );
        }
        // Our indices only: the contract is ours, and a C peer (tinybvh, Embree) given these
        // denormal directions may crash the process, which nothing can contain.
        let rays: Vec<Ray> = far.iter().chain(&near).copied().collect();
        let geom = scene.geometry();
        for name in index_names().into_iter().filter(|n| !is_peer(n)) {
            let index = build_index(&IndexSpec::named(name), &geom, kernel).unwrap();
            let m = compare_indices(brute.as_ref(), index.as_ref(), &rays);
            assert!(m.is_empty(), "{name} ({kernel}): {:?}", m.first());
        }
    }
}
