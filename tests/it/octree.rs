//! The octree's two traversals against brute force: the shared agreement kit, rays exactly
//! through the octree's own cell corners, edges and faces (axis-parallel with ±0.0, diagonal,
//! starting inside and outside), at most one test per primitive per ray, degenerate scenes, and
//! bad parameters.

use crate::common;

use accelbench::geometry::triangle::Watertight;
use accelbench::geometry::{Aabb, Ray, Triangle, TriangleKernelKind};
use accelbench::index::octree::OctreeTree;
use accelbench::index::{
    BuildError, Counters, IndexSpec, NeighborOctree, build_index, build_index_on, parse_params,
};
use accelbench::rays::{incoherent_rays, primary_rays};
use accelbench::scene::{Mixed, Scene, generators};
use glam::{Vec3, Vec3A};

const SPECS: [&str; 2] = ["octree", "octree-topdown"];

#[test]
fn agrees_with_small_leaves_and_deep_trees() {
    for spec in [
        "octree:max_prims=1,max_depth=8",
        "octree-topdown:max_prims=1,max_depth=8",
    ] {
        for name in ["icosphere", "soup", "stadium", "flat", "mixed"] {
            let scene = generators::generate(name, 800, 3).unwrap();
            common::assert_agrees(spec, &scene, &common::agreement_rays(&scene, 200));
        }
    }
}

/// Issue 17: far from the origin the overlap padding (about 100 units at 1e7) exceeds the cells
/// of a depth-10 tree; the build used to exceed its node budget. It must stay bounded, and rays
/// from inside the closed sphere must all hit, with brute force's hits.
#[test]
fn builds_bounded_far_from_the_origin_and_rays_from_inside_all_hit() {
    let scene = common::far::far_icosphere();
    let rays = common::far::rays_from_inside(2000);
    for spec in SPECS {
        common::far::assert_all_hit_from_inside(spec, &rays);
        common::assert_agrees(spec, &scene, &rays);
    }
    let tree = tree_of("octree", &scene);
    assert!(tree.leaves() < 100_000, "{} leaves", tree.leaves());
}

/// The tree `spec` builds on `scene` (both traversals build the same tree from the same params).
fn tree_of(spec: &str, scene: &Scene) -> OctreeTree {
    let spec: IndexSpec = spec.parse().unwrap();
    let params = parse_params::<NeighborOctree>(&spec).unwrap();
    let g = scene.geometry();
    let geom = Mixed::<Watertight>::new(g.triangles.clone(), g.spheres.clone());
    build_index_on::<NeighborOctree, _>("octree", geom, params)
        .unwrap()
        .index
        .tree()
        .clone()
}

/// Unit vector on `axis` with sign `s` and the other components `z` (`0.0` or `-0.0`).
fn axis_dir(axis: usize, s: f32, z: f32) -> Vec3 {
    let mut d = Vec3::splat(z);
    d[axis] = s;
    d
}

/// Rays built from the octree's own cell boundaries: along cell edges (axis-parallel, from
/// outside the root and from the corner itself, with +0.0 and -0.0 in the other components),
/// in face planes, diagonally from corners, and from face centres.
fn cell_rays(tree: &OctreeTree, cells: usize) -> Vec<Ray> {
    let root = tree.root_cell();
    let side = root.extent().max_element();
    let leaves: Vec<Aabb> = tree.leaf_cells().collect();
    let step = (leaves.len() / cells).max(1);
    let mut rays = Vec::new();
    let mut push = |o: Vec3A, d: Vec3| {
        if let Ok(r) = Ray::infinite(Vec3::from(o), d) {
            rays.push(r);
        }
    };
    for cell in leaves.iter().step_by(step) {
        for corner in [
            cell.min,
            cell.max,
            Vec3A::new(cell.min.x, cell.max.y, cell.min.z),
        ] {
            for axis in 0..3 {
                for z in [0.0f32, -0.0] {
                    for s in [1.0f32, -1.0] {
                        // Along the edge line through `corner`, from outside the root.
                        let mut o = corner;
                        o[axis] = if s > 0.0 {
                            root.min[axis] - side
                        } else {
                            root.max[axis] + side
                        };
                        push(o, axis_dir(axis, s, z));
                        // Along the same edge, starting exactly at the corner.
                        push(corner, axis_dir(axis, s, z));
                        // In a face plane through the corner, diagonally.
                        let mut d = Vec3::splat(s);
                        d[axis] = z;
                        push(corner, d);
                    }
                }
            }
            // Diagonals from the corner in all eight octants, and the same lines from outside.
            for oct in 0..8 {
                let d = Vec3::new(
                    if oct & 4 != 0 { -1.0 } else { 1.0 },
                    if oct & 2 != 0 { -1.0 } else { 1.0 },
                    if oct & 1 != 0 { -1.0 } else { 1.0 },
                );
                push(corner, d);
                push(corner - Vec3A::from(d) * (2.0 * side), d);
            }
        }
        // From face centres, into the cell and along the face.
        let c = cell.center();
        for axis in 0..3 {
            let mut o = c;
            o[axis] = cell.min[axis];
            push(o, axis_dir(axis, 1.0, 0.0));
            push(o, axis_dir(axis, -1.0, -0.0));
            push(o, axis_dir((axis + 1) % 3, 1.0, -0.0));
            push(o, Vec3::new(0.3, -0.7, 0.4));
        }
    }
    rays
}

