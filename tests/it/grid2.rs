//! The two-level grid against brute force: the grid's and octree's agreement scenes at several
//! densities, rays along and from the cell planes of both levels, flat and one-primitive scenes,
//! a closed mesh far from the origin, at most one test per primitive per ray, and bad
//! parameters.

use crate::common;

use accelbench::geometry::{Ray, TriangleKernelKind};
use accelbench::index::{Grid2, IndexSpec, build_index_on, parse_params};
use accelbench::scene::{Triangles, generators};
use common::{agreement_rays, assert_agrees};
use glam::Vec3;

type Tris = Triangles<accelbench::geometry::triangle::Watertight>;

const SPECS: [&str; 4] = [
    "grid2",
    "grid2:top_lambda=0.005,lambda=8",
    "grid2:top_lambda=1,lambda=0.3",
    "grid2:top_lambda=0.2,lambda=0.05",
];

#[test]
fn agrees_at_coarse_fine_and_lopsided_densities() {
    for spec in SPECS {
        for name in [
            "icosphere",
            "soup",
            "stadium",
            "flat",
            "mixed",
            "slivers",
            "room",
            "spheres",
        ] {
            let scene = generators::generate(name, 2000, 3).unwrap();
            assert_agrees(spec, &scene, &agreement_rays(&scene, 300));
        }
    }
}

#[test]
fn rays_along_and_from_the_cell_planes_of_both_levels() {
    for name in ["soup", "stadium", "icosphere"] {
        let scene = generators::generate(name, 2000, 5).unwrap();
        for spec in ["grid2", "grid2:top_lambda=0.01,lambda=4"] {
            let p: IndexSpec = spec.parse().unwrap();
            let params = parse_params::<Grid2>(&p).unwrap();
            let grid = build_index_on::<Grid2, Tris>(
                spec,
                Tris::new(scene.triangles.clone().into()),
                params,
            )
            .unwrap();
            // The top grid and the subdivided inner grids (small top cells keep one inner cell).
            let layouts: Vec<_> = grid.index.layouts().filter(|l| l.res != [1; 3]).collect();
            assert!(
                layouts.len() > 1,
                "{spec} on {name}: no subdivided inner grids"
            );
            let mut rays = Vec::new();
            // The top grid, and a spread of inner grids.
            for l in layouts.iter().step_by((layouts.len() / 6).max(1)) {
                rays.extend(common::grid_rays::boundary_rays(l));
            }
            assert!(rays.len() > 300);
            assert_agrees(spec, &scene, &rays);
        }
    }
}

#[test]
fn flat_and_one_primitive_scenes() {
    let flat = generators::generate("flat", 1000, 1).unwrap();
    let c = Vec3::from(flat.bounds().center());
    let mut rays = agreement_rays(&flat, 1000);
    // Rays in the plane of the flat scene (y = 0), along x and z.
    rays.extend([Vec3::X, Vec3::Z].map(|d| Ray::infinite(c - d * 10.0, d).unwrap()));
    assert_agrees("grid2", &flat, &rays);
    common::assert_one_primitive_agrees("grid2");
}

/// Issue 17: a closed sphere of radius 1000 about 1.2e7 from the origin; every ray from inside
/// hits, with brute force's hits.
#[test]
fn far_from_the_origin_rays_from_inside_all_hit() {
    let scene = common::far::far_icosphere();
    let rays = common::far::rays_from_inside(2000);
    for spec in ["grid2", "grid2:top_lambda=0.5,lambda=4"] {
        common::far::assert_all_hit_from_inside(spec, &rays);
        assert_agrees(spec, &scene, &rays);
    }
}

/// Big triangles stored in many cells of both levels: the mailbox keeps every primitive to one
/// test per ray, and the walk does cross many cells.
#[test]
fn each_primitive_is_tested_at_most_once_per_ray() {
    let scene = generators::generate("slivers", 400, 2).unwrap();
    let index = common::build(
        "grid2:top_lambda=0.1,lambda=8",
        &scene,
        TriangleKernelKind::Watertight,
    );
    let refs = index.info().prim_refs;
    assert!(refs > 10 * scene.len(), "only {refs} references");
    let rays = agreement_rays(&scene, 400);
    let mut hits = vec![None; rays.len()];
    let mut c = vec![accelbench::index::Counters::default(); rays.len()];
    index.closest_hits_counted(&rays, &mut hits, &mut c);
    assert!(c.iter().all(|c| c.prim_tests <= scene.len() as u64));
    let most = c.iter().map(|c| c.node_visits).max().unwrap();
    assert!(most > 30, "rays visit at most {most} cells");
}

#[test]
fn bad_parameters_are_typed_errors() {
    common::assert_params_rejected(&[
        ("grid2:lambda=0", "lambda"),
        ("grid2:top_lambda=-1", "top_lambda"),
        ("grid2:lambda=nan", "lambda"),
        ("grid2:top_lambda=inf", "top_lambda"),
        ("grid2:res=[4,4,4]", "res"),
    ]);
    let build = common::soup_builder();
    common::assert_refuses_empty_scenes("grid2");
    assert!(build("grid2:top_lambda=0.001,lambda=20").is_ok());
}

/// `accelbench sweep grid2` writes one CSV row per (top_lambda, lambda) point and both charts; a
/// bad density exits non-zero and names the option.
#[test]
fn cli_sweep_grid2_writes_csv_and_charts() {
    let points = ["--top-lambda", "0.05,0.5", "--lambda", "1,4"];
    let row = ["top_lambda=0.5", "lambda=4"];
    common::cli::small_sweep("grid2", "soup:n=1000", &points, 4, &row);
    common::cli::accelbench_fails(
        &["sweep", "grid2", "--scene", "soup", "--lambda=0"],
        &["lambda"],
    );
}
