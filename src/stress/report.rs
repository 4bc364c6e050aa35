//! Files and tables of `accelbench stress`: `stress.csv` (one row per case and index),
//! `self_intersection.csv`, and `stress.md` (the summary the run report includes).

use super::self_intersection::failures_per_method;
use super::{PEERS, StressSummary};
use crate::report::{ReportError, write_csv};
use std::fmt::Write as _;
use std::path::Path;

/// Writes `stress.csv`, `self_intersection.csv` and `stress.md` into `dir`.
pub fn write_all(dir: &Path, s: &StressSummary) -> Result<(), ReportError> {
    write_csv(&dir.join("stress.csv"), &s.cases)?;
    write_csv(&dir.join("self_intersection.csv"), &s.self_intersection)?;
    let path = dir.join("stress.md");
    std::fs::write(&path, markdown(s)).map_err(|e| ReportError::Write {
        path,
        message: e.to_string(),
    })
}

/// Cases as rows, indices as columns: `ok`, the mismatch count, or `FAIL`.
pub fn case_table(s: &StressSummary) -> String {
    let mut indices: Vec<&str> = Vec::new();
    let mut cases: Vec<&str> = Vec::new();
    for c in &s.cases {
        if !indices.contains(&c.index.as_str()) {
            indices.push(&c.index);
        }
        if !cases.contains(&c.case.as_str()) {
            cases.push(&c.case);
        }
    }
    let mut t = format!("| case | rays | {} |\n|---|---|", indices.join(" | "));
    t.push_str(&"---|".repeat(indices.len()));
    t.push('\n');
    for case in cases {
        let rays = s
            .cases
            .iter()
            .find(|c| c.case == case)
            .map_or(0, |c| c.rays);
        let cells: Vec<String> = indices
            .iter()
            .map(
                |i| match s.cases.iter().find(|c| c.case == case && c.index == *i) {
                    Some(c) if c.passed => "ok".to_owned(),
                    Some(c) if c.mismatches > 0 => format!("{} mismatches", c.mismatches),
                    Some(_) => "FAIL".to_owned(),
                    None => "-".to_owned(),
                },
            )
            .collect();
        let _ = writeln!(t, "| {case} | {rays} | {} |", cells.join(" | "));
    }
    t
}

/// The whole summary in Markdown.
pub fn markdown(s: &StressSummary) -> String {
    let mut m = String::from(
        "# Stress suite\n\nEvery case on every registered index against brute force (bit-identical closest hits, any-hit consistent). ",
    );
    let _ = writeln!(
        m,
        "Peers whose mismatches are reported but may be tolerated: {}.\n",
        PEERS.join(", ")
    );
    m.push_str(&case_table(s));
    let failures: Vec<_> = s.cases.iter().filter(|c| !c.passed).collect();
    if !failures.is_empty() {
        m.push_str("\n## Failures (first ray of each)\n\n");
        for f in failures {
            let _ = writeln!(m, "- {} on {}: {}", f.index, f.case, f.first_failure);
        }
    }
    m.push_str("\n## Bad rays at the boundary\n\n");
    for b in &s.boundary {
        let _ = match &b.outcome {
            Ok(msg) => writeln!(m, "- ok: {} (\"{msg}\")", b.name),
            Err(e) => writeln!(m, "- FAILED: {}: {e}", b.name),
        };
    }
    m.push_str(
        "\n## Shadow-ray self-intersection: t_min epsilon against origin offset\n\n\
         Tilted ground with an occluder 1e-4 (relative) above half of it; epsilon is relative to \
         the scene size.\n\n\
         | scale | offset | method | points | self-hit rate | contacts | missed-contact rate |\n\
         |---|---|---|---|---|---|---|\n",
    );
    for r in &s.self_intersection {
        let _ = writeln!(
            m,
            "| {:e} | {:e} | {} | {} | {:.3e} | {} | {:.3e} |",
            r.scale,
            r.offset,
            r.method,
            r.points,
            r.self_hit_rate,
            r.contacts,
            r.missed_contact_rate
        );
    }
    let totals = failures_per_method(&s.self_intersection);
    m.push_str("\nSelf-hits plus missed contacts over all configurations: ");
    let parts: Vec<String> = totals.iter().map(|(n, v)| format!("{n}: {v}")).collect();
    m.push_str(&parts.join(", "));
    if let Some((best, _)) = totals.iter().min_by_key(|(_, v)| *v) {
        let _ = writeln!(m, ". Fewest failures: **{best}**.");
    }
    m.push_str(
        "\nReading the table: an epsilon has to lie between the hit point's rounding error \
         (which grows with the distance from the origin) and the smallest real gap (here 1e-4 \
         of the scene), so the best epsilon depends on the scene; the offset needs no tuning \
         but moves the origin by 256 ulps of its coordinates (1/65536 near the origin), so it \
         loses contacts closer than that.\n",
    );
    m
}
