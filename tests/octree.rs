//! The octree's two traversals against brute force: the shared agreement kit, rays exactly
//! through the octree's own cell corners and edges (axis-parallel and oblique), at most one test
//! per primitive per ray, degenerate scenes, and bad parameters.

mod common;

use accelbench::scene::generators;

const SPECS: [&str; 2] = ["octree", "octree-topdown"];

#[test]
fn agrees_with_brute_force_everywhere() {
    for spec in SPECS {
        common::assert_agrees_everywhere(spec, 400);
    }
}

#[test]
fn agrees_with_small_leaves_and_deep_trees() {
    for spec in [
        "octree:max_prims=1,max_depth=8",
        "octree-topdown:max_prims=1,max_depth=8",
    ] {
        for name in ["icosphere", "soup", "stadium", "flat"] {
            let scene = generators::generate(name, 800, 3).unwrap();
            common::assert_agrees(spec, &scene, &common::agreement_rays(&scene, 200));
        }
    }
}
