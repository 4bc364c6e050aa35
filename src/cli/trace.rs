//! `accelbench trace`: trace a `.rays` file with one index, write the `.hits` file, and report
//! build time, rays/s and tests per ray.

use super::kernel_arg::parse_kernel;
use super::threads::{parse_threads, with_threads};
use crate::geometry::TriangleKernelKind;
use crate::harness::timing::{PassOutput, Query, TimedBatch, counting_pass_in, time_pass};
use crate::harness::verify::compare_closest;
use crate::index::{Counters, IndexSpec, TraceMode, build_index, is_peer};
use crate::rays::{read_rays_limit, write_hits};
use crate::scene::load_scene;
use anyhow::Context;
use std::path::PathBuf;

#[derive(Debug, clap::Args)]
pub struct TraceArgs {
    /// A mesh (.obj, .ply, .gltf, .glb) or .toml path, or a built-in scene name (`soup`, `soup:n=100000,seed=3`).
    #[arg(long)]
    scene: String,
    /// Index name with optional parameters, e.g. `brute` or `bvh:leaf_size=4`.
    #[arg(long, default_value = "brute")]
    index: IndexSpec,
    /// Input .rays file.
    #[arg(long)]
    rays: PathBuf,
    /// Trace only the first N rays of the file (the .hits file then has N records).
    #[arg(long, value_parser = clap::value_parser!(u64).range(1..))]
    limit: Option<u64>,
    /// Output .hits file (optional).
    #[arg(long)]
    hits: Option<PathBuf>,
    /// Worker threads (default: all cores).
    #[arg(long, value_parser = parse_threads)]
    threads: Option<usize>,
    /// Triangle kernel every index uses.
    #[arg(long, default_value = "exact", value_parser = parse_kernel)]
    kernel: TriangleKernelKind,
    /// Trace mode: single (one query at a time), stream (the index's own batch technique),
    /// last-hit, packets4, packets8, packets16, beams4, beams8, beams16 (bvh, bvh4, bvh8; other
    /// indices trace beams ray by ray), reorder (sorted by origin and direction first).
    #[arg(long, default_value = "single", value_parser = TraceMode::parse)]
    mode: TraceMode,
    /// The rays are an image this many rays wide in raster order (the protocol's `primary` set:
    /// 1024): the packet modes then take their packets from screen tiles. Without it, packets
    /// are runs of consecutive rays.
    #[arg(long, value_parser = clap::value_parser!(u64).range(1..))]
    image_width: Option<u64>,
    /// Timed passes; the reported time is their median (each pass traces every ray).
    #[arg(long, default_value_t = 1, value_parser = clap::value_parser!(u32).range(1..))]
    repeats: u32,
}

pub fn run(a: TraceArgs) -> anyhow::Result<()> {
    if let Some(hits) = &a.hits {
        super::out::refuse_overwriting(&a.rays, hits, "--hits")?;
    }
    let scene = load_scene(&a.scene).with_context(|| format!("loading scene '{}'", a.scene))?;
    let rays = read_rays_limit(&a.rays, a.limit)?;
    let threads = a.threads.unwrap_or_else(rayon::current_num_threads);
    let geom = scene.geometry();
    let index = with_threads(threads, || build_index(&a.index, &geom, a.kernel))??;
    if let Some((n, why)) = index.refused(&rays) {
        eprintln!(
            "note: {} refuses {n} of the {} rays and reports them as misses: {why}",
            index.name(),
            rays.len()
        );
    }
    // The pool and the batch (the index's own ray form, where it has one) are made before the
    // clock starts.
    let width = a.image_width.map(|w| w as usize);
    if let Some(w) = width.filter(|&w| w > rays.len()) {
        anyhow::bail!(
            "--image-width {w} is wider than the {} rays of {}: give the image's width in rays \
             (1024 for the protocol's primary set), at most the number of rays",
            rays.len(),
            a.rays.display()
        );
    }
    let batch = TimedBatch::new(index.as_ref(), a.mode, &rays, width);
    let mut out = PassOutput::new(Query::Closest, rays.len());
    let mut times = with_threads(threads, || {
        (0..a.repeats)
            .map(|_| time_pass(index.as_ref(), &batch, &mut out).as_secs_f64())
            .collect::<Vec<_>>()
    })?;
    times.sort_by(f64::total_cmp);
    let secs = times[times.len() / 2];
    let hits = out.hits();
    // Counting pass, separate from the timed one.
    let (per_ray, counted) = with_threads(threads, || {
        counting_pass_in(index.as_ref(), Query::Closest, a.mode, &rays, width)
    })?;
    let total: Counters = per_ray.iter().copied().sum();
    let n = rays.len().max(1) as f64;
    if let Some(path) = &a.hits {
        write_hits(path, &hits)?;
    }
    let info = index.info();
    println!(
        "scene:            {} ({} primitives)",
        scene.name,
        scene.len()
    );
    println!("index:            {} {}", index.name(), index.params());
    println!("kernel:           {}", a.kernel);
    println!("mode:             {}", a.mode.label());
    println!("threads:          {threads}");
    println!(
        "build:            {:.3} ms",
        info.build_time.as_secs_f64() * 1e3
    );
    println!("memory:           {} bytes", info.memory_bytes);
    println!("rays:             {}", rays.len());
    println!("hits:             {}", hits.iter().flatten().count());
    println!(
        "trace:            {:.3} ms (median of {})",
        secs * 1e3,
        a.repeats
    );
    println!("rays/s:           {:.0}", rays.len() as f64 / secs);
    println!("Mrays/s:          {:.3}", rays.len() as f64 / secs / 1e6);
    println!(
        "Mtests/s:         {:.3}",
        total.prim_tests as f64 / secs / 1e6
    );
    println!("tests/ray:        {:.2}", total.prim_tests as f64 / n);
    println!("node visits/ray:  {:.2}", total.node_visits as f64 / n);
    println!("box tests/ray:    {:.2}", total.box_tests as f64 / n);
    anyhow::ensure!(
        compare_closest(&rays, &hits, &counted).is_empty(),
        "the counting pass returned different hits from the timed pass ({})",
        match is_peer(index.name()) {
            true => "the peer is not deterministic",
            false => "an index bug",
        }
    );
    Ok(())
}
