//! `[[instance]]` entries and the `[object.NAME]` tables they may name: each distinct mesh is
//! loaded once and shared by its instances ([`crate::scene::instances`]), and every object of an
//! instanced file that has triangles becomes an instance (a `[[mesh]]` or `[[generator]]` of its
//! own placed triangles under the identity), so the instances cover the flattened ids in order.

use super::mesh::load_mesh;
use super::schema::{InstanceEntry, ObjectDef};
use crate::geometry::Triangle;
use crate::scene::generators::{DEFAULT_SEED, DEFAULT_SIZE, GeneratorSpec};
use crate::scene::instances::{Instance, InstanceSet};
use crate::scene::transform::Transform;
use std::collections::{BTreeMap, HashMap};
use std::path::Path;
use std::sync::Arc;

/// The instances of a file as its objects are loaded, in file (and id) order.
#[derive(Default)]
pub struct Instancing {
    meshes: Vec<Arc<[Triangle]>>,
    /// A mesh's index by its source (`path:...` or `object:NAME`).
    by_source: HashMap<String, u32>,
    instances: Vec<Instance>,
}

impl Instancing {
    /// The mesh an `[[instance]]` places (loaded on its first use), with its index.
    pub fn mesh_of(
        &mut self,
        entry: &InstanceEntry,
        objects: &BTreeMap<String, ObjectDef>,
        dir: &Path,
    ) -> Result<(u32, Arc<[Triangle]>), String> {
        let source = match (&entry.path, &entry.object) {
            (Some(p), None) => format!("path:{}", dir.join(p).display()),
            (None, Some(name)) => format!("object:{name}"),
            _ => {
                return Err(
                    "give exactly one of `path` (a mesh file) or `object` (the name of an \
                     [object.NAME] table)"
                        .into(),
                );
            }
        };
        if let Some(&i) = self.by_source.get(&source) {
            return Ok((i, self.meshes[i as usize].clone()));
        }
        let tris: Arc<[Triangle]> = match (&entry.path, &entry.object) {
            (Some(p), _) => Arc::from(
                load_mesh(&dir.join(p))
                    .map_err(|e| e.to_string())?
                    .triangles,
            ),
            (_, Some(name)) => object_mesh(name, objects, dir)?,
            _ => unreachable!("checked above"),
        };
        let i = self.meshes.len() as u32;
        self.meshes.push(tris.clone());
        self.by_source.insert(source, i);
        Ok((i, tris))
    }

    /// Places mesh `mesh` (`tris`) by `place`, its flattened triangles from id `first`.
    pub fn place(
        &mut self,
        mesh: u32,
        tris: &[Triangle],
        place: &Transform,
        first: usize,
    ) -> Result<(), String> {
        let inst = Instance::new(mesh, tris, place, first as u32)
            .ok_or("the placement cannot be inverted: give finite, non-zero scale factors")?;
        self.instances.push(inst);
        Ok(())
    }

    /// An object's own placed triangles (a `[[mesh]]` or `[[generator]]`) as an instance under
    /// the identity, from id `first`.
    pub fn own(&mut self, placed: &[Triangle], first: usize) {
        if placed.is_empty() {
            return;
        }
        let mesh = self.meshes.len() as u32;
        self.meshes.push(Arc::from(placed));
        self.place(mesh, placed, &Transform::IDENTITY, first)
            .expect("the identity inverts");
    }

    /// The finished set; `covers_scene` says whether the scene has nothing but the instances'
    /// triangles.
    pub fn finish(self, covers_scene: bool) -> InstanceSet {
        InstanceSet {
            meshes: self.meshes,
            instances: self.instances,
            covers_scene,
        }
    }
}

/// The triangles of `[object.NAME]`: its mesh file, or its generator's triangles.
fn object_mesh(
    name: &str,
    objects: &BTreeMap<String, ObjectDef>,
    dir: &Path,
) -> Result<Arc<[Triangle]>, String> {
    let Some(def) = objects.get(name) else {
        let known: Vec<&str> = objects.keys().map(String::as_str).collect();
        return Err(format!(
            "object \"{name}\" is not defined: add an [object.{name}] table with a `path` or a \
             `generator`{}",
            if known.is_empty() {
                String::new()
            } else {
                format!(", or use one of {}", known.join(", "))
            }
        ));
    };
    let at = |e: &dyn std::fmt::Display| format!("[object.{name}]: {e}");
    match (&def.path, &def.generator) {
        (Some(p), None) if def.n.is_none() && def.seed.is_none() => Ok(Arc::from(
            load_mesh(&dir.join(p)).map_err(|e| at(&e))?.triangles,
        )),
        (None, Some(g)) => {
            let spec = GeneratorSpec::new(
                g,
                def.n.unwrap_or(DEFAULT_SIZE as i64),
                def.seed.unwrap_or(DEFAULT_SEED),
            )
            .map_err(|e| at(&e))?;
            let scene = spec.generate().map_err(|e| at(&e))?;
            if !scene.spheres.is_empty() || !scene.shapes.is_empty() {
                return Err(at(&format!(
                    "generator \"{g}\" makes spheres or shapes; instances place triangle meshes \
                     only: choose a triangle generator (icosphere, terrain, soup, ...)"
                )));
            }
            Ok(Arc::from(scene.triangles))
        }
        _ => Err(at(
            &"give either `path` (a mesh file) or `generator` (with optional `n` and `seed`)",
        )),
    }
}
