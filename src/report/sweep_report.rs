//! A parameter sweep's files: its rows as CSV and two line charts (rays/s and build time
//! against the swept value), one line per series.

use super::{Chart, ReportError, Series, line_chart, write_csv};
use crate::harness::sweep::{SweepPlot, SweepRow};
use std::path::{Path, PathBuf};

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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::TriangleKernelKind;
    use crate::harness::sweep::{SweepError, SweepPoint, SweepSetup, run_sweep};
    use crate::index::IndexSpec;
    use crate::scene::generators;

    #[test]
    fn sweep_rows_agree_and_files_are_written() {
        let scene = generators::generate("soup", 500, 1).unwrap();
        let geom = scene.geometry();
        let rays = crate::rays::incoherent_rays(&scene.bounds(), 300, 42);
        let setup = SweepSetup {
            geom: &geom,
            kernel: TriangleKernelKind::Watertight,
            rays: &rays,
            repeats: 1,
        };
        let points: Vec<SweepPoint> = [1u32, 4, 9]
            .iter()
            .map(|&r| SweepPoint {
                series: "res".into(),
                x: r as f64,
                spec: format!("grid:res=[{r},{r},{r}]").parse().unwrap(),
            })
            .chain(std::iter::once(SweepPoint {
                series: "brute".into(),
                x: 1.0,
                spec: IndexSpec::named("brute"),
            }))
            .collect();
        let mut seen = 0;
        let rows = run_sweep(&setup, &points, |_| seen += 1, |_, _| ()).unwrap();
        assert_eq!((rows.len(), seen), (4, 4));
        assert_eq!(rows[2].cells, 729);
        assert_eq!(rows[3].prim_tests_per_ray, 500.0);
        assert!(rows[2].prim_tests_per_ray < rows[0].prim_tests_per_ray);
        assert!(rows.iter().all(|r| r.rays == 300 && r.rays_per_s > 0.0));
        let dir = tempfile::tempdir().unwrap();
        let plot = SweepPlot {
            title: "grid on soup".into(),
            x_label: "cells per axis".into(),
            log_x: true,
            marker: Some((4.0, "heuristic".into())),
        };
        let files = write_sweep(dir.path(), "primary", &rows, &plot).unwrap();
        assert!(files.csv.ends_with("primary.csv"));
        let csv = std::fs::read_to_string(&files.csv).unwrap();
        assert!(csv.starts_with("series,index,spec,params,x,cells"));
        assert_eq!(csv.lines().count(), 5);
        let svg = std::fs::read_to_string(&files.rays_chart).unwrap();
        assert!(svg.contains("heuristic") && svg.contains("brute"));
        assert!(files.build_chart.exists());
        assert!(matches!(
            run_sweep(&setup, &[], |_| (), |_, _| ()),
            Err(SweepError::Empty)
        ));
    }
}
