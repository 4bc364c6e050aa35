//! The SAH kd-tree returns brute force's hits bit for bit: on the agreement scenes, on rays
//! lying in its split planes and through their crossings, and on degenerate input; it tests
//! each primitive at most once per ray; bad parameters are typed errors.
mod common;
mod partition_kit;

use accelbench::geometry::TriangleKernelKind;
use accelbench::geometry::triangle::Watertight;
use accelbench::index::{BuildError, Index, IndexSpec, KdTree, build_index, build_index_on};
use accelbench::scene::{Scene, Triangles, generators};
use partition_kit::*;
use std::sync::Arc;

fn kdtree_on(scene: &Scene, params: &str) -> KdTree {
    let spec: IndexSpec = format!("kdtree{params}").parse().unwrap();
    let params = accelbench::index::parse_params::<KdTree>(&spec).unwrap();
    let geom = Triangles::<Watertight>::new(Arc::from(scene.triangles.as_slice()));
    build_index_on::<KdTree, _>("kdtree", geom, params)
        .unwrap()
        .index
}

#[test]
fn agrees_with_other_parameters() {
    let scene = generators::generate("stadium", 3000, 3).unwrap();
    let rays = common::agreement_rays(&scene, 1500);
    for spec in [
        "kdtree:leaf_size=8",
        "kdtree:max_depth=3",
        "kdtree:intersect_cost=2.0,empty_bonus=0.0",
    ] {
        common::assert_agrees(spec, &scene, &rays);
    }
}

#[test]
fn rays_in_split_planes_and_through_their_crossings() {
    for name in ["icosphere", "soup", "stadium", "room", "flat"] {
        let scene = generators::generate(name, 2000, 5).unwrap();
        let tree = kdtree_on(&scene, "");
        let planes = tree.split_planes();
        assert!(!planes.is_empty(), "{name}: the tree splits");
        let sample: Vec<_> = planes
            .iter()
            .step_by(planes.len() / 60 + 1)
            .copied()
            .collect();
        let b = scene.bounds();
        let mut rays = rays_in_axis_planes(&sample, &b, 8);
        rays.extend(rays_through_plane_crossings(&planes, &b, 600));
        common::assert_agrees("kdtree", &scene, &rays);
    }
}

#[test]
fn degenerate_input_terminates_and_agrees() {
    for scene in degenerate_scenes() {
        let tree = kdtree_on(&scene, "");
        let info = tree.info();
        assert!(info.depth <= 64 && info.leaves >= 1, "{}", scene.name);
        let rays = common::agreement_rays(&scene, 800);
        common::assert_agrees("kdtree", &scene, &rays);
        let mut rays = rays_in_axis_planes(&tree.split_planes(), &scene.bounds(), 4);
        rays.truncate(2000);
        common::assert_agrees("kdtree", &scene, &rays);
    }
}

#[test]
fn each_primitive_tested_at_most_once_per_ray() {
    for name in ["soup", "stadium", "slivers"] {
        let scene = generators::generate(name, 2000, 2).unwrap();
        let geom = Recording::new(&scene);
        let tree = KdTree::build(&geom, &Default::default()).unwrap();
        // References are duplicated, or the test proves nothing.
        assert!(tree.info().prim_refs > scene.triangles.len(), "{name}");
        let rays = common::agreement_rays(&scene, 400);
        assert_each_primitive_once(&tree, &geom, &rays);
    }
}

#[test]
fn structure_figures_are_consistent() {
    let scene = generators::generate("icosphere", 5000, 1).unwrap();
    let info = kdtree_on(&scene, "").info();
    assert_eq!(info.nodes, 2 * info.leaves - 1, "a full binary tree");
    assert!(info.prim_refs >= scene.triangles.len());
    assert_eq!(info.memory_bytes, info.nodes * 8 + info.prim_refs * 4);
    let max_depth = kdtree_on(&scene, ":max_depth=4").info().depth;
    assert!(max_depth <= 5, "depth {max_depth} within max_depth=4");
}

#[test]
fn bad_parameters_are_typed_errors() {
    let g = generators::generate("icosphere", 100, 1)
        .unwrap()
        .geometry();
    for (spec, says) in [
        ("kdtree:intersect_cost=-1.0", "intersect_cost"),
        ("kdtree:traversal_cost=nan", "traversal_cost"),
        ("kdtree:empty_bonus=1.0", "empty_bonus"),
        ("kdtree:max_depth=65", "max_depth"),
        ("kdtree:leaf_size=0", "leaf_size"),
        ("kdtree:leafsize=3", "unknown field"),
    ] {
        let spec: IndexSpec = spec.parse().unwrap();
        let err = build_index(&spec, &g, TriangleKernelKind::Watertight)
            .err()
            .unwrap_or_else(|| panic!("{spec} must fail"));
        assert!(matches!(err, BuildError::Params { .. }), "{spec}: {err}");
        assert!(err.to_string().contains(says), "{spec}: {err}");
    }
}
