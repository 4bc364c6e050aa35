//! Seeded procedural scene generators and the built-in default scenes.
//!
//! Every generator takes a target primitive count `n` (1k to 4M and beyond) and, where it is
//! random, a seed; the same arguments always give the same scene.

mod icosphere;
mod random;
mod surfaces;

pub use icosphere::{icosphere, icosphere_mesh};
pub use random::{slivers, sphere_field, triangle_soup};
pub use surfaces::{flat, level_for, room, teapot_in_stadium, terrain};

use super::{Scene, SceneError};

/// Generator names accepted by [`generate`] and as built-in scene names.
pub const GENERATOR_NAMES: &[&str] = &[
    "icosphere",
    "spheres",
    "soup",
    "terrain",
    "stadium",
    "slivers",
    "room",
    "flat",
    "mixed",
];

/// Names accepted by [`builtin`]: every generator, at its default size.
pub const BUILTIN_NAMES: &[&str] = GENERATOR_NAMES;

/// Default primitive count of a built-in scene.
pub const DEFAULT_SIZE: usize = 20_000;

/// Default seed of the random generators.
pub const DEFAULT_SEED: u64 = 1;

/// Generates scene `name` with about `n` primitives from `seed`; `None` for an unknown name.
pub fn generate(name: &str, n: usize, seed: u64) -> Option<Scene> {
    let tris = |t| Scene::from_triangles(name, t);
    Some(match name {
        "icosphere" => tris(icosphere(level_for(n))),
        "spheres" => Scene {
            name: name.to_owned(),
            spheres: sphere_field(n, seed),
            ..Scene::default()
        },
        "soup" => tris(triangle_soup(n, seed)),
        "terrain" => tris(terrain(n)),
        "stadium" => tris(teapot_in_stadium(n)),
        "slivers" => tris(slivers(n, seed)),
        "room" => tris(room(n)),
        "flat" => tris(flat(n)),
        "mixed" => {
            // Half triangles (an icosphere of radius 0.3 at the centre), half spheres around it.
            let mut s = tris(
                icosphere(level_for(n / 2))
                    .into_iter()
                    .map(|t| {
                        crate::geometry::Triangle::new(
                            t.v[0] * 0.3 + 0.5,
                            t.v[1] * 0.3 + 0.5,
                            t.v[2] * 0.3 + 0.5,
                        )
                    })
                    .collect(),
            );
            s.spheres = sphere_field(n / 2, seed);
            s
        }
        _ => return None,
    })
}

/// A built-in scene by name at [`DEFAULT_SIZE`], or `None` for an unknown name.
pub fn builtin(name: &str) -> Option<Result<Scene, SceneError>> {
    let scene = generate(name, DEFAULT_SIZE, DEFAULT_SEED)?;
    Some(scene.validate().map(|_| scene))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_builtin_is_valid() {
        for name in BUILTIN_NAMES {
            let s = builtin(name).unwrap().unwrap();
            assert!(s.len() > 1000, "{name}: {}", s.len());
        }
        assert!(builtin("nope").is_none());
        let m = generate("mixed", 2000, 1).unwrap();
        assert!(!m.triangles.is_empty() && !m.spheres.is_empty());
    }
}
