//! `accelbench merge DIR... --out DIR`: the report folders of `accelbench run --shard K/N`
//! (every K of one N) combined into one report, as if the run had not been split.

use crate::report::merge::{load_shard, merge_shards};
use crate::report::report_dir::ReportDir;
use crate::report::suite_report::write_report;
use crate::report::verdict::{verdict_text, verdicts};
use anyhow::Context;
use std::path::PathBuf;

#[derive(Debug, clap::Args)]
pub struct MergeArgs {
    /// The shards' report folders (one per K of the same N).
    #[arg(required = true)]
    shards: Vec<PathBuf>,
    /// The merged report's folder.
    #[arg(long)]
    out: PathBuf,
}

pub fn run(a: MergeArgs) -> anyhow::Result<()> {
    let claim = ReportDir::claim(&a.out)?;
    let out = claim.path();
    let shards = (a.shards.iter())
        .map(|d| load_shard(d).with_context(|| format!("reading shard {}", d.display())))
        .collect::<anyhow::Result<Vec<_>>>()?;
    let dirs: Vec<PathBuf> = shards.iter().map(|s| s.dir.clone()).collect();
    let command = std::env::args().collect::<Vec<_>>().join(" ");
    let (meta, rows, notes) = merge_shards(shards, command)?;
    // The pictures each shard rendered, and the mismatches each kept.
    for p in &notes.pictures {
        let to = out.join(&p.path);
        if let Some(from) = dirs.iter().map(|d| d.join(&p.path)).find(|f| f.is_file()) {
            std::fs::create_dir_all(to.parent().expect("a file path has a parent"))?;
            std::fs::copy(&from, &to).with_context(|| format!("copying {}", from.display()))?;
        }
    }
    let mut mismatches = String::new();
    for d in &dirs {
        mismatches.push_str(&std::fs::read_to_string(d.join("mismatches.txt")).unwrap_or_default());
    }
    if !mismatches.is_empty() {
        std::fs::write(out.join("mismatches.txt"), mismatches)?;
    }
    write_report(out, &meta, &rows, &notes)
        .and_then(|()| claim.publish())
        .with_context(|| format!("writing the merged report to {}", a.out.display()))?;
    print!("{}", verdict_text(&verdicts(&rows), 4));
    println!("\nreport: {}", a.out.join("index.html").display());
    Ok(())
}
