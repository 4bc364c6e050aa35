//! Files and tables of `accelbench stress`: `stress.csv` (one row per case and index),
//! `self_intersection.csv`, and `stress.md` (the summary the run report includes).

use super::StressSummary;
use super::self_intersection::{RESOLVABLE_ULPS, SpawnRow, failures_per_method};
use crate::index::peer_names;
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
        peer_names().join(", ")
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
    m.push_str(&self_intersection_markdown(&s.self_intersection));
    m
}

/// The self-intersection study: one row per scale, offset and gap, one column per method
/// (`self-hits / missed contacts`), then the failures per method and the verdict.
pub fn self_intersection_markdown(rows: &[SpawnRow]) -> String {
    let mut methods: Vec<&str> = Vec::new();
    for r in rows {
        if !methods.contains(&r.method.as_str()) {
            methods.push(&r.method);
        }
    }
    let mut m = String::from(
        "\n## Shadow-ray self-intersection: t_min epsilon against origin offset\n\n\
         A tilted ground with an occluder `gap` above half of it (gap and epsilon relative to the \
         scene size). Each cell: self-hits / missed contacts, over `points` surface points of \
         which `contacts` lie under the occluder. \"gap ulps\": the gap in ulps of the largest \
         coordinate.\n\n",
    );
    let _ = write!(
        m,
        "| scale | offset | gap | gap ulps | points | contacts | {} |\n|---|---|---|---|---|---|",
        methods.join(" | ")
    );
    m.push_str(&"---|".repeat(methods.len()));
    m.push('\n');
    let mut seen: Vec<(u64, u64, u64)> = Vec::new();
    for r in rows {
        let key = (r.scale.to_bits(), r.offset.to_bits(), r.gap.to_bits());
        if seen.contains(&key) {
            continue;
        }
        seen.push(key);
        let cells: Vec<String> = methods
            .iter()
            .map(|name| {
                rows.iter()
                    .find(|x| {
                        (x.scale.to_bits(), x.offset.to_bits(), x.gap.to_bits()) == key
                            && x.method == *name
                    })
                    .map_or("-".to_owned(), |x| {
                        format!("{} / {}", x.self_hits, x.missed_contacts)
                    })
            })
            .collect();
        let _ = writeln!(
            m,
            "| {:e} | {:e} | {:e} | {:.0} | {} | {} | {} |",
            r.scale,
            r.offset,
            r.gap,
            r.gap_ulps,
            r.points,
            r.contacts,
            cells.join(" | ")
        );
    }
    let totals = failures_per_method(rows);
    let _ = writeln!(
        m,
        "\nPer method: self-hits on every row (they darken every lit surface), and missed \
         contacts where the gap spans at least {RESOLVABLE_ULPS} ulps (a contact float \
         coordinates resolve with room to spare) and on every row.\n\n\
         | method | self-hits | rows with self-hits | missed resolvable contacts | rows | missed contacts, all rows |\n\
         |---|---|---|---|---|---|"
    );
    for t in &totals {
        let _ = writeln!(
            m,
            "| {} | {} | {} | {} | {} | {} |",
            t.method,
            t.self_hits,
            t.self_hit_rows,
            t.missed_resolvable,
            t.missed_resolvable_rows,
            t.missed_all
        );
    }
    if let Some(best) = totals.iter().min_by_key(|t| (t.counted(), t.missed_all)) {
        let _ = writeln!(
            m,
            "\nFewest self-hits plus missed resolvable contacts (ties: fewer missed contacts \
             overall): **{}**.",
            best.method
        );
    }
    m.push_str(
        "\nReading the table: an epsilon has to lie between the hit point's rounding error \
         (which grows with the distance from the origin relative to the scene's size) and the \
         smallest real gap, so the best epsilon depends on the scene. The offset needs no tuning \
         far from the origin (256 ulps of the coordinates); near the origin it moves the point by \
         an absolute 1/65536, too much for a scene a thousandth of a unit across, which the \
         scaled offset measures in units of the scene's size instead.\n",
    );
    m
}
