//! The report of `accelbench animate`: `frames.csv` (one line per frame and row), the charts of
//! the cost per frame, the update time and the SAH cost against the frame, and `summary.md`
//! (totals over the frames per row, and the frame where rebuilding overtakes refitting).

use super::{Chart, ReportError, Series, fixed, line_chart, write_csv};
use crate::harness::animate::{Animation, FrameRow, Update, rebuild_overtakes};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// The rows' names in first-seen order.
fn row_names(rows: &[FrameRow]) -> Vec<&str> {
    let mut names: Vec<&str> = Vec::new();
    for r in rows {
        if !names.contains(&r.row.as_str()) {
            names.push(&r.row);
        }
    }
    names
}

/// One line per row of `value` against the frame (rows without a value left out).
fn series(rows: &[FrameRow], value: impl Fn(&FrameRow) -> Option<f64>) -> Vec<Series> {
    row_names(rows)
        .into_iter()
        .map(|n| {
            let pts = rows
                .iter()
                .filter(|r| r.row == n)
                .filter_map(|r| Some((r.frame as f64, value(r)?)))
                .collect();
            Series::new(n, pts)
        })
        .filter(|s| !s.points.is_empty())
        .collect()
}

/// The indices with both a refit and a rebuild row, and where rebuilding overtakes.
pub fn overtakes(rows: &[FrameRow]) -> Vec<(String, Option<usize>)> {
    let mut out: Vec<(String, Option<usize>)> = Vec::new();
    for r in rows.iter().filter(|r| r.update == Update::Refit) {
        if !out.iter().any(|(n, _)| *n == r.index) {
            out.push((r.index.clone(), rebuild_overtakes(rows, &r.index)));
        }
    }
    out
}

/// The Markdown summary: its status (`complete`, `interrupted`, `failed: ...`), per row, totals over the frames; per index with both rows, where
/// rebuilding overtakes; the failures.
pub fn summary_markdown(title: &str, status: &str, anim: &Animation) -> String {
    let rows = &anim.rows;
    let mut md = format!("# {title}\n\n**Status: {status}**\n\n");
    md.push_str(
        "| row | frames | update ms (sum) | trace ms (sum) | total ms (sum) | Mrays/s (mean) \
         | SAH first → last | mismatches |\n|---|---|---|---|---|---|---|---|\n",
    );
    for name in row_names(rows) {
        let mine: Vec<&FrameRow> = rows.iter().filter(|r| r.row == name).collect();
        let sum = |f: fn(&FrameRow) -> f64| mine.iter().map(|r| f(r)).sum::<f64>();
        let sah = |r: Option<&&FrameRow>| r.and_then(|r| r.sah_cost).map_or(f64::NAN, |v| v);
        let _ = writeln!(
            md,
            "| {name} | {} | {} | {} | {} | {} | {} → {} | {} |",
            mine.len(),
            fixed(sum(|r| r.update_ms), 2),
            fixed(sum(|r| r.trace_ms), 2),
            fixed(sum(|r| r.total_ms), 2),
            fixed(sum(|r| r.mrays_per_s) / mine.len() as f64, 2),
            fixed(sah(mine.first()), 2),
            fixed(sah(mine.last()), 2),
            mine.iter().map(|r| r.mismatches).sum::<usize>(),
        );
    }
    md.push('\n');
    for (index, at) in overtakes(rows) {
        let _ = match at {
            Some(f) => writeln!(
                md,
                "- {index}: rebuilding costs less than refitting (update plus trace) from frame \
                 {f} to the last."
            ),
            None => writeln!(
                md,
                "- {index}: refitting is still as cheap as rebuilding, or cheaper, at the last \
                 frame."
            ),
        };
    }
    for f in &anim.failures {
        let _ = writeln!(md, "- {} failed at frame {}: {}", f.row, f.frame, f.reason);
    }
    md
}

/// A chart of a per-frame figure: its file, what it shows, the y axis and the figure.
type Plot = (
    &'static str,
    &'static str,
    &'static str,
    fn(&FrameRow) -> Option<f64>,
);

/// Writes `frames.csv`, the charts and `summary.md` into `dir`; returns the files written.
pub fn write_animate_report(
    dir: &Path,
    title: &str,
    status: &str,
    anim: &Animation,
) -> Result<Vec<PathBuf>, ReportError> {
    let csv = dir.join("frames.csv");
    write_csv(&csv, &anim.rows)?;
    let mut files = vec![csv];
    let markers: Vec<(f64, String)> = overtakes(&anim.rows)
        .into_iter()
        .filter_map(|(i, at)| Some((at? as f64, format!("{i}: rebuild overtakes"))))
        .collect();
    let charts: [Plot; 3] = [
        (
            "cost_per_frame.svg",
            "update plus trace per frame",
            "ms",
            |r| Some(r.total_ms),
        ),
        (
            "update_ms.svg",
            "update (refit or rebuild) per frame",
            "ms",
            |r| Some(r.update_ms),
        ),
        (
            "sah_cost.svg",
            "SAH cost of the tree per frame",
            "SAH cost",
            |r| r.sah_cost,
        ),
    ];
    for (file, what, y, value) in charts {
        let mut c = Chart::new(format!("{title}: {what}"), "frame", y);
        c.markers = markers.clone();
        let p = dir.join(file);
        match line_chart(&p, &c, &series(&anim.rows, value)) {
            Ok(()) => files.push(p),
            Err(ReportError::NoData(_)) => {}
            Err(e) => return Err(e),
        }
    }
    let summary = dir.join("summary.md");
    std::fs::write(&summary, summary_markdown(title, status, anim)).map_err(|e| {
        ReportError::Write {
            path: summary.clone(),
            message: e.to_string(),
        }
    })?;
    files.push(summary);
    Ok(files)
}
