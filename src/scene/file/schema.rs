//! The TOML scene format as serde types; unknown fields are rejected everywhere.
//!
//! `keyframes` (on `[[mesh]]`, `[[generator]]`, `[[sphere]]` and `[[shape]]`) gives an object
//! rigid poses over the animation time `t` in `[0, 1]`, applied after its static placement: a
//! key's `rotate` (default none) turns the placed object about its `translate` point (the
//! origin without one), then its `translate` (default `[0, 0, 0]`) moves it. Between keys the
//! move is linear and the turn a slerp (the shorter way round, so a turn of 180 degrees or more
//! between two keys needs a key in between); before the first key and after the last the
//! pose holds ([`crate::scene::keyframes`]). Other commands see the static placement.
//!
//! ```toml
//! name = "example"                       # optional; default: the file's stem
//!
//! [camera]                               # optional
//! eye = [0.5, 1.5, 3.0]
//! look_at = [0.5, 0.2, 0.5]
//! up = [0, 1, 0]                         # default +Y
//! fov_deg = 45                           # default 45
//!
//! [[light]]                              # any number
//! position = [2, 4, 2]
//! intensity = [1, 1, 1]                  # default white
//!
//! [[mesh]]                               # an OBJ file, relative to this file's directory
//! path = "../meshes/bunny.obj"
//! scale = 2                              # or [sx, sy, sz]; default 1
//! rotate = { axis = [0, 1, 0], degrees = 30 }
//! translate = [0, 0.1, 0]
//! keyframes = [                          # optional, any object table: for `animate`
//!   { t = 0 },                           # t in [0, 1], strictly increasing
//!   { t = 1, translate = [2, 0, 0], rotate = { axis = [0, 1, 0], degrees = 90 } },
//! ]                                      # or [[mesh.keyframes]] tables with the same keys
//!
//! [[generator]]                          # a built-in generator
//! name = "terrain"
//! n = 20000                              # default 20000
//! seed = 3                               # default 1
//! scale = [4, 1, 4]                      # same transform keys as [[mesh]]
//!
//! [[sphere]]
//! center = [0.5, 0.5, 0.5]
//! radius = 0.1
//! material = "red"                       # any object: a name from [material.NAME] ...
//! # material = { color = [1, 0, 0], specular = 0.5 }   # ... or an inline material
//!
//! [material.red]                         # named materials; every key optional
//! color = [0.8, 0.1, 0.1]                # default [0.8, 0.8, 0.8]
//! ambient = 0.1                          # default 0.1
//! diffuse = 0.7                          # default 0.7
//! specular = 0.2                         # default 0.2
//! shininess = 32                         # default 32
//! emission = [0, 0, 0]                   # default black
//!
//! [[area_light]]                         # any number: corner + a * edge1 + b * edge2
//! corner = [-0.5, 2, -0.5]
//! edge1 = [1, 0, 0]
//! edge2 = [0, 0, 1]
//! intensity = [1, 1, 1]                  # default white; the total over the rectangle
//! samples = 4                            # strata per edge (4 x 4 shadow rays); default 4
//!
//! [object.tree]                          # a mesh that instances place by name
//! generator = "icosphere"                # or path = "tree.ply"
//! n = 800                                # generator size; default 20000
//!
//! [[instance]]                           # places a mesh: `path` or `object`, same transform
//! object = "tree"                        #   and material keys as [[mesh]]; instances of one
//! translate = [2, 0, 0]                  #   mesh share its structure in the `tlas` index
//! scale = 0.5
//!
//! [[shape]]                              # box, polygons, cylinder, cone, ellipsoid
//! kind = "cylinder"                      # keys per kind: see shape_schema
//! base = [0, 0, 0]
//! top = [0, 1, 0]
//! radius = 0.2
//! ```

use super::placed::{KeySpec, MaterialRef, placed_entry};
use super::shape_schema::ShapeEntry;
use crate::scene::{AreaLight, CameraSpec, Material, PointLight};
use serde::Deserialize;
use std::collections::BTreeMap;
use toml::Spanned;

/// A whole scene file.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SceneFile {
    pub name: Option<String>,
    pub camera: Option<CameraSpec>,
    #[serde(default, rename = "light")]
    pub lights: Vec<PointLight>,
    /// Spanned so objects of different kinds can be put back into file order.
    #[serde(default, rename = "mesh")]
    pub meshes: Vec<Spanned<MeshEntry>>,
    #[serde(default, rename = "generator")]
    pub generators: Vec<Spanned<GeneratorEntry>>,
    #[serde(default, rename = "sphere")]
    pub spheres: Vec<Spanned<SphereEntry>>,
    /// `[material.NAME]` tables.
    #[serde(default, rename = "material")]
    pub materials: BTreeMap<String, Material>,
    #[serde(default, rename = "area_light")]
    pub area_lights: Vec<AreaLight>,
    #[serde(default, rename = "shape")]
    pub shapes: Vec<Spanned<ShapeEntry>>,
    #[serde(default, rename = "instance")]
    pub instances: Vec<Spanned<InstanceEntry>>,
    /// `[object.NAME]` tables.
    #[serde(default, rename = "object")]
    pub objects: BTreeMap<String, ObjectDef>,
}

placed_entry! {
    /// `[[mesh]]`: an OBJ file placed by a transform.
    MeshEntry {
        /// Relative to the directory of the scene file (or absolute).
        path: String,
    }
}

placed_entry! {
    /// `[[generator]]`: a built-in generator with its size and seed, placed by a transform.
    GeneratorEntry {
        name: String,
        n: Option<i64>,
        seed: Option<u64>,
    }
}

placed_entry! {
    /// `[[instance]]`: a mesh file (`path`) or a named `[object.NAME]` (`object`), placed by a
    /// transform; every instance of one mesh shares its structure in `tlas`. No `keyframes`.
    InstanceEntry {
        path: Option<String>,
        object: Option<String>,
    }
}

/// `[object.NAME]`: a mesh `[[instance]]` entries name: a mesh file (`path`) or a built-in
/// triangle generator (`generator`, `n`, `seed`).
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ObjectDef {
    pub path: Option<String>,
    pub generator: Option<String>,
    pub n: Option<i64>,
    pub seed: Option<u64>,
}

/// An `f32` field read from the file's number, refused (with the file's line, by toml) when
/// that number is finite but beyond `f32`'s range, which would otherwise read as infinite.
pub(super) fn f32_in_range<'de, D: serde::Deserializer<'de>>(d: D) -> Result<f32, D::Error> {
    let v = f64::deserialize(d)?;
    if v.is_finite() && v.abs() > f64::from(f32::MAX) {
        return Err(serde::de::Error::custom(format!(
            "{v:e} is beyond the range of f32 (about -3.4e38 to 3.4e38); scale the scene down"
        )));
    }
    Ok(v as f32)
}

/// `[[sphere]]`: one sphere.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SphereEntry {
    pub center: [f32; 3],
    #[serde(deserialize_with = "f32_in_range")]
    pub radius: f32,
    pub material: Option<MaterialRef>,
    /// Turning about the origin (a sphere has no `translate` key).
    pub keyframes: Option<Vec<KeySpec>>,
}
