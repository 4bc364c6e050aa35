//! The mesh instances of a glTF scene: its node tree walked depth first (children in order),
//! each node's transform composed down the tree.
//!
//! Arithmetic, in `f32` with glam: a node's local matrix is its `matrix`, or
//! `Mat4::from_scale_rotation_translation(scale, rotation, translation)` (translation *
//! rotation * scale, the rotation quaternion as stored); a node's world matrix is
//! `parent_world * local`; a vertex is placed by `world.transform_point3a(p)`. Where the world
//! matrix is the identity, positions are taken as stored (bit for bit, `-0.0` too).

use crate::scene::error::Location;
use glam::{Mat4, Quat, Vec3};
use gltf::scene::Transform;

/// A mesh placed by a node: the node (`None` for a document without nodes), the mesh, and
/// the world matrix.
pub struct Instance {
    pub node: Option<usize>,
    pub mesh: usize,
    pub world: Mat4,
}

/// A node's local matrix.
fn local(t: Transform) -> Mat4 {
    match t {
        Transform::Matrix { matrix } => Mat4::from_cols_array_2d(&matrix),
        Transform::Decomposed {
            translation,
            rotation,
            scale,
        } => Mat4::from_scale_rotation_translation(
            Vec3::from(scale),
            Quat::from_array(rotation),
            Vec3::from(translation),
        ),
    }
}

/// The instances of the document's scene (its `scene`, else its first scene; without scenes,
/// every node that is no node's child; without nodes, every mesh untransformed), in the order
/// a depth-first walk meets them. Errors: a node reached twice (two parents or a cycle).
pub fn instances(doc: &gltf::Document) -> Result<Vec<Instance>, (Location, String)> {
    let roots: Vec<gltf::Node> = match doc.default_scene().or_else(|| doc.scenes().next()) {
        Some(s) => s.nodes().collect(),
        None if doc.nodes().len() == 0 => {
            return Ok(doc
                .meshes()
                .map(|m| Instance {
                    node: None,
                    mesh: m.index(),
                    world: Mat4::IDENTITY,
                })
                .collect());
        }
        None => {
            let mut child = vec![false; doc.nodes().len()];
            for c in doc.nodes().flat_map(|n| n.children()) {
                child[c.index()] = true;
            }
            doc.nodes().filter(|n| !child[n.index()]).collect()
        }
    };
    let mut seen = vec![false; doc.nodes().len()];
    let mut out = Vec::new();
    let mut stack: Vec<(gltf::Node, Mat4)> = roots
        .into_iter()
        .rev()
        .map(|n| (n, Mat4::IDENTITY))
        .collect();
    while let Some((n, parent)) = stack.pop() {
        let i = n.index();
        if std::mem::replace(&mut seen[i], true) {
            return Err((
                Location::Json(format!("nodes[{i}]")),
                "the node is reached twice (a child of two nodes, a root and a child, or in a cycle); a glTF node hierarchy is a tree".into(),
            ));
        }
        let world = parent * local(n.transform());
        if let Some(m) = n.mesh() {
            out.push(Instance {
                node: Some(i),
                mesh: m.index(),
                world,
            });
        }
        let children: Vec<gltf::Node> = n.children().collect();
        stack.extend(children.into_iter().rev().map(|c| (c, world)));
    }
    Ok(out)
}
