//! Temporary files for the tests that write reports, rays or meshes.

use std::path::PathBuf;
use tempfile::TempDir;

/// A fresh temporary folder and the path `name` inside it (not created). The folder and all in
/// it are removed when the returned [`TempDir`] is dropped: bind it (`let (_tmp, out) = ...`)
/// for as long as the path is used.
pub fn temp_path(name: &str) -> (TempDir, PathBuf) {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join(name);
    (dir, path)
}
