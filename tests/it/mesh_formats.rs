//! PLY and glTF loaders (issue 49) against small hand-made files: each loaded scene equals,
//! triangle for triangle, the same scene written as OBJ (and has the same reference bounds);
//! malformed files of each format are refused with a location (line, byte or JSON path).

use crate::common::temp::temp_path;
use accelbench::geometry::Triangle;
use accelbench::scene::{Scene, load_scene};
use std::path::{Path, PathBuf};

/// Writes `bytes` to `dir/name` and returns the path.
fn file(dir: &Path, name: &str, bytes: &[u8]) -> PathBuf {
    let p = dir.join(name);
    std::fs::write(&p, bytes).unwrap();
    p
}

fn load(p: &Path) -> Scene {
    load_scene(p.to_str().unwrap()).unwrap_or_else(|e| panic!("{}: {e}", p.display()))
}

fn bits(t: &[Triangle]) -> Vec<u32> {
    t.iter()
        .flat_map(|t| t.v.iter().flat_map(|v| v.to_array().map(f32::to_bits)))
        .collect()
}

/// The scene at `p` has the triangles (bit for bit) and reference bounds of `obj`.
fn same_as_obj(dir: &Path, p: &Path, obj: &str) {
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
fn refused(p: &Path, expected: &[&str]) {
    let e = load_scene(p.to_str().unwrap())
        .map(drop)
        .unwrap_err()
        .to_string();
    for x in expected {
        assert!(e.contains(x), "{}: expected '{x}' in: {e}", p.display());
    }
}

/// Five vertices (the last used by no face), a quad and a triangle, as OBJ.
const OBJ: &str = "v 0 0 0\nv 1 0.1 0\nv 1 1 0\nv 0 1 -0.5\nv 5 5 5\nf 1 2 3 4\nf 4 3 1\n";
const VERTS: [[f32; 3]; 5] = [
    [0.0, 0.0, 0.0],
    [1.0, 0.1, 0.0],
    [1.0, 1.0, 0.0],
    [0.0, 1.0, -0.5],
    [5.0, 5.0, 5.0],
];

const ASCII: &str = "ply\nformat ascii 1.0\ncomment hand-made\nelement vertex 5\nproperty float x\nproperty float y\nproperty float z\nelement face 2\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0.1 0\n1 1 0\n0 1 -0.5\n5 5 5\n4 0 1 2 3\n3 3 2 0\n";

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

/// A glTF document's binary buffer and its views, built up by [`Gltf::view`].
#[derive(Default)]
struct Gltf {
    bin: Vec<u8>,
    views: Vec<String>,
    accessors: Vec<String>,
}

impl Gltf {
    /// Adds `data` as a buffer view with an accessor of `count` elements; returns the accessor.
    fn accessor(&mut self, data: &[u8], component: u32, ty: &str, count: usize) -> usize {
        pad(&mut self.bin, 0);
        let v = self.views.len();
        self.views.push(format!(
            r#"{{"buffer":0,"byteOffset":{},"byteLength":{}}}"#,
            self.bin.len(),
            data.len()
        ));
        self.bin.extend_from_slice(data);
        self.accessors.push(format!(
            r#"{{"bufferView":{v},"componentType":{component},"type":"{ty}","count":{count}}}"#
        ));
        self.accessors.len() - 1
    }

    fn positions(&mut self, p: &[[f32; 3]]) -> usize {
        let b: Vec<u8> = p.iter().flatten().flat_map(|x| x.to_le_bytes()).collect();
        self.accessor(&b, 5126, "VEC3", p.len())
    }

    /// The JSON with `meshes` and `rest` (nodes, scenes) and the buffer `uri` (none: GLB).
    fn json(&self, meshes: &str, rest: &str, uri: Option<&str>) -> String {
        let uri = uri.map_or(String::new(), |u| format!(r#","uri":"{u}""#));
        format!(
            r#"{{"asset":{{"version":"2.0"}},"buffers":[{{"byteLength":{}{uri}}}],"bufferViews":[{}],"accessors":[{}],"meshes":{meshes}{rest}}}"#,
            self.bin.len(),
            self.views.join(","),
            self.accessors.join(",")
        )
    }
}

/// `v` padded with `byte` to a multiple of 4 bytes (glTF's alignment).
fn pad(v: &mut Vec<u8>, byte: u8) {
    v.resize(v.len().next_multiple_of(4), byte);
}

/// A `.glb` file of `json` and `bin`.
fn glb(json: &str, bin: &[u8]) -> Vec<u8> {
    let mut j = json.as_bytes().to_vec();
    pad(&mut j, b' ');
    let mut b = bin.to_vec();
    pad(&mut b, 0);
    let mut out = b"glTF".to_vec();
    out.extend(2u32.to_le_bytes());
    out.extend(((28 + j.len() + b.len()) as u32).to_le_bytes());
    out.extend((j.len() as u32).to_le_bytes());
    out.extend(b"JSON");
    out.extend(j);
    out.extend((b.len() as u32).to_le_bytes());
    out.extend(b"BIN\0");
    out.extend(b);
    out
}

/// Node 0 (a matrix: 90 degrees about z, then +(1, 2, 3)) with child node 1 (scale 2, 180
/// degrees about y, then +(0, 0, -4)) placing mesh 0, and root node 2 placing it untransformed.
/// Every product is exact in `f32`.
const NODES: &str = r#","nodes":[{"matrix":[0,1,0,0, -1,0,0,0, 0,0,1,0, 1,2,3,1],"children":[1]},{"scale":[2,2,2],"rotation":[0,1,0,0],"translation":[0,0,-4],"mesh":0},{"mesh":0}],"scenes":[{"nodes":[0,2]}],"scene":0"#;

/// Where node 1 puts `p`, by hand.
fn placed(p: [f32; 3]) -> [f32; 3] {
    let s = p.map(|c| 2.0 * c);
    let t = [-s[0], s[1], -s[2] - 4.0];
    [-t[1] + 1.0, t[0] + 2.0, t[2] + 3.0]
}

/// The expected OBJ of the mesh `tris` (corner indices into `VERTS`) placed by node 1 and
/// then untransformed (node 2).
fn expected_obj(tris: &[[usize; 3]]) -> String {
    let mut obj = String::new();
    for v in VERTS.iter().map(|&v| placed(v)).chain(VERTS) {
        obj += &format!("v {} {} {}\n", v[0], v[1], v[2]);
    }
    for base in [1, 6] {
        for t in tris {
            obj += &format!("f {} {} {}\n", t[0] + base, t[1] + base, t[2] + base);
        }
    }
    obj
}

#[test]
fn gltf_and_glb_apply_the_node_hierarchy_and_read_every_index_size() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let mut g = Gltf::default();
    let pos = g.positions(&VERTS);
    let u16s: Vec<u8> = [0u16, 1, 2, 0, 2, 3]
        .iter()
        .flat_map(|i| i.to_le_bytes())
        .collect();
    let i16 = g.accessor(&u16s, 5123, "SCALAR", 6);
    let u32s: Vec<u8> = [3u32, 2, 0].iter().flat_map(|i| i.to_le_bytes()).collect();
    let i32 = g.accessor(&u32s, 5125, "SCALAR", 3);
    let i8 = g.accessor(&[1, 2, 4], 5121, "SCALAR", 3);
    let flat = g.positions(&[VERTS[4], VERTS[0], VERTS[2]]);
    let strip = g.accessor(&[0, 1, 3, 2], 5121, "SCALAR", 4);
    let p = |a: usize, i: Option<usize>, mode: u32| {
        let idx = i.map_or(String::new(), |i| format!(r#","indices":{i}"#));
        format!(r#"{{"attributes":{{"POSITION":{a}}}{idx},"mode":{mode}}}"#)
    };
    let meshes = format!(
        r#"[{{"name":"m","primitives":[{},{},{},{},{}]}}]"#,
        p(pos, Some(i16), 4),
        p(pos, Some(i32), 4),
        p(pos, Some(i8), 0),
        p(flat, None, 4),
        p(pos, Some(strip), 5)
    );
    // The non-indexed primitive's three vertices repeat vertices 4, 0 and 2; the points
    // primitive is skipped.
    let tris = [
        [0, 1, 2],
        [0, 2, 3],
        [3, 2, 0],
        [4, 0, 2],
        [0, 1, 3],
        [1, 2, 3],
    ];
    let obj = expected_obj(&tris);
    let gltf = file(
        d,
        "m.gltf",
        g.json(&meshes, NODES, Some("m%20data.bin")).as_bytes(),
    );
    file(d, "m data.bin", &g.bin);
    let want = load(&file(d, "expected.obj", obj.as_bytes()));
    for p in [
        gltf,
        file(d, "m.GLB", &glb(&g.json(&meshes, NODES, None), &g.bin)),
    ] {
        let got = load(&p);
        assert_eq!(got.triangles, want.triangles, "{}", p.display());
        assert_eq!(
            got.reference_bounds,
            want.reference_bounds,
            "{}",
            p.display()
        );
    }
}

/// A one-triangle glTF (`m.gltf` with `m.bin`) after `edit` of its JSON and buffer.
fn one_triangle(d: &Path, edit: impl FnOnce(String, Vec<u8>) -> (String, Vec<u8>)) -> PathBuf {
    let mut g = Gltf::default();
    let pos = g.positions(&VERTS[..3]);
    let idx = g.accessor(&[0, 1, 2, 0], 5121, "SCALAR", 3);
    let meshes =
        format!(r#"[{{"primitives":[{{"attributes":{{"POSITION":{pos}}},"indices":{idx}}}]}}]"#);
    let (json, bin) = edit(g.json(&meshes, "", Some("m.bin")), g.bin);
    file(d, "m.bin", &bin);
    file(d, "m.gltf", json.as_bytes())
}

#[test]
fn malformed_gltf_is_refused_with_a_location() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let ok = one_triangle(d, |j, b| (j, b));
    assert_eq!(load(&ok).triangles.len(), 1);
    let nan = one_triangle(d, |j, mut b| {
        b[16..20].copy_from_slice(&f32::NAN.to_le_bytes());
        (j, b)
    });
    refused(&nan, &["m.bin, byte 12", "NaN", "vertex 1"]);
    let index = one_triangle(d, |j, mut b| {
        b[37] = 7;
        (j, b)
    });
    refused(
        &index,
        &[
            "m.bin",
            "byte 37",
            "is 7, but the primitive's POSITION accessor has 3 vertices",
        ],
    );
    let short = one_triangle(d, |j, b| (j, b[..30].to_vec()));
    refused(
        &short,
        &["at buffers[0]", "byteLength 40 but its data has 30 bytes"],
    );
    let count = one_triangle(d, |j, b| (j.replace(r#""count":3}"#, r#""count":4}"#), b));
    refused(&count, &["at accessors[0]", "do not fit in bufferView 0"]);
    let syntax = one_triangle(d, |j, b| (j.replacen(',', ",\n,", 1), b));
    refused(&syntax, &["m.gltf is not a valid glTF file: line 2"]);
    let bad_ref = one_triangle(d, |j, b| (j.replace(r#""indices":1"#, r#""indices":9"#), b));
    refused(&bad_ref, &["meshes[0].primitives[0].indices"]);
    one_triangle(d, |j, b| (j, b));
    std::fs::remove_file(d.join("m.bin")).unwrap();
    refused(&d.join("m.gltf"), &["cannot read", "m.bin"]);
    let g = glb("{}", &[]);
    refused(
        &file(d, "t.glb", &g[..g.len() - 4]),
        &["byte 8", "truncated"],
    );
}

#[test]
fn meshes_named_by_a_scene_file_may_be_ply_or_gltf() {
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
