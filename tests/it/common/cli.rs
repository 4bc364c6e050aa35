//! Running the `accelbench` binary from tests, and the shared meshes they read.

use std::path::PathBuf;
use std::process::{Command, Output};

/// Runs the binary with `args` from the crate's root, so `scenes/` and `../shared` resolve.
pub fn accelbench(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_accelbench"))
        .args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .expect("the accelbench binary runs")
}

/// Runs `args`, asserts a zero exit (printing stderr otherwise) and returns stdout.
pub fn accelbench_ok(args: &[&str]) -> String {
    let out = accelbench(args);
    assert!(
        out.status.success(),
        "{args:?} failed:\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8_lossy(&out.stdout).into_owned()
}

/// Runs `args`, expects a non-zero exit without a panic, and every `expected` piece in stderr.
pub fn accelbench_fails(args: &[&str], expected: &[&str]) {
    let out = accelbench(args);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success(), "{args:?} should fail; stderr: {err}");
    for e in expected {
        assert!(
            err.contains(e),
            "{args:?}: expected '{e}' in stderr:\n{err}"
        );
    }
    assert!(!err.contains("panicked"), "{args:?} panicked:\n{err}");
}

/// Runs `accelbench sweep` with `args` and `--out out`, asserts a zero exit and that both
/// charts of the primary rays were written, and returns `primary.csv`.
pub fn sweep_ok(args: &[&str], out: &std::path::Path) -> String {
    let mut all = vec!["sweep"];
    all.extend_from_slice(args);
    all.extend(["--out", out.to_str().unwrap()]);
    accelbench_ok(&all);
    for f in ["primary-rays_per_s.svg", "primary-build_ms.svg"] {
        assert!(out.join(f).exists(), "{f}");
    }
    std::fs::read_to_string(out.join("primary.csv")).unwrap()
}

/// `../shared/meshes/<name>` when present; otherwise `None`, with a line saying the test part
/// that needs it is skipped.
pub fn shared_mesh(name: &str) -> Option<PathBuf> {
    let p = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../shared/meshes")
        .join(name);
    if !p.exists() {
        eprintln!("skipped: {} not found", p.display());
    }
    p.exists().then_some(p)
}
