//! `accelbench sweep <index>`: race one index at many parameter values on the same scene and
//! rays, and write a CSV and charts (`sweep grid` for the grid resolution). Each index's sweep
//! is a subcommand sharing [`CommonSweepArgs`]; its plan (points, charts, default) is the
//! harness's ([`crate::harness::sweep`]).

use super::threads::{parse_threads, with_threads};
use crate::geometry::{Ray, TriangleKernelKind};
use crate::harness::sweep::{
    SweepPlan, SweepRow, SweepSetup, bvh_plan, grid_plan, grid2_sweep, octree_sweep, run_sweep,
};
use crate::index::bvh::params::SPLIT_BUDGET;
use crate::index::grid::resolution;
use crate::rays::{RaySetKind, ray_set};
use crate::report::sweep_report::write_sweep;
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
    /// A mesh (.obj, .ply, .gltf, .glb) or .toml path, or a built-in scene name (`stadium`, `spheres:n=100000`).
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

fn run_grid(a: GridSweepArgs) -> anyhow::Result<()> {
    let p = prepare(&a.common, "grid")?;
    let plan = grid_plan(&p.scene, a.common.rays.name(), &a.res, &a.lambda)?;
    sweep_and_write(&p, &a.common, &plan)
}

fn run_grid2(a: Grid2SweepArgs) -> anyhow::Result<()> {
    let p = prepare(&a.common, "grid2")?;
    let plan = grid2_sweep(&a.top_lambda, &a.lambda).plan(&p.scene, a.common.rays.name())?;
    sweep_and_write(&p, &a.common, &plan)
}

fn run_octree(a: OctreeSweepArgs) -> anyhow::Result<()> {
    let name = a.traversal.as_str();
    let p = prepare(&a.common, name)?;
    let plan =
        octree_sweep(name, &a.max_prims, &a.max_depth).plan(&p.scene, a.common.rays.name())?;
    sweep_and_write(&p, &a.common, &plan)
}

fn run_bvh(a: BvhSweepArgs) -> anyhow::Result<()> {
    let p = prepare(&a.common, &a.trees.join("-"))?;
    let plan = bvh_plan(&p.scene, a.common.rays.name(), &a.trees, &a.split_budget)?;
    sweep_and_write(&p, &a.common, &plan)
}

/// Times every point of `plan` on the prepared scene and rays (progress on stderr, one line
/// per point), writes the CSV and charts, and prints the fastest point and how the plan's
/// default compares with it.
fn sweep_and_write(p: &Prepared, common: &CommonSweepArgs, plan: &SweepPlan) -> anyhow::Result<()> {
    let SweepPlan {
        index,
        size_label,
        points,
        plot,
        default,
    } = plan;
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
