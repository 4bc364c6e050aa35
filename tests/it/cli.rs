//! The command line on bad input (each case exits non-zero with a message that says what to
//! fix) and on the happy path (`rays`, then `trace` writes one hit record per ray; `gen` writes
//! an OBJ that loads back).

use std::path::Path;
use std::process::Command;

use crate::common;
use crate::common::temp::temp_path;
use common::cli::{accelbench, accelbench_fails as fails_with, accelbench_ok};

fn file(dir: &Path, name: &str, bytes: &[u8]) -> String {
    let p = dir.join(name);
    std::fs::write(&p, bytes).unwrap();
    p.to_string_lossy().into_owned()
}

fn ray_record(origin: [f32; 3], dir: [f32; 3]) -> Vec<u8> {
    let r = [
        origin[0],
        origin[1],
        origin[2],
        0.0,
        dir[0],
        dir[1],
        dir[2],
        f32::INFINITY,
    ];
    r.iter().flat_map(|x| x.to_le_bytes()).collect()
}

fn path(p: &Path) -> String {
    p.to_string_lossy().into_owned()
}

#[test]
fn bad_scenes_are_explained() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    fails_with(
        &["info", "--scene", "/nonexistent/missing.obj"],
        &["missing.obj", "cannot read"],
    );
    // Bad scene files: each error names the file and says what is wrong.
    let bad_files: [(&str, &[u8], &[&str]); 5] = [
        (
            "garbage.obj",
            b"this is not an obj file\n\x01\x02\n",
            &["'v' and 'f' lines"],
        ),
        (
            "nan.obj",
            b"v 0 0 0\nv 1 nan 0\nv 0 1 0\nf 1 2 3\n",
            &["line 2", "NaN"],
        ),
        ("empty.obj", b"", &["no primitives"]),
        (
            "bad.toml",
            b"[[sphere]]\ncenter = [0, 0, 0]\nradius = 1\ncolour = 2\n",
            &["unknown field `colour`"],
        ),
        (
            "radius.toml",
            b"[[sphere]]\ncenter = [0, 0, 0]\nradius = -1\n",
            &["radius > 0"],
        ),
    ];
    for (name, text, expected) in bad_files {
        let scene = file(d, name, text);
        let mut expected = expected.to_vec();
        expected.insert(0, name);
        fails_with(&["info", "--scene", &scene], &expected);
    }
    fails_with(
        &["info", "--scene", "teapot"],
        &["unknown scene 'teapot'", "icosphere", ".toml"],
    );
    fails_with(&["info", "--scene", "soup:n=0"], &["n = 0", "from 1 to"]);
    fails_with(
        &["info", "--scene", "soup:size=3"],
        &["unknown parameter 'size'"],
    );
}

#[test]
fn bad_trace_and_rays_arguments_are_explained() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let good = file(
        d,
        "good.rays",
        &ray_record([0.5, 0.5, -1.0], [0.0, 0.0, 1.0]),
    );
    let trace = |extra: &[&str], expected: &[&str]| {
        let mut args = vec!["trace", "--scene", "soup:n=1000"];
        args.extend_from_slice(extra);
        fails_with(&args, expected);
    };
    trace(
        &["--index", "nope", "--rays", &good],
        &["unknown index 'nope'", "brute"],
    );
    trace(
        &["--index", "brute:leaf=3", "--rays", &good],
        &["invalid parameters for index 'brute'", "leaf"],
    );
    trace(
        &["--rays", &good, "--threads", "0"],
        &["not a thread count"],
    );
    trace(&["--rays", &good, "--limit", "0"], &["--limit"]);
    let short = file(d, "short.rays", &[0u8; 33]);
    trace(&["--rays", &short], &["short.rays", "not a multiple of 32"]);
    let mut nan = ray_record([0.0; 3], [0.0, 0.0, 1.0]);
    nan.extend(ray_record([f32::NAN, 0.0, 0.0], [0.0, 0.0, 1.0]));
    let nan = file(d, "nan.rays", &nan);
    trace(&["--rays", &nan], &["nan.rays", "record 1", "origin"]);
    let zero = file(d, "zero.rays", &ray_record([0.0; 3], [0.0; 3]));
    trace(
        &["--rays", &zero],
        &["zero.rays", "record 0", "direction is zero"],
    );
    let out = path(&d.join("x.rays"));
    fails_with(
        &[
            "rays", "--scene", "soup", "--set", "primary", "--size", "0", "--out", &out,
        ],
        &["--size", "0"],
    );
    fails_with(
        &[
            "gen",
            "--generator",
            "spheres",
            "--out",
            &path(&d.join("s.obj")),
        ],
        &["spheres", "choose a triangle generator"],
    );
}

#[test]
fn rays_then_trace_writes_one_hit_per_ray() {
    let dir = tempfile::tempdir().unwrap();
    let rays = path(&dir.path().join("r.rays"));
    let hits = path(&dir.path().join("h.hits"));
    accelbench_ok(&[
        "rays",
        "--scene",
        "icosphere:n=2000",
        "--set",
        "incoherent",
        "--count",
        "300",
        "--out",
        &rays,
    ]);
    assert_eq!(std::fs::metadata(&rays).unwrap().len(), 300 * 32);
    let report = accelbench_ok(&[
        "trace",
        "--scene",
        "icosphere:n=2000",
        "--index",
        "brute",
        "--rays",
        &rays,
        "--hits",
        &hits,
        "--threads",
        "2",
    ]);
    assert!(report.contains("rays:             300"), "{report}");
    assert_eq!(std::fs::metadata(&hits).unwrap().len(), 300 * 8);
    accelbench_ok(&[
        "trace",
        "--scene",
        "icosphere:n=2000",
        "--rays",
        &rays,
        "--hits",
        &hits,
        "--limit",
        "17",
    ]);
    assert_eq!(std::fs::metadata(&hits).unwrap().len(), 17 * 8);
}

