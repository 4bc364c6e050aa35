//! Wavefront OBJ loading (positions only) with tobj, plus a scan of every `v` line for the
//! protocol's bounding box (which includes vertices no face uses) and for NaN/inf coordinates,
//! and of every `f` line for what tobj rejects or drops without a line number (indices out of
//! range, faces of fewer than 3 vertices).

use super::error::Location;
use super::obj_statements::unknown_statements;
use super::obj_text::read_obj_text;
use super::triangle_mesh::TriangleMesh;
use super::{SceneError, coordinate};
use crate::geometry::{Aabb, Triangle};
use glam::Vec3A;
use std::path::Path;

/// Loads an OBJ file: its triangles in file order (faces fan-triangulated `(v0, vi, vi+1)`,
/// models concatenated in order) and the bounds of all its `v` lines. The text is prepared by
/// [`read_obj_text`] prepared by [`read_obj_text`]: comments cut, names in any
/// encoding), warning on stderr once per kind of statement the format does not have
/// (ignored, as tobj ignores it), with its first line. Errors: missing or unreadable file, malformed content, NaN or infinite
/// coordinates (with the line), no vertices, or no faces.
pub fn load_obj(path: &Path) -> Result<TriangleMesh, SceneError> {
    let text = &read_obj_text(path)?;
    let vertex_bounds = scan_vertices(path, text)?;
    check_faces(path, text)?;
    for (word, line) in unknown_statements(text) {
        eprintln!(
            "warning: {}, line {line}: '{word}' is not an OBJ statement; its lines are ignored (a typo of 'f' or 'v'?)",
            path.display()
        );
    }
    let opts = tobj::LoadOptions {
        triangulate: true,
        single_index: true,
        ignore_points: true,
        ignore_lines: true,
    };
    let (models, _materials) =
        tobj::load_obj_buf(&mut text.as_bytes(), &opts, |_| Ok(Default::default())).map_err(
            |e| SceneError::Obj {
                path: path.to_owned(),
                message: e.to_string(),
            },
        )?;
    let mut triangles = Vec::new();
    for m in &models {
        let p = &m.mesh.positions;
        let vertex = |i: u32| -> Result<Vec3A, SceneError> {
            let i = i as usize * 3;
            p.get(i..i + 3)
                .map(|c| Vec3A::new(c[0], c[1], c[2]))
                .ok_or_else(|| SceneError::Obj {
                    path: path.to_owned(),
                    message: format!("face index {} out of range in model '{}'", i / 3, m.name),
                })
        };
        for f in m.mesh.indices.chunks_exact(3) {
            triangles.push(Triangle::new(vertex(f[0])?, vertex(f[1])?, vertex(f[2])?));
        }
    }
    if vertex_bounds.is_empty() || triangles.is_empty() {
        return Err(SceneError::Empty(format!(
            "{} (found {} triangles; an OBJ scene needs 'v' and 'f' lines)",
            path.display(),
            triangles.len()
        )));
    }
    Ok(TriangleMesh {
        triangles,
        vertex_bounds,
    })
}

/// Bounds of every `v x y z` line; rejects non-finite or unparsable coordinates with the line.
fn scan_vertices(path: &Path, text: &str) -> Result<Aabb, SceneError> {
    let mut b = Aabb::EMPTY;
    for (n, line) in text.lines().enumerate() {
        let mut it = line.split_whitespace();
        if it.next() != Some("v") {
            continue;
        }
        let err = |message: String| SceneError::Obj {
            path: path.to_owned(),
            message: format!("line {}: {message} ('{}')", n + 1, line.trim()),
        };
        let numbers: Vec<&str> = it.collect();
        if ![3, 4, 6].contains(&numbers.len()) {
            return Err(err(format!(
                "a vertex is 'v x y z', optionally with a weight w or a colour r g b; this one has {} numbers",
                numbers.len()
            )));
        }
        let mut c = [0.0f32; 3];
        for (ci, tok) in c.iter_mut().zip(&numbers) {
            *ci = match coordinate::parse(tok) {
                Ok(x) => x,
                Err(coordinate::Bad::NonFinite) => {
                    return Err(SceneError::NonFiniteVertex {
                        path: path.to_owned(),
                        at: Location::Line(n + 1),
                        text: line.trim().to_owned(),
                    });
                }
                Err(bad) => return Err(err(bad.message(tok))),
            };
        }
        b = b.grown(Vec3A::from(c));
    }
    Ok(b)
}

