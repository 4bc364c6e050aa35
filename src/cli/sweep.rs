//! `accelbench sweep <index>`: race one index at many parameter values on the same scene and
//! rays, and write a CSV and charts (`sweep grid` for the grid resolution). Each index's sweep
//! is a subcommand sharing [`CommonSweepArgs`].

use super::{parse_threads, with_threads};
use crate::geometry::{Aabb, Ray, TriangleKernelKind};
use crate::harness::sweep::{SweepPoint, SweepRow, SweepSetup, run_sweep};
use crate::index::bvh::params::{BvhParams, SPLIT_BUDGET};
use crate::index::grid::{DEFAULT_LAMBDA, MAX_CELLS, heuristic_resolution, resolution};
use crate::index::{Grid2Params, OctreeParams};
use crate::rays::{RaySetKind, ray_set};
use crate::report::sweep_report::{SweepPlot, write_sweep};
use crate::scene::{Scene, load_scene};
use anyhow::Context;
use std::path::PathBuf;

#[derive(Debug, clap::Args)]
pub struct SweepArgs {
    #[command(subcommand)]
    target: SweepTarget,
}

#[derive(Debug, clap::Subcommand)]
enum SweepTarget {
    /// Grid resolution: explicit cells along the longest axis (--res) and cube-root heuristic
    /// densities (--lambda), against cells along the longest axis.
    Grid(GridSweepArgs),
    /// Two-level grid densities: one line per --top-lambda, against the inner --lambda.
    Grid2(Grid2SweepArgs),
    /// Octree leaf size and depth: one line per --max-depth, against --max-prims.
    Octree(OctreeSweepArgs),
    /// BVH spatial-split budgets: one line per tree, against --split-budget (references per
    /// primitive; 1 is the tree without spatial splits).
    Bvh(BvhSweepArgs),
}

/// What every sweep takes: the scene, the rays, where to write, how many threads.
#[derive(Debug, clap::Args)]
pub struct CommonSweepArgs {
    /// An .obj or .toml path, or a built-in scene name (`stadium`, `spheres:n=100000`).
    #[arg(long)]
    scene: String,
    /// Which standard ray set (see ../shared/PROTOCOL.md), at a modest size.
    #[arg(long, value_enum, default_value = "primary")]
    rays: RaySetKind,
    /// Image width and height of the primary set.
    #[arg(long, default_value_t = 256, value_parser = clap::value_parser!(u32).range(1..=4096))]
    size: u32,
    /// Number of rays of the incoherent set.
    #[arg(long, default_value_t = 65536, value_parser = clap::value_parser!(u64).range(1..=(1u64 << 24)))]
    count: u64,
    /// Timed repeats per point (the median counts).
    #[arg(long, default_value_t = 3, value_parser = clap::value_parser!(u64).range(1..=100))]
    repeats: u64,
    /// Output directory (default: reports/sweeps/<scene>-<index>/); files are named after the
    /// ray set (`primary.csv`, `primary-rays_per_s.svg`, `primary-build_ms.svg`).
    #[arg(long)]
    out: Option<PathBuf>,
    /// Worker threads (default: all cores).
    #[arg(long, value_parser = parse_threads)]
    threads: Option<usize>,
}

#[derive(Debug, clap::Args)]
pub struct GridSweepArgs {
    #[command(flatten)]
    common: CommonSweepArgs,
    /// Cells along the scene's longest axis, comma-separated (the other axes in proportion, so
    /// cells stay cubic). Default: 1/8 to 4 times the heuristic's, when --lambda is not given.
    #[arg(long, value_delimiter = ',', value_parser = clap::value_parser!(u32).range(1..=65536))]
    res: Vec<u32>,
    /// Cube-root heuristic densities (cells per primitive), comma-separated. Default:
    /// 1,2,4,8,16, when --res is not given.
    #[arg(long, value_delimiter = ',', value_parser = parse_lambda)]
    lambda: Vec<f32>,
}

