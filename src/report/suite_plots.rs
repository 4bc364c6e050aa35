//! The suite report's SVG charts: Mrays/s and tests per ray per ray set, build time, memory and
//! thread scaling.

use super::rows::{index_label, scenes, uniq, uniq_threads};
use super::run_meta::RunMeta;
use super::{BarGroup, Chart, ReportError, Series, bar_chart, line_chart};
use crate::harness::suite::ResultRow;
use std::path::Path;

/// Bar groups (one per scene) of `value` for the rows `keep` selects, one bar per index.
fn groups(
    rows: &[ResultRow],
    keep: impl Fn(&ResultRow) -> bool,
    value: impl Fn(&ResultRow) -> f64,
) -> Vec<BarGroup> {
    scenes(rows)
        .into_iter()
        .map(|s| BarGroup {
            name: s.to_owned(),
            bars: rows
                .iter()
                .filter(|r| r.scene == s && keep(r))
                .map(|r| (index_label(r, rows), value(r)))
                .collect(),
        })
        .filter(|g| !g.bars.is_empty())
        .collect()
}

/// Draws every plot; returns `(title, file name)` of those written.
pub(super) fn write_plots(
    dir: &Path,
    meta: &RunMeta,
    rows: &[ResultRow],
) -> Result<Vec<(String, String)>, ReportError> {
    let mut out = Vec::new();
    let min_threads = meta.threads.iter().copied().min().unwrap_or(1);
    let mut draw = |title: String, file: String, y: &str, log_y: bool, g: Vec<BarGroup>| {
        if g.is_empty() {
            return Ok::<(), ReportError>(());
        }
        let mut c = Chart::new(&title, "scene", y);
        c.log_y = log_y;
        // A chart with nothing to draw (e.g. tests per ray when every index is a peer, which
        // counts nothing) is left out of the report rather than listed without a file.
        match bar_chart(&dir.join(&file), &c, &g) {
            Ok(()) => out.push((title, file)),
            Err(ReportError::NoData(_)) => {}
            Err(e) => return Err(e),
        }
        Ok(())
    };
    let sets = uniq(rows.iter().map(|r| r.ray_set.as_str()));
    for set in &sets {
        // A contender with wrong results is never drawn as fast: its rows stay out of the
        // speed charts (the verdict shows their speed, marked wrong).
        let timed = |r: &ResultRow| r.ray_set == *set && r.threads == min_threads;
        let wrong = rows.iter().any(|r| timed(r) && r.wrong().is_some());
        draw(
            format!(
                "{set} rays: Mrays/s on {min_threads} thread(s){}",
                if wrong {
                    " (indices with wrong results left out)"
                } else {
                    ""
                }
            ),
            format!("mrays_{set}.svg"),
            "Mrays/s (log)",
            true,
            groups(rows, |r| timed(r) && r.wrong().is_none(), |r| r.mrays_per_s),
        )?;
    }
    let first_row = |r: &ResultRow| {
        r.ray_set == rows[0].ray_set && r.threads == rows[0].threads && r.index != "brute"
    };
    draw(
        "Build time per index".into(),
        "build_ms.svg".into(),
        "build time, ms (log)",
        true,
        groups(rows, first_row, |r| r.build_ms),
    )?;
    draw(
        "Memory per index".into(),
        "memory.svg".into(),
        "bytes per primitive (log)",
        true,
        groups(rows, first_row, |r| {
            r.memory_bytes as f64 / r.primitives.max(1) as f64
        }),
    )?;
    for set in &sets {
        draw(
            format!("{set} rays: primitive tests per ray"),
            format!("tests_per_ray_{set}.svg"),
            "primitive tests per ray (log)",
            true,
            groups(
                rows,
                |r| r.ray_set == *set && r.threads == min_threads,
                |r| r.prim_tests_per_ray,
            ),
        )?;
    }
    // Thread scaling: geometric mean over scenes and sets of rate(t) / rate(min threads).
    let threads = uniq_threads(rows);
    if threads.len() > 1 {
        let mut series = Vec::new();
        let labels: Vec<String> = rows.iter().map(|r| index_label(r, rows)).collect();
        for index in uniq(labels.iter().map(String::as_str)) {
            let mut pts = Vec::new();
            for &t in &threads {
                let ratios: Vec<f64> = rows
                    .iter()
                    .zip(&labels)
                    .filter(|(r, l)| *l == index && r.threads == t)
                    .filter_map(|(r, _)| {
                        let base = rows.iter().find(|b| {
                            b.index == r.index
                                && b.params == r.params
                                && b.scene == r.scene
                                && b.ray_set == r.ray_set
                                && b.threads == min_threads
                        })?;
                        let q = r.mrays_per_s / base.mrays_per_s;
                        q.is_finite().then_some(q.ln())
                    })
                    .collect();
                if !ratios.is_empty() {
                    let g = (ratios.iter().sum::<f64>() / ratios.len() as f64).exp();
                    pts.push((t as f64, g));
                }
            }
            series.push(Series::new(index, pts));
        }
        let ideal = threads
            .iter()
            .map(|&t| (t as f64, t as f64 / min_threads as f64));
        series.push(Series::new("ideal (linear)", ideal.collect()));
        let title = "Thread scaling (geometric mean over scenes and ray sets)";
        let c = Chart::new(title, "threads", "speed-up over the fewest threads");
        line_chart(&dir.join("thread_scaling.svg"), &c, &series)?;
        out.push((title.into(), "thread_scaling.svg".into()));
    }
    Ok(out)
}
