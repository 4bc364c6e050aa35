//! The report of `accelbench run` under `reports/<run id>/`: `results.csv` (one row per scene x
//! index x ray set x threads), `meta.json` (date, git revision, machine, parameters),
//! `summary.md` (tables a person can read) and SVG plots (Mrays/s, build time, memory, tests per
//! ray, thread scaling), plus `mismatches.txt` when verification failed.

pub use super::run_meta::{RunMeta, run_id_now};
use super::suite_plots::{scenes, uniq, uniq_threads, write_plots};
use super::{ReportError, write_csv};
use crate::harness::suite::{ResultRow, SuiteResult};
use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::Path;

/// Creates the report folder `dir` (if needed) and checks that a file can be written in it, so a
/// bad `--out` fails before the suite runs rather than after.
pub fn prepare_report_dir(dir: &Path) -> Result<(), ReportError> {
    let err = |message: String| ReportError::Write {
        path: dir.to_owned(),
        message,
    };
    if dir.exists() && !dir.is_dir() {
        return Err(err(
            "it is a file, not a folder: give --out a folder (new or existing)".into(),
        ));
    }
    std::fs::create_dir_all(dir).map_err(|e| err(format!("cannot create the folder ({e})")))?;
    let probe = dir.join(".accelbench-write-check");
    std::fs::write(&probe, b"")
        .and_then(|()| std::fs::remove_file(&probe))
        .map_err(|e| err(format!("cannot write in the folder ({e})")))
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
            crate::index::PEERS.join(", "),
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
