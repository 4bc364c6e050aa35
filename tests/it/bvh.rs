//! The BVH (every preset) against brute force: the agreement scenes, the bunny, degenerate
//! inputs, the depth cap, bad parameters, and that it actually culls. Spatial splits
//! (`spatial_splits=true` on `bvh`, `bvh4`, `bvh8`): brute force's hits bit for bit with every
//! kernel on the agreement scenes, shapes, the bunny and the stress cases, in every trace mode;
//! they happen on slivers, within the reference budget, and the build is deterministic.

use crate::common;

use accelbench::geometry::{Ray, Triangle, TriangleKernelKind};
use accelbench::harness::verify::compare_closest;
use accelbench::index::bvh::{BvhParams, MAX_DEPTH, Preset};
use accelbench::index::{Counters, IndexInfo, IndexSpec, TraceIndex, TraceMode, build_index};
use accelbench::rays::incoherent_rays;
use accelbench::scene::{Scene, generators};
use common::{agreement_rays, agreement_scenes};
use glam::{Vec3, Vec3A};

fn preset_specs() -> Vec<String> {
    Preset::ALL
        .iter()
        .map(|p| format!("bvh:preset=\"{}\"", p.name()))
        .chain([
            "bvh:leaf_size=1,bins=2".to_owned(),
            "bvh:cost_ratio=100".to_owned(),
        ])
        .collect()
}

fn build(spec: &str, scene: &Scene) -> Box<dyn TraceIndex> {
    let spec: IndexSpec = spec.parse().unwrap();
    build_index(&spec, &scene.geometry(), TriangleKernelKind::Watertight).unwrap()
}

/// Brute force once, then every spec: closest hits bit for bit, any-hit equal to "has a closest
/// hit". Returns the number of mismatching rays per spec (closest and any-hit).
fn mismatches(specs: &[String], scene: &Scene, rays: &[Ray]) -> Vec<(String, usize, String)> {
    let brute = build("brute", scene);
    let mut expected = vec![None; rays.len()];
    brute.closest_hits(rays, &mut expected);
    specs
        .iter()
        .map(|spec| {
            let index = build(spec, scene);
            let mut got = vec![None; rays.len()];
            index.closest_hits(rays, &mut got);
            let m = compare_closest(rays, &expected, &got);
            let mut any = vec![false; rays.len()];
            index.any_hits(rays, &mut any);
            let any_bad = expected
                .iter()
                .zip(&any)
                .filter(|(e, a)| e.is_some() != **a)
                .count();
            let first = m.first().map(|m| m.to_string()).unwrap_or_default();
            (spec.clone(), m.len() + any_bad, first)
        })
        .collect()
}

fn assert_all_agree(specs: &[String], scene: &Scene, rays: &[Ray]) {
    for (spec, bad, first) in mismatches(specs, scene, rays) {
        assert_eq!(
            bad,
            0,
            "{spec} on {}: {bad} of {} rays mismatch; first: {first}",
            scene.name,
            rays.len()
        );
    }
}

#[test]
fn every_preset_agrees_on_the_agreement_scenes() {
    for scene in agreement_scenes() {
        assert_all_agree(&preset_specs(), &scene, &agreement_rays(&scene, 2000));
    }
}

#[test]
fn every_preset_agrees_on_the_bunny() {
    let Some(bunny) = common::bunny() else { return };
    let rays = common::bunny_protocol_sample(&bunny);
    assert_all_agree(&preset_specs(), &bunny, &rays);
}

/// Rays from all around `scene` towards its centre and random rays, plus the kit's rays.
fn rays_for(scene: &Scene, n: usize) -> Vec<Ray> {
    agreement_rays(scene, n)
}

#[test]
fn one_primitive() {
    let scene = Scene::from_triangles(
        "one",
        vec![Triangle::from_corners(
            [0.0; 3],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
        )],
    );
    let index = build("bvh", &scene);
    assert_eq!((index.info().nodes, index.info().leaves), (1, 1));
    let hit = index
        .closest_hit(&Ray::infinite(Vec3::new(0.2, 0.2, 1.0), Vec3::NEG_Z).unwrap())
        .unwrap();
    assert_eq!((hit.prim, hit.t), (0, 1.0));
    assert_all_agree(&preset_specs(), &scene, &rays_for(&scene, 400));
}

