//! Test helpers shared by the binary space partitions (kd-tree, BSP): degenerate scenes, rays
//! in and through split planes, and a geometry that records every kernel call.
#![allow(dead_code)]

use crate::common::call_log::CallLog;
use accelbench::geometry::triangle::Watertight;
use accelbench::geometry::{Aabb, Ray, Triangle, TriangleKernelKind};
use accelbench::index::kit::near_far::{NearFarIndex, Partition};
use accelbench::index::{BuildError, Counters, Index, IndexSpec, build_index, build_index_on};
use accelbench::rays::SplitMix64;
use accelbench::scene::{Scene, Triangles, generators};
use glam::{Vec3, Vec3A};
use std::sync::Arc;

/// Scenes that have broken naive builders: all one triangle, zero-area triangles (points and
/// segments), many triangles sharing one centroid, all in one plane.
pub fn degenerate_scenes() -> Vec<Scene> {
    let t = Triangle::from_corners([0.0, 0.0, 0.0], [1.0, 0.0, 0.2], [0.0, 1.0, 0.4]);
    let duplicates = vec![t; 500];
    let mut zero_area = Vec::new();
    for i in 0..300 {
        let p = Vec3A::new(i as f32 * 0.01, (i % 7) as f32 * 0.1, 0.3);
        zero_area.push(Triangle::new(p, p, p));
        zero_area.push(Triangle::new(p, p + Vec3A::X * 0.05, p + Vec3A::X * 0.1));
    }
    zero_area.push(t);
    let mut one_centroid = Vec::new();
    for i in 0..400 {
        let a = i as f32 * 0.7;
        let (s, c) = a.sin_cos();
        let u = Vec3A::new(c, s, 0.3 * s);
        let v = Vec3A::new(-s * 0.5, c * 0.5, 0.9);
        // Centroid exactly at the origin: (u + v + (-u - v)) / 3.
        one_centroid.push(Triangle::new(u, v, -u - v));
    }
    let mut flat = Vec::new();
    for i in 0..20 {
        for j in 0..20 {
            let p = Vec3A::new(i as f32, j as f32, 0.0);
            flat.push(Triangle::new(p, p + Vec3A::X, p + Vec3A::Y));
            flat.push(Triangle::new(
                p + Vec3A::X,
                p + Vec3A::ONE.with_z(0.0),
                p + Vec3A::Y,
            ));
        }
    }
    vec![
        Scene::from_triangles("all_duplicates", duplicates),
        Scene::from_triangles("zero_area", zero_area),
        Scene::from_triangles("one_centroid", one_centroid),
        Scene::from_triangles("one_plane", flat),
    ]
}

/// A point uniformly in `b` grown by half its extent.
pub fn point_near(b: &Aabb, rng: &mut SplitMix64) -> Vec3 {
    let e = Vec3::from(b.extent()).max(Vec3::splat(1e-3));
    let lo = Vec3::from(b.min) - e * 0.5;
    let r = Vec3::new(
        rng.next_unit() as f32,
        rng.next_unit() as f32,
        rng.next_unit() as f32,
    );
    lo + r * e * 2.0
}

/// A random unit direction.
pub fn direction(rng: &mut SplitMix64) -> Vec3 {
    loop {
        let d = Vec3::new(
            rng.next_unit() as f32 * 2.0 - 1.0,
            rng.next_unit() as f32 * 2.0 - 1.0,
            rng.next_unit() as f32 * 2.0 - 1.0,
        );
        if d.length_squared() > 0.01 && d.length_squared() <= 1.0 {
            return d.normalize();
        }
    }
}

/// Rays lying exactly in the axis plane `p[axis] = s` (origin on it, direction component `+0.0`
/// or `-0.0`), `per_plane` per plane.
pub fn rays_in_axis_planes(planes: &[(usize, f32)], b: &Aabb, per_plane: usize) -> Vec<Ray> {
    let mut rng = SplitMix64::new(11);
    let mut rays = Vec::new();
    for &(axis, s) in planes {
        for k in 0..per_plane {
            let mut o = point_near(b, &mut rng);
            o[axis] = s;
            let mut d = direction(&mut rng);
            d[axis] = if k.is_multiple_of(2) { 0.0 } else { -0.0 };
            if let Ok(r) = Ray::infinite(o, d) {
                rays.push(r);
            }
        }
    }
    rays
}

