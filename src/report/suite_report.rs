//! The report of `accelbench run` under `reports/<run id>/`: `results.csv` (one row per scene x
//! index x ray set x threads), `meta.json` (date, git revision, machine, parameters),
//! `notes.json` (verification, notes, pictures), `summary.md` (tables a person can read),
//! `index.html` (the verdict first, then why) and SVG plots (Mrays/s, build time, memory, tests
//! per ray, thread scaling), plus `mismatches.txt` when verification found mismatches.

use super::cost_fit::{CostFit, cost_fits};
use super::fixed as fmt_f;
use super::html::write_html;
use super::rows::{base_index, differing_peers, index_label, scenes, uniq, uniq_threads};
pub use super::run_meta::{RunMeta, RunStatus, run_id_now};
use super::run_notes::{PictureRef, RunNotes, pictures_markdown};
use super::suite_plots::write_plots;
use super::verdict::{Verdict, verdicts};
use super::{ReportError, write_csv};
use crate::harness::suite::{ResultRow, SuiteResult};
use std::fmt::Write as _;
use std::path::Path;

/// Writes the whole report of a suite run into `dir`: `mismatches.txt` when there are any,
/// then [`write_report`].
pub fn write_suite_report(
    dir: &Path,
    meta: &RunMeta,
    res: &SuiteResult,
    pictures: Vec<PictureRef>,
) -> Result<(), ReportError> {
    let err = |e: std::io::Error| ReportError::Write {
        path: dir.join("mismatches.txt"),
        message: e.to_string(),
    };
    std::fs::create_dir_all(dir).map_err(err)?;
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
    write_report(dir, meta, &res.rows, &RunNotes::of(res, pictures))
}

/// Writes `results.csv`, `meta.json`, `notes.json`, the charts, `summary.md` and `index.html`
/// of `rows` into `dir` (a suite run's, or the rows `accelbench merge` combined).
pub fn write_report(
    dir: &Path,
    meta: &RunMeta,
    rows: &[ResultRow],
    notes: &RunNotes,
) -> Result<(), ReportError> {
    let err = |e: std::io::Error| ReportError::Write {
        path: dir.to_owned(),
        message: e.to_string(),
    };
    std::fs::create_dir_all(dir).map_err(err)?;
    write_csv(&dir.join("results.csv"), rows)?;
    let json = serde_json::to_string_pretty(meta).expect("meta serializes");
    std::fs::write(dir.join("meta.json"), json).map_err(err)?;
    let json = serde_json::to_string_pretty(notes).expect("notes serialize");
    std::fs::write(dir.join("notes.json"), json).map_err(err)?;
    let plots = write_plots(dir, meta, rows)?;
    let fits = cost_fits(rows);
    let md = summary_markdown(meta, rows, notes, &fits, &plots);
    std::fs::write(dir.join("summary.md"), md).map_err(err)?;
    write_html(dir, meta, rows, notes, &verdicts(rows), &fits, &plots)
}

/// Rows of one index (name and parameters) with its label ([`index_label`]), in first-seen
/// order of the indices.
fn by_index<'a>(rows: &[&'a ResultRow]) -> Vec<(String, Vec<&'a ResultRow>)> {
    let mut v: Vec<(String, Vec<&ResultRow>)> = Vec::new();
    for r in rows {
        let label = index_label(r, rows.iter().copied());
        match v.iter_mut().find(|(l, _)| *l == label) {
            Some((_, rs)) => rs.push(r),
            None => v.push((label, vec![r])),
        }
    }
    v
}

/// Build time, resident memory and the build's peak memory per index of one scene (an index's rows in other modes share its
/// build: they are listed only for an index with no single row).
fn build_table(rows: &[&ResultRow]) -> String {
    let has_single = |r: &ResultRow| {
        rows.iter()
            .any(|o| o.mode == "single" && base_index(o) == base_index(r) && o.params == r.params)
    };
    let built: Vec<&ResultRow> = rows
        .iter()
        .copied()
        .filter(|r| r.mode == "single" || !has_single(r))
        .collect();
    let mut s = "| index | build ms | bytes/prim | peak build bytes/prim |\n|---|---:|---:|---:|\n"
        .to_owned();
    for (name, rs) in by_index(&built) {
        let r0 = rs[0];
        let per_prim = |bytes: usize| bytes as f64 / r0.primitives.max(1) as f64;
        let _ = writeln!(
            s,
            "| {name} | {} | {} | {} |",
            fmt_f(r0.build_ms, 2),
            fmt_f(per_prim(r0.memory_bytes), 1),
            fmt_f(r0.peak_build_bytes.map_or(f64::NAN, per_prim), 1)
        );
    }
    s
}