/// Rejects, with the line, a face with fewer than 3 vertices (tobj drops it silently), a vertex
/// reference that is not a number, and one out of range (1..=vertices, or -1..=-vertices
/// relative to the vertices read so far). Line continuations (`\\`) are not supported.
fn check_faces(path: &Path, text: &str) -> Result<(), SceneError> {
    let mut vertices = 0i64;
    for (n, line) in text.lines().enumerate() {
        let mut it = line.split_whitespace();
        match it.next() {
            Some("v") => vertices += 1,
            Some("f") => {
                let err = |what: String| SceneError::Obj {
                    path: path.to_owned(),
                    message: format!("line {}: {what} ('{}')", n + 1, line.trim()),
                };
                let refs: Vec<&str> = it.collect();
                if refs.len() < 3 {
                    return Err(err(format!(
                        "a face needs at least 3 vertices, this one has {}; complete or remove it",
                        refs.len()
                    )));
                }
                for r in refs {
                    let pos = r.split('/').next().unwrap_or("");
                    let i: i64 = pos
                        .parse()
                        .map_err(|_| err(format!("'{r}' is not a vertex number")))?;
                    let ok = (1..=vertices).contains(&i) || (-vertices..=-1).contains(&i);
                    if !ok {
                        return Err(err(format!(
                            "vertex {i} does not exist: {vertices} vertices are defined before this line"
                        )));
                    }
                }
            }
            _ => {}
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::io::Write;

    fn write(text: &str) -> tempfile::NamedTempFile {
        let mut f = tempfile::Builder::new().suffix(".obj").tempfile().unwrap();
        f.write_all(text.as_bytes()).unwrap();
        f
    }

    #[test]
    fn loads_quad_fan_triangulated_and_unused_vertex_bounds() {
        let f = write("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 5 5 5\nf 1 2 3 4\n");
        let m = load_obj(f.path()).unwrap();
        assert_eq!(m.triangles.len(), 2);
        assert_eq!(m.triangles[1].v[1], Vec3A::new(1.0, 1.0, 0.0));
        assert_eq!(m.vertex_bounds.max, Vec3A::splat(5.0));
    }

    #[test]
    fn errors_are_typed() {
        let missing = load_obj(Path::new("/nonexistent/x.obj"));
        assert!(matches!(missing, Err(SceneError::Io { .. })));
        let garbage = write("this is not an obj file\n\u{1}\u{2}\n");
        assert!(matches!(
            load_obj(garbage.path()),
            Err(SceneError::Empty(_))
        ));
        let bad_coord = write("v 0 0 zero\nf 1 1 1\n");
        assert!(matches!(
            load_obj(bad_coord.path()),
            Err(SceneError::Obj { .. })
        ));
        let nan = write("v 0 0 0\nv 1 nan 0\nv 0 1 0\nf 1 2 3\n");
        match load_obj(nan.path()) {
            Err(SceneError::NonFiniteVertex { at, .. }) => assert_eq!(at, Location::Line(2)),
            other => panic!("expected NonFiniteVertex, got {other:?}"),
        }
        let empty = write("");
        assert!(matches!(load_obj(empty.path()), Err(SceneError::Empty(_))));
        let no_faces = write("v 0 0 0\nv 1 0 0\nv 0 1 0\n");
        assert!(matches!(
            load_obj(no_faces.path()),
            Err(SceneError::Empty(_))
        ));
        let bad_index = write("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n");
        assert!(load_obj(bad_index.path()).is_err());
    }

    fn obj_message(text: &str) -> String {
        match load_obj(write(text).path()) {
            Err(SceneError::Obj { message, .. }) => message,
            other => panic!("expected an OBJ error, got {other:?}"),
        }
    }

    #[test]
    fn face_errors_name_their_line() {
        let m = obj_message("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 9\n");
        assert!(m.starts_with("line 5: vertex 9 does not exist"), "{m}");
        let m = obj_message("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2\n");
        assert!(m.starts_with("line 5: a face needs at least 3"), "{m}");
        let m = obj_message("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 x 3\n");
        assert!(m.starts_with("line 4: 'x' is not a vertex number"), "{m}");
        let m = obj_message("v 0 0 0\nv 1 0 0\nf -1 -2 -3\n");
        assert!(m.contains("vertex -3 does not exist"), "{m}");
    }

    #[test]
    fn byte_order_mark_is_not_part_of_the_first_line() {
        let f = write("\u{feff}v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf -3 -2 -1\n");
        let m = load_obj(f.path()).unwrap();
        assert_eq!(m.triangles.len(), 2);
        assert_eq!(m.vertex_bounds.min, Vec3A::ZERO);
    }
}
