//! A run, a verify or a ray file whose ray sets would not fit the memory budget is refused
//! before anything is allocated, with one message: what, how much, the budget, and which option
//! to lower (issue 47, case 2). A tiny `--memory-budget` makes these deterministic.

use crate::common::cli::{Suite, accelbench_fails, accelbench_ok};

#[test]
fn a_primary_set_over_the_budget_is_refused_before_the_run() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("r");
    Suite::run("soup:n=100", "bvh", "primary", &out)
        .without("--quiet")
        .without("--picture-size")
        .with("--primary-size", "8192")
        .with("--memory-budget", "1G")
        .fails(&[
            "not enough memory: the primary rays of scene",
            "(67108864 rays",
            "over the memory budget of 1.0 GiB (--memory-budget)",
            "lower --primary-size (8192)",
        ]);
    assert!(!out.exists(), "a refused run left a report folder");
}

#[test]
fn verify_names_the_incoherent_count() {
    Suite::verify("soup:n=100", "bvh", "incoherent")
        .with("--incoherent", "1000000")
        .with("--memory-budget", "10M")
        .fails(&["the incoherent rays", "lower --incoherent (1000000)"]);
}

#[test]
fn a_ray_file_over_the_budget_is_refused_and_one_within_is_written() {
    let tmp = tempfile::tempdir().unwrap();
    let f = tmp.path().join("a.rays");
    let path = f.to_str().unwrap();
    let rays = |set: &'static str, amount: &'static str, count: &'static str, budget| {
        let head = ["rays", "--scene", "soup:n=100", "--out", path, "--set", set];
        [&head[..], &[amount, count, "--memory-budget", budget]].concat()
    };
    accelbench_fails(
        &rays("primary", "--size", "16384", "1G"),
        &[
            "not enough memory: 268435456 primary rays",
            "lower --size (16384)",
        ],
    );
    accelbench_fails(
        &rays("incoherent", "--count", "100000", "1M"),
        &["lower --count (100000)"],
    );
    assert!(!f.exists());
    accelbench_ok(&rays("incoherent", "--count", "1000", "1M"));
    assert_eq!(std::fs::metadata(&f).unwrap().len(), 32 * 1000);
}

#[test]
fn a_budget_that_is_not_an_amount_is_a_usage_error() {
    Suite::verify("soup:n=100", "bvh", "primary")
        .with("--memory-budget", "lots")
        .fails(&["'lots' is not an amount of memory"]);
}
