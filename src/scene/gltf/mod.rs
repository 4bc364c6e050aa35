//! glTF 2.0 meshes: `.gltf` (JSON with `.bin` buffers beside it) and `.glb` (binary, the
//! buffer in the file). Every primitive of a triangle mode (`TRIANGLES`, `TRIANGLE_STRIP`,
//! `TRIANGLE_FAN`) of every mesh the scene's node tree places, with the node transforms
//! applied ([`nodes`] says how); indexed (8-, 16-, 32-bit) or not; other modes skipped with a
//! warning.
//!
//! The `gltf` crate parses and validates the JSON document and gives the node tree; it is
//! used without its `import` feature (which decodes images and copies buffers): the buffers
//! are memory-mapped here and every accessor is range-checked before it is read
//! ([`accessor`]).

mod accessor;
mod buffers;
mod glb;
mod nodes;

use super::SceneError;
use super::corners::{push_fan, push_strip};
use super::error::Location;
use super::mapped::Mapped;
use super::triangle_mesh::{TriangleMesh, bounds_of, push_triangles};
use crate::geometry::Aabb;
use buffers::Buffers;
use gltf::json::validation::Validate;
use gltf::mesh::Mode;
use rayon::prelude::*;
use std::collections::HashSet;
use std::path::Path;

