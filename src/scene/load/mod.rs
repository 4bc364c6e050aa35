//! Resolving a `--scene` argument ([`load_scene`]), in a folder of its own beside the sources it
//! picks from: a mesh file (OBJ, PLY, glTF; [`file::mesh`]), a TOML scene file ([`crate::scene::file`]) or a built-in generator
//! ([`crate::scene::generators`]).

use crate::scene::{Scene, SceneError, file, generators};
use std::path::Path;

/// Resolves a `--scene` argument: a path to an `.obj`, `.ply`, `.gltf`, `.glb` or `.toml` file
/// (extension in any case),
/// or a built-in scene name with optional parameters (`soup`, `stadium:n=1000000`,
/// `soup:n=100000,seed=3`; see [`generators::GeneratorSpec`]).
pub fn load_scene(arg: &str) -> Result<Scene, SceneError> {
    let path = Path::new(arg);
    let ext = path.extension().map(|e| e.to_string_lossy().to_lowercase());
    match ext.as_deref() {
        Some("obj" | "ply" | "gltf" | "glb") => {
            Scene::from_mesh(path, file::mesh::load_mesh(path)?)
        }
        Some("toml") => file::load_scene_file(path),
        _ => generators::builtin(arg).unwrap_or_else(|| {
            Err(SceneError::UnknownScene(
                arg.to_owned(),
                generators::GENERATOR_NAMES.join(", "),
            ))
        }),
    }
}
