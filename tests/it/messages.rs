//! Bad OBJ input gets a message that names the line and what to fix, and what the loader
//! ignores anyway (names, comments) is not a reason to refuse a file (issue 47, case 9).

use crate::common::cli::{Suite, accelbench, accelbench_fails, the_line_with};
use crate::common::temp::temp_path;

const TRIANGLE: &[u8] = b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";

/// Writes `bytes` as an .obj file and runs `info` on it.
fn info_of(bytes: &[u8], check: impl FnOnce(&str, std::process::Output)) {
    let (_dir, obj) = temp_path("m.obj");
    std::fs::write(&obj, bytes).unwrap();
    let path = obj.to_str().unwrap();
    check(path, accelbench(&["info", "--scene", path]));
}

fn loads(bytes: &[u8]) {
    info_of(bytes, |p, out| {
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(out.status.success(), "{p}: {err}");
    });
}

fn refused(bytes: &[u8], expected: &[&str]) {
    info_of(bytes, |p, _| {
        accelbench_fails(&["info", "--scene", p], expected)
    });
}

#[test]
fn names_in_latin1_and_trailing_comments_are_accepted() {
    loads(&[b"o caf\xe9\ng gr\xfcn\nusemtl m\xe4t\n", TRIANGLE].concat());
    loads(b"v 0 0 0 # origin\nv 1 0 0\nv 0 1 0\nf 1 2 3 # the face\n");
}

#[test]
fn vertex_errors_name_their_line_and_the_fix() {
    refused(
        b"v 0 0 0\nv 1 \xe9 0\nv 0 1 0\nf 1 2 3\n",
        &["line 2: ", "UTF-8"],
    );
    let counts = [&b"v 0 0 0 1 2 3 4 5\n"[..], b"v 0 0\n"];
    for v in counts {
        refused(&[v, TRIANGLE].concat(), &["line 1: a vertex is 'v x y z'"]);
    }
    refused(
        &[TRIANGLE, b"v 1e39 0 0\n"].concat(),
        &["line 5: ", "beyond the range of f32"],
    );
}

#[test]
fn a_seed_too_large_says_the_limit() {
    let spec = "soup:n=10,seed=18446744073709551616";
    accelbench_fails(
        &["info", "--scene", spec],
        &["the seed must be at most 18446744073709551615"],
    );
}

/// On one triangle at 1e30 the primary rays hit, but its normal overflows `f32`, so no
/// secondary ray starts: the skip says so instead of "no primary hit" (issue 47, case 7).
#[test]
fn secondary_sets_skipped_on_a_huge_triangle_say_why() {
    info_of(
        b"v 1e30 1e30 1e30\nv 2e30 1e30 1e30\nv 1e30 2e30 1e30\nf 1 2 3\n",
        |p, _| {
            let out = Suite::verify(p, "bvh", "primary,shadow").ok();
            assert!(
                out.contains("ray set shadow: skipped: none of the"),
                "{out}"
            );
            assert!(!out.contains("no primary hit"), "{out}");
        },
    );
}

/// A scene file with `toml` beside a one-triangle `tri.obj`; `info` on it.
fn scene_file_info(toml: &str) -> (tempfile::TempDir, String) {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("tri.obj"), TRIANGLE).unwrap();
    let p = dir.path().join("scene.toml");
    std::fs::write(&p, toml).unwrap();
    let path = p.to_str().unwrap().to_owned();
    (dir, path)
}

#[test]
fn a_radius_beyond_f32_says_so_with_its_line() {
    let (_dir, p) = scene_file_info("[[sphere]]\ncenter = [0, 0, 0]\nradius = 1e39\n");
    accelbench_fails(
        &["info", "--scene", &p],
        &["line 3", "1e39 is beyond the range of f32"],
    );
}

#[test]
fn a_scene_file_given_as_a_mesh_is_named_as_one() {
    let (dir, p) = scene_file_info("[[mesh]]\npath = \"other.toml\"\n");
    std::fs::write(
        dir.path().join("other.toml"),
        "[[mesh]]\npath = \"tri.obj\"\n",
    )
    .unwrap();
    accelbench_fails(
        &["info", "--scene", &p],
        &["other.toml", "is a scene file (.toml), not a mesh"],
    );
}

/// A folder given as the input file and a missing output folder get different messages.
#[test]
fn an_input_folder_and_a_missing_output_folder_are_told_apart() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path().to_str().unwrap();
    let out = accelbench(&["trace", "--scene", "icosphere:n=100", "--rays", d]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success());
    assert!(err.contains("it is a folder, not a file"), "{err}");
    let rays = dir.path().join("a.rays");
    let missing = dir.path().join("no/such/folder/a.rays");
    fn incoherent(out: &std::path::Path) -> Vec<&str> {
        let head = ["rays", "--scene", "icosphere:n=100", "--set", "incoherent"];
        [
            &head[..],
            &["--count", "10", "--out", out.to_str().unwrap()],
        ]
        .concat()
    }
    crate::common::cli::accelbench_ok(&incoherent(&rays));
    accelbench_fails(
        &incoherent(&missing),
        &[
            "cannot write",
            "does not exist: create it or give another path",
        ],
    );
    let hits = dir.path().join("gone/a.hits");
    accelbench_fails(
        &[
            "trace",
            "--scene",
            "icosphere:n=100",
            "--rays",
            rays.to_str().unwrap(),
            "--hits",
            hits.to_str().unwrap(),
        ],
        &["cannot write", "gone does not exist"],
    );
}

/// With `--quiet` the skip of a ray set still reaches the user, on stderr (issue 47, case 7).
#[test]
fn run_quiet_still_says_why_a_set_was_skipped() {
    let (dir, obj) = temp_path("huge.obj");
    std::fs::write(
        &obj,
        b"v 1e30 1e30 1e30\nv 2e30 1e30 1e30\nv 1e30 2e30 1e30\nf 1 2 3\n",
    )
    .unwrap();
    let out = Suite::run(
        obj.to_str().unwrap(),
        "bvh",
        "primary,shadow",
        &dir.path().join("r"),
    )
    .output();
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{err}");
    the_line_with(&err, "ray set shadow: skipped");
}
