//! `index.html`: one self-contained page per run (inline CSS and SVG, pictures by relative
//! path, no script, no outside assets) that opens with the verdict and then explains it: the
//! verdict matrix, the cost breakdown, build time and memory, the charts, the pictures,
//! verification, machine and command.
//!
//! The verdict matrix is `table#verdict`: a `tr` per scene, ray set and mode family
//! (`data-scene`, `data-set`, `data-family`, `data-threads`, `data-fastest`: the fastest
//! correct contender) and per contender a `td.ratio` with `data-index` and `data-ratio` (its
//! Mrays/s over the fastest's, full precision; the text shows two decimals, after `≈ ` for a
//! tie, and the cell has class `tie`), or a `td.wrong` with `data-index` and `data-wrong` (its
//! wrong rays) for a contender with wrong results, so tools can read it back. `p#status` has
//! the run's status (`meta.json`'s) in `data-status`.

use super::ReportError;
use super::cost_fit::CostFit;
use super::html_sections::{build_tables, cost_tables, esc, pictures_html, uniq_labels};
use super::rows::differing_peers;
use super::run_meta::RunMeta;
use super::run_notes::RunNotes;
use super::verdict::Verdict;
use crate::harness::suite::ResultRow;
use std::fmt::Write as _;
use std::path::Path;

/// The background of a verdict cell: green for the fastest, through yellow to red at a tenth of
/// its speed or less (log scale).
pub(super) fn ratio_colour(ratio: f64) -> String {
    let t = (-ratio.log10()).clamp(0.0, 1.0);
    format!("hsl({:.0},70%,78%)", 130.0 * (1.0 - t))
}

const STYLE: &str = "body{font-family:system-ui,sans-serif;margin:2em auto;max-width:1200px;\
padding:0 1em;color:#222}h1{margin-bottom:.2em}.sub{color:#555;margin-top:0}\
table{border-collapse:collapse;margin:.6em 0 1.4em}th,td{border:1px solid #ccc;\
padding:.25em .55em}td.num,td.ratio{text-align:right;font-variant-numeric:tabular-nums}\
th{background:#f3f3f3}td.na{color:#aaa;text-align:center}.pass{background:#dff3df;\
padding:.5em 1em;border-left:5px solid #3a3}.fail{background:#fadbdb;padding:.5em 1em;\
border-left:5px solid #c33}.chart svg{max-width:100%;height:auto}\
.pics{display:flex;flex-wrap:wrap;gap:.6em}.pics figure{margin:0}\
.pics img{width:192px;image-rendering:pixelated}figcaption{font-size:.85em;color:#444}\
dl{display:grid;grid-template-columns:max-content auto;gap:.2em 1em}dt{font-weight:600}\
code{background:#f3f3f3;padding:.1em .3em}";

/// Writes `index.html` into `dir`; `plots` are the charts written there, `(title, file)`.
pub fn write_html(
    dir: &Path,
    meta: &RunMeta,
    rows: &[ResultRow],
    notes: &RunNotes,
    verdicts: &[Verdict],
    fits: &[CostFit],
    plots: &[(String, String)],
) -> Result<(), ReportError> {
    let mut s = String::with_capacity(1 << 16);
    let _ = write!(
        s,
        "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\
         <meta name=\"viewport\" content=\"width=device-width,initial-scale=1\">\
         <title>accelbench run {id}</title><style>{STYLE}</style></head><body>\n\
         <h1>accelbench run {id}</h1><p class=\"sub\">{date} · {cpu} ({cores} cores) · kernel \
         {kernel} · {repeats} timed repeats (median; {interval})</p>\n",
        id = esc(&meta.run_id),
        date = esc(&meta.date),
        cpu = esc(&meta.cpu),
        cores = meta.cores,
        kernel = esc(&meta.kernel),
        repeats = meta.repeats,
        interval = crate::harness::median_interval::describe(meta.repeats),
    );
    let _ = writeln!(
        s,
        "<p id=\"status\" data-status=\"{}\" class=\"{}\"><b>Status: {}</b></p>",
        esc(&meta.status.to_string()),
        if meta.status.is_complete() {
            "pass"
        } else {
            "fail"
        },
        esc(&meta.status.sentence())
    );
    s.push_str(&verification_banner(rows, notes));
    s.push_str(&verdict_matrix(rows, verdicts));
    s.push_str(&cost_tables(rows, fits));
    s.push_str(&build_tables(rows));
    s.push_str(&charts(dir, plots)?);
    s.push_str(&pictures_html(notes));
    s.push_str(&verification_details(notes));
    s.push_str(&machine(meta));
    s.push_str("</body></html>\n");
    std::fs::write(dir.join("index.html"), s).map_err(|e| ReportError::Write {
        path: dir.join("index.html"),
        message: e.to_string(),
    })
}