#[derive(Debug, clap::Args)]
pub struct Grid2SweepArgs {
    #[command(flatten)]
    common: CommonSweepArgs,
    /// Top-grid densities (cells per primitive of the scene), comma-separated (one line each).
    #[arg(long, value_delimiter = ',', default_value = "0.0078125,0.015625,0.0625",
          value_parser = parse_lambda)]
    top_lambda: Vec<f32>,
    /// Densities of each top cell's own grid (cells per primitive of that cell), comma-separated.
    #[arg(long, value_delimiter = ',', default_value = "0.5,1,2,4,8", value_parser = parse_lambda)]
    lambda: Vec<f32>,
}

#[derive(Debug, clap::Args)]
pub struct OctreeSweepArgs {
    #[command(flatten)]
    common: CommonSweepArgs,
    /// Which traversal of the (same) tree to time.
    #[arg(long, default_value = "octree", value_parser = ["octree", "octree-topdown"])]
    traversal: String,
    /// Leaf sizes (subdivide while a cell holds more), comma-separated.
    #[arg(long, value_delimiter = ',', default_value = "1,2,4,8,16,32,64",
          value_parser = clap::value_parser!(u32).range(1..=1_000_000))]
    max_prims: Vec<u32>,
    /// Maximum depths, comma-separated (one line each).
    #[arg(long, value_delimiter = ',', default_value = "6,8,10,12",
          value_parser = clap::value_parser!(u32).range(0..=16))]
    max_depth: Vec<u32>,
}

#[derive(Debug, clap::Args)]
pub struct BvhSweepArgs {
    #[command(flatten)]
    common: CommonSweepArgs,
    /// Trees, comma-separated (one line each).
    #[arg(long, value_delimiter = ',', default_value = "bvh,bvh8",
          value_parser = ["bvh", "bvh4", "bvh8"])]
    trees: Vec<String>,
    /// Most references per primitive with spatial splits, comma-separated.
    #[arg(long, value_delimiter = ',', default_value = "1,1.5,2,4,8,16",
          value_parser = parse_split_budget)]
    split_budget: Vec<f32>,
}

fn parse_split_budget(s: &str) -> Result<f32, String> {
    let v: f32 = s
        .trim()
        .parse()
        .map_err(|_| format!("'{s}' is not a number"))?;
    match SPLIT_BUDGET.contains(&v) {
        true => Ok(v),
        false => Err(format!("{v} is outside {SPLIT_BUDGET:?}")),
    }
}

fn parse_lambda(s: &str) -> Result<f32, String> {
    let v: f32 = s
        .trim()
        .parse()
        .map_err(|_| format!("'{s}' is not a number"))?;
    resolution::check_lambda(v).map(|()| v)
}

pub fn run(a: SweepArgs) -> anyhow::Result<()> {
    match a.target {
        SweepTarget::Grid(g) => run_grid(g),
        SweepTarget::Grid2(g) => run_grid2(g),
        SweepTarget::Octree(o) => run_octree(o),
        SweepTarget::Bvh(b) => run_bvh(b),
    }
}

/// The scene, its rays, and the output directory of a sweep of `index`.
struct Prepared {
    scene: Scene,
    rays: Vec<Ray>,
    out: PathBuf,
    threads: usize,
}

fn prepare(c: &CommonSweepArgs, index: &str) -> anyhow::Result<Prepared> {
    let scene = load_scene(&c.scene).with_context(|| format!("loading scene '{}'", c.scene))?;
    let b = scene.ray_set_bounds();
    let rays = ray_set(c.rays, &b, c.size, c.count as usize, None)?;
    let safe: String = scene
        .name
        .chars()
        .map(|ch| {
            if ch.is_ascii_alphanumeric() || "-_.".contains(ch) {
                ch
            } else {
                '_'
            }
        })
        .collect();
    let out = c
        .out
        .clone()
        .unwrap_or_else(|| PathBuf::from(format!("reports/sweeps/{safe}-{index}")));
    Ok(Prepared {
        scene,
        rays,
        out,
        threads: c.threads.unwrap_or_else(rayon::current_num_threads),
    })
}

/// Cells per axis for `r` cells along the longest axis of `bounds` (cubic cells, at least one
/// per axis).
fn res_for_longest(bounds: &Aabb, r: u32) -> [u32; 3] {
    let e = bounds.extent();
    let longest = e.max_element();
    if longest <= 0.0 {
        return [1; 3];
    }
    e.to_array()
        .map(|x| ((x / longest * r as f32).round() as u32).clamp(1, r))
}