/// Rays through the lines where two axis planes of different axes meet: along the line, from a
/// point on it in a random direction, and aimed at a point on it from outside.
pub fn rays_through_plane_crossings(planes: &[(usize, f32)], b: &Aabb, n: usize) -> Vec<Ray> {
    let mut rng = SplitMix64::new(12);
    let mut rays = Vec::new();
    if planes.is_empty() {
        return rays;
    }
    for _ in 0..n {
        let (a1, s1) = planes[(rng.next_u64() % planes.len() as u64) as usize];
        let pick = planes
            .iter()
            .cycle()
            .skip((rng.next_u64() % planes.len() as u64) as usize)
            .take(planes.len())
            .find(|(a, _)| *a != a1);
        let Some(&(a2, s2)) = pick else {
            continue;
        };
        let mut p = point_near(b, &mut rng);
        p[a1] = s1;
        p[a2] = s2;
        let mut along = Vec3::ZERO;
        along[3 - a1 - a2] = if rng.next_u64().is_multiple_of(2) {
            1.0
        } else {
            -1.0
        };
        let from = point_near(b, &mut rng);
        for r in [
            Ray::infinite(p, along),
            Ray::infinite(p, direction(&mut rng)),
            Ray::infinite(from, p - from),
        ]
        .into_iter()
        .flatten()
        {
            rays.push(r);
        }
    }
    rays
}

/// Triangles with the watertight kernel that record the primitive of every kernel call.
pub type Recording = CallLog<Watertight, u32, fn(u32, &Ray) -> u32>;

impl Recording {
    pub fn new(scene: &Scene) -> Recording {
        CallLog {
            inner: Triangles::new(Arc::from(scene.triangles.as_slice())),
            note: |prim, _| prim,
            calls: Arc::default(),
        }
    }
}

/// Asserts that `index` tests each primitive at most once per ray (closest and any hit), and
/// that the `Counters` count exactly the kernel calls made.
pub fn assert_each_primitive_once<I: Index>(index: &I, geom: &Recording, rays: &[Ray]) {
    let mut repeated = 0;
    let mut total = 0;
    for ray in rays {
        for query in 0..2 {
            geom.calls.lock().unwrap().clear();
            let mut c = Counters::default();
            if query == 0 {
                index.closest_hit(geom, ray, &mut c);
            } else {
                index.any_hit(geom, ray, &mut c);
            }
            let mut calls = geom.calls.lock().unwrap().clone();
            assert_eq!(c.prim_tests, calls.len() as u64, "counters match the calls");
            total += calls.len();
            calls.sort_unstable();
            let n = calls.len();
            calls.dedup();
            repeated += n - calls.len();
        }
    }
    assert!(total > 0, "the rays tested something");
    assert_eq!(repeated, 0, "primitives tested twice in one ray");
}

/// Index `I`, registered as `name`, built with parameters `params` (`""` or `":key=value,.."`)
/// over the scene's triangles with the watertight kernel.
pub fn build_on<I: Index>(name: &str, scene: &Scene, params: &str) -> I {
    let spec: IndexSpec = format!("{name}{params}").parse().unwrap();
    let params = accelbench::index::parse_params::<I>(&spec).unwrap();
    let geom = Triangles::<Watertight>::new(Arc::from(scene.triangles.as_slice()));
    build_index_on::<I, _>(name, geom, params).unwrap().index
}

/// On scenes where `I` (default parameters) stores primitives in several leaves, it still tests
/// each primitive at most once per ray.
pub fn assert_tests_each_primitive_once<I: Index>() {
    for name in ["soup", "stadium", "slivers"] {
        let scene = generators::generate(name, 2000, 2).unwrap();
        let geom = Recording::new(&scene);
        let tree = I::build(&geom, &Default::default()).unwrap();
        // References are duplicated, or the test proves nothing.
        assert!(tree.info().prim_refs > scene.triangles.len(), "{name}");
        let rays = crate::common::agreement_rays(&scene, 400);
        assert_each_primitive_once(&tree, &geom, &rays);
    }
}

