//! `accelbench accuracy`: kernel time against error, and watertightness of closed meshes far
//! from the origin; writes `accuracy.csv`, `watertight.csv`, `time_vs_error.svg`,
//! `shapes_time_vs_error.svg`, `leaks_vs_offset.svg` and `accuracy.md`.

use super::threads::{parse_threads, with_threads};
use crate::accuracy::{self, AccuracyConfig, WatertightConfig};
use std::path::PathBuf;

#[derive(Debug, clap::Args)]
pub struct AccuracyArgs {
    /// Output folder.
    #[arg(long, default_value = "reports/accuracy")]
    out: PathBuf,
    /// Rays per ray family and offset in the time-against-error study.
    #[arg(long, value_parser = clap::value_parser!(u64).range(1..=10_000_000))]
    rays: Option<u64>,
    /// Rays per closed mesh and offset in the watertightness study.
    #[arg(long, value_parser = clap::value_parser!(u64).range(1..=100_000_000))]
    leak_rays: Option<u64>,
    /// A small run (fewer rays and offsets, one timing repeat), for a quick look.
    #[arg(long)]
    quick: bool,
    /// Worker threads (default: all cores; timing is single-threaded regardless).
    #[arg(long, value_parser = parse_threads)]
    threads: Option<usize>,
}

pub fn run(a: AccuracyArgs) -> anyhow::Result<()> {
    let (rays, leak_rays) = if a.quick {
        (1_000, 100_000)
    } else {
        (10_000, 1_000_000)
    };
    let rays = a.rays.map_or(rays, |n| n as usize);
    let leak_rays = a.leak_rays.map_or(leak_rays, |n| n as usize);
    let mut study = if a.quick {
        AccuracyConfig::quick(rays)
    } else {
        AccuracyConfig::full(rays)
    };
    study.rays = rays;
    let mut leaks = WatertightConfig::full(leak_rays);
    if a.quick {
        leaks.offsets = study.offsets.clone();
    }
    let threads = a.threads.unwrap_or_else(rayon::current_num_threads);
    eprintln!(
        "accuracy: {rays} rays per family and offset, {} offsets; watertightness: {leak_rays} rays per mesh and offset",
        study.offsets.len()
    );
    let rows = with_threads(threads, || accuracy::run(&study))??;
    let leak_rows = with_threads(threads, || accuracy::watertight::run(&leaks))??;
    accuracy::write_all(&a.out, &rows, &leak_rows)?;
    print!("{}", accuracy::report::markdown(&rows, &leak_rows));
    let leaking: Vec<_> = leak_rows
        .iter()
        .filter(|l| l.kernel == crate::geometry::TriangleKernelKind::Watertight && l.misses > 0)
        // Peers' losses are in the table; they do not fail the run.
        .filter(|l| !crate::index::is_peer(&l.index))
        .collect();
    eprintln!("wrote {}", a.out.display());
    // The watertight kernel must lose no ray from inside a closed mesh, in any of our indices.
    anyhow::ensure!(
        leaking.is_empty(),
        "the watertight kernel leaked: {}",
        leaking
            .iter()
            .map(|l| format!(
                "{} misses of {} on {} at offset {:e} through {}",
                l.misses, l.rays, l.mesh, l.offset, l.index
            ))
            .collect::<Vec<_>>()
            .join("; ")
    );
    Ok(())
}