#[test]
fn rays_through_cell_corners_edges_and_faces_agree() {
    for (name, n) in [
        ("icosphere", 1500),
        ("stadium", 1500),
        ("room", 1500),
        ("flat", 1500),
        ("mixed", 1000),
        ("terrain", 1500),
    ] {
        let scene = generators::generate(name, n, 11).unwrap();
        for params in ["", ":max_prims=2,max_depth=7"] {
            let tree = tree_of(&format!("octree{params}"), &scene);
            let rays = cell_rays(&tree, 60);
            assert!(rays.len() > 1000, "{name}: {} rays", rays.len());
            for spec in SPECS {
                common::assert_agrees(&format!("{spec}{params}"), &scene, &rays);
            }
        }
    }
}

/// Tiny triangles on a 6 x 6 x 6 lattice, which make the tree subdivide.
const TINY: usize = 216;

/// A few big triangles crossing the whole box, among [`TINY`] tiny ones that make splits pay:
/// each big one is stored in many leaves.
fn big_triangles() -> Scene {
    let t = |a: [f32; 3], b: [f32; 3], c: [f32; 3]| {
        Triangle::new(Vec3A::from(a), Vec3A::from(b), Vec3A::from(c))
    };
    let mut tris = vec![
        t([-1.0, -1.0, -1.0], [1.0, -1.0, 1.0], [0.0, 1.0, 0.0]),
        t([-1.0, 1.0, -1.0], [1.0, 1.0, 1.0], [0.0, -1.0, 0.3]),
        t([-1.0, 0.0, 1.0], [1.0, 0.2, -1.0], [0.0, 0.1, 1.0]),
        t([1.0, -1.0, -1.0], [-1.0, 1.0, -1.0], [1.0, 1.0, 1.0]),
        t([-1.0, -1.0, 1.0], [1.0, -1.0, -1.0], [-1.0, 1.0, 0.0]),
        t([0.0, -1.0, -1.0], [0.1, 1.0, 1.0], [-0.2, 1.0, -1.0]),
    ];
    for i in 0..TINY {
        let o = [i % 6, i / 6 % 6, i / 36].map(|k| -0.9 + 0.36 * k as f32);
        let o = Vec3A::from(o);
        tris.push(Triangle::new(o, o + Vec3A::X * 0.01, o + Vec3A::Y * 0.01));
    }
    Scene::from_triangles("big", tris)
}

#[test]
fn each_primitive_is_tested_at_most_once_per_ray() {
    let scene = big_triangles();
    let rays = common::agreement_rays(&scene, 300);
    for spec in [
        "octree:max_prims=1,max_depth=6",
        "octree-topdown:max_prims=1,max_depth=6",
    ] {
        let index = common::build(spec, &scene, TriangleKernelKind::Watertight);
        // The big triangles sit in many leaves (the tiny ones in about one each), so without the
        // mailbox rays would retest them.
        let refs = index.info().prim_refs;
        assert!(refs > TINY + 20 * 6, "{spec}: only {refs} references");
        let mut hits = vec![None; rays.len()];
        let mut c = vec![Counters::default(); rays.len()];
        index.closest_hits_counted(&rays, &mut hits, &mut c);
        let mut any = vec![false; rays.len()];
        let mut ca = vec![Counters::default(); rays.len()];
        index.any_hits_counted(&rays, &mut any, &mut ca);
        for counters in c.iter().chain(&ca) {
            assert!(
                counters.prim_tests <= scene.len() as u64,
                "{spec}: {counters:?}"
            );
        }
        // Some rays cross many leaves (the SAH tree cuts the big triangles' cells less finely
        // than midpoint splits did), meeting the big triangles in several of them.
        let most = c.iter().map(|c| c.node_visits).max().unwrap();
        assert!(most > 10, "{spec}: rays visit at most {most} nodes");
    }
}

