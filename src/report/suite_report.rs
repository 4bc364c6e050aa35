//! The report of `accelbench run` under `reports/<run id>/`: `results.csv` (one row per scene x
//! index x ray set x threads), `meta.json` (date, git revision, machine, parameters),
//! `summary.md` (tables a person can read) and SVG plots (Mrays/s, build time, memory, tests per
//! ray, thread scaling), plus `mismatches.txt` when verification failed.

use super::{BarGroup, Chart, ReportError, Series, bar_chart, line_chart, write_csv};
use crate::harness::suite::{ResultRow, SuiteConfig, SuiteResult};
use serde::Serialize;
use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::Path;

/// Facts about the run that are not in the rows.
#[derive(Debug, Clone, Serialize)]
pub struct RunMeta {
    pub run_id: String,
    /// UTC, `YYYY-MM-DDTHH:MM:SSZ`.
    pub date: String,
    pub git_revision: String,
    pub cpu: String,
    pub cores: usize,
    pub os: String,
    pub command: String,
    pub config: SuiteConfig,
}

impl RunMeta {
    /// Collects the machine facts and the date now.
    pub fn collect(run_id: String, command: String, config: SuiteConfig) -> RunMeta {
        RunMeta {
            run_id,
            date: utc_now(),
            git_revision: git_revision(),
            cpu: cpu_model(),
            cores: std::thread::available_parallelism().map_or(1, |n| n.get()),
            os: std::env::consts::OS.to_owned(),
            command,
            config,
        }
    }
}

/// `YYYYMMDD-HHMMSS` of the current UTC time (a run id).
pub fn run_id_now() -> String {
    utc_now()
        .replace(['-', ':'], "")
        .replace('T', "-")
        .trim_end_matches('Z')
        .to_owned()
}

fn utc_now() -> String {
    let secs = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map_or(0, |d| d.as_secs());
    let (days, rem) = (secs / 86_400, secs % 86_400);
    // Civil date from days since 1970-01-01 (Hinnant's algorithm).
    let z = days as i64 + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z - era * 146_097;
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let d = doy - (153 * mp + 2) / 5 + 1;
    let m = if mp < 10 { mp + 3 } else { mp - 9 };
    let y = yoe + era * 400 + i64::from(m <= 2);
    format!(
        "{y:04}-{m:02}-{d:02}T{:02}:{:02}:{:02}Z",
        rem / 3600,
        rem / 60 % 60,
        rem % 60
    )
}

fn git_revision() -> String {
    std::process::Command::new("git")
        .args(["rev-parse", "--short=12", "HEAD"])
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .ok()
        .filter(|o| o.status.success())
        .map(|o| String::from_utf8_lossy(&o.stdout).trim().to_owned())
        .unwrap_or_else(|| "unknown".into())
}

fn cpu_model() -> String {
    std::fs::read_to_string("/proc/cpuinfo")
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with("model name"))
                .and_then(|l| l.split_once(':'))
                .map(|(_, v)| v.trim().to_owned())
        })
        .unwrap_or_else(|| "unknown".into())
}

/// Writes the whole report into `dir`.
pub fn write_suite_report(
    dir: &Path,
    meta: &RunMeta,
    res: &SuiteResult,
    extra_md: &str,
) -> Result<(), ReportError> {
    let err = |e: std::io::Error| ReportError::Write {
        path: dir.to_owned(),
        message: e.to_string(),
    };
    std::fs::create_dir_all(dir).map_err(err)?;
    write_csv(&dir.join("results.csv"), &res.rows)?;
    let json = serde_json::to_string_pretty(meta).expect("meta serializes");
    std::fs::write(dir.join("meta.json"), json).map_err(err)?;
    let plots = write_plots(dir, meta, &res.rows)?;
    if res.mismatch_total + res.peer_mismatch_total > 0 {
        let mut t = String::new();
        for m in &res.mismatches {
            let _ = writeln!(
                t,
                "{} / {} / {} vs {}: {}",
                m.scene,
                m.index,
                m.ray_set.name(),
                m.against,
                m.mismatch
            );
        }
        std::fs::write(dir.join("mismatches.txt"), t).map_err(err)?;
    }
    let md = summary_markdown(meta, res, &plots, extra_md);
    std::fs::write(dir.join("summary.md"), md).map_err(err)
}