#[test]
fn all_primitives_share_one_centroid() {
    // Triangles of growing size, rotated about the z axis, all centred on the origin.
    let tris: Vec<Triangle> = (0..300)
        .map(|i| {
            let (s, a) = (0.1 + i as f32 * 0.01, i as f32 * 0.7);
            let p = |k: f32| {
                let ang = a + k * std::f32::consts::TAU / 3.0;
                Vec3A::new(ang.cos() * s, ang.sin() * s, (k - 1.0) * s * 0.3)
            };
            Triangle::new(p(0.0), p(1.0), p(2.0))
        })
        .collect();
    let scene = Scene::from_triangles("one centroid", tris);
    assert_all_agree(&preset_specs(), &scene, &rays_for(&scene, 1000));
    assert!(build("bvh", &scene).info().depth <= MAX_DEPTH as usize);
}

#[test]
fn zero_area_triangles() {
    let mut tris: Vec<Triangle> = (0..200)
        .map(|i| {
            let x = i as f32 * 0.05;
            if i % 3 == 0 {
                Triangle::from_corners([x, 0.0, 0.0], [x, 0.0, 0.0], [x, 0.0, 0.0]) // a point
            } else if i % 3 == 1 {
                Triangle::from_corners([x, 0.0, 0.0], [x, 1.0, 0.0], [x, 2.0, 0.0]) // a segment
            } else {
                Triangle::from_corners([x, -1.0, -1.0], [x, 1.0, -1.0], [x, 0.0, 1.0])
            }
        })
        .collect();
    tris.push(Triangle::from_corners(
        [5.0, 5.0, 5.0],
        [5.0, 5.0, 5.0],
        [5.0, 5.0, 5.0],
    ));
    let scene = Scene::from_triangles("zero area", tris);
    assert!(scene.degenerate_triangles() > 100);
    assert_all_agree(&preset_specs(), &scene, &rays_for(&scene, 1000));
}

#[test]
fn flat_scene_of_zero_thickness() {
    // A grid of triangles in the plane z = 0.5, and rays in and across that plane.
    let mut tris = Vec::new();
    for i in 0..20 {
        for j in 0..20 {
            let (x, y) = (i as f32, j as f32);
            tris.push(Triangle::from_corners(
                [x, y, 0.5],
                [x + 1.0, y, 0.5],
                [x, y + 1.0, 0.5],
            ));
            tris.push(Triangle::from_corners(
                [x + 1.0, y, 0.5],
                [x + 1.0, y + 1.0, 0.5],
                [x, y + 1.0, 0.5],
            ));
        }
    }
    let scene = Scene::from_triangles("flat", tris);
    let mut rays = rays_for(&scene, 1000);
    for i in 0..50 {
        let f = i as f32 * 0.4;
        rays.push(Ray::infinite(Vec3::new(f, 7.0, 3.0), Vec3::new(0.0, 0.0, -1.0)).unwrap());
        rays.push(Ray::infinite(Vec3::new(-1.0, f, 0.5), Vec3::new(1.0, 0.0, 0.0)).unwrap());
        rays.push(Ray::infinite(Vec3::new(f, f, 0.5), Vec3::new(0.3, 0.1, -0.0)).unwrap());
    }
    assert_all_agree(&preset_specs(), &scene, &rays);
}

#[test]
fn coincident_duplicate_triangles() {
    let base = generators::generate("icosphere", 500, 3).unwrap();
    let mut tris = base.triangles.clone();
    tris.extend(base.triangles.iter().rev()); // every triangle twice, at ids i and 2n-1-i
    tris.extend(base.triangles.iter().take(50));
    let scene = Scene::from_triangles("duplicates", tris);
    // Ties at equal t go to the lower id: every hit is on an id of the first copy.
    let index = build("bvh", &scene);
    let rays = rays_for(&scene, 1000);
    for r in &rays {
        if let Some(h) = index.closest_hit(r) {
            assert!((h.prim as usize) < base.triangles.len(), "{h:?}");
        }
    }
    assert_all_agree(&preset_specs(), &scene, &rays);
}

