//! How the report groups result rows: scenes, ray sets and thread counts in first-seen order,
//! and the label that names an index (with its trace mode) in every table and chart.

use crate::harness::suite::ResultRow;

/// Scenes in first-seen order.
pub(super) fn scenes(rows: &[ResultRow]) -> Vec<&str> {
    uniq(rows.iter().map(|r| r.scene.as_str()))
}

/// Distinct items in first-seen order.
pub(super) fn uniq<'a>(rows: impl Iterator<Item = &'a str>) -> Vec<&'a str> {
    let mut v: Vec<&str> = Vec::new();
    for r in rows {
        if !v.contains(&r) {
            v.push(r);
        }
    }
    v
}

/// Thread counts, ascending.
pub(super) fn uniq_threads(rows: &[ResultRow]) -> Vec<usize> {
    let mut t: Vec<usize> = rows.iter().map(|r| r.threads).collect();
    t.sort_unstable();
    t.dedup();
    t
}

/// A row's index label: its name (with `+MODE` for modes other than `single`), with its
/// parameters when the run has the same index name with other parameters too (`bvh` and
/// `bvh [preset=sweep]`).
pub fn index_label<'a>(row: &ResultRow, rows: impl IntoIterator<Item = &'a ResultRow>) -> String {
    let clash = rows
        .into_iter()
        .any(|r| r.index == row.index && r.params != row.params);
    match clash {
        true => format!("{} [{}]", row.index, row.params),
        false => row.index.clone(),
    }
}

/// The peers whose rows differ from brute force on some verified ray, by index name, each
/// once, in row order: the names the reports' peer notes list.
pub fn differing_peers(rows: &[ResultRow]) -> Vec<&str> {
    let mut names: Vec<&str> = Vec::new();
    for row in rows
        .iter()
        .filter(|r| r.peer_ties.is_some() && r.mismatches > 0)
    {
        if !names.contains(&base_index(row)) {
            names.push(base_index(row));
        }
    }
    names
}

/// The index a row traced: its label without the `+MODE` suffix (`bvh8+stream` -> `bvh8`).
pub(super) fn base_index(row: &ResultRow) -> &str {
    row.index.split('+').next().unwrap_or(&row.index)
}
