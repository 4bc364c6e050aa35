//! The grid against brute force: every agreement scene, rays along and starting on cell
//! boundaries, flat and one-primitive scenes, at most one test per primitive per ray, bad
//! parameters, and a small `sweep grid` run.

use crate::common;

use crate::common::temp::temp_path;
use accelbench::geometry::{Ray, Triangle};
use accelbench::index::{Counters, Grid, GridParams, Index, IndexSpec, build_index_on};
use accelbench::scene::{Geometry, Scene, Triangles, generators};
use common::cli::accelbench;
use common::{agreement_rays, assert_agrees};
use glam::{Vec3, Vec3A};
use std::collections::HashSet;

type Tris = Triangles<accelbench::geometry::triangle::Watertight>;

#[test]
fn agrees_at_coarse_fine_and_lopsided_resolutions() {
    for spec in [
        "grid:res=[1,1,1]",
        "grid:res=[37,3,50]",
        "grid:lambda=0.25",
        "grid:lambda=40",
    ] {
        for name in ["soup", "stadium", "mixed", "slivers"] {
            let scene = generators::generate(name, 2000, 3).unwrap();
            assert_agrees(spec, &scene, &agreement_rays(&scene, 300));
        }
    }
}

#[test]
fn rays_along_and_from_cell_boundaries() {
    for name in ["room", "soup", "stadium", "flat", "icosphere", "terrain"] {
        let scene = generators::generate(name, 2000, 5).unwrap();
        for spec in ["grid", "grid:res=[8,5,12]"] {
            let p: IndexSpec = spec.parse().unwrap();
            let params = accelbench::index::parse_params::<Grid>(&p).unwrap();
            let grid = build_index_on::<Grid, Tris>(
                spec,
                Tris::new(scene.triangles.clone().into()),
                params,
            )
            .unwrap();
            let rays = common::grid_rays::boundary_rays(grid.index.layout());
            assert!(rays.len() > 100);
            assert_agrees(spec, &scene, &rays);
        }
    }
}

#[test]
fn flat_and_one_primitive_scenes() {
    let flat = generators::generate("flat", 1000, 1).unwrap();
    assert_eq!(flat.bounds().extent().min_element(), 0.0);
    let g = Tris::new(flat.triangles.clone().into());
    let grid = Grid::build(&g, &GridParams::default()).unwrap();
    assert!(grid.layout().res.contains(&1));
    assert_agrees("grid", &flat, &agreement_rays(&flat, 1000));
    // A ray in the plane of the flat scene, along each axis.
    let c = Vec3::from(flat.bounds().center());
    let flat_axis = flat
        .bounds()
        .extent()
        .to_array()
        .iter()
        .position(|&e| e == 0.0)
        .unwrap();
    let mut in_plane = Vec::new();
    for a in 0..3 {
        if a != flat_axis {
            let mut d = Vec3::ZERO;
            d[a] = 1.0;
            in_plane.push(Ray::infinite(c - d * 10.0, d).unwrap());
        }
    }
    assert_agrees("grid", &flat, &in_plane);

    common::assert_one_primitive_agrees("grid");
    let point = Scene::from_triangles(
        "point",
        vec![Triangle::new(Vec3A::ONE, Vec3A::ONE, Vec3A::ONE)],
    );
    assert_agrees(
        "grid",
        &point,
        &[Ray::infinite(Vec3::ZERO, Vec3::ONE).unwrap()],
    );
}

