//! The HTML report's explaining sections (the cost breakdown: fitted time per step and per
//! test, steps and tests per ray; build time and memory; the pictures) and the text helpers the
//! whole page shares (escaping, index labels).

use super::cost_fit::CostFit;
use super::fixed as num;
use super::rows::{index_label, scenes, uniq};
use super::run_notes::RunNotes;
use crate::harness::suite::ResultRow;
use std::fmt::Write as _;

/// Escapes text for HTML content and attribute values.
pub(super) fn esc(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// Index labels in first-seen order.
pub(super) fn uniq_labels(rows: &[ResultRow]) -> Vec<String> {
    let labels: Vec<String> = rows.iter().map(|r| index_label(r, rows)).collect();
    uniq(labels.iter().map(String::as_str))
        .into_iter()
        .map(str::to_owned)
        .collect()
}

fn header(first: &[&str], labels: &[String]) -> String {
    let mut s = "<thead><tr>".to_owned();
    for h in first {
        let _ = write!(s, "<th>{h}</th>");
    }
    for l in labels {
        let _ = write!(s, "<th>{}</th>", esc(l));
    }
    s.push_str("</tr></thead>");
    s
}

/// The fitted costs per index, then steps and tests per ray per scene and ray set.
pub(super) fn cost_tables(rows: &[ResultRow], fits: &[CostFit]) -> String {
    let mut s = "<h2>Why: the cost breakdown</h2>\n<p>Per index, time per node (or cell) step \
                 and per primitive test, fitted by least squares over this run's scenes and ray \
                 sets at the fewest threads: <i>ns per ray = a · steps per ray + b · tests per \
                 ray + c</i> (<i>c</i> with six or more points; costs kept non-negative). R² near 1: the model \
                 explains the times; a low R² or steps that move with tests make the split \
                 uncertain.</p>\n<table id=\"cost-fit\"><thead><tr><th>index</th>\
                 <th>ns per step (a)</th><th>ns per test (b)</th><th>ns per ray (c)</th>\
                 <th>R²</th><th>points</th></tr></thead><tbody>\n"
        .to_owned();
    for f in fits {
        let [index, numbers @ ..] = f.cells();
        let _ = write!(s, "<tr><td>{}</td>", esc(&index));
        for n in numbers {
            let _ = write!(s, "<td class=\"num\">{n}</td>");
        }
        s.push_str("</tr>\n");
    }
    s.push_str("</tbody></table>\n<p>Primitive tests / node steps per ray (counting pass):</p>\n");
    let labels = uniq_labels(rows);
    let _ = writeln!(
        s,
        "<table id=\"counts\">{}<tbody>",
        header(&["scene", "rays"], &labels)
    );
    for scene in scenes(rows) {
        let in_scene: Vec<&ResultRow> = rows.iter().filter(|r| r.scene == scene).collect();
        for set in uniq(in_scene.iter().map(|r| r.ray_set.as_str())) {
            let _ = write!(s, "<tr><td>{}</td><td>{}</td>", esc(scene), esc(set));
            for l in &labels {
                let r = in_scene
                    .iter()
                    .find(|r| r.ray_set == set && index_label(r, rows) == *l);
                match r {
                    Some(r) => {
                        let _ = write!(
                            s,
                            "<td class=\"num\">{} / {}</td>",
                            num(r.prim_tests_per_ray, 1),
                            num(r.node_visits_per_ray, 1)
                        );
                    }
                    None => s.push_str("<td class=\"na\">–</td>"),
                }
            }
            s.push_str("</tr>\n");
        }
    }
    s.push_str("</tbody></table>\n");
    s
}

/// Build time (ms), memory and the build's peak memory (bytes per primitive) per scene and index.
pub(super) fn build_tables(rows: &[ResultRow]) -> String {
    let labels = uniq_labels(rows);
    let mut s = "<h2>Build time and memory</h2>\n".to_owned();
    type Cell<'a> = &'a dyn Fn(&ResultRow) -> String;
    let per_prim = |r: &ResultRow, bytes: Option<usize>| {
        num(
            bytes.map_or(f64::NAN, |b| b as f64 / r.primitives.max(1) as f64),
            1,
        )
    };
    let tables: [(&str, &str, Cell); 3] = [
        ("build-ms", "Build time, ms (all threads):", &|r| {
            num(r.build_ms, 2)
        }),
        ("memory", "Memory, bytes per primitive:", &|r| {
            per_prim(r, Some(r.memory_bytes))
        }),
        (
            "peak-memory",
            "Peak memory during the build (structure and temporaries), bytes per primitive:",
            &|r| per_prim(r, r.peak_build_bytes),
        ),
    ];
    for (id, caption, cell) in tables {
        let _ = writeln!(
            s,
            "<p>{caption}</p><table id=\"{id}\">{}<tbody>",
            header(&["scene", "primitives"], &labels)
        );
        for scene in scenes(rows) {
            let in_scene: Vec<&ResultRow> = rows.iter().filter(|r| r.scene == scene).collect();
            let _ = write!(
                s,
                "<tr><td>{}</td><td class=\"num\">{}</td>",
                esc(scene),
                in_scene[0].primitives
            );
            for l in &labels {
                match in_scene.iter().find(|r| index_label(r, rows) == *l) {
                    Some(r) => {
                        let _ = write!(s, "<td class=\"num\">{}</td>", cell(r));
                    }
                    None => s.push_str("<td class=\"na\">–</td>"),
                }
            }
            s.push_str("</tr>\n");
        }
        s.push_str("</tbody></table>\n");
    }
    s
}

/// Per scene, the shaded render and each index's heat maps side by side.
pub(super) fn pictures_html(notes: &RunNotes) -> String {
    let groups = notes.picture_groups();
    if groups.is_empty() {
        return String::new();
    }
    let mut s = "<h2>Pictures</h2>\n<p>The shaded render (the same through every index), then \
                 each index's heat maps of primitive tests and node/cell visits per camera ray \
                 (fixed log scale: black 0, blue 1 … red 1024 and more).</p>\n"
        .to_owned();
    let fig = |s: &mut String, path: &str, caption: &str| {
        let _ = write!(
            s,
            "<figure><img src=\"{}\" alt=\"{c}\" loading=\"lazy\"><figcaption>{c}</figcaption>\
             </figure>",
            esc(path),
            c = esc(caption)
        );
    };
    for g in groups {
        let _ = write!(s, "<h3>{}</h3><div class=\"pics\">", esc(g.scene));
        for p in &g.shaded {
            fig(&mut s, p, "shaded");
        }
        s.push_str("</div>\n");
        for (index, maps) in &g.heatmaps {
            s.push_str("<div class=\"pics\">");
            for (kind, p) in maps {
                fig(&mut s, p, &format!("{index}: {kind}"));
            }
            s.push_str("</div>\n");
        }
    }
    s
}
