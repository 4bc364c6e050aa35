//! Scene files in TOML: meshes (OBJ, PLY, glTF) and generators placed by transforms, spheres, shapes, a
//! camera, point and area lights, and materials per object (format in [`schema`] and
//! [`shape_schema`]).
//!
//! Primitive ids: all triangles, then all spheres, then all shapes. Within each kind, objects
//! contribute in the order their tables appear in the file (`[[mesh]]` and `[[generator]]`
//! tables interleaved as written; a generator's spheres and shapes, e.g. from `spheres`, `mixed`
//! or `shapes`, sit among the `[[sphere]]` and `[[shape]]` tables at the generator's place), and
//! each object's primitives keep their own order.
//!
//! An object table with a `keyframes` key is remembered in [`Scene::keyframed`] with the id
//! ranges it produced; its primitives here are its static placement ([`super::keyframes`]).

pub mod instance;
pub mod mesh;
pub mod placed;
pub mod schema;
pub mod shape_schema;

use super::generators::{DEFAULT_SEED, DEFAULT_SIZE, GeneratorSpec};
use super::keyframes::{KeyframeError, KeyframedObject, Track};
use super::{Material, Scene, SceneError};
use crate::camera::Camera;
use glam::Vec3A;
use placed::{MaterialRef, Placed};
use schema::{GeneratorEntry, InstanceEntry, MeshEntry, SceneFile, SphereEntry};
use shape_schema::ShapeEntry;
use std::collections::BTreeMap;
use std::path::Path;
use toml::Spanned;