#[test]
fn degenerate_scenes_build_small_trees_and_agree() {
    let tri = Triangle::new(
        Vec3A::new(0.1, 0.2, 0.3),
        Vec3A::new(1.0, 0.2, 0.3),
        Vec3A::new(0.1, 1.5, 0.3),
    );
    let point = |p: Vec3A| Triangle::new(p, p, p);
    let scenes = [
        Scene::from_triangles("duplicates", vec![tri; 500]),
        Scene::from_triangles("one", vec![tri]),
        Scene::from_triangles("point", vec![point(Vec3A::new(1.0, 2.0, 3.0)); 20]),
        Scene::from_triangles("origin", vec![point(Vec3A::ZERO); 20]),
        Scene::from_triangles(
            "segment",
            (0..50)
                .map(|i| {
                    let x = i as f32 * 0.1;
                    Triangle::new(
                        Vec3A::new(x, 0.0, 0.0),
                        Vec3A::new(x + 0.1, 0.0, 0.0),
                        Vec3A::new(x + 0.05, 0.0, 0.0),
                    )
                })
                .collect(),
        ),
    ];
    for scene in &scenes {
        for spec in [
            "octree:max_prims=1,max_depth=16",
            "octree-topdown:max_prims=1",
        ] {
            let index = common::build(spec, scene, TriangleKernelKind::Watertight);
            // No runaway subdivision on coincident primitives.
            assert!(
                index.info().nodes < 20_000,
                "{spec} on {}: {:?}",
                scene.name,
                index.info()
            );
            // Around the (possibly zero-extent) bounds: protocol rays from a box one unit larger.
            let b = scene.bounds();
            let b = Aabb::new(b.min - Vec3A::ONE, b.max + Vec3A::ONE);
            let mut rays = primary_rays(&b, 16, 16).unwrap();
            rays.extend(incoherent_rays(&b, 300, 5));
            for v in scene.triangles.iter().flat_map(|t| t.v).take(30) {
                for o in [Vec3::new(-3.0, 0.5, 7.0), Vec3::new(2.0, -4.0, -1.0)] {
                    rays.push(Ray::infinite(o, Vec3::from(v) - o).unwrap());
                }
            }
            common::assert_agrees(spec, scene, &rays);
        }
    }
}

#[test]
fn bad_parameters_and_scenes_are_typed_errors() {
    common::assert_params_rejected(&[
        ("octree:max_prims=0", "max_prims"),
        ("octree-topdown:max_depth=17", "max_depth"),
        ("octree:max_depth=-1", "max_depth"),
        ("octree:max_prims=\"many\"", "max_prims"),
        ("octree:leaf_size=4", "unknown field"),
    ]);
    common::assert_refuses_empty_scenes("octree");
    // NaN coordinates are rejected where scenes enter (`Scene::validate`); infinite ones that
    // reach the index give non-finite bounds.
    let inf = Scene::from_triangles(
        "inf",
        vec![Triangle::new(
            Vec3A::new(f32::INFINITY, 0.0, 0.0),
            Vec3A::ONE,
            Vec3A::Y,
        )],
    );
    let e = common::build_error("octree-topdown", &inf);
    assert!(matches!(e, BuildError::Failed { .. }), "{e:?}");
    assert!(e.to_string().contains("not finite"), "{e}");
}

/// Rays clipped around brute force's hit: `t_max` exactly at the hit (kept), one ulp before
/// it, `t_min` exactly at it, and one ulp after it (starting inside the octree, possibly on a
/// cell face).
#[test]
fn ray_intervals_ending_and_starting_at_the_hit_agree() {
    let next_up = |t: f32| f32::from_bits(t.to_bits() + 1);
    let next_down = |t: f32| f32::from_bits(t.to_bits() - 1);
    for name in ["icosphere", "room", "mixed"] {
        let scene = generators::generate(name, 1500, 6).unwrap();
        let brute = build_index(
            &IndexSpec::named("brute"),
            &scene.geometry(),
            TriangleKernelKind::Watertight,
        )
        .unwrap();
        let base = common::agreement_rays(&scene, 300);
        let mut hits = vec![None; base.len()];
        brute.closest_hits(&base, &mut hits);
        let mut rays = Vec::new();
        for (r, h) in base.iter().zip(&hits) {
            let Some(h) = h else { continue };
            if h.t <= 0.0 {
                continue;
            }
            for (lo, hi) in [
                (0.0, h.t),
                (0.0, next_down(h.t)),
                (h.t, f32::INFINITY),
                (next_up(h.t), f32::INFINITY),
                (0.5 * h.t, 2.0 * h.t),
            ] {
                rays.push(r.with_interval(lo, hi).unwrap());
            }
        }
        for spec in SPECS {
            common::assert_agrees(spec, &scene, &rays);
        }
    }
}

/// `accelbench sweep octree` writes one CSV row per (max_depth, max_prims) point and both charts;
/// bad values exit non-zero with a message.
#[test]
fn cli_sweep_octree_writes_csv_and_charts() {
    let mut points = vec!["--max-prims", "2,8", "--max-depth", "5,9"];
    points.extend(["--traversal", "octree-topdown"]);
    let row = ["octree-topdown:max_depth=9,max_prims=2"];
    common::cli::small_sweep("octree", "icosphere:n=800", &points, 4, &row);
    common::cli::accelbench_fails(
        &[
            "sweep",
            "octree",
            "--scene",
            "icosphere",
            "--max-depth",
            "99",
        ],
        &["99"],
    );
}
