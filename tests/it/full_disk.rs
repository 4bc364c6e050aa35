//! A full disk (stdout on `/dev/full`): every command that prints ends with one message and a
//! non-zero exit, never a panic and never a silent success (issue 47, case 6).

use crate::common::cli::{Suite, accelbench, write_rays};
use std::process::{Command, Stdio};

/// Runs the binary with `args` and stdout on `/dev/full`; asserts the failure it must report.
fn fails_on_full_disk(args: &[&str]) {
    let full = std::fs::OpenOptions::new()
        .write(true)
        .open("/dev/full")
        .expect("/dev/full exists on Linux");
    let out = Command::new(env!("CARGO_BIN_EXE_accelbench"))
        .args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .stdout(Stdio::from(full))
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{args:?}: {err}");
    assert!(!err.contains("panicked"), "{args:?} panicked:\n{err}");
    assert_eq!(
        err.matches("error: writing to standard output").count(),
        1,
        "{args:?}:\n{err}"
    );
}

#[test]
fn every_printing_command_fails_cleanly_on_a_full_disk() {
    let dir = tempfile::tempdir().unwrap();
    let (rays, report) = (dir.path().join("r.rays"), dir.path().join("report"));
    let scene = "icosphere:n=200";
    write_rays(&rays, scene, "primary", &["--size", "8"]);
    fails_on_full_disk(&["--help"]);
    fails_on_full_disk(&["info", "--scene", scene]);
    let r = rays.to_str().unwrap();
    fails_on_full_disk(&["trace", "--scene", scene, "--rays", r]);
    fails_on_full_disk(&Suite::verify(scene, "bvh", "primary").args());
    fails_on_full_disk(&Suite::run(scene, "bvh", "primary", &report).args());
    // The report was written before the verdict failed to print.
    assert!(report.join("results.csv").exists());
    let report = report.to_str().unwrap();
    fails_on_full_disk(&["compare", report, report]);
    // Usage errors still go to stderr with clap's exit code.
    assert_eq!(accelbench(&["--no-such-flag"]).status.code(), Some(2));
}
