//! Instanced scene files: `[[instance]]` places a mesh as `[[mesh]]` would, bad tables are
//! refused with their line, and a run races `tlas` against the flattened scene, classifying it
//! (the bit-for-bit contract against brute force over the instances is `index::tlas::tests`).

use crate::common::cli::accelbench_ok;
use accelbench::scene::load_scene;

/// Writes `toml` (and a one-triangle-pair OBJ beside it) into a temporary folder and loads it.
fn load(toml: &str) -> Result<accelbench::scene::Scene, String> {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(
        dir.path().join("quad.obj"),
        "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0.2\nf 1 2 3\nf 1 3 4\n",
    )
    .unwrap();
    let path = dir.path().join("scene.toml");
    std::fs::write(&path, toml).unwrap();
    load_scene(path.to_str().unwrap()).map_err(|e| format!("{e:#}"))
}

#[test]
fn an_instance_places_its_mesh_as_a_mesh_table_does() {
    let placement = r#"scale = [2, 1, 0.5]
rotate = { axis = [1, 2, 3], degrees = 33 }
translate = [4, -5, 6]"#;
    let meshed = load(&format!("[[mesh]]\npath = \"quad.obj\"\n{placement}\n")).unwrap();
    let instanced = load(&format!(
        "[[instance]]\npath = \"quad.obj\"\n{placement}\n\n[[instance]]\npath = \"quad.obj\"\n"
    ))
    .unwrap();
    assert!(meshed.instances.is_none());
    assert_eq!(instanced.triangles[..2], meshed.triangles[..]);
    let set = instanced.instances.as_ref().unwrap();
    assert_eq!(set.meshes.len(), 1, "one mesh file, loaded once");
    assert_eq!(set.instances.len(), 2);
    assert_eq!(set.instances[1].first, 2);
}

#[test]
fn bad_instance_tables_are_refused_with_their_line() {
    for (toml, says) in [
        (
            "[[instance]]\npath = \"quad.obj\"\nobject = \"a\"\n",
            "exactly one of `path`",
        ),
        ("\n[[instance]]\nobject = \"tree\"\n", "line 2"),
        ("[[instance]]\nobject = \"tree\"\n", "[object.tree]"),
        (
            "[object.s]\ngenerator = \"spheres\"\n[[instance]]\nobject = \"s\"\n",
            "triangle meshes only",
        ),
        (
            "[[instance]]\npath = \"quad.obj\"\nkeyframes = [{ t = 0 }]\n",
            "keyframes on [[instance]]",
        ),
        (
            "[object.q]\npath = \"quad.obj\"\n[[mesh]]\npath = \"quad.obj\"\n",
            "no [[instance]] places it",
        ),
        (
            "[object.q]\npath = \"quad.obj\"\ngenerator = \"soup\"\n[[instance]]\nobject = \"q\"\n",
            "either `path`",
        ),
        ("[[instance]]\npath = \"missing.obj\"\n", "missing.obj"),
    ] {
        let err = load(toml).err().unwrap_or_else(|| panic!("{toml} loaded"));
        assert!(err.contains(says), "{toml}: expected '{says}' in: {err}");
    }
}

#[test]
fn a_run_races_tlas_against_the_flattened_scene_and_classifies_it() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("report");
    accelbench_ok(&[
        "run",
        "--scenes",
        "scenes/instances.toml",
        "--indices",
        "bvh8,tlas,tlas:inner=\"kdtree\",top=\"bvh8\"",
        "--rays",
        "primary,incoherent",
        "--primary-size",
        "64",
        "--incoherent",
        "4000",
        "--repeats",
        "1",
        "--threads",
        "1",
        "--quiet",
        "--out",
        out.to_str().unwrap(),
    ]);
    let mut csv = csv::Reader::from_path(out.join("results.csv")).unwrap();
    let head = csv.headers().unwrap().clone();
    let col = |name: &str| head.iter().position(|h| h == name).unwrap();
    let (index, set, wrong, mismatches) = (
        col("index"),
        col("ray_set"),
        col("peer_wrong"),
        col("mismatches"),
    );
    let mut tlas_rows = 0;
    for row in csv.records() {
        let row = row.unwrap();
        let rays = if &row[set] == "primary" {
            64 * 64
        } else {
            4000
        };
        if row[index].starts_with("tlas") {
            tlas_rows += 1;
            let w: usize = row[wrong].parse().unwrap();
            assert!(w * 100 <= rays, "{:?}: {w} wrong", row);
        } else {
            assert_eq!(&row[mismatches], "0", "{row:?}");
            assert_eq!(&row[wrong], "", "ours on the flattened scene: {row:?}");
        }
    }
    assert!(
        tlas_rows >= 4,
        "two tlas configurations on two sets: {tlas_rows} rows"
    );
}
