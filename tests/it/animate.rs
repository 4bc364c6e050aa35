//! Scenes that move: refitted box trees keep the hit contract on every frame (also under a scene
//! file's keyframes), indices without a refit say so, and `accelbench animate` writes a
//! verified report per frame.

use crate::common::cli::{accelbench_fails, accelbench_ok};
#[cfg(unix)]
use crate::common::cli::{interrupt_at, spawn_piped};
use crate::common::temp::temp_path;
use crate::common::{agreement_rays, assert_no_mismatch};
use accelbench::geometry::TriangleKernelKind;
use accelbench::harness::verify::compare_indices;
use accelbench::index::{BuildError, IndexSpec, build_index};
use accelbench::scene::motion::MotionSpec;
use accelbench::scene::{Scene, generators, load_scene};

/// The extra figure `key` of an index's info.
fn extra(index: &dyn accelbench::index::TraceIndex, key: &str) -> f64 {
    let found = index.info().extra.iter().find(|(k, _)| k == key);
    found.map(|(_, v)| *v).unwrap_or(f64::NAN)
}

/// Builds `spec` on frame 0 of `motion`, refits it to every later frame and checks it against
/// brute force built on that frame, closest and any hit, bit for bit.
fn assert_refit_agrees(spec: &str, scene: &Scene, motion: &str, frames: usize) {
    let motion: MotionSpec = motion.parse().unwrap();
    let spec: IndexSpec = spec.parse().unwrap();
    let brute = IndexSpec::named("brute");
    let k = TriangleKernelKind::Exact;
    let rays = agreement_rays(scene, 400);
    let first = motion.frame(scene, 0.0).unwrap();
    let mut index = build_index(&spec, &first, k).unwrap();
    assert!(index.can_refit(), "{spec}");
    let sah_first = extra(index.as_ref(), "sah_cost");
    for f in 1..frames {
        let frame = motion.frame(scene, f as f32 / (frames - 1) as f32).unwrap();
        index.refit(&frame).unwrap();
        let reference = build_index(&brute, &frame, k).unwrap();
        let what = format!("{spec} refitted to frame {f} of {motion}");
        let m = compare_indices(reference.as_ref(), index.as_ref(), &rays);
        assert_no_mismatch(&what, scene, rays.len(), &m);
    }
    // The twisted tree is looser: the refit recomputed the bounds it reports.
    let sah_last = extra(index.as_ref(), "sah_cost");
    assert!(
        sah_last > sah_first,
        "{spec}: SAH {sah_first} -> {sah_last}"
    );
}

#[test]
fn refitted_box_trees_keep_the_hit_contract_on_every_frame() {
    let tris = generators::generate("icosphere", 3000, 7).unwrap();
    let soup = generators::generate("soup", 2000, 3).unwrap();
    let mixed = generators::generate("mixed", 2000, 5).unwrap();
    for spec in [
        "bvh",
        "bvh4",
        "bvh8",
        "bvh:spatial_splits=true",
        "bvh8:spatial_splits=true",
    ] {
        assert_refit_agrees(spec, &tris, "twist:turns=1", 4);
        assert_refit_agrees(spec, &soup, "twist:turns=-0.5", 3);
        // Spheres move with the twist; the wide trees' leaves are ids here, not blocks.
        assert_refit_agrees(spec, &mixed, "twist:turns=0.75", 3);
    }
    let terrain = generators::generate("terrain", 3000, 2).unwrap();
    for spec in ["bvh", "bvh4", "bvh8"] {
        let m = compare_after_wave(spec, &terrain);
        assert_no_mismatch(spec, &terrain, 0, &m);
    }
}

/// `spec` refitted along a wave's frames, against brute force on the last frame.
fn compare_after_wave(spec: &str, scene: &Scene) -> Vec<accelbench::harness::verify::Mismatch> {
    let motion: MotionSpec = "wave:amplitude=0.1,waves=1.5".parse().unwrap();
    let k = TriangleKernelKind::Exact;
    let mut index = build_index(
        &spec.parse().unwrap(),
        &motion.frame(scene, 0.0).unwrap(),
        k,
    )
    .unwrap();
    let mut last = None;
    for t in [0.3, 0.6, 0.9] {
        let frame = motion.frame(scene, t).unwrap();
        index.refit(&frame).unwrap();
        last = Some(frame);
    }
    let brute = build_index(&IndexSpec::named("brute"), &last.unwrap(), k).unwrap();
    compare_indices(brute.as_ref(), index.as_ref(), &agreement_rays(scene, 400))
}

