//! A parameter sweep's files: its rows as CSV and two line charts (rays/s and build time
//! against the swept value), one line per series.

use super::{Chart, ReportError, Series, line_chart, write_csv};
use crate::harness::sweep::SweepRow;
use std::path::{Path, PathBuf};

/// Titles, axis and marker of a sweep's charts.
#[derive(Debug, Clone, Default)]
pub struct SweepPlot {
    /// What was swept, for titles (`grid on stanford_bunny, primary rays`).
    pub title: String,
    pub x_label: String,
    pub log_x: bool,
    /// The default or heuristic choice `(x, label)`, drawn as a vertical line.
    pub marker: Option<(f64, String)>,
}

/// The files a sweep wrote.
#[derive(Debug, Clone)]
pub struct SweepFiles {
    pub csv: PathBuf,
    pub rays_chart: PathBuf,
    pub build_chart: PathBuf,
}

/// Writes `<stem>.csv`, `<stem>-rays_per_s.svg` and `<stem>-build_ms.svg` (one line per series,
/// the marker on both) into `dir`; the stem (e.g. the ray set) lets several sweeps of one scene
/// share a directory.
pub fn write_sweep(
    dir: &Path,
    stem: &str,
    rows: &[SweepRow],
    plot: &SweepPlot,
) -> Result<SweepFiles, ReportError> {
    let files = SweepFiles {
        csv: dir.join(format!("{stem}.csv")),
        rays_chart: dir.join(format!("{stem}-rays_per_s.svg")),
        build_chart: dir.join(format!("{stem}-build_ms.svg")),
    };
    write_csv(&files.csv, rows)?;
    let mut names: Vec<&str> = Vec::new();
    for r in rows {
        if !names.contains(&r.series.as_str()) {
            names.push(&r.series);
        }
    }
    let series = |y: fn(&SweepRow) -> f64| -> Vec<Series> {
        names
            .iter()
            .map(|&name| {
                let mut pts: Vec<(f64, f64)> = rows
                    .iter()
                    .filter(|r| r.series == name)
                    .map(|r| (r.x, y(r)))
                    .collect();
                pts.sort_by(|a, b| a.0.total_cmp(&b.0));
                Series::new(name, pts)
            })
            .collect()
    };
    let chart = |what: &str, y_label: &str, log_y: bool| Chart {
        title: format!("{}: {what}", plot.title),
        x_label: plot.x_label.clone(),
        y_label: y_label.to_owned(),
        log_x: plot.log_x,
        log_y,
        markers: plot.marker.iter().cloned().collect(),
    };
    line_chart(
        &files.rays_chart,
        &chart("rays/s", "Mrays/s (closest hit)", false),
        &series(|r| r.rays_per_s / 1e6),
    )?;
    line_chart(
        &files.build_chart,
        &chart("build time", "build time (ms)", true),
        &series(|r| r.build_ms),
    )?;
    Ok(files)
}