/// One table of the file that contributes primitives.
enum Object<'a> {
    Mesh(&'a MeshEntry),
    Generator(&'a GeneratorEntry),
    Sphere(&'a SphereEntry),
    Shape(&'a ShapeEntry),
    Instance(&'a InstanceEntry),
}

impl Object<'_> {
    /// The table as messages name it: `[[mesh]] path = "tri.obj"`.
    fn label(&self) -> String {
        match self {
            Object::Mesh(m) => format!("[[mesh]] path = \"{}\"", m.path),
            Object::Generator(g) => format!("[[generator]] name = \"{}\"", g.name),
            Object::Sphere(_) => "[[sphere]]".to_owned(),
            Object::Shape(s) => format!("[[shape]] kind = \"{}\"", s.kind()),
            Object::Instance(i) => match (&i.path, &i.object) {
                (Some(p), _) => format!("[[instance]] path = \"{p}\""),
                (None, Some(o)) => format!("[[instance]] object = \"{o}\""),
                (None, None) => "[[instance]]".to_owned(),
            },
        }
    }

    /// Its `keyframes` key's track (`None` when absent).
    fn track(&self) -> Result<Option<Track>, KeyframeError> {
        match self {
            Object::Mesh(m) => m.track(),
            Object::Generator(g) => g.track(),
            Object::Sphere(s) => placed::track(s.keyframes.as_deref(), None),
            Object::Shape(s) => s.placed().track(),
            Object::Instance(i) => match i.keyframes {
                None => Ok(None),
                Some(_) => Err(KeyframeError::NotOnInstances),
            },
        }
    }
}

/// The entries of one table as objects, each with its byte offset in the file.
fn at_offsets<'a, T>(
    table: &'a [Spanned<T>],
    object: impl Fn(&'a T) -> Object<'a>,
) -> impl Iterator<Item = (usize, Object<'a>)> {
    table
        .iter()
        .map(move |e| (e.span().start, object(e.get_ref())))
}

/// Loads a `.toml` scene file. Every error names the file and, for an object, its line.
pub fn load_scene_file(path: &Path) -> Result<Scene, SceneError> {
    let text = std::fs::read_to_string(path).map_err(|source| SceneError::Io {
        path: path.to_owned(),
        cause: source,
    })?;
    let bad = |message: String| SceneError::SceneFile {
        path: path.to_owned(),
        message,
    };
    let file: SceneFile = toml::from_str(&text).map_err(|e| bad(e.to_string()))?;
    let line = |offset: usize| text[..offset.min(text.len())].matches('\n').count() + 1;

    let mut objects: Vec<(usize, Object)> = Vec::new();
    objects.extend(at_offsets(&file.meshes, Object::Mesh));
    objects.extend(at_offsets(&file.generators, Object::Generator));
    objects.extend(at_offsets(&file.spheres, Object::Sphere));
    objects.extend(at_offsets(&file.shapes, Object::Shape));
    objects.extend(at_offsets(&file.instances, Object::Instance));
    objects.sort_by_key(|(start, _)| *start);
    if objects.is_empty() {
        return Err(bad(
            "the scene is empty: add at least one [[mesh]], [[generator]], [[instance]], [[sphere]] or [[shape]]"
                .into(),
        ));
    }

    for (name, m) in &file.materials {
        m.validate()
            .map_err(|e| bad(format!("[material.{name}]: {e}")))?;
    }
    let dir = path.parent().unwrap_or(Path::new(""));
    let name = file.name.clone().unwrap_or_else(|| {
        path.file_stem()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_else(|| path.display().to_string())
    });
    let mut scene = Scene {
        name,
        ..Scene::default()
    };
    // Only a file with [[instance]] entries keeps its objects as instances.
    let mut instancing = (!file.instances.is_empty()).then(instance::Instancing::default);
    for (start, object) in &objects {
        let what = object.label();
        let at = |what: &str, e: &dyn std::fmt::Display| {
            bad(format!("line {}, {what}: {e}", line(*start)))
        };
        let track = object.track().map_err(|e| at(&what, &e))?;
        let before = (
            scene.triangles.len(),
            scene.spheres.len(),
            scene.shapes.len(),
        );
        match object {
            Object::Mesh(m) => {
                let t = m.transform().map_err(|e| at(&what, &e))?;
                let mesh = mesh::load_mesh(&dir.join(&m.path)).map_err(|e| at(&what, &e))?;
                let material =
                    material(m.material_ref(), &file.materials).map_err(|e| at(&what, &e))?;
                scene
                    .materials
                    .start_triangles(scene.triangles.len(), material);
                scene
                    .triangles
                    .extend(mesh.triangles.iter().map(|tri| t.triangle(tri)));
            }
            Object::Instance(i) => {
                let t = i.transform().map_err(|e| at(&what, &e))?;
                let instancing = instancing.as_mut().expect("a file with instances");
                let (mesh, tris) = instancing
                    .mesh_of(i, &file.objects, dir)
                    .map_err(|e| at(&what, &e))?;
                instancing
                    .place(mesh, &tris, &t, scene.triangles.len())
                    .map_err(|e| at(&what, &e))?;
                let material =
                    material(i.material_ref(), &file.materials).map_err(|e| at(&what, &e))?;
                scene
                    .materials
                    .start_triangles(scene.triangles.len(), material);
                scene
                    .triangles
                    .extend(tris.iter().map(|tri| t.triangle(tri)));
            }
            Object::Generator(g) => {
                let t = g.transform().map_err(|e| at(&what, &e))?;
                let spec = GeneratorSpec::new(
                    &g.name,
                    g.n.unwrap_or(DEFAULT_SIZE as i64),
                    g.seed.unwrap_or(DEFAULT_SEED),
                )
                .map_err(|e| at(&what, &e))?;
                let generated = spec.generate().map_err(|e| at(&what, &e))?;
                let material =
                    material(g.material_ref(), &file.materials).map_err(|e| at(&what, &e))?;
                scene
                    .materials
                    .start_triangles(scene.triangles.len(), material);
                scene.materials.start_spheres(scene.spheres.len(), material);
                scene.materials.start_shapes(scene.shapes.len(), material);
                scene
                    .triangles
                    .extend(generated.triangles.iter().map(|tri| t.triangle(tri)));
                for s in &generated.spheres {
                    scene.spheres.push(t.sphere(s).map_err(|e| at(&what, &e))?);
                }
                for s in &generated.shapes {
                    scene.shapes.push(t.shape(s).map_err(|e| at(&what, &e))?);
                }
            }
            Object::Sphere(s) => {
                let ok = s.center.iter().all(|c| c.is_finite())
                    && s.radius.is_finite()
                    && s.radius > 0.0;
                if !ok {
                    return Err(at(
                        &what,
                        &format!(
                            "center {:?} and radius {} are invalid: give a finite center and a finite radius > 0",
                            s.center, s.radius
                        ),
                    ));
                }
                let material =
                    material(s.material.as_ref(), &file.materials).map_err(|e| at(&what, &e))?;
                scene.materials.start_spheres(scene.spheres.len(), material);
                scene.spheres.push(crate::geometry::Sphere::new(
                    Vec3A::from(s.center),
                    s.radius,
                ));
            }
            Object::Shape(s) => {
                let local = s.local_shape();
                let local = local.map_err(|e| at(&what, &e))?;
                let t = s.placed().transform().map_err(|e| at(&what, &e))?;
                let material = material(s.placed().material_ref(), &file.materials)
                    .map_err(|e| at(&what, &e))?;
                scene.materials.start_shapes(scene.shapes.len(), material);
                scene
                    .shapes
                    .push(t.shape(&local).map_err(|e| at(&what, &e))?);
            }
        }
        if let (Some(instancing), Object::Mesh(_) | Object::Generator(_)) =
            (&mut instancing, object)
        {
            instancing.own(&scene.triangles[before.0..], before.0);
        }
        if let Some(track) = track {
            scene.keyframed.push(KeyframedObject {
                entry: format!("line {}, {what}", line(*start)),
                triangles: before.0..scene.triangles.len(),
                spheres: before.1..scene.spheres.len(),
                shapes: before.2..scene.shapes.len(),
                track,
            });
        }
    }

    if let Some(c) = &file.camera {
        Camera::look_at(
            c.eye.as_dvec3(),
            c.look_at.as_dvec3(),
            c.up.as_dvec3(),
            c.fov_deg as f64,
            1,
            1,
        )
        .map_err(|e| bad(format!("[camera]: {e}")))?;
    }
    for (i, l) in file.lights.iter().enumerate() {
        let ok =
            l.position.is_finite() && l.intensity.is_finite() && l.intensity.min_element() >= 0.0;
        if !ok {
            return Err(bad(format!(
                "[[light]] {}: position {:?} and intensity {:?} are invalid: give a finite position and a finite intensity >= 0",
                i + 1,
                l.position.to_array(),
                l.intensity.to_array()
            )));
        }
    }
    for (i, l) in file.area_lights.iter().enumerate() {
        l.validate()
            .map_err(|e| bad(format!("[[area_light]] {}: {e}", i + 1)))?;
    }
    if let Some(instancing) = instancing {
        let covers = scene.spheres.is_empty() && scene.shapes.is_empty();
        scene.instances = Some(std::sync::Arc::new(instancing.finish(covers)));
    } else if !file.objects.is_empty() {
        return Err(bad(format!(
            "[object.{}] is defined but no [[instance]] places it: add an [[instance]] with              object = \"{0}\", or remove the table",
            file.objects.keys().next().expect("not empty")
        )));
    }
    scene.area_lights = file.area_lights;
    scene.camera = file.camera;
    scene.lights = file.lights;
    scene.validate().map_err(|e| bad(e.to_string()))?;
    Ok(scene)
}

/// An object's material: a `[material.NAME]` by name, or an inline table (validated).
fn material(
    r: Option<&MaterialRef>,
    named: &BTreeMap<String, Material>,
) -> Result<Option<Material>, String> {
    match r {
        None => Ok(None),
        Some(MaterialRef::Named(name)) => named.get(name).copied().map(Some).ok_or_else(|| {
            let known: Vec<&str> = named.keys().map(String::as_str).collect();
            format!(
                "material \"{name}\" is not defined: add a [material.{name}] table{}",
                if known.is_empty() {
                    String::new()
                } else {
                    format!(" or use one of {}", known.join(", "))
                }
            )
        }),
        Some(MaterialRef::Inline(m)) => m.validate().map(|()| Some(*m)),
    }
}

#[cfg(test)]
mod tests;