/// One ray set of one scene: a row per index with Mrays/s at each thread count, the 95%
/// interval at the most threads, its share of the fastest correct index of its mode family at
/// the most threads (`≈` a tie, `wrong N` for wrong results; [`Verdict::cell`]), and tests and
/// node steps per ray.
fn set_table(rows: &[&ResultRow], threads: &[usize], verdicts: &[&Verdict]) -> String {
    let most = threads.last().copied().unwrap_or(1);
    fn at<'a>(rs: &[&'a ResultRow], t: usize) -> Option<&'a ResultRow> {
        rs.iter().find(|r| r.threads == t).copied()
    }
    let rate = |rs: &[&ResultRow], t: usize| at(rs, t).map_or(f64::NAN, |r| r.mrays_per_s);
    let mut s = "| index |".to_owned();
    for t in threads {
        let _ = write!(s, " Mrays/s {t}t |");
    }
    let _ = writeln!(
        s,
        " 95% interval ({most}t) | vs fastest ({most}t) | tests/ray | steps/ray |"
    );
    s.push_str("|---");
    s.push_str(&"|---:".repeat(threads.len() + 4));
    s.push_str("|\n");
    for (name, rs) in &by_index(rows) {
        let _ = write!(s, "| {name} |");
        for &t in threads {
            let _ = write!(s, " {} |", fmt_f(rate(rs, t), 2));
        }
        let interval = at(rs, most).map_or("–".into(), |r| {
            format!("{}–{}", fmt_f(r.mrays_ci_low, 2), fmt_f(r.mrays_ci_high, 2))
        });
        // The race the row runs in as itself (not as a stand-in).
        let vs = verdicts
            .iter()
            .find(|v| v.get(name).is_some_and(|c| !c.stand_in))
            .and_then(|v| v.cell(name))
            .unwrap_or_else(|| "–".into());
        let _ = writeln!(
            s,
            " {interval} | {vs} | {} | {} |",
            fmt_f(rs[0].prim_tests_per_ray, 1),
            fmt_f(rs[0].node_visits_per_ray, 1)
        );
    }
    s
}

/// With the exact kernel, the share of edge functions its exact fallback decided, per index
/// (from the counting pass); empty otherwise.
fn fallback_line(rows: &[&ResultRow]) -> String {
    let seen: Vec<(String, f64)> = by_index(rows)
        .into_iter()
        .filter_map(|(name, rs)| {
            let r = rs.iter().find(|r| r.exact_fallback_rate.is_finite())?;
            Some((name, r.exact_fallback_rate))
        })
        .collect();
    if seen.is_empty() {
        return String::new();
    }
    let parts: Vec<String> = seen
        .iter()
        .map(|(name, rate)| match rate {
            0.0 => format!("{name} 0"),
            _ => format!("{name} {rate:.2e}"),
        })
        .collect();
    format!(
        "Exact kernel: share of edge functions decided by the exact fallback: {}.\n\n",
        parts.join(", ")
    )
}

/// The fitted cost per node step and per primitive test of each index ([`cost_fits`]).
fn cost_table(fits: &[CostFit]) -> String {
    let mut s = "## Cost breakdown\n\nPer index, fitted by least squares over this run's scenes \
                 and ray sets at the fewest threads: ns per ray = a * steps per ray + b * tests \
                 per ray + c (c with six or more points; costs kept non-negative).\n\n\
                 | index | ns per step (a) | ns per test (b) | ns per ray (c) | R² | points |\n\
                 |---|---:|---:|---:|---:|---:|\n"
        .to_owned();
    for f in fits {
        let _ = writeln!(s, "| {} |", f.cells().join(" | "));
    }
    s.push('\n');
    s
}

/// Per peer, its disagreements with brute force on the verified rays of one set: ties, hits
/// with an imprecise `t` and wrong results (`harness::peer_check`); empty when no peer ran.
fn peer_line(rows: &[&ResultRow]) -> String {
    let parts: Vec<String> = by_index(rows)
        .into_iter()
        .filter_map(|(name, rs)| {
            let r = rs[0];
            let (ties, t_off, wrong) = (r.peer_ties?, r.peer_t_off?, r.peer_wrong?);
            Some(format!(
                "{name} {ties} ties, {t_off} with t off by more than 1e-6 t, {wrong} wrong"
            ))
        })
        .collect();
    if parts.is_empty() {
        return String::new();
    }
    format!(
        "Peers against brute force (verified rays): {}.\n\n",
        parts.join("; ")
    )
}

/// The human-readable summary.
pub fn summary_markdown(
    meta: &RunMeta,
    rows: &[ResultRow],
    notes: &RunNotes,
    fits: &[CostFit],
    plots: &[(String, String)],
) -> String {
    let mut s = String::new();
    let _ = writeln!(s, "# accelbench run {}\n", meta.run_id);
    let _ = writeln!(
        s,
        "{} · git {} · {} ({} cores) · kernel {} · threads {:?} · {} timed repeats (median; {})\n",
        meta.date,
        meta.git_revision,
        meta.cpu,
        meta.cores,
        meta.kernel,
        meta.threads,
        meta.repeats,
        crate::harness::median_interval::describe(meta.repeats)
    );
    let _ = writeln!(s, "Command: `{}`\n", meta.command);
    let _ = writeln!(s, "**Status: {}**\n", meta.status.sentence());
    if notes.peer_mismatch_total > 0 {
        let _ = writeln!(
            s,
            "**Peers** ({}) returned {} results that differ from brute force: obvhs traverses \
             with its own box tests, which lose ties at shared edges and some grazing or \
             very-near hits; Embree and tinybvh also test triangles themselves. Reported in the \
             `mismatches` column and `mismatches.txt` (ties and wrong results per set below), \
             not a failure of the run.\n",
            differing_peers(rows).join(", "),
            notes.peer_mismatch_total
        );
    }
    if notes.mismatch_total == 0 {
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
            notes.mismatch_total
        );
    }
    s.push_str(&scenes_markdown(rows, notes, fits));
    if !plots.is_empty() {
        let _ = writeln!(s, "## Plots\n");
        for (title, file) in plots {
            let _ = writeln!(s, "### {title}\n\n![{title}]({file})\n");
        }
    }
    s.push_str(&pictures_markdown(notes));
    s
}