/// Exact check of "each primitive at most once per ray": on a ray that misses two big
/// triangles parallel to it, every cell it crosses holds one of them, so the grid visits every
/// cell on its path and tests exactly that one triangle once.
#[test]
fn each_primitive_tested_once_on_a_long_walk() {
    let big = |z: f32| {
        [
            Triangle::new(
                Vec3A::new(0.0, 0.0, z),
                Vec3A::new(8.0, 0.0, z),
                Vec3A::new(8.0, 8.0, z),
            ),
            Triangle::new(
                Vec3A::new(0.0, 0.0, z),
                Vec3A::new(8.0, 8.0, z),
                Vec3A::new(0.0, 8.0, z),
            ),
        ]
    };
    let tris: Vec<Triangle> = [big(0.0), big(2.0), big(8.0)].concat();
    let g = Tris::new(tris.into());
    let grid = Grid::build(
        &g,
        &GridParams {
            res: Some([16, 16, 16]),
            lambda: None,
        },
    )
    .unwrap();
    // z = 1.5 lies in the cells z in [1.0, 1.5] and [1.5, 2.0]; the ray sits on that boundary
    // and runs along x, in the cells holding the two triangles at z = 2.
    let r = Ray::infinite(Vec3::new(-1.0, 3.3, 1.5), Vec3::X).unwrap();
    let mut c = Counters::default();
    assert_eq!(grid.closest_hit(&g, &r, &mut c), None);
    assert_eq!(c.node_visits, 16, "one visit per cell along x");
    assert_eq!(
        c.box_tests,
        1 + 2,
        "the grid box, then two triangles stored in all 16 cells, each tested once"
    );
    // The ray misses both triangles' bounds (z = 2), so the kernel never runs.
    assert_eq!(c.prim_tests, 0);
}

/// On the bunny (or a soup), the primitives a ray tests (its bounds first, one box test each, the
/// kernel only when the ray meets them) are the distinct primitives of the cells it visited (the
/// walk up to the cell where it stopped): never more (mailbox), never fewer (no cell's primitive
/// skipped).
#[test]
fn prim_tests_equal_distinct_primitives_of_visited_cells() {
    let scene = common::bunny().unwrap_or_else(|| generators::generate("soup", 20_000, 2).unwrap());
    let g = Tris::new(scene.triangles.clone().into());
    let grid = Grid::build(&g, &GridParams::default()).unwrap();
    let rays = agreement_rays(&scene, 2000);
    let mut long_walks = 0;
    let (mut kernel_calls, mut bounds_tests) = (0, 0);
    for r in &rays {
        let mut c = Counters::default();
        let hit = grid.closest_hit(&g, r, &mut c);
        let mut seen = HashSet::new();
        let mut visits = 0;
        if let Some(walk) = grid.walk(r) {
            for (cell, t_exit) in walk {
                visits += 1;
                seen.extend(grid.cell_prims(cell).iter().copied());
                if hit.is_some_and(|h| h.t <= t_exit) {
                    break;
                }
            }
        }
        assert_eq!(c.box_tests, 1 + seen.len() as u64, "ray {r:?}");
        assert!(c.prim_tests <= seen.len() as u64, "ray {r:?}");
        kernel_calls += c.prim_tests;
        bounds_tests += c.box_tests - 1;
        assert_eq!(c.node_visits, visits);
        assert!(c.prim_tests <= g.len() as u64);
        if visits > 10 {
            long_walks += 1;
        }
    }
    assert!(
        long_walks > 100,
        "the rays should cross many cells ({long_walks})"
    );
    // Most primitives of a cell lie off the ray: their bounds spare the kernel.
    assert!(
        2 * kernel_calls < bounds_tests,
        "{kernel_calls} kernel calls, {bounds_tests} bounds tests"
    );
}

#[test]
fn bad_parameters_are_typed_errors() {
    common::assert_params_rejected(&[
        ("grid:res=[0,4,4]", "res"),
        ("grid:res=[100000,100000,100000]", "res"),
        ("grid:res=[4,4]", "res"),
        ("grid:lambda=0", "lambda"),
        ("grid:lambda=-3", "lambda"),
        ("grid:lambda=nan", "lambda"),
        ("grid:lambda=inf", "lambda"),
        ("grid:lambda=2,res=[4,4,4]", "lambda"),
        ("grid:cells=4", "unknown field"),
    ]);
    let build = common::soup_builder();
    assert!(build("grid:res=[4,4,4]").is_ok());
    assert!(build("grid:lambda=0.01").is_ok());
}