#[test]
fn depth_is_capped_on_exponentially_spaced_primitives() {
    // Triangles at x = 0.8^i: each SAH split peels off a few, so the uncapped tree would be
    // deeper than the traversal stack.
    let tris: Vec<Triangle> = (0..400)
        .map(|i| {
            let x = 0.8f32.powi(i);
            let s = x * 0.05;
            Triangle::from_corners([x, -s, -s], [x, s, -s], [x, 0.0, s])
        })
        .collect();
    let scene = Scene::from_triangles("exponential", tris);
    let mut rays = rays_for(&scene, 500);
    for i in 0..400 {
        let x = 0.8f32.powi(i);
        rays.push(Ray::infinite(Vec3::new(x, 0.0, 0.0) - Vec3::X * x, Vec3::X).unwrap());
        rays.push(Ray::infinite(Vec3::new(x, 0.0, 1.0), Vec3::new(0.0, 0.0, -1.0)).unwrap());
    }
    for spec in preset_specs() {
        let info = build(&spec, &scene).info().clone();
        assert!(
            info.depth <= MAX_DEPTH as usize,
            "{spec}: depth {}",
            info.depth
        );
    }
    assert_eq!(
        build("bvh:leaf_size=1,bins=2", &scene).info().depth,
        MAX_DEPTH as usize
    );
    assert_all_agree(&preset_specs(), &scene, &rays);
}

#[test]
fn bad_parameters_and_empty_scenes_are_errors() {
    common::assert_params_rejected(&[
        ("bvh:bins=0", "bins"),
        ("bvh:bins=1000", "bins"),
        ("bvh:leaf_size=0", "leaf_size"),
        ("bvh:cost_ratio=-2.0", "cost_ratio"),
        ("bvh:preset=\"slowest\"", "preset"),
        ("bvh:split=\"median\"", "split"),
        ("bvh:leafsize=4", "unknown field"),
        ("bvh:spatial_splits=2", "spatial_splits"),
        ("bvh8:spatial_splits=\"yes\"", "spatial_splits"),
    ]);
    common::assert_refuses_empty_scenes("bvh");
}

#[test]
fn culls_most_primitives_and_reports_memory() {
    let scene = generators::generate("icosphere", 20_000, 1).unwrap();
    let rays = incoherent_rays(&scene.ray_set_bounds(), 2000, 42);
    let index = build("bvh", &scene);
    let mut out = vec![None; rays.len()];
    let mut c = vec![Counters::default(); rays.len()];
    index.closest_hits_counted(&rays, &mut out, &mut c);
    let total: Counters = c.into_iter().sum();
    let per_ray = total.prim_tests as f64 / rays.len() as f64;
    assert!(
        per_ray < 0.01 * scene.len() as f64,
        "{per_ray} tests per ray"
    );
    assert!(total.node_visits > 0 && total.box_tests >= total.node_visits);
    let info = index.info();
    let bpp = info
        .extra
        .iter()
        .find(|(k, _)| k == "bytes_per_prim")
        .unwrap()
        .1;
    assert_eq!(bpp, info.memory_bytes as f64 / scene.len() as f64);
    assert_eq!(info.memory_bytes, info.nodes * 32 + scene.len() * 4);
}

/// The spatial-split variants: each tree with the default preset, and the binary tree with the
/// full sweep and with one-primitive leaves and two bins.
fn spatial_specs() -> Vec<String> {
    ["bvh", "bvh4", "bvh8"]
        .map(|n| format!("{n}:spatial_splits=true"))
        .into_iter()
        .chain([
            "bvh:spatial_splits=true,preset=\"sweep\"".to_owned(),
            "bvh:spatial_splits=true,leaf_size=1,bins=2".to_owned(),
        ])
        .collect()
}

/// Asserts that every spatial-split variant returns brute force's hits on `rays` over `scene`
/// with `kernel`.
fn assert_spatial_agrees(scene: &Scene, kernel: TriangleKernelKind, rays: &[Ray]) {
    common::assert_specs_agree(&spatial_specs(), scene, kernel, rays);
}

#[test]
fn spatial_splits_agree_on_the_generated_scenes_with_every_kernel() {
    let mut scenes = agreement_scenes();
    scenes.push(generators::generate("shapes", 2000, 7).unwrap());
    for scene in &scenes {
        let rays = agreement_rays(scene, 1500);
        for kernel in TriangleKernelKind::ALL {
            assert_spatial_agrees(scene, kernel, &rays);
        }
    }
}

#[test]
fn spatial_splits_agree_on_the_bunny() {
    let Some(bunny) = common::bunny() else { return };
    let rays = common::bunny_protocol_sample(&bunny);
    assert_spatial_agrees(&bunny, TriangleKernelKind::Watertight, &rays);
}

#[test]
fn spatial_splits_pass_the_stress_cases() {
    for case in accelbench::stress::cases::all_cases(500, 1000) {
        let scene = Scene {
            name: case.name.into(),
            triangles: case.scene.triangles.to_vec(),
            spheres: case.scene.spheres.to_vec(),
            shapes: case.scene.shapes.to_vec(),
            ..Scene::default()
        };
        assert_spatial_agrees(&scene, case.kernel, &case.rays);
    }
}