/// Loads a `.gltf` or `.glb` file: the triangles of its scene in node-walk order (within a
/// mesh, primitives in order, each primitive's triangles in index order), and the bounds of
/// every transformed position of its triangle primitives (also unused ones, like OBJ).
/// Errors name the file and the JSON path or byte offset, what is wrong and what to fix.
pub fn load_gltf(path: &Path) -> Result<TriangleMesh, SceneError> {
    let map = Mapped::open(path)?;
    let bytes = map.bytes();
    let bad = |at: Location, message: String| SceneError::Mesh {
        path: path.to_owned(),
        format: "glTF",
        at,
        message,
    };
    let (json, json_at, bin) = if bytes.starts_with(b"glTF") {
        let g = glb::split(bytes).map_err(|(at, m)| bad(at, m))?;
        (g.json, Some(20), g.bin)
    } else {
        (bytes, None, None)
    };
    let root = gltf::json::Root::from_slice(json).map_err(|e| {
        let text = e.to_string();
        let message = text
            .rsplit_once(" at line ")
            .map_or(text.as_str(), |(m, _)| m)
            .to_owned();
        let at = match json_at {
            None => Location::Line(e.line()),
            Some(base) => Location::Byte((base + offset_of(json, e.line(), e.column())) as u64),
        };
        bad(at, format!("{message} (JSON column {})", e.column()))
    })?;
    // POSITION's `min` and `max` are required by the specification but not needed here (the
    // bounds are computed), and often left out by exporters: their absence is not an error.
    let needed = |p: &gltf::json::Path| {
        let p = p.to_string();
        !(p.ends_with("[\"POSITION\"].min") || p.ends_with("[\"POSITION\"].max"))
    };
    // The crate's validation reads the POSITION accessor of every primitive without checking
    // its index (gltf-json 1.4.1, `primitive_validate_hook`), so an index out of range is
    // refused here first.
    if let Some((at, message)) = position_out_of_range(&root) {
        return Err(bad(at, message));
    }
    let doc = gltf::Document::from_json_without_validation(root);
    let mut errs = Vec::new();
    doc.as_json()
        .validate(doc.as_json(), gltf::json::Path::new, &mut |path, why| {
            let p = path();
            if needed(&p) {
                errs.push((p, why));
            }
        });
    if let Some((p, why)) = errs.first() {
        return Err(bad(
            Location::Json(p.to_string()),
            format!(
                "{why} ({} problems in all); fix the document, e.g. with the Khronos glTF validator",
                errs.len()
            ),
        ));
    }
    let buffers = Buffers::load(&doc, path, bin)?;
    let instances = nodes::instances(&doc).map_err(|(at, m)| bad(at, m))?;
    let mut triangles = Vec::new();
    let mut bounds = Aabb::EMPTY;
    let mut skipped = HashSet::new();
    for inst in &instances {
        let mesh = doc.meshes().nth(inst.mesh).expect("validated");
        for prim in mesh.primitives() {
            let at = || {
                Location::Json(format!(
                    "meshes[{}].primitives[{}]",
                    inst.mesh,
                    prim.index()
                ))
            };
            if matches!(
                prim.mode(),
                Mode::Points | Mode::Lines | Mode::LineLoop | Mode::LineStrip
            ) {
                if skipped.insert((inst.mesh, prim.index())) {
                    eprintln!(
                        "warning: {}: mesh '{}' (meshes[{}]) primitive {} has mode {:?}; only triangle modes are loaded, so it is skipped",
                        path.display(),
                        mesh.name().unwrap_or(""),
                        inst.mesh,
                        prim.index(),
                        prim.mode()
                    );
                }
                continue;
            }
            let Some(pos) = prim.get(&gltf::json::mesh::Semantic::Positions) else {
                return Err(bad(at(), "the primitive has no POSITION attribute".into()));
            };
            let mut positions = accessor::positions(&buffers, path, &pos)?;
            if inst.world != glam::Mat4::IDENTITY {
                let w = inst.world;
                positions
                    .par_iter_mut()
                    .for_each(|p| *p = w.transform_point3a(*p));
                if let Some(k) = positions.iter().position(|p| !p.is_finite()) {
                    let node = Location::Json(format!("nodes[{}]", inst.node.unwrap_or(0)));
                    return Err(bad(
                        node,
                        format!(
                            "the node's transform takes vertex {k} of accessor {} to a non-finite point; scale the model down",
                            pos.index()
                        ),
                    ));
                }
            }
            let indices = match prim.indices() {
                Some(a) => accessor::indices(&buffers, path, &a, positions.len())?,
                None => (0..positions.len() as u32).collect(),
            };
            let corners: Vec<[u32; 3]> = match prim.mode() {
                Mode::TriangleStrip | Mode::TriangleFan => {
                    let mut c = Vec::new();
                    let push = if prim.mode() == Mode::TriangleFan {
                        push_fan
                    } else {
                        push_strip
                    };
                    push(&mut c, &indices);
                    c
                }
                _ if indices.len() % 3 != 0 => {
                    return Err(bad(
                        at(),
                        format!(
                            "{} indices (or vertices) in TRIANGLES mode, not a multiple of 3",
                            indices.len()
                        ),
                    ));
                }
                _ => indices
                    .chunks_exact(3)
                    .map(|c| [c[0], c[1], c[2]])
                    .collect(),
            };
            push_triangles(&mut triangles, &positions, &corners);
            bounds = bounds.union(bounds_of(&positions));
        }
    }
    if triangles.is_empty() {
        return Err(SceneError::Empty(format!(
            "{} (found no triangles: a glTF scene needs a mesh primitive of a triangle mode placed by a node)",
            path.display()
        )));
    }
    Ok(TriangleMesh {
        triangles,
        vertex_bounds: bounds,
    })
}

/// The byte offset in `text` of 1-based `line` and `column`.
fn offset_of(text: &[u8], line: usize, column: usize) -> usize {
    let start: usize = text
        .split_inclusive(|&b| b == b'\n')
        .take(line.saturating_sub(1))
        .map(<[u8]>::len)
        .sum();
    (start + column.saturating_sub(1)).min(text.len())
}

/// The first primitive whose `POSITION` attribute names an accessor the document lacks: its
/// JSON path and what to fix.
fn position_out_of_range(root: &gltf::json::Root) -> Option<(Location, String)> {
    use gltf::json::validation::Checked;
    let position = Checked::Valid(gltf::json::mesh::Semantic::Positions);
    root.meshes.iter().enumerate().find_map(|(m, mesh)| {
        mesh.primitives.iter().enumerate().find_map(|(p, prim)| {
            let index = prim.attributes.get(&position)?.value();
            (index >= root.accessors.len()).then(|| {
                (
                    Location::Json(format!("meshes[{m}].primitives[{p}].attributes.POSITION")),
                    format!(
                        "names accessor {index}, but the document has {} accessors; point it at \
                         an accessor of the document",
                        root.accessors.len()
                    ),
                )
            })
        })
    })
}