/// Per scene: the build table, each ray set's table with its verdict, the verification and the
/// notes; then the cost fits. The body of `summary.md` and of a dated results page
/// ([`super::results_page`]).
pub fn scenes_markdown(rows: &[ResultRow], notes: &RunNotes, fits: &[CostFit]) -> String {
    let mut s = String::new();
    let threads = uniq_threads(rows);
    let all_verdicts = verdicts(rows);
    for scene in scenes(rows) {
        let rows: Vec<&ResultRow> = rows.iter().filter(|r| r.scene == scene).collect();
        let _ = writeln!(s, "## {scene} ({} primitives)\n", rows[0].primitives);
        let _ = writeln!(s, "{}", build_table(&rows));
        for set in uniq(rows.iter().map(|r| r.ray_set.as_str())) {
            let in_set: Vec<&ResultRow> =
                rows.iter().copied().filter(|r| r.ray_set == set).collect();
            let races: Vec<&Verdict> = all_verdicts
                .iter()
                .filter(|v| v.scene == scene && v.ray_set == set)
                .collect();
            let _ = writeln!(
                s,
                "### {scene}, {set} rays\n\n{}",
                set_table(&in_set, &threads, &races)
            );
            s.push_str(&fallback_line(&in_set));
            s.push_str(&peer_line(&in_set));
        }
        for v in notes.verification.iter().filter(|v| v.scene == scene) {
            let _ = writeln!(s, "- verification, {}: {}", v.what, v.reason);
        }
        for n in notes.notes.iter().filter(|n| n.scene == scene) {
            let _ = writeln!(s, "- {}: {}", n.what, n.reason);
        }
        s.push('\n');
    }
    // Scenes with no rows at all (every index failed, or the camera failed).
    for n in &notes.notes {
        if !rows.iter().any(|r| r.scene == n.scene) {
            let _ = writeln!(s, "- {} / {}: {}", n.scene, n.what, n.reason);
        }
    }
    s.push_str(&cost_table(fits));
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    fn row(index: &str, params: &str, mrays: f64) -> ResultRow {
        ResultRow {
            scene: "s".into(),
            primitives: 10,
            index: index.into(),
            params: params.into(),
            mode: "single".into(),
            ray_set: "primary".into(),
            rays: 100,
            threads: 1,
            build_ms: 1.0,
            memory_bytes: 100,
            peak_build_bytes: Some(300),
            trace_ms_median: 1.0,
            trace_ms_spread: 0.0,
            mrays_per_s: mrays,
            mrays_ci_low: mrays,
            mrays_ci_high: mrays,
            mtests_per_s: 1.0,
            prim_tests_per_ray: 1.0,
            node_visits_per_ray: 1.0,
            box_tests_per_ray: 1.0,
            hits: 1,
            mismatches: 0,
            brute_verified_rays: 100,
            query: "closest".into(),
            kernel: "exact".into(),
            repeats: 1,
            exact_fallback_rate: 0.0,
            peer_ties: None,
            peer_t_off: None,
            peer_wrong: None,
            gpu_kernel_ms: None,
            gpu_upload_ms: None,
        }
    }

    /// One index name with two parameter sets gives two rows, each labelled with its parameters;
    /// an index without a twin keeps its bare name.
    #[test]
    fn the_same_index_with_other_parameters_keeps_its_own_row() {
        let rows = [
            row("bvh", "a = 1", 2.0),
            row("bvh", "a = 2", 4.0),
            row("grid", "", 1.0),
        ];
        let refs: Vec<&ResultRow> = rows.iter().collect();
        let v = verdicts(&rows);
        let table = set_table(&refs, &[1], &v.iter().collect::<Vec<_>>());
        assert!(
            table.contains("| bvh [a = 1] | 2.00 | 2.00–2.00 | 0.50 |"),
            "{table}"
        );
        assert!(
            table.contains("| bvh [a = 2] | 4.00 | 4.00–4.00 | 1.00 |"),
            "{table}"
        );
        assert!(
            table.contains("| grid | 1.00 | 1.00–1.00 | 0.25 |"),
            "{table}"
        );
        assert_eq!(build_table(&refs).lines().count(), 5);
        let fits = cost_fits(&rows);
        assert_eq!(fits.len(), 3);
    }
}
