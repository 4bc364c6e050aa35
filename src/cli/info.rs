//! `accelbench info`: what a scene holds, and with `--indices` what building each index on it
//! takes (time, resident memory, the build's peak memory and its estimate).

use crate::geometry::TriangleKernelKind;
use crate::harness::memory::{Budget, parse_bytes};
use crate::index::{BuildError, IndexSpec, build_index, estimated_build_bytes};
use crate::scene::{Scene, load_scene};
use anyhow::Context;

#[derive(Debug, clap::Args)]
pub struct InfoArgs {
    /// A mesh (.obj, .ply, .gltf, .glb) or .toml path, or a built-in scene name (`soup`, `soup:n=100000,seed=3`).
    #[arg(long)]
    scene: String,
    /// Also build these indices (comma-separated specs, `bvh,kdtree:cost_ratio=2`) one after
    /// another and print each one's build time, resident memory and the heap's high-water mark
    /// during its build.
    #[arg(long)]
    indices: Option<String>,
    /// Triangle kernel the indices of `--indices` use.
    #[arg(long, default_value = "exact", value_parser = super::kernel_arg::parse_kernel)]
    kernel: TriangleKernelKind,
    /// The memory the builds of `--indices` may take (`512M`, `4G`; 1024-based): an index
    /// whose estimate would not fit, or that outgrows it while building, is listed as skipped
    /// [default: 80% of the available memory].
    #[arg(long, value_parser = parse_bytes)]
    memory_budget: Option<u64>,
}

pub fn run(a: InfoArgs) -> anyhow::Result<()> {
    let start = std::time::Instant::now();
    let scene = load_scene(&a.scene).with_context(|| format!("loading scene '{}'", a.scene))?;
    let seconds = start.elapsed().as_secs_f64();
    let b = scene.bounds();
    println!("scene:       {}", scene.name);
    println!("{}", load_line(&a.scene, seconds, scene.triangles.len()));
    println!("primitives:  {}", scene.len());
    println!("triangles:   {}", scene.triangles.len());
    println!("spheres:     {}", scene.spheres.len());
    println!("shapes:      {}", scene.shapes.len());
    println!(
        "degenerate:  {} zero-area triangles",
        scene.degenerate_triangles()
    );
    println!("bounds min:  {:?}", b.min.to_array());
    println!("bounds max:  {:?}", b.max.to_array());
    println!("lights:      {}", scene.lights.len());
    for l in &scene.lights {
        println!(
            "  position {:?} intensity {:?}",
            l.position.to_array(),
            l.intensity.to_array()
        );
    }
    match &scene.camera {
        Some(c) => println!(
            "camera:      eye {:?} look_at {:?} up {:?} fov {} deg",
            c.eye.to_array(),
            c.look_at.to_array(),
            c.up.to_array(),
            c.fov_deg
        ),
        None => println!("camera:      none (the protocol camera is used)"),
    }
    if let Some(list) = &a.indices {
        if let Some(b) = Budget::of(a.memory_budget) {
            b.hold_builds();
        }
        builds(&scene, list, a.kernel)?;
    }
    Ok(())
}

/// Builds each index of `list` on `scene` in turn (each dropped before the next) and prints a
/// table of its build time and its memory in bytes: resident after the build, the heap's
/// high-water mark during it (`-` where not measured: a C++ peer's own allocator) and the
/// estimate of that mark the memory budget is checked against (`-` where there is none). An
/// index the budget refuses gets a `skipped:` line instead.
fn builds(scene: &Scene, list: &str, kernel: TriangleKernelKind) -> anyhow::Result<()> {
    let geom = scene.geometry();
    println!(
        "{:<24} {:>10} {:>14} {:>14} {:>14}",
        "index", "build ms", "resident B", "peak build B", "estimate B"
    );
    let bytes = |b: Option<usize>| b.map_or_else(|| "-".to_owned(), |b| b.to_string());
    for name in super::suite_args::split_list(list) {
        let spec: IndexSpec = name.parse().with_context(|| format!("index '{name}'"))?;
        let estimate = estimated_build_bytes(&spec, geom.len())?;
        let index = match build_index(&spec, &geom, kernel) {
            Ok(index) => index,
            Err(e @ BuildError::OverBudget { .. }) => {
                println!("{:<24} skipped: {e}", spec.to_string());
                continue;
            }
            Err(e) => return Err(e).with_context(|| format!("building index '{spec}'")),
        };
        let info = index.info();
        println!(
            "{:<24} {:>10.1} {:>14} {:>14} {:>14}",
            spec.to_string(),
            info.build_time.as_secs_f64() * 1e3,
            info.memory_bytes,
            bytes(info.peak_build_bytes),
            bytes(estimate)
        );
    }
    Ok(())
}

/// The `load:` line: the seconds `load_scene` took and, for a file, its size and the rates
/// (1 MB = 10^6 bytes; a `.gltf` counts its JSON only, not the `.bin` files it names).
fn load_line(arg: &str, seconds: f64, triangles: usize) -> String {
    let mtris = triangles as f64 / 1e6 / seconds.max(1e-9);
    match std::fs::metadata(arg) {
        Ok(m) if m.is_file() => {
            let mb = m.len() as f64 / 1e6;
            format!(
                "load:        {seconds:.3} s ({mb:.1} MB at {:.0} MB/s, {mtris:.1} Mtriangles/s)",
                mb / seconds.max(1e-9)
            )
        }
        _ => format!("load:        {seconds:.3} s (generated, {mtris:.1} Mtriangles/s)"),
    }
}
