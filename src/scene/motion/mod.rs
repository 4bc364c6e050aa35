//! Scenes that move: a [`Motion`] deforms a scene's primitives over time, vertex by vertex,
//! keeping their number, kinds and ids (the topology), so an index built on one frame can be
//! refitted to the next ([`crate::index::TraceIndex::refit`]).
//!
//! - `twist`: the scene turns about the vertical axis through its centre, by an angle that grows
//!   with height and with time ([`twist`]).
//! - `wave`: a travelling wave lifts and lowers the scene vertically ([`wave`]).
//! - `cloth`: the scene falls like a sheet and drapes over a ball ([`cloth`]).
//! - `keyframes`: the scene file's keyframed entries move rigidly, each by its own keys
//!   ([`keyframed_geometry`]).
//!
//! A motion is a pure function of the rest pose and the time `t` in `[0, 1]` (first to last
//! frame): the same spec and frame give the same primitives, bit for bit. Under the three
//! deformations triangle corners and sphere centres move, spheres keep their radius, and the
//! other shapes (boxes, polygons, ...) stay where they are; under `keyframes` a keyframed
//! entry's shapes turn and move with it.

pub mod cloth;
mod keyframed;
mod spec;
pub mod twist;
pub mod wave;

pub use keyframed::keyframed_geometry;
pub use spec::MotionSpec;

use super::{Scene, SceneGeometry};
use crate::geometry::{Aabb, Sphere, Triangle};
use glam::Vec3A;
use rayon::prelude::*;
use std::sync::Arc;

/// A deformation of space over time: where the rest-pose point `p` is at time `t`.
pub trait Motion: Sync {
    /// The position at time `t` (`0..=1`) of the point at `p` in the rest pose, whose bounds
    /// are `rest`.
    fn place(&self, p: Vec3A, rest: &Aabb, t: f32) -> Vec3A;
}

/// The primitives of `scene` at time `t` under `motion` (triangle corners and sphere centres
/// placed; shapes unmoved), in the shared form indices are built from.
pub fn frame_geometry(scene: &Scene, motion: &dyn Motion, t: f32) -> SceneGeometry {
    let rest = scene.bounds();
    let place = |p: Vec3A| motion.place(p, &rest, t);
    let triangles: Vec<Triangle> = scene
        .triangles
        .par_iter()
        .map(|tri| Triangle {
            v: tri.v.map(place),
        })
        .collect();
    let spheres: Vec<Sphere> = scene
        .spheres
        .iter()
        .map(|s| Sphere::new(place(s.center), s.radius))
        .collect();
    SceneGeometry {
        triangles: Arc::from(triangles),
        spheres: Arc::from(spheres),
        shapes: Arc::from(scene.shapes.as_slice()),
        // A moved frame is not the placements' scene any more: traced flattened.
        instances: None,
    }
}

/// Where `x` lies from `min` to `max`, as a fraction (0 at `min`, 1 at `max`), or `flat` when
/// the extent `max - min` is not positive.
fn fraction(x: f32, min: f32, max: f32, flat: f32) -> f32 {
    let extent = max - min;
    match extent > 0.0 {
        true => (x - min) / extent,
        false => flat,
    }
}
