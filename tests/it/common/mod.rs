//! Shared test scenes and ray families for the cross-index agreement tests: the same test body
//! runs against every index (`assert_agrees("grid", ...)`, and `tests/it/agreement.rs` over
//! the whole registry).
#![allow(dead_code)]

pub mod call_log;
pub mod checksum;
pub mod cli;
pub mod drop_one;
pub mod far;
pub mod grid_rays;
pub mod judge;
pub mod temp;

use accelbench::geometry::Hit;
use accelbench::geometry::{Ray, TriangleKernelKind};
use accelbench::harness::verify::{Mismatch, compare_with_expected, verify_against_brute};
use accelbench::index::{IndexSpec, TraceIndex, build_index};
use accelbench::rays::{incoherent_rays, primary_rays};
use accelbench::scene::{Scene, generators};
use glam::Vec3;

/// Small versions of the agreement scenes every index is tested on.
pub fn agreement_scenes() -> Vec<Scene> {
    let mut v: Vec<Scene> = [
        "icosphere",
        "spheres",
        "mixed",
        "soup",
        "stadium",
        "flat",
        "room",
        "slivers",
        "terrain",
    ]
    .iter()
    .map(|n| generators::generate(n, 3000, 7).unwrap())
    .collect();
    // Coincident duplicates (both windings) and zero-area triangles.
    let mut dup = generators::generate("icosphere", 1000, 1).unwrap();
    let extra: Vec<_> = dup
        .triangles
        .iter()
        .take(200)
        .map(|t| accelbench::geometry::Triangle::new(t.v[0], t.v[2], t.v[1]))
        .collect();
    dup.triangles.extend(extra);
    let t0 = dup.triangles[0];
    dup.triangles.push(accelbench::geometry::Triangle::new(
        t0.v[0], t0.v[1], t0.v[1],
    ));
    dup.name = "duplicates".into();
    v.push(dup);
    v
}

/// The bunny from ../shared/meshes when present (otherwise says the test part is skipped).
pub fn bunny() -> Option<Scene> {
    cli::shared_mesh("stanford_bunny.obj").map(|p| Scene::load_obj(&p).unwrap())
}

/// Protocol primary and incoherent rays, plus rays aimed exactly at vertices and edge midpoints
/// (from outside and from the centre), and axis-parallel rays with +0.0 and -0.0 components.
pub fn agreement_rays(scene: &Scene, n: usize) -> Vec<Ray> {
    let b = scene.ray_set_bounds();
    let side = ((n as f64).sqrt() as u32).max(2);
    let mut rays = primary_rays(&b, side, side).unwrap();
    rays.extend(incoherent_rays(&b, n, 42));
    let c = Vec3::from(b.center());
    let eye = c + Vec3::from(b.extent()) * Vec3::new(0.9, 0.7, 1.3) + Vec3::splat(0.01);
    for t in scene
        .triangles
        .iter()
        .step_by((scene.triangles.len() / (n / 4).max(1)).max(1))
    {
        for target in [t.v[0], (t.v[0] + t.v[1]) * 0.5] {
            let target = Vec3::from(target);
            for o in [eye, c] {
                if let Ok(r) = Ray::infinite(o, target - o) {
                    rays.push(r);
                }
            }
        }
    }
    let e = Vec3::from(b.extent());
    for i in 0..16 {
        let f = (i as f32 + 0.5) / 16.0;
        let o = Vec3::from(b.min) + e * Vec3::new(f, 1.0 - f, f * f) - e;
        for d in [
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::new(1.0, -0.0, -0.0),
            Vec3::new(0.0, 1.0, 0.0),
            Vec3::new(-0.0, 0.0, 1.0),
        ] {
            let o2 = o + e * (Vec3::ONE - d.abs()) * 1.0;
            rays.push(Ray::infinite(o2 - d * e, d).unwrap());
        }
    }
    rays
}

/// Asserts agreement with brute force on one scene and ray set, with the watertight and the
/// exact kernel, printing the first mismatches.
pub fn assert_agrees(spec: &str, scene: &Scene, rays: &[Ray]) {
    let spec: IndexSpec = spec.parse().unwrap();
    for kernel in [TriangleKernelKind::Watertight, TriangleKernelKind::Exact] {
        assert_agrees_with(&spec, kernel, scene, rays);
    }
}

fn assert_agrees_with(spec: &IndexSpec, kernel: TriangleKernelKind, scene: &Scene, rays: &[Ray]) {
    let m = verify_against_brute(spec, &scene.geometry(), kernel, rays).unwrap();
    assert_no_mismatch(&format!("{spec} ({kernel})"), scene, rays.len(), &m);
}

/// Asserts that every index of `specs` returns brute force's hits on `rays` over `scene` with
/// `kernel` ([`compare_with_expected`]); brute force is traced once for all of them.
pub fn assert_specs_agree(
    specs: &[String],
    scene: &Scene,
    kernel: TriangleKernelKind,
    rays: &[Ray],
) {
    let geom = scene.geometry();
    let brute = build_index(&IndexSpec::named("brute"), &geom, kernel).unwrap();
    let mut expected = vec![None; rays.len()];
    brute.closest_hits(rays, &mut expected);
    for spec in specs {
        let index = build_index(&spec.parse().unwrap(), &geom, kernel).unwrap();
        let m = compare_with_expected(index.as_ref(), rays, &expected);
        assert_no_mismatch(&format!("{spec} ({kernel})"), scene, rays.len(), &m);
    }
}

