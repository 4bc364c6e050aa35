//! The report of `accelbench scale`: how build time, memory and speed grow with the scene size,
//! per index, on log-log axes.

use super::{Chart, ReportError, Series, line_chart, write_csv};
use crate::harness::suite::ResultRow;
use std::path::{Path, PathBuf};

/// One line per index of `value` against the primitive count, over the rows `keep` selects.
fn series(
    rows: &[ResultRow],
    keep: impl Fn(&ResultRow) -> bool,
    value: impl Fn(&ResultRow) -> f64,
) -> Vec<Series> {
    let mut names: Vec<&str> = Vec::new();
    for r in rows.iter().filter(|r| keep(r)) {
        if !names.contains(&r.index.as_str()) {
            names.push(&r.index);
        }
    }
    names
        .into_iter()
        .map(|n| {
            let pts = rows
                .iter()
                .filter(|r| r.index == n && keep(r))
                .map(|r| (r.primitives as f64, value(r)))
                .collect();
            Series::new(n, pts)
        })
        .collect()
}

/// Writes `scale.csv` and the plots (build time, memory, Mrays/s per ray set) into `dir`;
/// returns the plot files.
pub fn write_scale_report(
    dir: &Path,
    generator: &str,
    rows: &[ResultRow],
) -> Result<Vec<PathBuf>, ReportError> {
    write_csv(&dir.join("scale.csv"), rows)?;
    let Some(first) = rows.first() else {
        return Err(ReportError::NoData(format!("scale {generator}")));
    };
    let one = |r: &ResultRow| r.ray_set == first.ray_set && r.index != "brute";
    let mut files = Vec::new();
    let mut plot = |file: &str, title: String, y: &str, s: Vec<Series>| {
        let mut c = Chart::new(title, "primitives (log)", y);
        c.log_x = true;
        c.log_y = true;
        let p = dir.join(file);
        match line_chart(&p, &c, &s) {
            Ok(()) => files.push(p),
            // Nothing to draw (e.g. brute force has no build): no plot.
            Err(ReportError::NoData(_)) => {}
            Err(e) => return Err(e),
        }
        Ok(())
    };
    plot(
        "build_ms.svg",
        format!("Build time against size ({generator})"),
        "build time, ms (log)",
        series(rows, one, |r| r.build_ms),
    )?;
    plot(
        "memory.svg",
        format!("Memory against size ({generator})"),
        "index memory, bytes (log)",
        series(rows, one, |r| r.memory_bytes as f64),
    )?;
    let mut sets: Vec<&str> = Vec::new();
    for r in rows {
        if !sets.contains(&r.ray_set.as_str()) {
            sets.push(&r.ray_set);
        }
    }
    for set in sets {
        plot(
            &format!("mrays_{set}.svg"),
            format!("{set} rays: Mrays/s against size ({generator})"),
            "Mrays/s (log)",
            series(rows, |r| r.ray_set == set, |r| r.mrays_per_s),
        )?;
    }
    Ok(files)
}
