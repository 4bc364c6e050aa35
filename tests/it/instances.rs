//! Instanced scene files and `tlas`: `[[instance]]` places a mesh as `[[mesh]]` would, bad
//! tables are refused with their line; every `tlas` configuration answers as brute force over the
//! instances does, bit for bit, with the flattened scene's ids; and a run races `tlas` against
//! the flattened scene, classifying it.

use crate::common::cli::accelbench_ok;
use accelbench::geometry::{Hit, Ray, TriangleKernelKind};
use accelbench::index::{IndexSpec, TraceIndex, TraceMode, build_index};
use accelbench::rays::{incoherent_rays, primary_rays};
use accelbench::scene::Scene;
use accelbench::scene::file::load_scene_file;
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

/// Two meshes placed eight times: scaled, turned, overlapping, one placed twice at the same spot
/// (ties between instances), beside a generator of its own (an identity instance).
const SCENE: &str = r#"
[object.ball]
generator = "icosphere"
n = 320

[object.rocks]
generator = "soup"
n = 200
seed = 5

[[generator]]
name = "terrain"
n = 300
scale = [6, 0.5, 6]
translate = [-3, -1, -3]

[[instance]]
object = "ball"

[[instance]]
object = "ball"
translate = [1.2, 0.1, 0]
scale = 0.5
rotate = { axis = [0, 1, 1], degrees = 40 }

[[instance]]
object = "ball"
translate = [1.2, 0.1, 0]
scale = 0.5
rotate = { axis = [0, 1, 1], degrees = 40 }

[[instance]]
object = "ball"
translate = [-1.5, 0.4, 0.5]
scale = [0.3, 0.9, 0.6]

[[instance]]
object = "rocks"
translate = [0, 0.2, -1.5]
scale = 1.7
rotate = { axis = [1, 0, 0], degrees = 75 }

[[instance]]
object = "rocks"
translate = [0.3, 0.2, -1.2]
rotate = { axis = [0, 0, 1], degrees = -120 }

[[instance]]
object = "rocks"
translate = [-0.5, -0.3, 1.4]
scale = -0.8

[[instance]]
object = "ball"
translate = [2.0, -0.5, 1.5]
scale = 0.01
"#;

fn scene() -> Scene {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("instances.toml");
    std::fs::write(&path, SCENE).unwrap();
    load_scene_file(&path).unwrap()
}

fn rays(scene: &Scene) -> Vec<Ray> {
    let b = scene.bounds();
    let mut rays = primary_rays(&b, 48, 48).unwrap();
    rays.extend(incoherent_rays(&b, 3000, 9));
    rays
}

fn tlas(scene: &Scene, params: &str) -> Box<dyn TraceIndex> {
    let spec: IndexSpec = format!("tlas:{params}").parse().unwrap();
    build_index(&spec, &scene.geometry(), TriangleKernelKind::Watertight).unwrap()
}

fn closest(index: &dyn TraceIndex, rays: &[Ray], mode: TraceMode) -> Vec<Option<Hit>> {
    let mut out = vec![None; rays.len()];
    index.closest_hits_in(mode, rays, &mut out, None);
    out
}

fn any(index: &dyn TraceIndex, rays: &[Ray], mode: TraceMode) -> Vec<bool> {
    let mut out = vec![false; rays.len()];
    index.any_hits_in(mode, rays, &mut out, None);
    out
}

fn bits(hits: &[Option<Hit>]) -> Vec<Option<(u32, u32)>> {
    hits.iter()
        .map(|h| h.map(|h| (h.prim, h.t.to_bits())))
        .collect()
}

#[test]
fn the_scene_file_keeps_its_instances_beside_the_flattened_triangles() {
    let scene = scene();
    let set = scene.instances.as_ref().expect("instanced");
    // The terrain (its own mesh) and the two named objects, each loaded once.
    assert_eq!(set.meshes.len(), 3);
    assert_eq!(set.instances.len(), 9);
    assert!(set.covers_scene);
    assert_eq!(set.instanced_triangles(), scene.triangles.len());
    let mut next = 0;
    for inst in &set.instances {
        assert_eq!(inst.first, next, "instances cover the ids in order");
        next += inst.len;
    }
}

