//! Writes triangles as a Wavefront OBJ file that loads back to the identical triangles.
//!
//! Corners with identical bits share one `v` line (so a welded mesh stays welded); every
//! coordinate is written as the shortest decimal that parses back to the same `f32` (Rust's
//! `Display`), faces are in triangle order. Spheres have no OBJ form: callers refuse scenes with
//! spheres instead of tessellating them (a tessellated sphere would hit differently).

use super::SceneError;
use super::triangle_mesh::weld;
use crate::geometry::Triangle;
use std::io::{BufWriter, Write};
use std::path::Path;

/// Writes `triangles` to `path`, with `comment` lines (`# ...`) at the top.
pub fn write_obj(path: &Path, triangles: &[Triangle], comment: &str) -> Result<(), SceneError> {
    write_with(path, |w| write_to(w, triangles, comment))
}

/// Creates `path` and writes it through a buffer with `write` (the mesh writers' shared part).
pub fn write_with(
    path: &Path,
    write: impl FnOnce(&mut BufWriter<std::fs::File>) -> std::io::Result<()>,
) -> Result<(), SceneError> {
    let io = |source| SceneError::Io {
        path: path.to_owned(),
        cause: source,
    };
    let mut w = BufWriter::new(std::fs::File::create(path).map_err(io)?);
    write(&mut w).and_then(|_| w.flush()).map_err(io)
}

fn write_to(w: &mut impl Write, triangles: &[Triangle], comment: &str) -> std::io::Result<()> {
    for line in comment.lines() {
        writeln!(w, "# {line}")?;
    }
    let (vertices, faces) = weld(triangles);
    for v in vertices {
        writeln!(w, "v {} {} {}", v.x, v.y, v.z)?;
    }
    // OBJ indices are 1-based.
    for [a, b, c] in faces {
        writeln!(w, "f {} {} {}", a + 1, b + 1, c + 1)?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::generators::generate;
    use crate::scene::obj::load_obj;
    use glam::Vec3A;

    fn round_trip(tris: &[Triangle]) -> Vec<Triangle> {
        let f = tempfile::Builder::new().suffix(".obj").tempfile().unwrap();
        write_obj(f.path(), tris, "test").unwrap();
        load_obj(f.path()).unwrap().triangles
    }

    fn bits(tris: &[Triangle]) -> Vec<[u32; 9]> {
        tris.iter()
            .map(|t| {
                let a: Vec<u32> =
                    t.v.iter()
                        .flat_map(|v| v.to_array().map(f32::to_bits))
                        .collect();
                a.try_into().unwrap()
            })
            .collect()
    }

    #[test]
    fn generated_meshes_load_back_bit_identical() {
        for name in ["soup", "icosphere", "slivers", "stadium", "terrain"] {
            let tris = generate(name, 2000, 5).unwrap().triangles;
            assert_eq!(bits(&round_trip(&tris)), bits(&tris), "{name}");
        }
    }

    #[test]
    fn awkward_floats_round_trip() {
        let odd = Vec3A::new(-0.0, f32::MIN_POSITIVE / 8.0, f32::MAX);
        let tris = [
            Triangle::new(
                odd,
                Vec3A::new(0.1, 1.0 / 3.0, -1e-30),
                Vec3A::new(0.0, 7e30, 1.0),
            ),
            Triangle::new(odd, odd, odd),
        ];
        assert_eq!(bits(&round_trip(&tris)), bits(&tris));
    }
}