/// Scenes in first-seen order.
fn scenes(rows: &[ResultRow]) -> Vec<&str> {
    let mut v: Vec<&str> = Vec::new();
    for r in rows {
        if !v.contains(&r.scene.as_str()) {
            v.push(&r.scene);
        }
    }
    v
}

fn uniq<'a>(rows: impl Iterator<Item = &'a str>) -> Vec<&'a str> {
    let mut v: Vec<&str> = Vec::new();
    for r in rows {
        if !v.contains(&r) {
            v.push(r);
        }
    }
    v
}

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
                .map(|r| (r.index.clone(), value(r)))
                .collect(),
        })
        .filter(|g| !g.bars.is_empty())
        .collect()
}

/// Draws every plot; returns `(title, file name)` of those written.
fn write_plots(
    dir: &Path,
    meta: &RunMeta,
    rows: &[ResultRow],
) -> Result<Vec<(String, String)>, ReportError> {
    let mut out = Vec::new();
    let min_threads = meta.config.threads.iter().copied().min().unwrap_or(1);
    let mut draw = |title: String, file: String, y: &str, log_y: bool, g: Vec<BarGroup>| {
        if g.is_empty() {
            return Ok::<(), ReportError>(());
        }
        let mut c = Chart::new(&title, "scene", y);
        c.log_y = log_y;
        match bar_chart(&dir.join(&file), &c, &g) {
            Ok(()) | Err(ReportError::NoData(_)) => {}
            Err(e) => return Err(e),
        }
        out.push((title, file));
        Ok(())
    };
    let sets = uniq(rows.iter().map(|r| r.ray_set.as_str()));
    for set in &sets {
        draw(
            format!("{set} rays: Mrays/s on {min_threads} thread(s)"),
            format!("mrays_{set}.svg"),
            "Mrays/s (log)",
            true,
            groups(
                rows,
                |r| r.ray_set == *set && r.threads == min_threads,
                |r| r.mrays_per_s,
            ),
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
        for index in uniq(rows.iter().map(|r| r.index.as_str())) {
            let mut pts = Vec::new();
            for &t in &threads {
                let ratios: Vec<f64> = rows
                    .iter()
                    .filter(|r| r.index == index && r.threads == t)
                    .filter_map(|r| {
                        let base = rows.iter().find(|b| {
                            b.index == r.index
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
        let title = "Thread scaling (geometric mean over scenes and ray sets)";
        let c = Chart::new(title, "threads", "speed-up over the fewest threads");
        line_chart(&dir.join("thread_scaling.svg"), &c, &series)?;
        out.push((title.into(), "thread_scaling.svg".into()));
    }
    Ok(out)
}

fn uniq_threads(rows: &[ResultRow]) -> Vec<usize> {
    let mut t: Vec<usize> = rows.iter().map(|r| r.threads).collect();
    t.sort_unstable();
    t.dedup();
    t
}

fn fmt_f(v: f64, digits: usize) -> String {
    if v.is_finite() {
        format!("{v:.digits$}")
    } else {
        "–".into()
    }
}

/// The human-readable summary.
pub fn summary_markdown(
    meta: &RunMeta,
    res: &SuiteResult,
    plots: &[(String, String)],
    extra_md: &str,
) -> String {
    let mut s = String::new();
    let _ = writeln!(s, "# accelbench run {}\n", meta.run_id);
    let _ = writeln!(
        s,
        "{} · git {} · {} ({} cores) · kernel {} · threads {:?} · {} timed repeats (median)\n",
        meta.date,
        meta.git_revision,
        meta.cpu,
        meta.cores,
        meta.config.kernel,
        meta.config.threads,
        meta.config.repeats
    );
    let _ = writeln!(s, "Command: `{}`\n", meta.command);
    if res.peer_mismatch_total > 0 {
        let _ = writeln!(
            s,
            "**Peers** ({}) returned {} results that differ from brute force: obvhs traverses \
             with its own box tests, which lose ties at shared edges and some grazing or \
             very-near hits. Reported in the `mismatches` column and `mismatches.txt`, not a \
             failure of the run.\n",
            crate::index::peer_names().join(", "),
            res.peer_mismatch_total
        );
    }
    if res.mismatch_total == 0 {
        let _ = writeln!(
            s,
            "**Verification: passed.** Every one of our indices returned brute force's hits bit \
             for bit on the verified rays, and they agreed with each other on every ray.\n"
        );
    } else {
        let _ = writeln!(
            s,
            "**Verification: FAILED, {} mismatching results** (first ones in `mismatches.txt`, \
             with the rays' bits).\n",
            res.mismatch_total
        );
    }
    let threads = uniq_threads(&res.rows);
    for scene in scenes(&res.rows) {
        let rows: Vec<&ResultRow> = res.rows.iter().filter(|r| r.scene == scene).collect();
        let _ = writeln!(s, "## {scene} ({} primitives)\n", rows[0].primitives);
        let sets = uniq(rows.iter().map(|r| r.ray_set.as_str()));
        let mut header = "| index | build ms | bytes/prim |".to_owned();
        let mut rule = "|---|---:|---:|".to_owned();
        for set in &sets {
            for t in &threads {
                let _ = write!(header, " {set} Mrays/s {t}t |");
                rule.push_str("---:|");
            }
            let _ = write!(header, " {set} tests/ray | {set} nodes/ray |");
            rule.push_str("---:|---:|");
        }
        let _ = writeln!(s, "{header}\n{rule}");
        let mut by_index: BTreeMap<usize, (&str, Vec<&ResultRow>)> = BTreeMap::new();
        for r in &rows {
            let pos = rows.iter().position(|x| x.index == r.index).unwrap_or(0);
            by_index
                .entry(pos)
                .or_insert((&r.index, Vec::new()))
                .1
                .push(r);
        }
        for (name, rs) in by_index.values() {
            let r0 = rs[0];
            let _ = write!(
                s,
                "| {name} | {} | {} |",
                fmt_f(r0.build_ms, 2),
                fmt_f(r0.memory_bytes as f64 / r0.primitives.max(1) as f64, 1)
            );
            for set in &sets {
                for t in &threads {
                    let v = rs
                        .iter()
                        .find(|r| r.ray_set == *set && r.threads == *t)
                        .map_or(f64::NAN, |r| r.mrays_per_s);
                    let _ = write!(s, " {} |", fmt_f(v, 2));
                }
                let r = rs.iter().find(|r| r.ray_set == *set);
                let _ = write!(
                    s,
                    " {} | {} |",
                    fmt_f(r.map_or(f64::NAN, |r| r.prim_tests_per_ray), 1),
                    fmt_f(r.map_or(f64::NAN, |r| r.node_visits_per_ray), 1)
                );
            }
            s.push('\n');
        }
        s.push('\n');
        for v in res.verification.iter().filter(|v| v.scene == scene) {
            let _ = writeln!(s, "- verification, {}: {}", v.what, v.reason);
        }
        for n in res.notes.iter().filter(|n| n.scene == scene) {
            let _ = writeln!(s, "- {}: {}", n.what, n.reason);
        }
        s.push('\n');
    }
    // Scenes with no rows at all (every index failed, or the camera failed).
    for n in &res.notes {
        if !res.rows.iter().any(|r| r.scene == n.scene) {
            let _ = writeln!(s, "- {} / {}: {}", n.scene, n.what, n.reason);
        }
    }
    if !plots.is_empty() {
        let _ = writeln!(s, "## Plots\n");
        for (title, file) in plots {
            let _ = writeln!(s, "### {title}\n\n![{title}]({file})\n");
        }
    }
    s.push_str(extra_md);
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn utc_date_format() {
        let d = utc_now();
        assert_eq!(d.len(), 20, "{d}");
        assert!(d.starts_with("20") && d.ends_with('Z'));
        let id = run_id_now();
        assert_eq!(id.len(), 15, "{id}");
    }
}