/// Fails with the first three mismatches when `m` is not empty (`what`: index and kernel).
pub fn assert_no_mismatch(what: &str, scene: &Scene, rays: usize, m: &[Mismatch]) {
    assert!(
        m.is_empty(),
        "{what} on {}: {} of {rays} rays mismatch, first: {}",
        scene.name,
        m.len(),
        m.iter()
            .take(3)
            .map(|m| m.to_string())
            .collect::<Vec<_>>()
            .join("\n")
    );
}

/// The small protocol sample the bunny tests share: 48 x 48 primary rays and 2000 incoherent
/// rays (seed 42).
pub fn bunny_protocol_sample(bunny: &Scene) -> Vec<Ray> {
    let b = bunny.ray_set_bounds();
    let mut rays = primary_rays(&b, 48, 48).unwrap();
    rays.extend(incoherent_rays(&b, 2000, 42));
    rays
}

/// Asserts that every index of ours traced in `mode` returns brute force's closest hits and
/// any-hit answers on `rays` (the kernel `Exact`), on the camera sets and protocol rays of
/// small agreement scenes, plus the same rays cut to a finite `t_max` (occlusion queries).
pub fn assert_mode_agrees(mode: accelbench::index::TraceMode) {
    use accelbench::camera::ModelKind;
    use accelbench::index::{build_index, index_names, is_peer};
    use accelbench::rays::{CAMERA_SET_SEED, camera_model_rays};
    let mut scenes = agreement_scenes();
    scenes.truncate(7);
    if let Some(b) = bunny() {
        scenes.push(b);
    }
    for scene in scenes {
        let geom = scene.geometry();
        let b = scene.ray_set_bounds();
        let mut rays = agreement_rays(&scene, 400);
        for kind in [ModelKind::Dof, ModelKind::Motion, ModelKind::Lens] {
            rays.extend(camera_model_rays(&b, 20, kind, CAMERA_SET_SEED).unwrap());
        }
        let cut = b.extent().length() * 0.9;
        let short: Vec<Ray> = rays
            .iter()
            .filter_map(|r| Ray::new(r.origin.into(), r.dir.into(), r.t_min, cut).ok())
            .collect();
        rays.extend(short);
        let kernel = TriangleKernelKind::Exact;
        let brute =
            accelbench::index::build_index(&IndexSpec::named("brute"), &geom, kernel).unwrap();
        let mut expected = vec![None; rays.len()];
        brute.closest_hits(&rays, &mut expected);
        for name in index_names().into_iter().filter(|n| !is_peer(n)) {
            let index = build_index(&IndexSpec::named(name), &geom, kernel).unwrap();
            let mut got = vec![None; rays.len()];
            index.closest_hits_in(mode, &rays, &mut got, None);
            let what = format!("{name} in {mode:?}");
            let m = accelbench::harness::verify::compare_closest(&rays, &expected, &got);
            assert_no_mismatch(&what, &scene, rays.len(), &m);
            let mut counters = vec![accelbench::index::Counters::default(); rays.len()];
            index.closest_hits_in(mode, &rays, &mut got, Some(&mut counters));
            let m = accelbench::harness::verify::compare_closest(&rays, &expected, &got);
            assert_no_mismatch(&format!("{what}, counted"), &scene, rays.len(), &m);
            let mut any = vec![false; rays.len()];
            index.any_hits_in(mode, &rays, &mut any, None);
            let wrong = (0..rays.len())
                .filter(|&i| any[i] != expected[i].is_some())
                .count();
            assert_eq!(wrong, 0, "{what} any-hit on {}: {wrong} wrong", scene.name);
        }
    }
}

/// The bunny's full protocol sets (1024 x 1024 primary, 1,048,576 incoherent rays, one batch
/// each) as `(set, rays, expected)`: the expected hits are `bvh`'s (exact kernel), which are
/// brute force's bit for bit (`tests/it/agreement.rs`), so every ray can be checked.
pub fn bunny_protocol_sets(bunny: &Scene) -> Vec<(String, Vec<Ray>, Vec<Option<Hit>>)> {
    let sizes = accelbench::harness::workload::SetSizes {
        primary_side: 1024,
        incoherent: 1 << 20,
        ao_fraction: 0.05,
    };
    let reference = build("bvh", bunny, TriangleKernelKind::Exact);
    let primary = accelbench::harness::workload::primary(bunny, &sizes).unwrap();
    let incoherent = accelbench::harness::workload::incoherent(bunny, &sizes);
    [("primary", primary), ("incoherent", incoherent)]
        .into_iter()
        .map(|(set, rays)| {
            let expected = closest(reference.as_ref(), &rays);
            (set.to_owned(), rays, expected)
        })
        .collect()
}