#[test]
fn indices_without_a_refit_and_changed_scenes_are_refused() {
    let scene = generators::generate("icosphere", 500, 1).unwrap();
    let geom = scene.geometry();
    let k = TriangleKernelKind::Exact;
    for name in ["kdtree", "grid", "octree", "bsp", "brute"] {
        let mut index = build_index(&IndexSpec::named(name), &geom, k).unwrap();
        assert!(!index.can_refit(), "{name}");
        let e = index.refit(&geom).unwrap_err();
        assert!(matches!(e, BuildError::Unsupported { .. }), "{name}: {e}");
        assert!(e.to_string().contains("rebuild"), "{name}: {e}");
    }
    let smaller = generators::generate("icosphere", 100, 1)
        .unwrap()
        .geometry();
    for name in ["bvh", "bvh4", "bvh8"] {
        let mut index = build_index(&IndexSpec::named(name), &geom, k).unwrap();
        let e = index.refit(&smaller).unwrap_err().to_string();
        assert!(
            e.contains("refit needs the primitives it was built over"),
            "{name}: {e}"
        );
    }
}

#[test]
fn animate_writes_a_verified_report_per_frame() {
    let (_out, dir) = temp_path("anim");
    let args = [
        "animate",
        "--scene",
        "icosphere:n=2000",
        "--motion",
        "twist:turns=0.5",
        "--frames",
        "3",
        "--indices",
        "bvh8,grid",
        "--primary-size",
        "32",
        "--incoherent",
        "1000",
        "--repeats",
        "1",
        "--threads",
        "1",
        "--quiet",
        "--out",
        dir.to_str().unwrap(),
    ];
    // A second run on the same folder replaces the first whole.
    accelbench_ok(&args);
    std::fs::write(dir.join("stale.svg"), "").unwrap();
    let stdout = accelbench_ok(&args);
    assert!(!dir.join("stale.svg").exists());
    let csv = std::fs::read_to_string(dir.join("frames.csv")).unwrap();
    let lines: Vec<&str> = csv.lines().skip(1).collect();
    // Frames 0..3, rows bvh8+refit, bvh8+rebuild, grid+rebuild.
    assert_eq!(lines.len(), 9, "{csv}");
    for (i, row) in ["bvh8+refit", "bvh8+rebuild", "grid+rebuild"]
        .iter()
        .cycle()
        .take(9)
        .enumerate()
    {
        let cells: Vec<&str> = lines[i].split(',').collect();
        assert_eq!((cells[0], cells[1]), ((i / 3).to_string().as_str(), *row));
        // Every ray verified (2000 primitives x 2024 rays is within the budget), none wrong.
        assert_eq!(cells[9..], ["2024", "0"], "{}", lines[i]);
        assert_eq!(cells[8].is_empty(), row.starts_with("grid"), "{}", lines[i]);
    }
    for file in [
        "cost_per_frame.svg",
        "update_ms.svg",
        "sah_cost.svg",
        "summary.md",
    ] {
        assert!(dir.join(file).is_file(), "{file}");
    }
    assert!(stdout.contains("| bvh8+refit | 3 |"), "{stdout}");
    assert!(stdout.contains("- bvh8: "), "{stdout}");
}

