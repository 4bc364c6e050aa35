//! `accelbench compare RUN_A RUN_B [--fail-above PCT]`: run B against run A row by row (B's
//! speed over A's, the noise from the repeats' spread), for people and for CI.

use crate::report::run_compare::{compare_runs, comparison_text, load_timed_rows};
use std::path::PathBuf;

#[derive(Debug, clap::Args)]
pub struct CompareArgs {
    /// The baseline: a report folder of `accelbench run` (or its results.csv).
    run_a: PathBuf,
    /// The run compared with it.
    run_b: PathBuf,
    /// Exit non-zero when a row of B is slower than A's by more than PCT percent (and by more
    /// than the noise).
    #[arg(long, value_name = "PCT", value_parser = parse_pct)]
    fail_above: Option<f64>,
}

fn parse_pct(s: &str) -> Result<f64, String> {
    match s.trim_end_matches('%').parse::<f64>() {
        Ok(p) if p.is_finite() && p >= 0.0 => Ok(p),
        _ => Err(format!(
            "'{s}' is not a percentage: give a number >= 0, e.g. 10"
        )),
    }
}

pub fn run(a: CompareArgs) -> anyhow::Result<()> {
    let rows_a = load_timed_rows(&a.run_a)?;
    let rows_b = load_timed_rows(&a.run_b)?;
    let c = compare_runs(&rows_a, &rows_b);
    print!("{}", comparison_text(&c, a.fail_above));
    if let Some(pct) = a.fail_above {
        // A gate that compared nothing has not passed.
        anyhow::ensure!(
            !c.changes.is_empty(),
            "{} and {} share no row (scene x index x ray set x threads), so --fail-above compared \
             nothing: compare runs of the same scenes, indices, ray sets and thread counts",
            a.run_a.display(),
            a.run_b.display()
        );
        let failing: Vec<&str> = (c.changes.iter())
            .filter(|x| x.fails(pct))
            .map(|x| x.key.as_str())
            .collect();
        anyhow::ensure!(
            failing.is_empty(),
            "{} row(s) of {} are more than {pct}% slower than in {} (and outside the noise):\n  {}",
            failing.len(),
            a.run_b.display(),
            a.run_a.display(),
            failing.join("\n  ")
        );
    }
    Ok(())
}
