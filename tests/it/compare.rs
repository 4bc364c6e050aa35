//! `accelbench compare`: a run against itself changes nothing and passes any gate; against a
//! copy with one row twice as slow it exits non-zero and names that row, and a row the copy
//! lacks is listed as missing, not an error.

use accelbench::harness::suite::ResultRow;
use std::path::Path;

use crate::common;
use crate::common::temp::temp_path;
use common::cli::{Suite, accelbench, accelbench_fails};

fn read_rows(dir: &Path) -> Vec<ResultRow> {
    csv::Reader::from_path(dir.join("results.csv"))
        .unwrap()
        .deserialize()
        .collect::<Result<_, _>>()
        .unwrap()
}

fn write_rows(dir: &Path, rows: &[ResultRow]) {
    std::fs::create_dir_all(dir).unwrap();
    let mut w = csv::Writer::from_path(dir.join("results.csv")).unwrap();
    for r in rows {
        w.serialize(r).unwrap();
    }
    w.flush().unwrap();
}

#[test]
fn a_row_twice_as_slow_fails_the_gate_and_is_named() {
    let (dir, a) = temp_path("a");
    Suite::run("icosphere:n=400", "bvh,grid", "primary,incoherent", &a)
        .without("--repeats")
        .ok();
    let (a_s, gate) = (a.to_str().unwrap(), ["--fail-above", "20"]);

    let same = accelbench(&["compare", a_s, a_s, gate[0], gate[1]]);
    let text = String::from_utf8_lossy(&same.stdout);
    assert!(same.status.success(), "{text}");
    assert!(
        !text.contains("FAIL") && text.contains("~ (within noise)"),
        "{text}"
    );

    // B: a copy with the grid's incoherent row twice as slow (and with no noise), and the
    // bvh's primary row missing.
    let mut rows = read_rows(&a);
    let slow = rows
        .iter()
        .position(|r| r.index == "grid" && r.ray_set == "incoherent")
        .unwrap();
    rows[slow].trace_ms_median *= 2.0;
    rows[slow].trace_ms_spread = 0.0;
    rows[slow].mrays_per_s /= 2.0;
    rows[slow].mrays_ci_low = rows[slow].mrays_per_s;
    rows[slow].mrays_ci_high = rows[slow].mrays_per_s;
    rows.retain(|r| !(r.index == "bvh" && r.ray_set == "primary"));
    let b = dir.path().join("b");
    write_rows(&b, &rows);
    let o = accelbench(&["compare", a_s, b.to_str().unwrap(), gate[0], gate[1]]);
    let (out, err) = (
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr),
    );
    assert!(!o.status.success(), "{out}");
    let named = "icosphere:n=400,seed=1 / grid [";
    assert!(
        err.contains(named) && err.contains("/ incoherent / 1 threads"),
        "{err}"
    );
    assert!(err.contains("1 row(s)"), "only that row fails: {err}");
    assert!(out.contains("FAIL: 100% slower"), "{out}");
    assert!(out.contains("Rows of A missing in B (1)"), "{out}");
    // Without a gate the slowdown is reported but the command succeeds.
    assert!(
        accelbench(&["compare", a_s, b.to_str().unwrap()])
            .status
            .success()
    );
    // A folder without results.csv is a clear error.
    let not_a_report = dir.path().to_str().unwrap();
    accelbench_fails(&["compare", a_s, not_a_report], &["results.csv"]);
}