/// Asserts that `index`'s any-hit answers for `rays` traced in `mode` are its closest hits
/// `got` (of the same rays) made boolean; `what` names the case.
pub fn assert_any_hit_is_closest_hit(
    index: &dyn TraceIndex,
    mode: accelbench::index::TraceMode,
    rays: &[Ray],
    got: &[Option<Hit>],
    what: &str,
) {
    let mut any = vec![false; rays.len()];
    index.any_hits_in(mode, rays, &mut any, None);
    let differ = any
        .iter()
        .zip(got)
        .filter(|(a, g)| **a != g.is_some())
        .count();
    assert_eq!(differ, 0, "{what}: any-hit disagrees with its closest hit");
}

/// Builds `spec` over `scene` with the triangle kernel `kernel`.
pub fn build(spec: &str, scene: &Scene, kernel: TriangleKernelKind) -> Box<dyn TraceIndex> {
    let spec: IndexSpec = spec.parse().unwrap();
    build_index(&spec, &scene.geometry(), kernel).unwrap()
}

/// The closest hits of `rays` through `index`.
pub fn closest(index: &dyn TraceIndex, rays: &[Ray]) -> Vec<Option<Hit>> {
    closest_in(index, accelbench::index::TraceMode::Single, rays)
}

/// [`closest`] traced in `mode`.
pub fn closest_in(
    index: &dyn TraceIndex,
    mode: accelbench::index::TraceMode,
    rays: &[Ray],
) -> Vec<Option<Hit>> {
    let mut out = vec![None; rays.len()];
    index.closest_hits_in(mode, rays, &mut out, None);
    out
}

/// Asserts that every spec of `cases` fails to build on a small triangle soup with a typed
/// parameter error ([`accelbench::index::BuildError::Params`]) whose message contains the
/// case's word.
pub fn assert_params_rejected(cases: &[(&str, &str)]) {
    let build = soup_builder();
    for (bad, says) in cases {
        let err = build(bad).unwrap_err();
        assert!(
            matches!(err, accelbench::index::BuildError::Params { .. }),
            "{bad}: {err}"
        );
        assert!(err.to_string().contains(says), "{bad}: {err}");
    }
}

/// Builds a spec (parsed from text) over a triangle soup of 100 with the watertight kernel.
pub fn soup_builder() -> impl Fn(&str) -> Result<(), accelbench::index::BuildError> {
    let geom = generators::generate("soup", 100, 1).unwrap().geometry();
    move |s: &str| build_index(&s.parse()?, &geom, TriangleKernelKind::Watertight).map(|_| ())
}

/// Asserts that `spec` refuses a scene without primitives with [`BuildError::EmptyScene`].
///
/// [`BuildError::EmptyScene`]: accelbench::index::BuildError::EmptyScene
pub fn assert_refuses_empty_scenes(spec: &str) {
    let empty = Scene::from_triangles("empty", vec![]);
    let err = build_error(spec, &empty);
    assert!(
        matches!(err, accelbench::index::BuildError::EmptyScene),
        "{spec}: {err}"
    );
}

/// The error that building `spec` over `scene` must give (with the watertight kernel).
pub fn build_error(spec: &str, scene: &Scene) -> accelbench::index::BuildError {
    spec.parse::<IndexSpec>()
        .and_then(|s| build_index(&s, &scene.geometry(), TriangleKernelKind::Watertight))
        .err()
        .unwrap_or_else(|| panic!("{spec} should fail"))
}

/// Proptest's configuration with `cases` cases per property, unless the environment's
/// `PROPTEST_CASES` gives another number (CI runs the fuzz targets with more).
pub fn proptest_config(cases: u32) -> proptest::prelude::ProptestConfig {
    let cases = std::env::var("PROPTEST_CASES")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(cases);
    proptest::prelude::ProptestConfig {
        cases,
        ..Default::default()
    }
}

/// Asserts that `spec` agrees with brute force on a scene of one triangle (and hits it and
/// misses beside it where a ray aims) and on a scene of one sphere.
pub fn assert_one_primitive_agrees(spec: &str) {
    use accelbench::geometry::Triangle;
    use glam::Vec3A;
    let one = Scene::from_triangles("one", vec![Triangle::new(Vec3A::ZERO, Vec3A::X, Vec3A::Y)]);
    let hit = Ray::infinite(Vec3::new(0.2, 0.2, 1.0), Vec3::NEG_Z).unwrap();
    let miss = Ray::infinite(Vec3::new(0.8, 0.8, 1.0), Vec3::NEG_Z).unwrap();
    let mut rays = agreement_rays(&one, 200);
    rays.extend([hit, miss]);
    assert_agrees(spec, &one, &rays);
    let built = build(spec, &one, TriangleKernelKind::Watertight);
    assert!(built.closest_hit(&hit).is_some() && built.closest_hit(&miss).is_none());
    let sphere = generators::generate("spheres", 1, 1).unwrap();
    assert_agrees(spec, &sphere, &agreement_rays(&sphere, 200));
}