#[test]
fn animate_refuses_bad_motions_sets_and_frame_counts() {
    let base = [
        "animate",
        "--scene",
        "icosphere:n=100",
        "--quiet",
        "--out",
        "/nonexistent/x",
    ];
    let with = |extra: &[&'static str]| -> Vec<&'static str> {
        base.iter().chain(extra).copied().collect()
    };
    accelbench_fails(
        &with(&["--motion", "spin"]),
        &["unknown motion 'spin'", "twist"],
    );
    accelbench_fails(
        &with(&["--motion", "twist:turns=x"]),
        &["use a number from"],
    );
    accelbench_fails(
        &with(&["--rays", "shadow"]),
        &["ray set 'shadow'", "primary"],
    );
    accelbench_fails(&with(&["--frames", "1"]), &["--frames"]);
    accelbench_fails(
        &with(&["--motion", "keyframes"]),
        &["--motion keyframes", "has no keyframes", "twist"],
    );
    accelbench_fails(&with(&["--indices", "nope"]), &["unknown index 'nope'"]);
}

/// The example scene file with keyframes: its entries move differently (the icosphere slides,
/// the soup turns and rises, the box tumbles, the sphere orbits), the floor stays, and refitted
/// box trees keep the hit contract on every frame.
#[test]
fn keyframed_scene_files_move_their_entries_and_refits_agree() {
    let scene = load_scene("scenes/keyframes.toml").unwrap();
    assert_eq!(scene.keyframed.len(), 4);
    let keys = MotionSpec::Keyframes;
    let start = keys.frame(&scene, 0.0).unwrap();
    let end = keys.frame(&scene, 1.0).unwrap();
    let floor = scene.keyframed[0].triangles.start;
    assert!(floor > 0, "the terrain comes first and has no keys");
    assert_eq!(start.triangles[..floor], end.triangles[..floor]);
    // The first keys are identities or held before: every object starts where it is placed.
    assert_eq!(start.triangles[..], scene.triangles[..]);
    let ico = scene.keyframed[0].triangles.clone();
    let shift = end.triangles[ico.start].v[0] - start.triangles[ico.start].v[0];
    assert!(
        (shift - glam::Vec3A::new(1.6, 0.0, 0.0)).length() < 1e-5,
        "{shift}"
    );
    assert_ne!(
        start.triangles[ico.end], end.triangles[ico.end],
        "the soup moves"
    );
    assert_ne!(start.spheres[..], end.spheres[..]);
    assert_ne!(start.shapes[..], end.shapes[..]);
    let rays = agreement_rays(&scene, 400);
    let k = TriangleKernelKind::Exact;
    for spec in ["bvh", "bvh4", "bvh8"] {
        let mut index = build_index(&IndexSpec::named(spec), &start, k).unwrap();
        for f in 1..5 {
            let frame = keys.frame(&scene, f as f32 / 4.0).unwrap();
            // Bit for bit the same frame when asked again.
            assert_eq!(
                frame.triangles[..],
                keys.frame(&scene, f as f32 / 4.0).unwrap().triangles[..]
            );
            index.refit(&frame).unwrap();
            let brute = build_index(&IndexSpec::named("brute"), &frame, k).unwrap();
            let m = compare_indices(brute.as_ref(), index.as_ref(), &rays);
            assert_no_mismatch(&format!("{spec} frame {f}"), &scene, rays.len(), &m);
        }
    }
}

/// `animate` on a keyframed scene file animates by its keyframes without being told, every
/// frame verified: refit and rebuild rows for bvh and bvh8, no mismatch.
#[test]
fn animate_runs_a_keyframed_scene_file() {
    let (_out, dir) = temp_path("keys");
    let stdout = accelbench_ok(&[
        "animate",
        "--scene",
        "scenes/keyframes.toml",
        "--frames",
        "3",
        "--indices",
        "bvh,bvh8",
        "--primary-size",
        "32",
        "--incoherent",
        "1000",
        "--repeats",
        "1",
        "--threads",
        "1",
        "--quiet",
        "--out",
        dir.to_str().unwrap(),
    ]);
    let meta = std::fs::read_to_string(dir.join("meta.json")).unwrap();
    let meta: serde_json::Value = serde_json::from_str(&meta).unwrap();
    assert_eq!(
        (&meta["motion"], &meta["status"]),
        (&"keyframes".into(), &"complete".into())
    );
    let csv = std::fs::read_to_string(dir.join("frames.csv")).unwrap();
    let lines: Vec<&str> = csv.lines().skip(1).collect();
    assert_eq!(lines.len(), 12, "{csv}");
    let rows = ["bvh+refit", "bvh+rebuild", "bvh8+refit", "bvh8+rebuild"];
    for (i, row) in rows.iter().cycle().take(12).enumerate() {
        let cells: Vec<&str> = lines[i].split(',').collect();
        assert_eq!((cells[0], cells[1]), ((i / 4).to_string().as_str(), *row));
        // Every ray verified (primary 32 x 32 and 1000 incoherent), none wrong.
        assert_eq!(cells[9..], ["2024", "0"], "{}", lines[i]);
    }
    assert!(stdout.contains("keyframes"), "{stdout}");
}

/// SIGINT during the second frame: `animate` stops before the next frame, writes the frames it
/// finished with the status `interrupted`, and exits 130.
#[cfg(unix)]
#[test]
fn an_interrupted_animation_keeps_its_finished_frames() {
    let (_tmp, out) = temp_path("a");
    let child = spawn_piped(&[
        "animate",
        "--scene",
        "icosphere:n=200000",
        "--frames",
        "50",
        "--indices",
        "bvh",
        "--primary-size",
        "16",
        "--incoherent",
        "100",
        "--repeats",
        "1",
        "--threads",
        "1",
        "--out",
        out.to_str().unwrap(),
    ]);
    let early = "animate ended before its second frame";
    let (code, seen, rest) = interrupt_at(child, "frame 2/50 started", early);
    assert_eq!(code, Some(130), "{seen}{rest}");
    let meta = std::fs::read_to_string(out.join("meta.json")).unwrap();
    let meta: serde_json::Value = serde_json::from_str(&meta).unwrap();
    assert_eq!(meta["status"], "interrupted");
    let csv = std::fs::read_to_string(out.join("frames.csv")).unwrap();
    let frames = csv
        .lines()
        .skip(1)
        .map(|l| l.split(',').next().unwrap())
        .max();
    assert!(matches!(frames, Some("0") | Some("1")), "{csv}");
    let md = std::fs::read_to_string(out.join("summary.md")).unwrap();
    assert!(md.contains("**Status: interrupted**"), "{md}");
}