fn run_grid(a: GridSweepArgs) -> anyhow::Result<()> {
    let p = prepare(&a.common, "grid")?;
    let bounds = p.scene.bounds();
    let n = p.scene.len();
    let longest = bounds.largest_axis();
    let heuristic = heuristic_resolution(bounds.extent(), n, DEFAULT_LAMBDA)[longest];
    let (mut res, mut lambdas) = (a.res.clone(), a.lambda.clone());
    if res.is_empty() && lambdas.is_empty() {
        lambdas = vec![1.0, 2.0, 4.0, 8.0, 16.0];
        res = [0.125, 0.25, 0.5, 1.0, 2.0, 4.0]
            .iter()
            .map(|f| ((heuristic as f64 * f).round() as u32).max(1))
            .filter(|&r| resolution::total_cells(res_for_longest(&bounds, r)) <= MAX_CELLS)
            .collect();
        res.dedup();
    }
    let mut points: Vec<SweepPoint> = Vec::new();
    for &r in &res {
        let [x, y, z] = res_for_longest(&bounds, r);
        points.push(SweepPoint {
            series: "res (cubic cells)".into(),
            x: r as f64,
            spec: format!("grid:res=[{x},{y},{z}]").parse()?,
        });
    }
    for &l in &lambdas {
        points.push(SweepPoint {
            series: "lambda (heuristic)".into(),
            x: heuristic_resolution(bounds.extent(), n, l)[longest] as f64,
            spec: format!("grid:lambda={l}").parse()?,
        });
    }
    let plot = SweepPlot {
        title: format!("grid on {}, {} rays", p.scene.name, a.common.rays.name()),
        x_label: "cells along the longest axis".into(),
        log_x: true,
        marker: Some((
            heuristic as f64,
            format!("heuristic (lambda={DEFAULT_LAMBDA})"),
        )),
    };
    let default = format!("grid:lambda={DEFAULT_LAMBDA}");
    sweep_and_write(&p, &a.common, "grid", "cells", &points, &plot, &default)
}

/// Times every point on the prepared scene and rays (progress on stderr, one line per point;
/// `size_label` names what the structure's size counts, e.g. "cells"), writes the CSV and
/// charts, and prints the fastest point and how the `default` spec compares with it.
fn sweep_and_write(
    p: &Prepared,
    common: &CommonSweepArgs,
    index: &str,
    size_label: &str,
    points: &[SweepPoint],
    plot: &SweepPlot,
    default: &str,
) -> anyhow::Result<()> {
    let geom = p.scene.geometry();
    let setup = SweepSetup {
        geom: &geom,
        kernel: TriangleKernelKind::default(),
        rays: &p.rays,
        repeats: common.repeats as usize,
    };
    eprintln!(
        "sweeping {index} on '{}' ({} primitives), {} {} rays, {} points, {} threads",
        p.scene.name,
        p.scene.len(),
        p.rays.len(),
        common.rays.name(),
        points.len(),
        p.threads
    );
    let rows = with_threads(p.threads, || {
        run_sweep(
            &setup,
            points,
            |r| {
                eprintln!(
                    "  x={:<6} {:<44} {size_label} {:>10}  refs {:>10}  build {:>9.2} ms  {:>8.3} Mrays/s  {:>8.2} tests/ray  {:>7.2} {size_label}/ray",
                    r.x,
                    r.spec,
                    r.cells,
                    r.prim_refs,
                    r.build_ms,
                    r.rays_per_s / 1e6,
                    r.prim_tests_per_ray,
                    r.node_visits_per_ray
                )
            },
            |p, e| eprintln!("  skipped {}: {e}", p.spec),
        )
    })??;
    let files = write_sweep(&p.out, common.rays.name(), &rows, plot)?;
    summarize(&rows, default)?;
    println!("wrote {}", files.csv.display());
    println!("wrote {}", files.rays_chart.display());
    println!("wrote {}", files.build_chart.display());
    Ok(())
}

