//! The SAH kd-tree returns brute force's hits bit for bit: on the agreement scenes, on rays
//! lying in its split planes and through their crossings, and on degenerate input; it tests
//! each primitive at most once per ray; bad parameters are typed errors.
use crate::common;
use crate::partition_kit;

use accelbench::index::kdtree::KdNode;
use accelbench::index::{Index, KdTree};
use accelbench::scene::{Scene, generators};
use partition_kit::*;

fn kdtree_on(scene: &Scene, params: &str) -> KdTree {
    build_on::<KdTree>("kdtree", scene, params)
}

#[test]
fn agrees_with_other_parameters() {
    assert_agrees_with_parameters(&[
        "kdtree:leaf_size=8",
        "kdtree:max_depth=3",
        "kdtree:intersect_cost=2.0,empty_bonus=0.0",
        "kdtree:mailbox=false",
        "kdtree:mailbox=false,max_depth=6",
        "kdtree:bins=0",
        "kdtree:bins=2,binned_above=8",
    ]);
}

#[test]
fn rays_in_split_planes_and_through_their_crossings() {
    for name in ["icosphere", "soup", "stadium", "room", "flat"] {
        let scene = generators::generate(name, 2000, 5).unwrap();
        let tree = kdtree_on(&scene, "");
        let planes = tree.split_planes();
        assert!(!planes.is_empty(), "{name}: the tree splits");
        let b = scene.bounds();
        let mut rays = rays_in_axis_planes(&spaced(&planes, 60), &b, 8);
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

/// Mailboxing, the structure figures and typed parameter errors (`partition_kit`).
#[test]
fn partition_basics_hold() {
    let bad_bins = [("bins=1", "bins"), ("bins=1025", "bins")];
    assert_partition_basics::<KdNode>("kdtree", 8, &bad_bins);
}
