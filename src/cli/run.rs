//! `accelbench run`: the suite. Every scene x index x ray set x thread count, timed and counted,
//! every hit verified, and a report under `reports/<run id>/`.

use super::parse_threads;
use super::suite_args::SuiteArgs;
use crate::harness::suite::{check_specs, run_suite};
use crate::report::suite_report::{RunMeta, run_id_now, write_suite_report};
use anyhow::Context;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::io::IsTerminal;
use std::path::PathBuf;

#[derive(Debug, clap::Args)]
pub struct RunArgs {
    #[command(flatten)]
    suite: SuiteArgs,
    /// Thread counts, comma-separated [default: 1 and all cores].
    #[arg(long, value_delimiter = ',', value_parser = parse_threads)]
    threads: Vec<usize>,
    /// Timed repeats per measurement (the median is reported) [default: 5, quick 3].
    #[arg(long, value_parser = clap::value_parser!(u64).range(1..=1000))]
    repeats: Option<u64>,
    /// Report directory [default: reports/<run id>].
    #[arg(long)]
    out: Option<PathBuf>,
}

/// A progress bar on stderr, hidden with `--quiet` or when stderr is not a terminal.
pub(crate) fn progress_bar(quiet: bool) -> ProgressBar {
    if quiet || !std::io::stderr().is_terminal() {
        return ProgressBar::hidden();
    }
    let pb = ProgressBar::with_draw_target(Some(0), ProgressDrawTarget::stderr());
    pb.set_style(
        ProgressStyle::with_template("{elapsed_precise} [{bar:30}] {pos}/{len} {wide_msg}")
            .expect("valid template")
            .progress_chars("=> "),
    );
    pb
}

/// The default thread counts: 1 and all cores.
pub(crate) fn default_threads(given: &[usize]) -> Vec<usize> {
    let mut t = if given.is_empty() {
        vec![1, rayon::current_num_threads()]
    } else {
        given.to_vec()
    };
    t.sort_unstable();
    t.dedup();
    t
}

pub fn run(a: RunArgs) -> anyhow::Result<()> {
    let repeats = a
        .repeats
        .map_or(if a.suite.quick { 3 } else { 5 }, |r| r as usize);
    let cfg = a.suite.config(default_threads(&a.threads), repeats, true)?;
    check_specs(&cfg.indices, cfg.kernel)?;
    let scenes = a.suite.load_scenes()?;
    let run_id = format!(
        "{}{}",
        run_id_now(),
        if a.suite.quick { "-quick" } else { "" }
    );
    let dir = a
        .out
        .clone()
        .unwrap_or_else(|| PathBuf::from("reports").join(&run_id));
    let command = std::env::args().collect::<Vec<_>>().join(" ");
    let pb = progress_bar(a.suite.quiet);
    let res = run_suite(&scenes, &cfg, &pb)?;
    let meta = RunMeta::collect(run_id, command, cfg);
    write_suite_report(&dir, &meta, &res, "")
        .with_context(|| format!("writing the report to {}", dir.display()))?;
    let summary = std::fs::read_to_string(dir.join("summary.md")).unwrap_or_default();
    println!("{summary}");
    eprintln!("report: {}", dir.display());
    let failed_builds: Vec<String> = res
        .notes
        .iter()
        .filter(|n| n.reason.starts_with("build failed"))
        .map(|n| format!("{} / {}: {}", n.scene, n.what, n.reason))
        .collect();
    anyhow::ensure!(
        res.mismatch_total == 0,
        "verification failed: {} mismatching results; the rays are in {}",
        res.mismatch_total,
        dir.join("mismatches.txt").display()
    );
    anyhow::ensure!(
        failed_builds.is_empty(),
        "some indices could not be built:\n{}",
        failed_builds.join("\n")
    );
    Ok(())
}
