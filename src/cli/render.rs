//! `accelbench render`: a Phong-shaded picture of a scene through one index, or with
//! `--heatmap tests|nodes` the per-pixel cost of its camera rays on a fixed colour scale.

use super::kernel_arg::parse_kernel;
use super::threads::{parse_threads, with_threads};
use crate::camera::ModelKind;
use crate::geometry::TriangleKernelKind;
use crate::index::{IndexSpec, TraceMode, build_index};
use crate::render::{
    Filter, HeatmapKind, RenderOptions, Sampling, render_heatmap, render_shaded_with,
};
use crate::scene::load_scene;
use anyhow::Context;
use std::path::PathBuf;
use std::time::Instant;

#[derive(Debug, clap::Args)]
pub struct RenderArgs {
    /// A mesh (.obj, .ply, .gltf, .glb) or .toml path, or a built-in scene name (`stadium`, `soup:n=100000,seed=3`).
    #[arg(long)]
    scene: String,
    /// Index name with optional parameters, e.g. `brute` or `bvh:leaf_size=4`.
    #[arg(long, default_value = "brute")]
    index: IndexSpec,
    /// Output PNG file.
    #[arg(long)]
    out: PathBuf,
    /// Image width in pixels.
    #[arg(long, default_value_t = 512)]
    width: u32,
    /// Image height in pixels (a heat map adds its legend band underneath).
    #[arg(long, default_value_t = 512)]
    height: u32,
    /// Instead of shading, colour each pixel by its ray's primitive tests or node visits.
    #[arg(long)]
    heatmap: Option<HeatmapKind>,
    /// Worker threads (default: all cores).
    #[arg(long, value_parser = parse_threads)]
    threads: Option<usize>,
    /// Samples per pixel of a shaded render (stratified film, lens and time samples).
    #[arg(long, default_value_t = 1)]
    spp: u32,
    /// Reconstruction filter of the samples of a pixel.
    #[arg(long, value_enum, default_value_t = Filter::Box)]
    filter: Filter,
    /// Camera model of a shaded render: pinhole, dof (thin lens), motion (moving eye), lens
    /// (barrel distortion); defaults relative to the scene as for the ray sets.
    #[arg(long, value_enum, default_value_t = ModelKind::Pinhole)]
    camera: ModelKind,
    /// Triangle kernel every index uses.
    #[arg(long, default_value = "exact", value_parser = parse_kernel)]
    kernel: TriangleKernelKind,
    /// Trace mode of each row's camera rays: single, stream, last-hit, packets4, packets8,
    /// packets16, beams4, beams8, beams16, reorder (the image is the same in every mode; the
    /// time is not).
    #[arg(long, default_value = "single", value_parser = TraceMode::parse)]
    mode: TraceMode,
}

pub fn run(a: RenderArgs) -> anyhow::Result<()> {
    let opts = RenderOptions::new(a.width, a.height);
    opts.validate()?;
    let sampling = Sampling {
        spp: a.spp,
        filter: a.filter,
        camera: a.camera,
        mode: a.mode,
        ..Sampling::default()
    };
    anyhow::ensure!(
        a.heatmap.is_none() || (a.spp == 1 && a.camera == ModelKind::Pinhole),
        "--spp and --camera apply to shaded renders; a heat map counts one pinhole ray per pixel"
    );
    anyhow::ensure!(
        crate::index::kind_of(&a.index.name) != Some(crate::index::Kind::Gpu),
        "render traces its shadow rays one at a time, and {} traces batches on the GPU (one \
         dispatch per shadow ray): render with a CPU index such as bvh8",
        a.index.name
    );
    let scene = load_scene(&a.scene).with_context(|| format!("loading scene '{}'", a.scene))?;
    let threads = a.threads.unwrap_or_else(rayon::current_num_threads);
    let geom = scene.geometry();
    let index = with_threads(threads, || build_index(&a.index, &geom, a.kernel))??;
    let start = Instant::now();
    let img = with_threads(threads, || match a.heatmap {
        Some(kind) => render_heatmap(&scene, index.as_ref(), &opts, kind),
        None => render_shaded_with(&scene, index.as_ref(), &opts, &sampling),
    })??;
    let secs = start.elapsed().as_secs_f64();
    img.write_png(&a.out)?;
    let what = a
        .heatmap
        .map_or("shaded".to_owned(), |k| format!("{k} heat map"));
    println!(
        "{}: {what} of {} ({} primitives) through {}, {}x{} in {:.3} s",
        a.out.display(),
        scene.name,
        scene.len(),
        index.name(),
        img.width(),
        img.height(),
        secs
    );
    Ok(())
}