/// Prints the fastest point and how the default (spec `default`) compares with it.
fn summarize(rows: &[SweepRow], default: &str) -> anyhow::Result<()> {
    let Some(best) = rows
        .iter()
        .max_by(|a, b| a.rays_per_s.total_cmp(&b.rays_per_s))
    else {
        return Ok(());
    };
    println!(
        "fastest:   {} (x = {}): {:.3} Mrays/s, {:.2} tests/ray, build {:.1} ms",
        best.spec,
        best.x,
        best.rays_per_s / 1e6,
        best.prim_tests_per_ray,
        best.build_ms
    );
    if let Some(h) = rows.iter().find(|r| r.spec == default) {
        println!(
            "default:   {} (x = {}): {:.3} Mrays/s ({:.0}% of the fastest), {:.2} tests/ray",
            h.spec,
            h.x,
            h.rays_per_s / 1e6,
            100.0 * h.rays_per_s / best.rays_per_s,
            h.prim_tests_per_ray
        );
    }
    Ok(())
}

fn run_grid2(a: Grid2SweepArgs) -> anyhow::Result<()> {
    let p = prepare(&a.common, "grid2")?;
    let d = Grid2Params::default();
    let mut points: Vec<SweepPoint> = Vec::new();
    for &top in &a.top_lambda {
        for &l in &a.lambda {
            points.push(SweepPoint {
                series: format!("top_lambda={top}"),
                x: l as f64,
                spec: format!("grid2:top_lambda={top},lambda={l}").parse()?,
            });
        }
    }
    let plot = SweepPlot {
        title: format!("grid2 on {}, {} rays", p.scene.name, a.common.rays.name()),
        x_label: "inner cells per primitive (lambda)".into(),
        log_x: true,
        marker: Some((
            d.lambda as f64,
            format!("default (top_lambda={}, lambda={})", d.top_lambda, d.lambda),
        )),
    };
    let default: crate::index::IndexSpec =
        format!("grid2:top_lambda={},lambda={}", d.top_lambda, d.lambda).parse()?;
    sweep_and_write(
        &p,
        &a.common,
        "grid2",
        "cells",
        &points,
        &plot,
        &default.to_string(),
    )
}

fn run_octree(a: OctreeSweepArgs) -> anyhow::Result<()> {
    let name = a.traversal.as_str();
    let p = prepare(&a.common, name)?;
    let d = OctreeParams::default();
    let mut points: Vec<SweepPoint> = Vec::new();
    for &depth in &a.max_depth {
        for &m in &a.max_prims {
            points.push(SweepPoint {
                series: format!("max_depth={depth}"),
                x: m as f64,
                spec: format!("{name}:max_prims={m},max_depth={depth}").parse()?,
            });
        }
    }
    let plot = SweepPlot {
        title: format!("{name} on {}, {} rays", p.scene.name, a.common.rays.name()),
        x_label: "max primitives per leaf".into(),
        log_x: true,
        marker: Some((
            d.max_prims as f64,
            format!(
                "default (max_prims={}, max_depth={})",
                d.max_prims, d.max_depth
            ),
        )),
    };
    let default: crate::index::IndexSpec =
        format!("{name}:max_prims={},max_depth={}", d.max_prims, d.max_depth).parse()?;
    sweep_and_write(
        &p,
        &a.common,
        name,
        "nodes",
        &points,
        &plot,
        &default.to_string(),
    )
}

fn run_bvh(a: BvhSweepArgs) -> anyhow::Result<()> {
    let p = prepare(&a.common, &a.trees.join("-"))?;
    let spec = |tree: &str, b: f32| format!("{tree}:spatial_splits=true,split_budget={b}");
    let mut points: Vec<SweepPoint> = Vec::new();
    for tree in &a.trees {
        for &b in &a.split_budget {
            points.push(SweepPoint {
                series: tree.clone(),
                x: b as f64,
                spec: spec(tree, b).parse()?,
            });
        }
    }
    let default_budget = BvhParams::default().config()?.split_budget;
    let plot = SweepPlot {
        title: format!(
            "spatial splits on {}, {} rays",
            p.scene.name,
            a.common.rays.name()
        ),
        x_label: "references per primitive at most (split_budget)".into(),
        log_x: true,
        marker: Some((
            default_budget.into(),
            format!("default (split_budget={default_budget})"),
        )),
    };
    let default = spec(&a.trees[0], default_budget);
    sweep_and_write(&p, &a.common, "bvh", "nodes", &points, &plot, &default)
}