#[test]
fn cli_sweep_writes_csv_and_charts_and_trace_takes_grid() {
    let (dir, out) = temp_path("sweep");
    let o = out.to_str().unwrap();
    let run = accelbench(&[
        "sweep",
        "grid",
        "--scene",
        "soup:n=2000",
        "--size",
        "32",
        "--res",
        "2,8",
        "--lambda",
        "0.5,4",
        "--repeats",
        "1",
        "--threads",
        "1",
        "--out",
        o,
    ]);
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert!(run.status.success(), "{stderr}");
    let csv = std::fs::read_to_string(out.join("primary.csv")).unwrap();
    let rows: Vec<&str> = csv.lines().collect();
    assert_eq!(rows.len(), 5, "{csv}");
    assert!(rows[0].contains("rays_per_s") && rows[0].contains("prim_tests_per_ray"));
    assert!(csv.contains("grid:lambda=4") && csv.contains("res = [8, 8, 8]"));
    for svg in ["primary-rays_per_s.svg", "primary-build_ms.svg"] {
        let s = std::fs::read_to_string(out.join(svg)).unwrap();
        assert!(
            s.contains("<svg") && s.contains("heuristic (lambda=4)"),
            "{svg}"
        );
    }
    let stdout = String::from_utf8_lossy(&run.stdout);
    assert!(
        stdout.contains("fastest:") && stdout.contains("default:"),
        "{stdout}"
    );

    // Bad sweep input: a clear message and a non-zero exit, no panic.
    for (args, expect) in [
        (vec!["--res", "0"], "0"),
        (vec!["--lambda=-2"], "lambda"),
        (vec!["--lambda", "1,0"], "lambda"),
        (vec!["--res", "100000"], "65536"),
        (vec!["--rays", "sideways"], "sideways"),
    ] {
        let mut all = vec!["sweep", "grid", "--scene", "soup:n=100", "--out", o];
        all.extend(args.iter().copied());
        let r = accelbench(&all);
        let err = String::from_utf8_lossy(&r.stderr);
        assert!(
            !r.status.success() && err.contains(expect),
            "{all:?}: {err}"
        );
        assert!(!err.contains("panicked"), "{err}");
    }

    // `trace --index grid:...` on a protocol ray file.
    let rays = dir.path().join("p.rays");
    common::cli::write_rays(&rays, "icosphere", "primary", &["--size", "16"]);
    let t = accelbench(&[
        "trace",
        "--scene",
        "icosphere",
        "--index",
        "grid:res=[5,6,7]",
        "--rays",
        rays.to_str().unwrap(),
    ]);
    let stdout = String::from_utf8_lossy(&t.stdout);
    assert!(t.status.success(), "{}", String::from_utf8_lossy(&t.stderr));
    assert!(stdout.contains("res = [5, 6, 7]") && stdout.contains("rays:             256"));
}

/// Rays from 5 to 60 scene diagonals away, aimed at edge midpoints and vertices of a scene
/// centred on the coordinate origin, where the shared overlap pad (relative to a cell's own
/// coordinates) is smallest. Without the grid's build margin (`Layout::margin`) the stadium
/// fails here (ties on shared edges at cell boundaries resolved to the wrong triangle).
#[test]
fn far_rays_into_a_scene_centred_on_the_origin() {
    for name in ["stadium", "soup"] {
        let mut scene = generators::generate(name, 4000, 3).unwrap();
        let c = scene.bounds().center();
        for t in &mut scene.triangles {
            for v in &mut t.v {
                *v -= c;
            }
        }
        let diag = scene.bounds().extent().length();
        let mut rays = Vec::new();
        for t in scene.triangles.iter().step_by(2) {
            for dist in [5.0f32, 30.0, 60.0] {
                let mid = Vec3::from((t.v[0] + t.v[1]) * 0.5);
                let o = Vec3::new(0.3, 0.7, -0.6).normalize() * diag * dist + mid * 0.1;
                rays.push(Ray::infinite(o, mid - o).unwrap());
                rays.push(Ray::infinite(o, Vec3::from(t.v[2]) - o).unwrap());
            }
        }
        assert_agrees("grid:lambda=16", &scene, &rays);
    }
}
