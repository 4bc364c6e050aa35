//! The camera-model ray sets (`dof`, `motion`, `lens`): reproducible from their seed (checksums
//! of the rays' 32-byte records, as `accelbench rays` writes them), different for another seed,
//! and every index returns brute force's hits on them bit for bit.

use crate::common;

use accelbench::camera::ModelKind;
use accelbench::geometry::{Aabb, TriangleKernelKind};
use accelbench::harness::verify::compare_indices;
use accelbench::index::{IndexSpec, TraceMode, build_index, index_names, is_peer};
use accelbench::rays::{CAMERA_SET_SEED, camera_model_rays};
use accelbench::scene::generators;

const MODELS: [ModelKind; 3] = [ModelKind::Dof, ModelKind::Motion, ModelKind::Lens];

fn icosphere_bounds() -> Aabb {
    generators::generate("icosphere", 2000, 1)
        .unwrap()
        .ray_set_bounds()
}

/// Asserts each model's `side x side` set over `b` has the expected checksum.
fn assert_checksums(b: &Aabb, side: u32, expected: [(ModelKind, &str); 3], scene: &str) {
    for (kind, sum) in expected {
        let rays = camera_model_rays(b, side, kind, CAMERA_SET_SEED).unwrap();
        let got = common::checksum::md5_of_rays(&rays);
        assert_eq!(got, sum, "{kind:?} on {scene}, {side} x {side}");
    }
}

#[test]
fn camera_sets_reproduce_their_checksums() {
    let expected = [
        (ModelKind::Dof, "1f15c8c3139bbc8a3d2c82e1602ee02c"),
        (ModelKind::Motion, "12a0a6987665abab8f0db12e736ed452"),
        (ModelKind::Lens, "0507a39839b3569b7120e57f31acc62b"),
    ];
    assert_checksums(&icosphere_bounds(), 64, expected, "icosphere:n=2000,seed=1");
    let Some(bunny) = common::bunny() else { return };
    let expected = [
        (ModelKind::Dof, "2e2ba5fc082b92cb69587ff2c659cab9"),
        (ModelKind::Motion, "f7d45e8865ac3828d215b7fddbfa1045"),
        (ModelKind::Lens, "0fe7252f1e7885948f8e6824b5ce68c8"),
    ];
    assert_checksums(&bunny.ray_set_bounds(), 1024, expected, "the bunny");
}

#[test]
fn the_seed_chooses_the_lens_and_time_samples() {
    let b = icosphere_bounds();
    for kind in MODELS {
        let a = camera_model_rays(&b, 16, kind, 1).unwrap();
        assert_eq!(a, camera_model_rays(&b, 16, kind, 1).unwrap());
        let other = camera_model_rays(&b, 16, kind, 2).unwrap();
        // The lens set draws nothing; the others change with the seed.
        assert_eq!(a == other, kind == ModelKind::Lens, "{kind:?}");
    }
}

#[test]
fn every_index_agrees_with_brute_force_on_the_camera_sets() {
    let mut scenes = common::agreement_scenes();
    scenes.truncate(6);
    for scene in scenes {
        let geom = scene.geometry();
        let b = scene.ray_set_bounds();
        let mut rays = Vec::new();
        for kind in MODELS {
            rays.extend(camera_model_rays(&b, 24, kind, CAMERA_SET_SEED).unwrap());
        }
        let kernel = TriangleKernelKind::Exact;
        let brute = build_index(&IndexSpec::named("brute"), &geom, kernel).unwrap();
        for name in index_names()
            .into_iter()
            .filter(|n| !is_peer(n) && *n != "brute")
        {
            let index = build_index(&IndexSpec::named(name), &geom, kernel).unwrap();
            let m = compare_indices(brute.as_ref(), index.as_ref(), &rays);
            common::assert_no_mismatch(name, &scene, rays.len(), &m);
        }
    }
}

#[test]
fn a_depth_of_field_render_is_byte_identical_through_every_index() {
    use accelbench::render::{Filter, RenderOptions, Sampling, render_shaded_with};
    let scene = generators::generate("mixed", 1500, 3).unwrap();
    let geom = scene.geometry();
    let opts = RenderOptions::new(24, 16);
    let sampling = Sampling {
        spp: 16,
        filter: Filter::Tent,
        camera: ModelKind::Dof,
        seed: 5,
        mode: TraceMode::Single,
    };
    let kernel = TriangleKernelKind::Exact;
    let render_in = |name: &str, mode: TraceMode| {
        let index = build_index(&IndexSpec::named(name), &geom, kernel).unwrap();
        let sampling = Sampling { mode, ..sampling };
        render_shaded_with(&scene, index.as_ref(), &opts, &sampling).unwrap()
    };
    let render = |name: &str| render_in(name, TraceMode::Single);
    let reference = render("brute");
    let pinhole = {
        let index = build_index(&IndexSpec::named("bvh"), &geom, kernel).unwrap();
        let one = Sampling::default();
        render_shaded_with(&scene, index.as_ref(), &opts, &one).unwrap()
    };
    // Depth of field blurs: the image is not the pinhole's.
    assert_ne!(reference.as_bytes(), pinhole.as_bytes());
    for name in index_names()
        .into_iter()
        .filter(|n| !is_peer(n) && *n != "brute")
    {
        assert!(
            render(name).as_bytes() == reference.as_bytes(),
            "{name}: the dof render differs from brute force's"
        );
    }
    // Every trace mode renders the same image (`render --mode`).
    for mode in [TraceMode::Stream, TraceMode::LastHit, TraceMode::Packets(8)] {
        for name in ["bvh", "bvh8", "grid"] {
            assert!(
                render_in(name, mode).as_bytes() == reference.as_bytes(),
                "{name} in {mode:?}: the dof render differs from brute force's"
            );
        }
    }
}
