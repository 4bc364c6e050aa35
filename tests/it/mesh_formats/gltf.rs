//! glTF and GLB files (the node hierarchy, every index size) against their OBJ, and malformed
//! ones refused with a JSON path or byte.

use super::{VERTS, file, load, refused};
use std::path::{Path, PathBuf};

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
pub(super) fn one_triangle(
    d: &Path,
    edit: impl FnOnce(String, Vec<u8>) -> (String, Vec<u8>),
) -> PathBuf {
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
