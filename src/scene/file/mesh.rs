//! The mesh file a `[[mesh]]` table or a `--scene` path names, loaded by its extension (in any
//! case): `.ply` as PLY, `.gltf` and `.glb` as glTF, anything else as OBJ; a `.toml` scene file
//! is refused as a mesh.

use crate::scene::triangle_mesh::TriangleMesh;
use crate::scene::{SceneError, gltf, obj, ply};
use std::path::Path;

/// Loads the mesh file at `path` (see the module doc).
pub fn load_mesh(path: &Path) -> Result<TriangleMesh, SceneError> {
    let ext = path.extension().map(|e| e.to_string_lossy().to_lowercase());
    match ext.as_deref() {
        Some("toml") => Err(SceneError::Invalid(
            path.display().to_string(),
            "this is a scene file (.toml), not a mesh: a [[mesh]] path names an .obj, .ply, .gltf or .glb file; \
             copy that scene's tables into this file instead"
                .into(),
        )),
        Some("ply") => ply::load_ply(path),
        Some("gltf" | "glb") => gltf::load_gltf(path),
        _ => obj::load_obj(path),
    }
}
