//! `index.html` of a run: the verdict matrix read back with an HTML parser equals what
//! `results.csv` says (the fastest index per scene and ray set at the most threads, every
//! index's speed over the fastest's), the page needs nothing from outside, and every picture it
//! shows exists. With Debian's `chromium` installed, a headless render loads the page.

use accelbench::harness::suite::ResultRow;
use scraper::{Html, Selector};
use std::collections::HashMap;
use std::path::Path;
use std::process::Command;

use crate::common;
use crate::common::temp::temp_path;

fn quick_run(out: &Path) {
    let stdout = common::cli::accelbench_ok(&[
        "run",
        "--quick",
        "--quiet",
        "--scenes",
        "icosphere:n=600,soup:n=500,seed=2",
        "--indices",
        "bvh,grid,brute",
        "--rays",
        "primary,shadow",
        "--threads",
        "1,2",
        "--repeats",
        "2",
        "--picture-size",
        "32",
        "--out",
        out.to_str().unwrap(),
    ]);
    // The terminal gets the short verdict and the page's path, not the whole summary.
    assert!(stdout.contains("Verdict at 2 thread(s)"), "{stdout}");
    assert!(stdout.contains("index.html"), "{stdout}");
    assert!(!stdout.contains("## Plots"), "{stdout}");
}

fn sel(s: &str) -> Selector {
    Selector::parse(s).unwrap()
}

#[test]
fn verdict_matrix_matches_results_csv() {
    let (_dir, out) = temp_path("report");
    quick_run(&out);
    let rows: Vec<ResultRow> = csv::Reader::from_path(out.join("results.csv"))
        .unwrap()
        .deserialize()
        .collect::<Result<_, _>>()
        .unwrap();
    let html = std::fs::read_to_string(out.join("index.html")).unwrap();
    let page = Html::parse_document(&html);
    assert!(page.errors.is_empty(), "parse errors: {:?}", page.errors);

    // What results.csv says, per (scene, set) at the most threads: index -> Mrays/s.
    let most = rows.iter().map(|r| r.threads).max().unwrap();
    let mut expected: HashMap<(String, String), HashMap<String, f64>> = HashMap::new();
    let mut ci: HashMap<(String, String), HashMap<String, (f64, f64)>> = HashMap::new();
    for r in rows.iter().filter(|r| r.threads == most) {
        let key = (r.scene.clone(), r.ray_set.clone());
        expected
            .entry(key.clone())
            .or_default()
            .insert(r.index.clone(), r.mrays_per_s);
        ci.entry(key)
            .or_default()
            .insert(r.index.clone(), (r.mrays_ci_low, r.mrays_ci_high));
    }
    let table_rows: Vec<_> = page.select(&sel("table#verdict tr[data-scene]")).collect();
    assert_eq!(
        table_rows.len(),
        expected.len(),
        "one matrix row per scene and set"
    );
    for tr in table_rows {
        let attr = |k: &str| tr.value().attr(k).unwrap().to_owned();
        let key = (attr("data-scene"), attr("data-set"));
        let (speeds, intervals) = (&expected[&key], &ci[&key]);
        // No index here has a batch mode of its own: one race per set, one query at a time.
        assert_eq!(attr("data-family"), "one at a time");
        assert_eq!(attr("data-threads"), most.to_string());
        let best = speeds.values().copied().fold(f64::NAN, f64::max);
        let fastest = speeds.iter().find(|(_, v)| **v == best).unwrap().0.clone();
        assert_eq!(attr("data-fastest"), fastest);
        let cells: Vec<_> = tr.select(&sel("td.ratio")).collect();
        assert_eq!(cells.len(), speeds.len(), "a cell per index with a row");
        for td in cells {
            let index = td.value().attr("data-index").unwrap();
            let ratio: f64 = td.value().attr("data-ratio").unwrap().parse().unwrap();
            let want = speeds[index] / best;
            assert_eq!(ratio, want, "{index}");
            let text: String = td.text().collect();
            // A tie (the intervals overlap the fastest's) reads `≈ 0.98`, in the fastest's colour.
            let tie = td.value().attr("class") == Some("ratio tie");
            let (lo, hi) = intervals[index];
            let (wlo, whi) = intervals[fastest.as_str()];
            assert_eq!(tie, index != fastest && hi >= wlo && whi >= lo, "{index}");
            let shown = if tie {
                format!("≈ {want:.2}")
            } else {
                format!("{want:.2}")
            };
            assert_eq!(text, shown);
            assert!(td.value().attr("style").unwrap().contains("hsl("));
        }
    }

    // Self-contained: no script, no outside assets; every picture it shows is in the folder.
    assert!(
        page.select(&sel("script, link, iframe, object, embed"))
            .next()
            .is_none()
    );
    for el in page.select(&sel("[src], [href]")) {
        for link in ["src", "href"].iter().filter_map(|a| el.value().attr(a)) {
            let outside = link.contains("://") || link.starts_with("//") || link.starts_with('/');
            assert!(!outside, "{link}: the page links outside its folder");
        }
    }
    assert!(!html.contains("url("), "no outside resources in CSS");
    let imgs: Vec<_> = page.select(&sel("img")).collect();
    assert!(!imgs.is_empty(), "the pictures are shown");
    for img in imgs {
        let src = img.value().attr("src").unwrap();
        assert!(out.join(src).is_file(), "{src} missing");
    }
    assert!(
        page.select(&sel(".chart svg")).next().is_some(),
        "charts inline"
    );
    assert!(page.select(&sel("table#cost-fit tr td")).next().is_some());
    let md = std::fs::read_to_string(out.join("summary.md")).unwrap();
    assert!(md.contains("## Cost breakdown"), "{md}");

    if let Some(browser) = chromium() {
        let o = Command::new(browser)
            .args(["--headless", "--no-sandbox", "--disable-gpu", "--dump-dom"])
            .arg(format!("file://{}", out.join("index.html").display()))
            .output()
            .unwrap();
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        let dom = String::from_utf8_lossy(&o.stdout);
        assert!(
            dom.contains("id=\"verdict\""),
            "the browser loaded the page"
        );
    }
}

/// Debian's headless-capable browser, when installed.
fn chromium() -> Option<&'static str> {
    ["chromium", "chromium-browser"].into_iter().find(|b| {
        Command::new(b)
            .arg("--version")
            .output()
            .is_ok_and(|o| o.status.success())
    })
}