#[test]
fn gen_writes_an_obj_that_loads_back_and_example_scenes_load() {
    let (_dir, obj) = temp_path("meshes/terrain.obj");
    accelbench_ok(&[
        "gen",
        "--generator",
        "terrain",
        "--n",
        "2000",
        "--out",
        &path(&obj),
    ]);
    let info = accelbench_ok(&["info", "--scene", &path(&obj)]);
    assert!(info.contains("triangles:   2048"), "{info}");
    let info = accelbench_ok(&["info", "--scene", "scenes/generated_mix.toml"]);
    assert!(
        info.contains("lights:      2") && info.contains("fov 50 deg"),
        "{info}"
    );
}

#[test]
fn bunny_example_scene_loads_when_shared_meshes_are_present() {
    if common::cli::shared_mesh("stanford_bunny.obj").is_none() {
        return;
    }
    let info = accelbench_ok(&["info", "--scene", "scenes/bunny_on_terrain.toml"]);
    // 69,451 bunny triangles + a 50,000-triangle terrain (2 * 158^2 = 49,928).
    assert!(info.contains("triangles:   119379"), "{info}");
}

/// Each cause appears once in the message (no "cause: cause" from a `{source}` in the text that
/// anyhow's `{:#}` also prints as a chained source).
#[test]
fn error_causes_are_printed_once() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let folder = d.join("folder.obj");
    std::fs::create_dir(&folder).unwrap();
    let out = accelbench(&["info", "--scene", &path(&folder)]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success());
    assert_eq!(err.matches("os error 21").count(), 1, "{err}");
    let rays = file(d, "zero.rays", &ray_record([0.0; 3], [0.0; 3]));
    let out = accelbench(&["trace", "--scene", "icosphere:n=100", "--rays", &rays]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success());
    assert!(err.contains("record 0"), "{err}");
    assert_eq!(err.matches("direction is zero").count(), 1, "{err}");
}

#[test]
fn obj_face_errors_name_the_line_and_a_byte_order_mark_is_accepted() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    let truncated = file(d, "truncated.obj", format!("{tri}f 1 2\n").as_bytes());
    fails_with(
        &["info", "--scene", &truncated],
        &["truncated.obj", "line 5", "at least 3 vertices"],
    );
    let out_of_range = file(d, "range.obj", format!("{tri}f 1 2 7\n").as_bytes());
    fails_with(
        &["info", "--scene", &out_of_range],
        &["range.obj", "line 5", "vertex 7 does not exist"],
    );
    let bom = file(d, "bom.obj", format!("\u{feff}{tri}").as_bytes());
    assert!(accelbench_ok(&["info", "--scene", &bom]).contains("primitives:  1"));
}

#[test]
fn run_checks_its_output_folder_before_any_work() {
    let dir = tempfile::tempdir().unwrap();
    let a_file = file(dir.path(), "not-a-folder", b"");
    let start = std::time::Instant::now();
    fails_with(
        &["run", "--quick", "--out", &a_file],
        &["not-a-folder", "not a folder"],
    );
    let below = format!("{a_file}/sub");
    fails_with(
        &["run", "--quick", "--out", &below],
        &["not-a-folder/sub", "cannot create the folder"],
    );
    // A quick suite takes seconds; the check takes milliseconds.
    assert!(start.elapsed().as_secs() < 2, "{:?}", start.elapsed());
}

/// `accelbench info ... | true`: the reader is gone before the output is written.
#[test]
fn a_closed_output_pipe_ends_the_command_quietly() {
    use std::process::Stdio;
    let mut child = Command::new(env!("CARGO_BIN_EXE_accelbench"))
        .args(["info", "--scene", "icosphere:n=20000"])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    drop(child.stdout.take());
    let out = child.wait_with_output().unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        !err.contains("panicked") && !err.contains("Broken pipe"),
        "{err}"
    );
}

/// `info --indices` builds each index and prints its resident memory and the heap's
/// high-water mark during its build: the mark holds at least the finished structure, and a
/// build's temporaries (primitive references, bins) put it above.
#[test]
fn info_prints_each_index_build_peak_memory_above_its_resident_memory() {
    let out = accelbench_ok(&[
        "info",
        "--scene",
        "soup:n=20000",
        "--indices",
        "bvh,bvh8,grid,kdtree:leaf_size=2",
    ]);
    let rows: Vec<Vec<&str>> = out
        .lines()
        .skip_while(|l| !l.starts_with("index "))
        .skip(1)
        .map(|l| l.split_whitespace().collect())
        .collect();
    let names: Vec<&str> = rows.iter().map(|r| r[0]).collect();
    assert_eq!(
        names,
        ["bvh", "bvh8", "grid", "kdtree:leaf_size=2"],
        "{out}"
    );
    for r in &rows {
        let resident: u64 = r[2].parse().unwrap();
        let peak: u64 = r[3].parse().unwrap();
        assert!(resident > 0 && peak > resident, "{}: {out}", r[0]);
    }
    fails_with(
        &["info", "--scene", "soup:n=10", "--indices", "bvh,nope"],
        &["index 'nope'", "unknown"],
    );
}
