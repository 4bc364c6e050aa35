//! PLY files (ASCII, binary of either byte order, triangle strips) against their OBJ, and
//! malformed ones refused with a line or byte.

use super::{OBJ, VERTS, file, refused, same_as_obj};

pub(super) const ASCII: &str = "ply\nformat ascii 1.0\ncomment hand-made\nelement vertex 5\nproperty float x\nproperty float y\nproperty float z\nelement face 2\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0.1 0\n1 1 0\n0 1 -0.5\n5 5 5\n4 0 1 2 3\n3 3 2 0\n";

/// The same scene as binary PLY: `z` stored as a double, a `uchar` after each vertex and
/// each face, faces as `list uchar int`.
fn binary_ply(big: bool) -> Vec<u8> {
    let format = if big {
        "binary_big_endian"
    } else {
        "binary_little_endian"
    };
    let mut b = format!("ply\nformat {format} 1.0\nelement vertex 5\nproperty float x\nproperty float y\nproperty double z\nproperty uchar flag\nelement face 2\nproperty list uchar int vertex_indices\nproperty uchar material\nend_header\n").into_bytes();
    let f32b = |x: f32| {
        if big {
            x.to_be_bytes()
        } else {
            x.to_le_bytes()
        }
    };
    let i32b = |x: i32| {
        if big {
            x.to_be_bytes()
        } else {
            x.to_le_bytes()
        }
    };
    for v in VERTS {
        b.extend(f32b(v[0]));
        b.extend(f32b(v[1]));
        b.extend(if big {
            (v[2] as f64).to_be_bytes()
        } else {
            (v[2] as f64).to_le_bytes()
        });
        b.push(7);
    }
    for face in [&[0, 1, 2, 3][..], &[3, 2, 0]] {
        b.push(face.len() as u8);
        face.iter().for_each(|&i| b.extend(i32b(i)));
        b.push(1);
    }
    b
}

#[test]
fn ascii_and_binary_ply_load_as_their_obj() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    same_as_obj(d, &file(d, "a.ply", ASCII.as_bytes()), OBJ);
    same_as_obj(d, &file(d, "le.PLY", &binary_ply(false)), OBJ);
    same_as_obj(d, &file(d, "be.ply", &binary_ply(true)), OBJ);
    // All triangles (the parallel path) and CRLF line ends.
    let tri = ASCII
        .replace("4 0 1 2 3\n", "3 0 1 2\n")
        .replace('\n', "\r\n");
    same_as_obj(
        d,
        &file(d, "t.ply", tri.as_bytes()),
        &OBJ.replace("f 1 2 3 4", "f 1 2 3"),
    );
}

#[test]
fn tristrips_load_with_alternating_winding_and_restarts() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let ply = "ply\nformat ascii 1.0\nelement vertex 6\nproperty float x\nproperty float y\nproperty float z\nelement tristrips 1\nproperty list int int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n1 1 0\n0 2 0\n1 2 0\n9 0 1 2 3 -1 2 3 4 5\n";
    // Strip 0 1 2 3: (0 1 2), (1 3 2); strip 2 3 4 5: (2 3 4), (3 5 4).
    let obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nv 0 2 0\nv 1 2 0\nf 1 2 3\nf 2 4 3\nf 3 4 5\nf 4 6 5\n";
    same_as_obj(d, &file(d, "s.ply", ply.as_bytes()), obj);
}

#[test]
fn malformed_ply_is_refused_with_a_location() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let ascii = |name: &str, text: String| file(d, name, text.as_bytes());
    refused(
        &ascii("n.ply", ASCII.replace("0 1 -0.5", "0 nan -0.5")),
        &["line 14", "NaN"],
    );
    refused(
        &ascii("i.ply", ASCII.replace("3 3 2 0", "3 3 2 9")),
        &["line 17", "vertex index 9 is out of range"],
    );
    refused(
        &ascii("c.ply", ASCII.replace("vertex 5", "vertex 6")),
        &["line 16", "more values than a 'vertex' record"],
    );
    refused(
        &ascii("e.ply", ASCII.replace("face 2", "face 3")),
        &["the file ends after 2 of the 3 'face' lines"],
    );
    refused(
        &ascii("x.ply", ASCII.replace("face 2", "face 1")),
        &["line 17", "data after the last element"],
    );
    refused(
        &ascii(
            "h.ply",
            ASCII.replace("property float y", "property half y"),
        ),
        &["line 6", "unknown property type 'half'"],
    );
    let bin = binary_ply(false);
    let header = bin.len() - 5 * 17 - 18 - 14;
    refused(
        &file(d, "t.ply", &bin[..bin.len() - 3]),
        &["byte", "the file ends inside face 1"],
    );
    let mut nan = bin.clone();
    nan[header + 17 + 4..header + 17 + 8].copy_from_slice(&f32::NAN.to_le_bytes());
    refused(
        &file(d, "bn.ply", &nan),
        &[&format!("byte {}", header + 17), "NaN"],
    );
    let mut index = bin.clone();
    let last = index.len() - 5;
    index[last..last + 4].copy_from_slice(&9i32.to_le_bytes());
    refused(
        &file(d, "bi.ply", &index),
        &["byte", "face 1: vertex index 9 is out of range"],
    );
    let mut extra = bin.clone();
    extra.push(0);
    refused(
        &file(d, "bx.ply", &extra),
        &["1 bytes follow the last element"],
    );
    // A header claiming 4e9 vertices in a tiny file is refused before anything is allocated.
    let huge = String::from_utf8_lossy(&bin[..header]).replace("vertex 5", "vertex 4000000000");
    refused(
        &file(d, "huge.ply", huge.as_bytes()),
        &["declares 4000000000 records", "truncated"],
    );
}
