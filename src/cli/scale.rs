//! `accelbench scale`: every index on one generator at growing sizes (1k to 4M primitives by
//! default), with build time, memory and rays/s plotted against size on log axes.

use super::kernel_arg::parse_kernel;
use super::run::progress_bar;
use super::suite_args::{parse_index_specs, split_list};
use super::threads::parse_threads;
use crate::geometry::TriangleKernelKind;
use crate::harness::suite::{Shard, SuiteConfig, check_specs, run_suite};
use crate::harness::workload::{RaySet, SetSizes};
use crate::index::{IndexSpec, index_names};
use crate::report::scale_report::write_scale_report;
use crate::report::suite_report::run_id_now;
use crate::scene::generators::GeneratorSpec;
use std::path::PathBuf;

#[derive(Debug, clap::Args)]
pub struct ScaleArgs {
    /// Generator name (icosphere, spheres, soup, terrain, stadium, slivers, room, flat, mixed,
    /// shapes).
    #[arg(long)]
    generator: String,
    /// Primitive counts, comma-separated.
    #[arg(
        long,
        value_delimiter = ',',
        default_value = "1000,10000,100000,1000000,4000000"
    )]
    sizes: Vec<i64>,
    /// Seed of the random generators.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Indices, comma-separated, with optional parameters [default: all but brute].
    #[arg(long)]
    indices: Option<String>,
    /// Thread count [default: all cores].
    #[arg(long, value_parser = parse_threads)]
    threads: Option<usize>,
    /// Width and height of the primary image.
    #[arg(long, default_value_t = 256, value_parser = clap::value_parser!(u32).range(1..=4096))]
    primary_size: u32,
    /// Number of incoherent rays.
    #[arg(long, default_value_t = 65_536, value_parser = clap::value_parser!(u64).range(1..=(1u64 << 24)))]
    incoherent: u64,
    /// Triangle kernel every index uses.
    #[arg(long, default_value = "exact", value_parser = parse_kernel)]
    kernel: TriangleKernelKind,
    /// Report directory [default: reports/scale-<generator>-<run id>].
    #[arg(long)]
    out: Option<PathBuf>,
    /// No progress bars.
    #[arg(long)]
    quiet: bool,
}

pub fn run(a: ScaleArgs) -> anyhow::Result<()> {
    let specs: Vec<IndexSpec> = match &a.indices {
        Some(s) => parse_index_specs(&split_list(s))?,
        None => index_names()
            .into_iter()
            .filter(|n| *n != "brute")
            .map(IndexSpec::named)
            .collect(),
    };
    anyhow::ensure!(
        !a.sizes.is_empty(),
        "--sizes is empty: give at least one size"
    );
    check_specs(&specs, a.kernel)?;
    // Validate every size before generating anything.
    let gens: Vec<GeneratorSpec> = a
        .sizes
        .iter()
        .map(|&n| GeneratorSpec::new(&a.generator, n, a.seed))
        .collect::<Result<_, _>>()?;
    let cfg = SuiteConfig {
        indices: specs,
        sets: vec![RaySet::Primary, RaySet::Incoherent],
        threads: vec![a.threads.unwrap_or_else(rayon::current_num_threads)],
        sizes: SetSizes {
            primary_side: a.primary_size,
            incoherent: a.incoherent as usize,
            ao_fraction: 0.05,
        },
        repeats: 3,
        kernel: a.kernel,
        verify_budget: 500_000_000,
        brute_timing_budget: 2_000_000_000,
        timed: true,
        shard: Shard::WHOLE,
        modes: vec![crate::index::TraceMode::Single],
    };
    let pb = progress_bar(a.quiet);
    let mut rows = Vec::new();
    let mut mismatches = 0;
    for g in &gens {
        pb.set_message(format!("generating {g}"));
        let scene = g.generate()?;
        let res = run_suite(std::slice::from_ref(&scene), &cfg, &pb)?;
        for n in &res.notes {
            eprintln!("{} / {}: {}", n.scene, n.what, n.reason);
        }
        for m in &res.mismatches {
            eprintln!(
                "MISMATCH {} / {} vs {}: {}",
                m.scene, m.index, m.against, m.mismatch
            );
        }
        mismatches += res.mismatch_total;
        rows.extend(res.rows);
    }
    let dir = a.out.unwrap_or_else(|| {
        PathBuf::from("reports").join(format!("scale-{}-{}", a.generator, run_id_now()))
    });
    let files = write_scale_report(&dir, &a.generator, &rows)?;
    println!(
        "{:>10} {:<16} {:>10} {:>12} {:>10} {:>10}",
        "prims", "index", "build ms", "bytes", "prim Mr/s", "inc Mr/s"
    );
    for r in rows.iter().filter(|r| r.ray_set == "primary") {
        let inc = rows
            .iter()
            .find(|x| x.ray_set == "incoherent" && x.index == r.index && x.scene == r.scene)
            .map_or(f64::NAN, |x| x.mrays_per_s);
        println!(
            "{:>10} {:<16} {:>10.2} {:>12} {:>10.3} {:>10.3}",
            r.primitives, r.index, r.build_ms, r.memory_bytes, r.mrays_per_s, inc
        );
    }
    eprintln!("report: {} ({} plots)", dir.display(), files.len());
    anyhow::ensure!(
        mismatches == 0,
        "verification failed: {mismatches} mismatching results (above)"
    );
    Ok(())
}
