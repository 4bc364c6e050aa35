//! Seeded procedural scene generators and the built-in default scenes.
//!
//! Every generator takes a target primitive count `n` (1k to 4M and beyond) and, where it is
//! random, a seed; the same arguments always give the same scene.

mod city;
mod icosphere;
mod random;
mod shapes;
mod spec;
mod surfaces;

pub use city::{CITY_EYE, CITY_LOOK_AT, city};
pub use icosphere::{icosphere, icosphere_mesh};
pub use random::{slivers, sphere_field, triangle_soup};
pub use shapes::shape_field;
pub use spec::{GeneratorSpec, MAX_GENERATED};
pub use surfaces::{flat, level_for, room, teapot_in_stadium, terrain};

use super::{CameraSpec, PointLight, Scene, SceneError};
use glam::Vec3;

/// Generator names accepted by [`generate`] and as built-in scene names (`city` last: see
/// [`BUILTIN_NAMES`]).
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
    "shapes",
    "city",
];

/// The scenes `run` takes by default, at its scene size: every generator but the last, `city`,
/// which is for studies at scale (`city:n=10000000`) and would add a tenth to the default run's
/// time.
pub const BUILTIN_NAMES: &[&str] = GENERATOR_NAMES.split_at(GENERATOR_NAMES.len() - 1).0;

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
        "room" => Scene {
            // The protocol camera looks at the closed box from outside; this one is inside.
            camera: Some(CameraSpec {
                eye: Vec3::new(0.5, 0.5, 0.95),
                look_at: Vec3::new(0.5, 0.4, 0.0),
                up: Vec3::Y,
                fov_deg: 70.0,
            }),
            lights: vec![PointLight {
                position: Vec3::new(0.5, 0.9, 0.5),
                intensity: Vec3::ONE,
            }],
            ..tris(room(n))
        },
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
        "shapes" => shape_field(name, n, seed),
        "city" => Scene {
            camera: Some(CameraSpec {
                eye: CITY_EYE.into(),
                look_at: CITY_LOOK_AT.into(),
                up: Vec3::Y,
                fov_deg: 60.0,
            }),
            ..tris(city(n, seed))
        },
        _ => return None,
    })
}

/// A built-in scene: a generator name, optionally with size and seed (`soup`,
/// `stadium:n=1000000`, `soup:n=100000,seed=3`; see [`GeneratorSpec::parse`]). `None` when the
/// name is not a generator; `Some(Err)` for bad parameters.
pub fn builtin(arg: &str) -> Option<Result<Scene, SceneError>> {
    match GeneratorSpec::parse(arg) {
        Err(SceneError::UnknownScene(..)) => None,
        spec => Some(spec.and_then(|s| s.generate())),
    }
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
        assert_eq!(GENERATOR_NAMES.last(), Some(&"city"));
        assert_eq!(BUILTIN_NAMES.len() + 1, GENERATOR_NAMES.len());
        let room = generate("room", 2000, 1).unwrap();
        let inside = |p: Vec3| room.bounds().contains(p.into());
        assert!(inside(room.camera.unwrap().eye) && inside(room.lights[0].position));
        let m = generate("mixed", 2000, 1).unwrap();
        assert!(!m.triangles.is_empty() && !m.spheres.is_empty());
    }

    /// Every generator gives within a factor of 2 of the requested count at 1k; the cheap ones
    /// also at 4M (one at a time, about 0.2 GB each). The structured generators' arithmetic at
    /// large sizes is checked in `surfaces` without generating.
    #[test]
    fn sizes_within_factor_two_from_1k_to_4m() {
        let within = |name: &str, n: usize| {
            let len = generate(name, n, 1).unwrap().len();
            assert!(len >= n / 2 && len <= n * 2, "{name}: {len} for n = {n}");
        };
        for name in GENERATOR_NAMES {
            within(name, 1000);
        }
        for name in ["soup", "spheres", "terrain", "room", "city"] {
            within(name, 4_000_000);
        }
    }
}