fn verification_banner(rows: &[ResultRow], notes: &RunNotes) -> String {
    let mut s = if notes.mismatch_total == 0 {
        "<p class=\"pass\"><b>Verification passed.</b> Every one of our indices returned brute \
         force's hits bit for bit on the verified rays, and they agreed with each other on every \
         ray.</p>\n"
            .to_owned()
    } else {
        format!(
            "<p class=\"fail\"><b>Verification FAILED: {} mismatching results</b> (the rays' \
             bits are in <a href=\"mismatches.txt\">mismatches.txt</a>).</p>\n",
            notes.mismatch_total
        )
    };
    if notes.peer_mismatch_total > 0 {
        let _ = writeln!(
            s,
            "<p>Outside peers ({}) differed from brute force on {} results (their own box \
             tests); reported, not a failure.</p>",
            esc(&differing_peers(rows).join(", ")),
            notes.peer_mismatch_total
        );
    }
    s
}

/// The verdict: a row per scene, ray set and mode family, a colour-scaled cell per index (ties
/// in the winner's colour, wrong contenders in red with their speed and wrong count).
fn verdict_matrix(rows: &[ResultRow], verdicts: &[Verdict]) -> String {
    let Some(first) = verdicts.first() else {
        return "<h2>Verdict</h2><p>No timed results.</p>\n".into();
    };
    let labels = uniq_labels(rows);
    let mut s = format!(
        "<h2 id=\"verdict-title\">Verdict</h2>\n<p>Per scene, ray set and mode family (one \
         query at a time, or batch), the fastest index whose results are correct (Mrays/s at {} \
         thread(s)) and every index's speed as a share of it: 1 is the fastest, 0.5 half its \
         speed. <b>≈</b>: a tie, the 95% intervals of the two medians overlap. An index with \
         wrong results never wins: its cell shows its own Mrays/s and its wrong rays, in red. \
         In the batch rows, an index without a batch mode of its own is represented by its \
         single row. Colour: green for the fastest, red at a tenth of its speed or less.</p>\n\
         <table id=\"verdict\"><thead><tr><th>scene</th><th>rays</th><th>modes</th>\
         <th>fastest</th><th>Mrays/s</th>",
        first.threads
    );
    for l in &labels {
        let _ = write!(s, "<th>{}</th>", esc(l));
    }
    s.push_str("</tr></thead><tbody>\n");
    for v in verdicts {
        let (name, best) = v
            .winner()
            .map_or(("(none correct)".to_owned(), f64::NAN), |w| {
                (w.shown(), w.mrays)
            });
        let _ = write!(
            s,
            "<tr data-scene=\"{sc}\" data-set=\"{set}\" data-family=\"{fam}\" \
             data-threads=\"{t}\" data-fastest=\"{f}\"><td>{sc}</td><td>{set}</td><td>{fam}</td>\
             <td><b>{f}</b></td><td class=\"num\">{best:.2}</td>",
            sc = esc(&v.scene),
            set = esc(&v.ray_set),
            fam = v.family.label(),
            t = v.threads,
            f = esc(&name),
        );
        for l in &labels {
            let (Some(c), Some(text)) = (v.get(l), v.cell(l)) else {
                s.push_str("<td class=\"na\">–</td>");
                continue;
            };
            match (c.wrong, v.ratio(l)) {
                (Some(n), _) => {
                    let _ = write!(
                        s,
                        "<td class=\"wrong\" data-index=\"{}\" data-wrong=\"{n}\" \
                         style=\"background:hsl(0,85%,62%)\">{}</td>",
                        esc(l),
                        esc(&text)
                    );
                }
                (None, Some(r)) => {
                    let tie = v.tied(l);
                    let _ = write!(
                        s,
                        "<td class=\"ratio{}\" data-index=\"{}\" data-ratio=\"{r:?}\" \
                         style=\"background:{}\">{}</td>",
                        if tie { " tie" } else { "" },
                        esc(l),
                        ratio_colour(if tie { 1.0 } else { r }),
                        esc(&text)
                    );
                }
                (None, None) => s.push_str("<td class=\"na\">–</td>"),
            }
        }
        s.push_str("</tr>\n");
    }
    s.push_str("</tbody></table>\n");
    s
}

