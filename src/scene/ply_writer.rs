//! Writes triangles as a binary little-endian PLY file that loads back to the identical
//! triangles: welded vertices (`float x y z`, the `f32` bits as they are) and one triangle
//! face each (`list uchar uint vertex_indices`), in triangle order. Like OBJ, PLY has no
//! spheres or shapes.

use super::SceneError;
use super::obj_writer::write_with;
use super::triangle_mesh::weld;
use crate::geometry::Triangle;
use std::io::Write;
use std::path::Path;

/// Writes `triangles` to `path`, with `comment` lines in the header.
pub fn write_ply(path: &Path, triangles: &[Triangle], comment: &str) -> Result<(), SceneError> {
    write_with(path, |w| write_to(w, triangles, comment))
}

fn write_to(w: &mut impl Write, triangles: &[Triangle], comment: &str) -> std::io::Result<()> {
    let (vertices, faces) = weld(triangles);
    writeln!(w, "ply\nformat binary_little_endian 1.0")?;
    for line in comment.lines() {
        writeln!(w, "comment {line}")?;
    }
    writeln!(w, "element vertex {}", vertices.len())?;
    writeln!(w, "property float x\nproperty float y\nproperty float z")?;
    writeln!(w, "element face {}", faces.len())?;
    writeln!(w, "property list uchar uint vertex_indices\nend_header")?;
    for v in vertices {
        for c in v.to_array() {
            w.write_all(&c.to_le_bytes())?;
        }
    }
    for f in faces {
        w.write_all(&[3])?;
        for i in f {
            w.write_all(&i.to_le_bytes())?;
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::generators::generate;
    use crate::scene::ply::load_ply;

    #[test]
    fn generated_meshes_load_back_bit_identical() {
        for name in ["icosphere", "soup", "terrain"] {
            let tris = generate(name, 3000, 5).unwrap().triangles;
            let f = tempfile::Builder::new().suffix(".ply").tempfile().unwrap();
            write_ply(f.path(), &tris, "test\ntwo lines").unwrap();
            let back = load_ply(f.path()).unwrap().triangles;
            let bits = |t: &[Triangle]| -> Vec<u32> {
                t.iter()
                    .flat_map(|t| t.v.iter().flat_map(|v| v.to_array().map(f32::to_bits)))
                    .collect()
            };
            assert_eq!(bits(&back), bits(&tris), "{name}");
        }
    }
}
