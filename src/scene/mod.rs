//! Scenes: primitives stored per type, lights, an optional camera, and where they came from.

mod accept;
mod area_light;
mod coordinate;
mod corners;
mod error;
pub mod file;
pub mod generators;
mod geometry;
mod geometry_traits;
pub mod gltf;
pub mod instances;
pub mod keyframes;
mod load;
mod mapped;
mod material;
mod meshes_dir;
pub mod motion;
pub mod obj;
mod obj_statements;
mod obj_text;
pub mod obj_writer;
pub mod ply;
pub mod ply_writer;
pub mod transform;
mod transform_shapes;
pub mod triangle_mesh;

pub use area_light::{AreaLight, MAX_AREA_LIGHT_SAMPLES};
pub use error::{Location, SceneError};
pub use geometry::{
    FromScene, GeometryVisitor, Mixed, SceneGeometry, Triangles, WithShapes, with_geometry,
};
pub use geometry_traits::{Geometry, GeometryWrapper, ShapeQueries};
pub use load::load_scene;
pub use material::{Material, MaterialMap};
pub use meshes_dir::meshes_in;
pub use transform_shapes::ShapeTransformError;

use crate::geometry::{Aabb, Shape, Sphere, Triangle};
use glam::{Vec3, Vec3A};
use serde::{Deserialize, Serialize};
use std::path::Path;
use std::sync::Arc;

/// A point light (position in scene units, RGB intensity).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PointLight {
    pub position: Vec3,
    #[serde(default = "white")]
    pub intensity: Vec3,
}

/// The default light intensity (point and area lights).
fn white() -> Vec3 {
    Vec3::ONE
}

/// A camera given by a scene: eye, look-at point, up, vertical field of view in degrees.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CameraSpec {
    pub eye: Vec3,
    pub look_at: Vec3,
    #[serde(default = "up_y")]
    pub up: Vec3,
    #[serde(default = "fov45")]
    pub fov_deg: f32,
}

fn up_y() -> Vec3 {
    Vec3::Y
}

fn fov45() -> f32 {
    45.0
}

/// A scene. Primitive ids: triangles `0..triangles.len()` in source order, then spheres, then
/// shapes.
#[derive(Debug, Clone, Default)]
pub struct Scene {
    pub name: String,
    pub triangles: Vec<Triangle>,
    pub spheres: Vec<Sphere>,
    /// Boxes, polygons, cylinders, cones and ellipsoids (valid by construction).
    pub shapes: Vec<Shape>,
    pub lights: Vec<PointLight>,
    pub camera: Option<CameraSpec>,
    /// Bounds the protocol's standard ray sets use: for mesh files, every vertex (an OBJ's `v`
    /// lines, a PLY's vertices, a glTF's transformed positions; also unused ones); otherwise
    /// the primitives' bounds.
    pub reference_bounds: Option<Aabb>,
    /// Materials per object (empty: every primitive uses [`Material::DEFAULT`]).
    pub materials: MaterialMap,
    /// Rectangular area lights (in addition to `lights`).
    pub area_lights: Vec<AreaLight>,
    /// The scene file's keyframed entries, in file order, with the primitives each produced
    /// (disjoint ranges). The primitives above are the static placement, the keyframes not
    /// applied; `animate` applies them ([`motion::keyframed_geometry`]).
    pub keyframed: Vec<keyframes::KeyframedObject>,
    /// The meshes and placements of a scene file with `[[instance]]` entries (`None`
    /// otherwise); the primitives above are then the flattened scene.
    pub instances: Option<Arc<instances::InstanceSet>>,
}

impl Scene {
    /// A scene of triangles only.
    pub fn from_triangles(name: impl Into<String>, triangles: Vec<Triangle>) -> Scene {
        Scene {
            name: name.into(),
            triangles,
            ..Scene::default()
        }
    }

    pub fn len(&self) -> usize {
        self.triangles.len() + self.spheres.len() + self.shapes.len()
    }

    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Bounds of all primitives.
    pub fn bounds(&self) -> Aabb {
        let t = self.triangles.iter().map(|t| t.bounds());
        let s = self.spheres.iter().map(|s| s.bounds());
        let q = self.shapes.iter().map(|s| s.bounds());
        t.chain(s).chain(q).fold(Aabb::EMPTY, Aabb::union)
    }

