//! `accelbench stress`: every stress case on every registered index against brute force, the
//! bad-ray boundary checks and the self-intersection study; writes `stress.csv`,
//! `self_intersection.csv` and `stress.md`, and exits non-zero on any failure of our indices
//! (of peers too with `--strict-peers`).

use super::threads::{parse_threads, with_threads};
use crate::index::peer_names;
use crate::stress::{self, StressConfig};
use std::path::PathBuf;

#[derive(Debug, clap::Args)]
pub struct StressArgs {
    /// Output folder.
    #[arg(long, default_value = "reports/stress")]
    out: PathBuf,
    /// A small run (smaller scenes, fewer rays).
    #[arg(long)]
    quick: bool,
    /// Report this index's failures without failing the run (repeatable).
    #[arg(long, value_name = "INDEX")]
    tolerate: Vec<String>,
    /// Fail the run on the peers' failures too (obvhs-bvh2, obvhs-cwbvh). By default, as in
    /// `run`, peers use their own triangle tests: their failures are reported, not failing.
    #[arg(long)]
    strict_peers: bool,
    /// The former opt-in to tolerating peers, now the default (accepted, does nothing).
    #[arg(long, hide = true, conflicts_with = "strict_peers")]
    tolerate_peers: bool,
    /// Worker threads (default: all cores).
    #[arg(long, value_parser = parse_threads)]
    threads: Option<usize>,
}

pub fn run(a: StressArgs) -> anyhow::Result<()> {
    let config = if a.quick {
        StressConfig::quick()
    } else {
        StressConfig::full()
    };
    let threads = a.threads.unwrap_or_else(rayon::current_num_threads);
    let summary = with_threads(threads, || stress::run(&config))??;
    stress::report::write_all(&a.out, &summary)?;
    println!("{}", stress::report::markdown(&summary));
    eprintln!("wrote {}", a.out.display());
    let mut tolerated: Vec<&str> = a.tolerate.iter().map(String::as_str).collect();
    if !a.strict_peers {
        tolerated.extend(peer_names());
    }
    let failures = summary.failures(&tolerated);
    if failures.is_empty() {
        return Ok(());
    }
    for f in &failures {
        eprintln!("FAILED {} on {}: {}", f.index, f.case, f.first_failure);
    }
    anyhow::bail!(
        "{} stress case(s) failed (see above; replay a ray with `accelbench trace`)",
        failures.len()
    )
}