#[test]
fn spatial_splits_agree_in_every_trace_mode() {
    let mut scenes: Vec<Scene> = agreement_scenes().into_iter().take(8).collect();
    scenes.extend(common::bunny());
    for scene in &scenes {
        let rays = agreement_rays(scene, 600);
        let brute = build("brute", scene);
        let mut expected = vec![None; rays.len()];
        brute.closest_hits(&rays, &mut expected);
        for spec in spatial_specs() {
            let index = build(&spec, scene);
            for mode in [
                TraceMode::LastHit,
                TraceMode::Packets(4),
                TraceMode::Packets(8),
            ] {
                let mut got = vec![None; rays.len()];
                index.closest_hits_in(mode, &rays, &mut got, None);
                let m = compare_closest(&rays, &expected, &got);
                common::assert_no_mismatch(&format!("{spec} {mode:?}"), scene, rays.len(), &m);
                let mut any = vec![false; rays.len()];
                index.any_hits_in(mode, &rays, &mut any, None);
                let wrong = (0..rays.len()).filter(|&i| any[i] != expected[i].is_some());
                assert_eq!(
                    wrong.count(),
                    0,
                    "{spec} {mode:?} any-hit on {}",
                    scene.name
                );
            }
        }
    }
}

/// On slivers (long thin triangles crossing each other) spatial splits happen: more references
/// than primitives, at most `split_budget` per primitive (the default, and 2 when asked), fewer primitive tests per
/// ray than without; and the tree is the same on every build and thread count.
#[test]
fn spatial_splits_happen_on_slivers_and_the_build_is_deterministic() {
    let scene = generators::generate("slivers", 20_000, 1).unwrap();
    let n = scene.len();
    let rays = incoherent_rays(&scene.ray_set_bounds(), 2000, 42);
    let tests_per_ray = |index: &dyn TraceIndex| {
        let mut out = vec![None; rays.len()];
        let mut c = vec![Counters::default(); rays.len()];
        index.closest_hits_counted(&rays, &mut out, &mut c);
        c.into_iter().sum::<Counters>().prim_tests as f64 / rays.len() as f64
    };
    for name in ["bvh", "bvh4", "bvh8"] {
        let spec = format!("{name}:spatial_splits=true");
        let pool = |t| {
            rayon::ThreadPoolBuilder::new()
                .num_threads(t)
                .build()
                .unwrap()
        };
        let [a, b, c] = [1, 1, 2].map(|t| pool(t).install(|| build(&spec, &scene)));
        let refs = a.info().prim_refs;
        let per_prim = BvhParams::default().config().unwrap().split_budget;
        assert!(
            refs > n && refs as f32 <= per_prim * n as f32,
            "{spec}: {refs} references"
        );
        let two = build(&format!("{spec},split_budget=2"), &scene)
            .info()
            .prim_refs;
        assert!(
            two > n && two <= 2 * n,
            "{spec}: {two} references at budget 2"
        );
        // Everything but the build time and the peak heap during the build, which differ
        // between any two builds (other threads allocate meanwhile).
        let key = |i: &dyn TraceIndex| {
            let info = IndexInfo {
                build_time: Default::default(),
                peak_build_bytes: None,
                ..i.info().clone()
            };
            format!("{info:?}")
        };
        assert_eq!(key(a.as_ref()), key(b.as_ref()), "{spec}");
        assert_eq!(key(a.as_ref()), key(c.as_ref()), "{spec}");
        let plain = build(name, &scene);
        assert_eq!(plain.info().prim_refs, n);
        let (with, without) = (tests_per_ray(a.as_ref()), tests_per_ray(plain.as_ref()));
        assert!(
            with < without,
            "{spec}: {with} tests per ray, {without} without"
        );
    }
}

/// `accelbench sweep bvh` writes one CSV row per (tree, budget) point, each with its
/// references, and both charts; a budget outside 1..=64 exits non-zero and names the option.
#[test]
fn cli_sweep_bvh_writes_csv_and_charts() {
    let points = ["--trees", "bvh,bvh8", "--split-budget", "1,4"];
    let row = ["bvh8", "split_budget=4"];
    common::cli::small_sweep("bvh", "slivers:n=300", &points, 4, &row);
    let bad = ["sweep", "bvh", "--scene", "soup", "--split-budget=0.5"];
    common::cli::accelbench_fails(&bad, &["split-budget"]);
}
