//! `accelbench report DIR --markdown`: a report folder's dated results page for `docs/results/`
//! (machine, command, commit, verdict and tables), printed or written to `--out`.

use crate::report::merge::load_shard;
use crate::report::results_page::results_page;
use anyhow::Context;
use std::path::PathBuf;

#[derive(Debug, clap::Args)]
pub struct ReportArgs {
    /// A report folder written by `accelbench run` or `accelbench merge`.
    dir: PathBuf,
    /// Write the page in Markdown (the only format today; required so that a later format is
    /// an addition, not a change of meaning).
    #[arg(long, required = true)]
    markdown: bool,
    /// The page's title after its date [default: the run's scenes].
    #[arg(long)]
    title: Option<String>,
    /// Write the page to this file (for example `docs/results/2026-12-02-bunny.md`) instead of
    /// standard output.
    #[arg(long)]
    out: Option<PathBuf>,
}

pub fn run(a: ReportArgs) -> anyhow::Result<()> {
    let report = load_shard(&a.dir)
        .with_context(|| format!("reading the report folder {}", a.dir.display()))?;
    let page = results_page(
        &report.meta,
        &report.rows,
        &report.notes,
        a.title.as_deref(),
    );
    match &a.out {
        Some(path) => std::fs::write(path, page)
            .with_context(|| format!("writing the results page {}", path.display()))?,
        None => print!("{page}"),
    }
    Ok(())
}
