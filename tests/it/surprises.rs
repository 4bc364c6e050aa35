//! Input that used to be taken silently with a surprising result now gets a message (issue 47,
//! case 8): a command's output over its own input, OBJ statements that are not OBJ, a CI gate
//! that compared nothing, duplicate parameters and indices, more threads than cores.

use crate::common::cli::{Suite, accelbench, accelbench_fails, accelbench_ok, write_rays};
use crate::common::temp::temp_path;

/// The scene the ray-file cases trace.
const SCENE: &str = "icosphere:n=200";

/// A temporary folder (removed when dropped) and in it 8 x 8 primary rays of [`SCENE`].
fn primary_rays() -> (tempfile::TempDir, std::path::PathBuf) {
    let (dir, rays) = temp_path("r.rays");
    write_rays(&rays, SCENE, "primary", &["--size", "8"]);
    (dir, rays)
}

#[test]
fn trace_refuses_to_write_its_hits_over_its_rays() {
    let (_dir, rays) = primary_rays();
    let (r, scene) = (rays.to_str().unwrap(), SCENE);
    let before = std::fs::read(&rays).unwrap();
    let args = ["trace", "--scene", scene, "--rays", r, "--hits", r];
    accelbench_fails(&args, &["--hits", "would overwrite the input"]);
    assert_eq!(std::fs::read(&rays).unwrap(), before);
}

/// An image width beyond the batch (up to `u64::MAX`) is refused with a message, never a panic
/// or an overflow in the tiling; a width that fits traces in packets from tiles.
#[test]
fn trace_refuses_an_image_wider_than_its_rays() {
    let (_dir, rays) = primary_rays();
    let (r, scene) = (rays.to_str().unwrap(), SCENE);
    for w in ["18446744073709551615", "100000000"] {
        let args = ["trace", "--scene", scene, "--rays", r, "--image-width", w];
        accelbench_fails(&args, &["--image-width", "wider than the", "rays of"]);
    }
    let args = [
        "trace",
        "--scene",
        scene,
        "--rays",
        r,
        "--mode",
        "packets16",
        "--image-width",
        "7",
    ];
    accelbench_ok(&args);
}

#[test]
fn unknown_obj_statements_are_warned_about_once_each_with_their_line() {
    let (_dir, obj) = temp_path("typo.obj");
    let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\nF 2 4 3\nfo 2 4 3\nF 2 4 3\n";
    std::fs::write(&obj, text).unwrap();
    let out = accelbench(&["info", "--scene", obj.to_str().unwrap()]);
    assert!(out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(err.matches("warning:").count(), 2, "{err}");
    assert!(err.contains("line 6: 'F' is not an OBJ statement"), "{err}");
    assert!(
        err.contains("line 7: 'fo' is not an OBJ statement"),
        "{err}"
    );
}

#[test]
fn a_comparison_gate_that_compared_nothing_fails() {
    let dir = tempfile::tempdir().unwrap();
    let report = |scene: &str| {
        let out = dir.path().join(scene.replace([':', '='], "_"));
        Suite::run(scene, "bvh", "primary", &out).ok();
        out.to_str().unwrap().to_owned()
    };
    let (a, b) = (report("icosphere:n=200"), report("soup:n=200"));
    accelbench_ok(&["compare", &a, &b]);
    accelbench_fails(
        &["compare", &a, &b, "--fail-above", "10"],
        &["share no row"],
    );
}

#[test]
fn a_parameter_or_an_index_given_twice_is_refused() {
    accelbench_fails(
        &["info", "--scene", "soup:n=10,n=20"],
        &["'n' is given twice"],
    );
    Suite::verify("soup:n=100", "bvh,bvh", "primary").fails(&["--indices lists 'bvh' twice"]);
    Suite::verify("soup:n=100", "bvh:leaf_size=2,leaf_size=4", "primary")
        .without("--quick")
        .fails(&["leaf_size"]);
}

#[test]
fn more_threads_than_cores_get_a_note() {
    let (_dir, rays) = primary_rays();
    let (r, scene) = (rays.to_str().unwrap(), SCENE);
    let cores = std::thread::available_parallelism().unwrap().get();
    let many = (cores + 1).to_string();
    let out = accelbench(&["trace", "--scene", scene, "--rays", r, "--threads", &many]);
    assert!(out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains(&format!(
            "note: --threads {many} is more than the {cores} cores"
        )),
        "{err}"
    );
    let out = accelbench(&["trace", "--scene", scene, "--rays", r, "--threads", "1"]);
    assert!(!String::from_utf8_lossy(&out.stderr).contains("note:"));
}
