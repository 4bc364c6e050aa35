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
