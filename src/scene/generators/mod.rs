//! Seeded procedural scene generators and the built-in default scenes.

mod icosphere;

pub use icosphere::icosphere;

use super::{Scene, SceneError};

/// Names accepted by [`builtin`].
pub const BUILTIN_NAMES: &[&str] = &["icosphere"];

/// A built-in scene by name, or `None` for an unknown name.
pub fn builtin(name: &str) -> Option<Result<Scene, SceneError>> {
    let scene = match name {
        "icosphere" => Scene::from_triangles("icosphere", icosphere(4)),
        _ => return None,
    };
    Some(scene.validate().map(|_| scene))
}