#[test]
fn every_configuration_answers_as_brute_force_over_the_instances_bit_for_bit() {
    let scene = scene();
    let rays = rays(&scene);
    let reference = tlas(&scene, "inner=\"brute\",top=\"brute\"");
    let want = bits(&closest(reference.as_ref(), &rays, TraceMode::Single));
    let want_any = any(reference.as_ref(), &rays, TraceMode::Single);
    let hits = want.iter().filter(|h| h.is_some()).count();
    assert!(hits > rays.len() / 4, "the rays must hit: {hits}");
    for inner in [
        "bvh",
        "bvh4",
        "bvh8",
        "grid",
        "grid2",
        "octree",
        "octree-topdown",
        "kdtree",
        "bsp",
    ] {
        for top in ["bvh", "bvh4", "bvh8"] {
            let index = tlas(&scene, &format!("inner=\"{inner}\",top=\"{top}\""));
            for mode in [TraceMode::Single, TraceMode::Stream, TraceMode::Packets(8)] {
                if !index.traces_in(mode) {
                    continue;
                }
                let got = bits(&closest(index.as_ref(), &rays, mode));
                let wrong = (got.iter().zip(&want)).filter(|(g, w)| g != w).count();
                assert_eq!(wrong, 0, "inner={inner} top={top} {}", mode.label());
                let got_any = any(index.as_ref(), &rays, mode);
                assert_eq!(got_any, want_any, "any hit: inner={inner} top={top}");
            }
            for (ray, w) in rays.iter().zip(&want).step_by(37) {
                let one = index.closest_hit(ray).map(|h| (h.prim, h.t.to_bits()));
                assert_eq!(one, *w, "one ray: inner={inner} top={top}");
            }
        }
    }
}

#[test]
fn ties_between_instances_go_to_the_lower_id_and_ids_are_the_flattened_ones() {
    let scene = scene();
    let set = scene.instances.clone().unwrap();
    let index = tlas(&scene, "");
    let flat = build_index(
        &IndexSpec::named("brute"),
        &scene.geometry(),
        TriangleKernelKind::Watertight,
    )
    .unwrap();
    let rays = rays(&scene);
    let got = closest(index.as_ref(), &rays, TraceMode::Single);
    let want = closest(flat.as_ref(), &rays, TraceMode::Single);
    // Instances 2 and 3 (after the terrain's own, 0) are the same placement: the second never
    // answers, the first does.
    let second = set.instances[3].ids();
    assert!(got.iter().flatten().all(|h| !second.contains(&h.prim)));
    assert!(
        got.iter()
            .flatten()
            .any(|h| set.instances[2].ids().contains(&h.prim))
    );
    // Against the flattened scene: the same triangle almost always (rounding decides grazing
    // rays and near-ties), and a `t` within a few ulps of it when the triangle is the same.
    let (mut same, mut both) = (0, 0);
    for (g, w) in got.iter().zip(&want) {
        if let (Some(g), Some(w)) = (g, w) {
            both += 1;
            if g.prim == w.prim {
                same += 1;
                assert!(
                    (g.t - w.t).abs() <= 1e-4 * w.t.abs().max(1.0),
                    "{g:?} {w:?}"
                );
            }
        }
    }
    assert!(both > 1000 && same * 100 >= both * 99, "{same} of {both}");
}

#[test]
fn a_scene_without_instances_is_skipped_and_bad_parameters_are_refused() {
    let plain = accelbench::scene::generators::generate("icosphere", 100, 1).unwrap();
    let spec: IndexSpec = "tlas".parse().unwrap();
    let err = build_index(&spec, &plain.geometry(), TriangleKernelKind::Watertight)
        .err()
        .unwrap();
    assert!(err.to_string().contains("no [[instance]]"), "{err}");
    let scene = scene();
    for (params, says) in [
        ("inner=\"embree\"", "inner"),
        ("inner=\"tlas\"", "not one of our indices"),
        ("top=\"kdtree\"", "not a top level"),
        ("depth=3", "unknown field"),
    ] {
        let spec: IndexSpec = format!("tlas:{params}").parse().unwrap();
        let err = build_index(&spec, &scene.geometry(), TriangleKernelKind::Watertight)
            .err()
            .unwrap();
        assert!(err.to_string().contains(says), "{params}: {err}");
    }
}

#[test]
fn its_memory_counts_each_mesh_once() {
    let scene = scene();
    let index = tlas(&scene, "inner=\"bvh8\"");
    let info = index.info();
    let extra = |k: &str| info.extra.iter().find(|(n, _)| n == k).unwrap().1;
    assert_eq!(extra("instances"), 9.0);
    assert_eq!(extra("meshes"), 3.0);
    assert!(info.uncounted);
    // The flattened bvh8 holds every placed triangle; the instanced one each mesh once.
    let flat = build_index(
        &IndexSpec::named("bvh8"),
        &scene.geometry(),
        TriangleKernelKind::Watertight,
    )
    .unwrap();
    assert!(info.memory_bytes < flat.info().memory_bytes);
}
