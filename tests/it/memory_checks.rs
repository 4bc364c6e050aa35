//! A run, a verify or a ray file whose ray sets would not fit the memory budget is refused
//! before anything is allocated, with one message: what, how much, the budget, and which option
//! to lower (issue 47, case 2). A tiny `--memory-budget` makes these deterministic.

use crate::common::cli::{accelbench_fails, accelbench_ok};

#[test]
fn a_primary_set_over_the_budget_is_refused_before_the_run() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("r");
    accelbench_fails(
        &[
            "run",
            "--quick",
            "--scenes",
            "soup:n=100",
            "--indices",
            "bvh",
            "--rays",
            "primary",
            "--primary-size",
            "8192",
            "--repeats",
            "1",
            "--threads",
            "1",
            "--memory-budget",
            "1G",
            "--out",
            out.to_str().unwrap(),
        ],
        &[
            "not enough memory: the primary rays of scene",
            "(67108864 rays",
            "over the memory budget of 1.0 GiB (--memory-budget)",
            "lower --primary-size (8192)",
        ],
    );
    assert!(!out.exists(), "a refused run left a report folder");
}

#[test]
fn verify_names_the_incoherent_count() {
    accelbench_fails(
        &[
            "verify",
            "--quick",
            "--scenes",
            "soup:n=100",
            "--indices",
            "bvh",
            "--rays",
            "incoherent",
            "--incoherent",
            "1000000",
            "--memory-budget",
            "10M",
        ],
        &["the incoherent rays", "lower --incoherent (1000000)"],
    );
}

#[test]
fn a_ray_file_over_the_budget_is_refused_and_one_within_is_written() {
    let tmp = tempfile::tempdir().unwrap();
    let f = tmp.path().join("a.rays");
    let path = f.to_str().unwrap();
    let base = ["rays", "--scene", "soup:n=100", "--out", path];
    accelbench_fails(
        &[
            &base[..],
            &[
                "--set",
                "primary",
                "--size",
                "16384",
                "--memory-budget",
                "1G",
            ],
        ]
        .concat(),
        &[
            "not enough memory: 268435456 primary rays",
            "lower --size (16384)",
        ],
    );
    accelbench_fails(
        &[
            &base[..],
            &[
                "--set",
                "incoherent",
                "--count",
                "100000",
                "--memory-budget",
                "1M",
            ],
        ]
        .concat(),
        &["lower --count (100000)"],
    );
    assert!(!f.exists());
    accelbench_ok(
        &[
            &base[..],
            &[
                "--set",
                "incoherent",
                "--count",
                "1000",
                "--memory-budget",
                "1M",
            ],
        ]
        .concat(),
    );
    assert_eq!(std::fs::metadata(&f).unwrap().len(), 32 * 1000);
}

#[test]
fn a_budget_that_is_not_an_amount_is_a_usage_error() {
    accelbench_fails(
        &[
            "verify",
            "--quick",
            "--scenes",
            "soup:n=100",
            "--memory-budget",
            "lots",
        ],
        &["'lots' is not an amount of memory"],
    );
}