    /// The bounds the standard ray sets are derived from (see [`Scene::reference_bounds`]).
    pub fn ray_set_bounds(&self) -> Aabb {
        self.reference_bounds.unwrap_or_else(|| self.bounds())
    }

    /// Number of zero-area triangles (kept, and reported).
    pub fn degenerate_triangles(&self) -> usize {
        self.triangles.iter().filter(|t| t.is_degenerate()).count()
    }

    /// Checks what every index relies on: at least one primitive, finite coordinates, spheres
    /// with a finite positive radius, and fewer than `u32::MAX` primitives (shapes are checked
    /// by their constructors).
    pub fn validate(&self) -> Result<(), SceneError> {
        if self.is_empty() {
            return Err(SceneError::Empty(self.name.clone()));
        }
        if self.len() >= u32::MAX as usize {
            return Err(SceneError::Invalid(
                self.name.clone(),
                format!(
                    "{} primitives; at most {} are supported",
                    self.len(),
                    u32::MAX - 1
                ),
            ));
        }
        if let Some(i) = self
            .triangles
            .iter()
            .position(|t| !t.v.iter().all(|v| v.is_finite()))
        {
            return Err(SceneError::Invalid(
                self.name.clone(),
                format!("triangle {i} has a NaN or infinite coordinate"),
            ));
        }
        if let Some(i) = self
            .spheres
            .iter()
            .position(|s| !(s.center.is_finite() && s.radius.is_finite() && s.radius > 0.0))
        {
            return Err(SceneError::Invalid(
                self.name.clone(),
                format!(
                    "sphere {i} needs a finite centre and a finite radius > 0 (got {:?})",
                    self.spheres[i]
                ),
            ));
        }
        Ok(())
    }

    /// The primitives in the shared form indices are built from.
    pub fn geometry(&self) -> SceneGeometry {
        SceneGeometry {
            triangles: Arc::from(self.triangles.as_slice()),
            spheres: Arc::from(self.spheres.as_slice()),
            shapes: Arc::from(self.shapes.as_slice()),
            instances: self.instances.clone(),
        }
    }

    /// Loads a `.obj` file as a triangle scene named after the file.
    pub fn load_obj(path: &Path) -> Result<Scene, SceneError> {
        Scene::from_mesh(path, obj::load_obj(path)?)
    }

    /// The triangle scene of a mesh file loaded from `path` (named after the file), checked.
    pub fn from_mesh(path: &Path, mesh: triangle_mesh::TriangleMesh) -> Result<Scene, SceneError> {
        let name = path
            .file_stem()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_else(|| path.display().to_string());
        let scene = Scene {
            name,
            triangles: mesh.triangles,
            reference_bounds: Some(mesh.vertex_bounds),
            ..Scene::default()
        };
        scene.validate()?;
        Ok(scene)
    }

    /// The material of primitive `prim` (triangles first, then spheres, then shapes).
    #[inline]
    pub fn material(&self, prim: u32) -> &Material {
        let i = prim as usize;
        match i.checked_sub(self.triangles.len()) {
            None => self.materials.triangle(i),
            Some(s) if s < self.spheres.len() => self.materials.sphere(s),
            Some(s) => self.materials.shape(s - self.spheres.len()),
        }
    }

    /// Unit geometric normal of primitive `prim` at the surface point `p` (a triangle's from its
    /// winding, a sphere's and a shape's outward); for shading the final hit only.
    #[inline]
    pub fn normal(&self, prim: u32, p: Vec3A) -> Vec3A {
        geometry::normal_of(&self.triangles, &self.spheres, &self.shapes, prim, p)
    }

    /// The scene's lights, or one default light above the front-right of the bounds when it has
    /// none.
    pub fn lights_or_default(&self) -> Vec<PointLight> {
        if !self.lights.is_empty() {
            return self.lights.clone();
        }
        let b = self.bounds();
        let c = Vec3::from(b.center());
        let d = Vec3::from(b.extent()).length().max(f32::MIN_POSITIVE);
        vec![PointLight {
            position: c + Vec3::new(0.5, 1.0, 0.8) * d,
            intensity: Vec3::ONE,
        }]
    }
}
