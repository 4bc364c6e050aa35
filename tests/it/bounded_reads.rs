//! Input files are checked as they are read, not after they are read whole (issue 47, case 3):
//! a `.rays` file's bad first record is reported at once and `--limit N` reads N records, and a
//! binary file given as OBJ is refused by its first bytes. The large inputs are sparse files of
//! zeros (no disk used), which the old whole-file reads took seconds and gigabytes over.

use crate::common::cli::{accelbench, accelbench_fails};
use crate::common::temp::temp_path;
use std::time::{Duration, Instant};

/// A sparse file of `len` zero bytes at `path`, starting with `head`.
fn sparse(path: &std::path::Path, head: &[u8], len: u64) {
    std::fs::write(path, head).unwrap();
    std::fs::OpenOptions::new()
        .write(true)
        .open(path)
        .unwrap()
        .set_len(len)
        .unwrap();
}

/// `args` fail within `within` with every `expected` piece in stderr.
fn fails_quickly(args: &[&str], expected: &[&str], within: Duration) {
    let start = Instant::now();
    accelbench_fails(args, expected);
    let took = start.elapsed();
    assert!(
        took < within,
        "{args:?} took {took:?}: the file was read whole"
    );
}

const GIB: u64 = 1 << 30;

/// One valid ray record: from (0.25, 0.25, -5) along +z.
fn good_record() -> Vec<u8> {
    [0.25f32, 0.25, -5.0, 0.0, 0.0, 0.0, 1.0, f32::INFINITY]
        .iter()
        .flat_map(|x| x.to_le_bytes())
        .collect()
}

#[test]
fn a_bad_first_ray_record_is_reported_before_the_file_is_read() {
    let (_tmp, f) = temp_path("zeros.rays");
    sparse(&f, &[], 2 * GIB);
    fails_quickly(
        &[
            "trace",
            "--scene",
            "icosphere:n=100",
            "--rays",
            f.to_str().unwrap(),
        ],
        &["record 0 is not a valid ray"],
        Duration::from_secs(5),
    );
}

#[test]
fn a_limit_reads_only_the_records_it_traces() {
    let (_tmp, f) = temp_path("ten.rays");
    // Ten good records, then zeros (invalid rays) up to 2 GiB.
    sparse(&f, &good_record().repeat(10), 2 * GIB);
    let start = Instant::now();
    let out = accelbench(&[
        "trace",
        "--scene",
        "icosphere:n=100",
        "--rays",
        f.to_str().unwrap(),
        "--limit",
        "10",
    ]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{err}");
    assert!(String::from_utf8_lossy(&out.stdout).contains("rays:             10"));
    assert!(
        start.elapsed() < Duration::from_secs(5),
        "{:?}",
        start.elapsed()
    );
    // Without the limit, record 10 is reported.
    accelbench_fails(
        &[
            "trace",
            "--scene",
            "icosphere:n=100",
            "--rays",
            f.to_str().unwrap(),
        ],
        &["record 10 is not a valid ray"],
    );
}

#[test]
fn a_binary_file_given_as_obj_is_refused_by_its_first_bytes() {
    let (_tmp, f) = temp_path("zeros.obj");
    sparse(&f, b"v 0 0 0\n", 2 * GIB);
    fails_quickly(
        &["info", "--scene", f.to_str().unwrap()],
        &["byte 8 is a NUL byte", "binary file, not OBJ text"],
        Duration::from_secs(5),
    );
}