/// Each chart inlined (the SVG files' content, scaled to the page's width).
fn charts(dir: &Path, plots: &[(String, String)]) -> Result<String, ReportError> {
    if plots.is_empty() {
        return Ok(String::new());
    }
    let mut s = "<h2>Charts</h2>\n".to_owned();
    for (title, file) in plots {
        let path = dir.join(file);
        let svg = std::fs::read_to_string(&path).map_err(|e| ReportError::Write {
            path: path.clone(),
            message: format!("cannot read the chart back to inline it ({e})"),
        })?;
        let _ = writeln!(
            s,
            "<h3>{}</h3><div class=\"chart\">{}</div>",
            esc(title),
            scalable_svg(&svg)
        );
    }
    Ok(s)
}

/// The SVG element of `svg` (no XML declaration), with a `viewBox` from its width and height so
/// CSS can scale it.
fn scalable_svg(svg: &str) -> String {
    let body = svg.find("<svg").map_or(svg, |i| &svg[i..]);
    if body.contains("viewBox") {
        return body.to_owned();
    }
    let attr = |name: &str| {
        let key = format!("{name}=\"");
        let head = &body[..body.find('>').unwrap_or(body.len())];
        let start = head.find(&key)? + key.len();
        head[start..].split('"').next().map(str::to_owned)
    };
    match (attr("width"), attr("height")) {
        (Some(w), Some(h)) => body.replacen("<svg", &format!("<svg viewBox=\"0 0 {w} {h}\""), 1),
        _ => body.to_owned(),
    }
}

fn verification_details(notes: &RunNotes) -> String {
    let mut s = "<h2>Verification and notes</h2>\n<ul>".to_owned();
    let verification = notes.verification.iter().map(|n| (n, "verification, "));
    for (n, kind) in verification.chain(notes.notes.iter().map(|n| (n, ""))) {
        let (scene, what, reason) = (esc(&n.scene), esc(&n.what), esc(&n.reason));
        let _ = write!(s, "<li>{scene}: {kind}{what}: {reason}</li>");
    }
    s.push_str("</ul>\n");
    s
}

fn machine(meta: &RunMeta) -> String {
    let mut s = "<h2>Machine and command</h2>\n<dl>".to_owned();
    let threads: Vec<String> = meta.threads.iter().map(usize::to_string).collect();
    for (k, v) in [
        ("date", meta.date.clone()),
        ("git revision", meta.git_revision.clone()),
        (
            "CPU",
            format!("{} ({} cores, {})", meta.cpu, meta.cores, meta.os),
        ),
        ("threads", threads.join(", ")),
        ("shard", meta.shard.to_string()),
        ("command", meta.command.clone()),
    ] {
        let _ = write!(s, "<dt>{k}</dt><dd><code>{}</code></dd>", esc(&v));
    }
    s.push_str(
        "</dl>\n<p>Files: <a href=\"results.csv\">results.csv</a>, \
                <a href=\"summary.md\">summary.md</a>, <a href=\"meta.json\">meta.json</a>.</p>\n",
    );
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn escapes_and_scales() {
        assert_eq!(esc("<a & \"b\">"), "&lt;a &amp; &quot;b&quot;&gt;");
        let svg = "<?xml version=\"1.0\"?>\n<svg width=\"960\" height=\"600\" x=\"1\"><g/></svg>";
        assert_eq!(
            scalable_svg(svg),
            "<svg viewBox=\"0 0 960 600\" width=\"960\" height=\"600\" x=\"1\"><g/></svg>"
        );
        assert_eq!(ratio_colour(1.0), "hsl(130,70%,78%)");
        assert_eq!(ratio_colour(0.01), "hsl(0,70%,78%)");
    }
}
