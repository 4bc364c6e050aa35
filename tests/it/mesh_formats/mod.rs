//! PLY and glTF loaders (issue 49) against small hand-made files: each loaded scene equals,
//! triangle for triangle, the same scene written as OBJ (and has the same reference bounds);
//! malformed files of each format are refused with a location (line, byte or JSON path). The
//! PLY files are in [`ply`], the glTF ones in [`gltf`]; the helpers and the OBJ they are
//! compared with are here.

mod gltf;
mod ply;

use crate::common::temp::temp_path;
use accelbench::geometry::Triangle;
use accelbench::scene::{Scene, load_scene};
use std::path::{Path, PathBuf};

/// Writes `bytes` to `dir/name` and returns the path.
pub(super) fn file(dir: &Path, name: &str, bytes: &[u8]) -> PathBuf {
    let p = dir.join(name);
    std::fs::write(&p, bytes).unwrap();
    p
}

pub(super) fn load(p: &Path) -> Scene {
    load_scene(p.to_str().unwrap()).unwrap_or_else(|e| panic!("{}: {e}", p.display()))
}

pub(super) fn bits(t: &[Triangle]) -> Vec<u32> {
    t.iter()
        .flat_map(|t| t.v.iter().flat_map(|v| v.to_array().map(f32::to_bits)))
        .collect()
}

/// The scene at `p` has the triangles (bit for bit) and reference bounds of `obj`.
pub(super) fn same_as_obj(dir: &Path, p: &Path, obj: &str) {
    let want = load(&file(dir, "expected.obj", obj.as_bytes()));
    let got = load(p);
    assert_eq!(
        bits(&got.triangles),
        bits(&want.triangles),
        "{}",
        p.display()
    );
    assert_eq!(
        got.reference_bounds,
        want.reference_bounds,
        "{}",
        p.display()
    );
}

/// `p` is refused with every piece of `expected` in the message.
pub(super) fn refused(p: &Path, expected: &[&str]) {
    let e = load_scene(p.to_str().unwrap())
        .map(drop)
        .unwrap_err()
        .to_string();
    for x in expected {
        assert!(e.contains(x), "{}: expected '{x}' in: {e}", p.display());
    }
}

/// Five vertices (the last used by no face), a quad and a triangle, as OBJ.
pub(super) const OBJ: &str =
    "v 0 0 0\nv 1 0.1 0\nv 1 1 0\nv 0 1 -0.5\nv 5 5 5\nf 1 2 3 4\nf 4 3 1\n";
pub(super) const VERTS: [[f32; 3]; 5] = [
    [0.0, 0.0, 0.0],
    [1.0, 0.1, 0.0],
    [1.0, 1.0, 0.0],
    [0.0, 1.0, -0.5],
    [5.0, 5.0, 5.0],
];
#[test]
fn meshes_named_by_a_scene_file_may_be_ply_or_gltf() {
    use gltf::one_triangle;
    use ply::ASCII;
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    file(d, "a.ply", ASCII.as_bytes());
    one_triangle(d, |j, b| (j, b));
    let toml = "[[mesh]]\npath = \"a.ply\"\n\n[[mesh]]\npath = \"m.gltf\"\ntranslate = [0, 0, 1]\n";
    let s = load(&file(d, "s.toml", toml.as_bytes()));
    assert_eq!(s.triangles.len(), 4);
}

#[test]
fn gen_writes_binary_ply_that_info_reads() {
    use crate::common::cli::{accelbench_fails, accelbench_ok};
    let (dir, ply) = temp_path("t.ply");
    let obj = dir.path().join("t.obj");
    for out in [&ply, &obj] {
        let args = [
            "gen",
            "--generator",
            "terrain",
            "--n",
            "500",
            "--out",
            out.to_str().unwrap(),
        ];
        accelbench_ok(&args);
    }
    assert!(
        std::fs::read(&ply)
            .unwrap()
            .starts_with(b"ply\nformat binary_little_endian 1.0\n")
    );
    assert_eq!(bits(&load(&ply).triangles), bits(&load(&obj).triangles));
    let info = accelbench_ok(&["info", "--scene", ply.to_str().unwrap()]);
    assert!(
        info.contains("triangles:") && info.contains("scene:       t"),
        "{info}"
    );
    let args = [
        "gen",
        "--generator",
        "soup",
        "--format",
        "ply",
        "--out",
        obj.to_str().unwrap(),
    ];
    accelbench_fails(&args, &["name the file .ply"]);
}