/// The figures of `NearFarIndex<N>` (registered as `name`, nodes of `node_bytes`, 4-byte ids)
/// describe a full binary tree whose leaves hold every reference: a leaf of one primitive holds
/// a primitive id itself, the others index the id array, which holds nothing else; and
/// `max_depth=4` bounds its depth.
pub fn assert_structure_figures<N: Partition>(name: &str, node_bytes: usize) {
    let scene = generators::generate("icosphere", 5000, 1).unwrap();
    let index = build_on::<NearFarIndex<N>>(name, &scene, "");
    let info = index.info();
    assert_eq!(info.nodes, 2 * info.leaves - 1, "a full binary tree");
    assert!(info.prim_refs >= scene.triangles.len());
    let leaves: Vec<(u32, u32)> = index.leaves().collect();
    assert_eq!(leaves.len(), info.leaves);
    let refs: u32 = leaves.iter().map(|l| l.1).sum();
    assert_eq!(
        refs as usize, info.prim_refs,
        "the leaves hold every reference"
    );
    let (ones, runs): (Vec<&(u32, u32)>, Vec<_>) = leaves.iter().partition(|l| l.1 == 1);
    assert!(!ones.is_empty(), "one-primitive leaves are exercised");
    assert!(ones.iter().all(|l| (l.0 as usize) < scene.triangles.len()));
    let id_slots = (info.memory_bytes - info.nodes * node_bytes) / 4;
    assert_eq!(
        info.memory_bytes,
        info.nodes * node_bytes + id_slots * 4,
        "nodes and 4-byte ids"
    );
    assert_eq!(
        id_slots,
        runs.iter().map(|l| l.1 as usize).sum::<usize>(),
        "the id array holds the runs of the leaves of other sizes"
    );
    assert!(runs.iter().all(|l| (l.0 + l.1) as usize <= id_slots));
    let depth = build_on::<NearFarIndex<N>>(name, &scene, ":max_depth=4")
        .info()
        .depth;
    assert!(depth <= 5, "depth {depth} within max_depth=4");
}

/// `index:params` fails to build with a parameter error whose message contains the given
/// words, for the shared SAH parameters' bad values and for `own`.
pub fn assert_bad_parameters(index: &str, own: &[(&str, &str)]) {
    let g = generators::generate("icosphere", 100, 1)
        .unwrap()
        .geometry();
    // The SAH parameters both trees share (`SahParams::validate`), then `index`'s own.
    let shared = [
        ("intersect_cost=-1.0", "intersect_cost"),
        ("intersect_cost=0.0", "intersect_cost"),
        ("traversal_cost=nan", "traversal_cost"),
        ("traversal_cost=inf", "traversal_cost"),
        ("empty_bonus=1.0", "empty_bonus"),
        ("empty_bonus=-0.5", "empty_bonus"),
        ("max_depth=65", "max_depth"),
        ("max_depth=1000", "max_depth"),
        ("leaf_size=0", "leaf_size"),
        ("leafsize=3", "unknown field"),
    ];
    for &(params, says) in shared.iter().chain(own) {
        let spec: IndexSpec = format!("{index}:{params}").parse().unwrap();
        let err = build_index(&spec, &g, TriangleKernelKind::Watertight)
            .err()
            .unwrap_or_else(|| panic!("{spec} must fail"));
        assert!(matches!(err, BuildError::Params { .. }), "{spec}: {err}");
        assert!(err.to_string().contains(says), "{spec}: {err}");
    }
}

/// What every binary space partition `NearFarIndex<N>` (registered as `index`, nodes of
/// `node_bytes`) promises: [`assert_tests_each_primitive_once`], [`assert_structure_figures`]
/// and [`assert_bad_parameters`] with its own bad parameters `own_bad`.
pub fn assert_partition_basics<N: Partition>(
    index: &str,
    node_bytes: usize,
    own_bad: &[(&str, &str)],
) {
    assert_tests_each_primitive_once::<NearFarIndex<N>>();
    assert_structure_figures::<N>(index, node_bytes);
    assert_bad_parameters(index, own_bad);
}

/// Each of `specs` (an index with non-default parameters) returns brute force's hits on a
/// 3,000-triangle stadium (many coplanar, axis-aligned faces).
pub fn assert_agrees_with_parameters(specs: &[&str]) {
    let scene = generators::generate("stadium", 3000, 3).unwrap();
    let rays = crate::common::agreement_rays(&scene, 1500);
    for spec in specs {
        crate::common::assert_agrees(spec, &scene, &rays);
    }
}

/// Evenly spaced items of `items`, about `about` of them (every `len / about + 1`-th).
pub fn spaced<T: Copy>(items: &[T], about: usize) -> Vec<T> {
    items
        .iter()
        .step_by(items.len() / about + 1)
        .copied()
        .collect()
}
