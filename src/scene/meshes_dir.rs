//! The `meshes/` pickup: every mesh file (`.obj`, `.ply`, `.gltf`, `.glb`) a user or
//! `accelbench gen` puts in a directory.

use super::SceneError;
use super::triangle_mesh::is_mesh_path;
use std::path::{Path, PathBuf};

/// The mesh files (extensions of [`super::triangle_mesh::MESH_EXTENSIONS`], in any case)
/// directly in `dir`, sorted by path. A directory that
/// does not exist holds no meshes (an empty list); one that cannot be read is an error.
/// Subdirectories and other files (README, `.toml`) are ignored.
pub fn meshes_in(dir: &Path) -> Result<Vec<PathBuf>, SceneError> {
    let io = |source| SceneError::Io {
        path: dir.to_owned(),
        cause: source,
    };
    let entries = match std::fs::read_dir(dir) {
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(Vec::new()),
        other => other.map_err(io)?,
    };
    let mut meshes = Vec::new();
    for entry in entries {
        let path = entry.map_err(io)?.path();
        if is_mesh_path(&path) && path.is_file() {
            meshes.push(path);
        }
    }
    meshes.sort();
    Ok(meshes)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lists_obj_files_sorted() {
        let dir = tempfile::tempdir().unwrap();
        for f in ["b.obj", "a.OBJ", "README.md", "c.toml", "d.ply", "e.bin"] {
            std::fs::write(dir.path().join(f), "").unwrap();
        }
        std::fs::create_dir(dir.path().join("sub.obj")).unwrap();
        let names: Vec<_> = meshes_in(dir.path())
            .unwrap()
            .iter()
            .map(|p| p.file_name().unwrap().to_string_lossy().into_owned())
            .collect();
        assert_eq!(names, ["a.OBJ", "b.obj", "d.ply"]);
        assert!(meshes_in(&dir.path().join("absent")).unwrap().is_empty());
        assert!(meshes_in(&dir.path().join("b.obj")).is_err());
    }
}
