//! `accelbench run --shard K/N` and `accelbench merge`: shards 1/2 and 2/2 of a run merge into
//! the rows of the unsharded run (timings aside), in its order; an incomplete set of shards is
//! refused with the missing shard named.

use accelbench::harness::suite::ResultRow;
use std::path::Path;

use crate::common;
use common::cli::{Suite, accelbench};

fn run(out: &Path, shard: &str) {
    let scenes = "icosphere:n=300,soup:n=300,seed=2";
    Suite::run(scenes, "bvh,grid,octree", "primary,shadow", out)
        .with("--picture-size", "16")
        .with("--shard", shard)
        .ok();
}

/// A row without its timings (build and trace times and the rates derived from them).
fn untimed(r: &ResultRow) -> String {
    let mut r = r.clone();
    (r.build_ms, r.trace_ms_median, r.trace_ms_spread) = (0.0, 0.0, 0.0);
    (r.mrays_per_s, r.mtests_per_s) = (0.0, 0.0);
    (r.mrays_ci_low, r.mrays_ci_high) = (0.0, 0.0);
    // A parallel build's peak heap depends on how its threads interleave.
    r.peak_build_bytes = None;
    format!("{r:?}")
}

fn rows(dir: &Path) -> Vec<String> {
    csv::Reader::from_path(dir.join("results.csv"))
        .unwrap()
        .deserialize::<ResultRow>()
        .map(|r| untimed(&r.unwrap()))
        .collect()
}

#[test]
fn two_shards_merge_to_the_whole_run() {
    let dir = tempfile::tempdir().unwrap();
    let p = |n: &str| dir.path().join(n);
    run(&p("whole"), "1/1");
    run(&p("s1"), "1/2");
    run(&p("s2"), "2/2");
    let (s1, s2) = (rows(&p("s1")), rows(&p("s2")));
    assert!(!s1.is_empty() && !s2.is_empty(), "each shard has work");
    // Shards give their folders in any order.
    let out = p("merged");
    let o = accelbench(&[
        "merge",
        p("s2").to_str().unwrap(),
        p("s1").to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert_eq!(rows(&out), rows(&p("whole")));
    assert_eq!(s1.len() + s2.len(), rows(&out).len());
    let html = std::fs::read_to_string(out.join("index.html")).unwrap();
    assert!(html.contains("id=\"verdict\""));
    for pic in [
        "pictures/soup_n_300_seed_2_octree_tests.png",
        "pictures/icosphere_n_300_seed_1_shaded.png",
    ] {
        assert!(out.join(pic).is_file(), "{pic} copied");
    }

    let o = accelbench(&[
        "merge",
        p("s1").to_str().unwrap(),
        "--out",
        p("m2").to_str().unwrap(),
    ]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        !o.status.success() && err.contains("shard 2/2 is missing"),
        "{err}"
    );
    let o = accelbench(&["run", "--shard", "3/2"]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success() && err.contains("K/N"), "{err}");
}
