//! The GPU backend (feature `gpu`; CI runs it on Mesa's lavapipe, a software Vulkan driver):
//! `gpu-cwbvh`, `gpu-bvh2` and `gpu-grid` build and trace the generated triangle scenes and the
//! bunny with none of their hits wrong against brute force (ties and `t off`, from their own
//! `f32` kernel, are counted and printed), also on the bunny's full protocol sets and a batch
//! that is not a multiple of the workgroup size, any-hit agrees with closest hit, a batch of one
//! ray gets what it gets in a batch, a scene with spheres and a machine without an adapter skip
//! them with the reason, and `run` reports them as `+stream` rows with the adapter in
//! `meta.json`.
#![cfg(feature = "gpu")]

use crate::common;
use crate::common::cli::Suite;

use accelbench::geometry::{Hit, TriangleKernelKind};
use accelbench::index::{BuildError, IndexSpec, TraceIndex, TraceMode, build_index};
use accelbench::scene::{Scene, generators};

const GPU_INDICES: [&str; 3] = ["gpu-cwbvh", "gpu-bvh2", "gpu-grid"];

/// Built with the exact kernel, the suite's default: brute force with it is the reference, and
/// the classification of a difference rests on exact arithmetic.
fn build(spec: &str, scene: &Scene) -> Box<dyn TraceIndex> {
    common::build(spec, scene, TriangleKernelKind::Exact)
}

use common::judge::judge;

/// Every GPU index on the generated triangle scenes and the bunny, on protocol-like rays (48 x
/// 48 primary, 2,000 incoherent) and on rays aimed exactly at vertices and edge midpoints
/// (`common::agreement_rays`): wrong no more often than our own `f32` watertight kernel (`bvh`
/// with it, classified the same way against exact brute force), with 1 in 1,000 protocol rays
/// and 1 in 100 aimed rays of room (an `f32` kernel is wrong where the last bit of an edge
/// function decides: rays leaving the zero-thickness `flat` from its plane, rays grazing a
/// vertex; both counts are printed). Any-hit equals "closest hit exists", and a ray alone gets
/// what it gets in its batch.
#[test]
fn gpu_indices_are_never_wrong() {
    let mut scenes: Vec<Scene> = common::agreement_scenes()
        .into_iter()
        .filter(|s| s.spheres.is_empty() && s.shapes.is_empty())
        .collect();
    scenes.extend(common::bunny());
    for scene in scenes {
        let brute = build("brute", &scene);
        let protocol = common::bunny_protocol_sample(&scene);
        let aimed = common::agreement_rays(&scene, 500);
        let watertight = common::build("bvh", &scene, TriangleKernelKind::Watertight);
        // Our own f32 kernel's wrong count on each kind of rays, and the room a GPU index has
        // above it: 1 in 1,000 protocol rays, 1 in 100 aimed ones.
        let baseline = |kind: &str, rays: &[accelbench::geometry::Ray]| {
            let expected = common::closest(brute.as_ref(), rays);
            let ours = common::closest(watertight.as_ref(), rays);
            let what = format!("bvh (watertight) on {}, {kind} rays", scene.name);
            let base = judge(&what, &scene, rays, &expected, &ours);
            eprintln!("{what}: {base:?}");
            let room = if kind == "protocol" {
                rays.len() / 1000
            } else {
                rays.len() / 100
            };
            base.wrong + room
        };
        let allowed = [baseline("protocol", &protocol), baseline("aimed", &aimed)];
        for name in GPU_INDICES {
            let index = build(name, &scene);
            assert!(index.traces_in(TraceMode::Stream) && !index.traces_in(TraceMode::Single));
            for ((kind, rays), allowed) in [("protocol", &protocol), ("aimed", &aimed)]
                .into_iter()
                .zip(allowed)
            {
                let expected = common::closest(brute.as_ref(), rays);
                let hits = expected.iter().flatten().count();
                let got = common::closest_in(index.as_ref(), TraceMode::Stream, rays);
                let what = format!("{name} on {}, {kind} rays", scene.name);
                let c = judge(&what, &scene, rays, &expected, &got);
                eprintln!("{what}: {c:?} of {hits} hits");
                assert!(
                    c.wrong <= allowed,
                    "{what}: {c:?} of {} rays; allowed {allowed}",
                    rays.len()
                );
                common::assert_any_hit_is_closest_hit(
                    index.as_ref(),
                    TraceMode::Stream,
                    rays,
                    &got,
                    &what,
                );
                for k in [0, rays.len() / 2, rays.len() - 1] {
                    let alone = index.closest_hit(&rays[k]);
                    let bits = |h: Option<Hit>| h.map(|h| (h.prim, h.t.to_bits()));
                    assert_eq!(bits(alone), bits(got[k]), "{what}: ray {k} alone");
                }
            }
        }
    }
}

/// The bunny's full protocol sets (`common::bunny_protocol_sets`) and a batch of 1,007 rays
/// (not a multiple of the workgroup size): no wrong hit.
#[test]
fn gpu_indices_are_never_wrong_on_the_bunny_protocol_sets() {
    let Some(bunny) = common::bunny() else { return };
    let mut sets = common::bunny_protocol_sets(&bunny);
    let (_, incoherent, expected) = &sets[1];
    let part = (incoherent[..1007].to_vec(), expected[..1007].to_vec());
    sets.insert(1, ("1007 incoherent".to_owned(), part.0, part.1));
    for (set, rays, expected) in &sets {
        for name in GPU_INDICES {
            let index = build(name, &bunny);
            let got = common::closest_in(index.as_ref(), TraceMode::Stream, rays);
            let what = format!("{name} {set}");
            let c = judge(&what, &bunny, rays, expected, &got);
            eprintln!("{what}, the bunny: {} rays, {c:?}", rays.len());
            assert_eq!(c.wrong, 0, "{what}: {c:?}");
        }
    }
}

/// Large leaves (up to 64 primitives: more than one wide node's 24 triangle slots) and a
/// one-triangle scene collapse into wide nodes that still find every hit.
#[test]
fn gpu_cwbvh_takes_any_leaf_size() {
    for (scene, spec) in [
        (
            generators::generate("soup", 3000, 3).unwrap(),
            "gpu-cwbvh:leaf_size=64,preset=\"fastest\"",
        ),
        (
            generators::generate("icosphere", 1, 3).unwrap(),
            "gpu-cwbvh",
        ),
    ] {
        let brute = build("brute", &scene);
        let rays = common::bunny_protocol_sample(&scene);
        let expected = common::closest(brute.as_ref(), &rays);
        let index = build(spec, &scene);
        let got = common::closest_in(index.as_ref(), TraceMode::Stream, &rays);
        let c = judge(spec, &scene, &rays, &expected, &got);
        assert_eq!(c.wrong, 0, "{spec} on {}: {c:?}", scene.name);
    }
}

/// A scene with spheres skips every GPU index with the reason.
#[test]
fn gpu_indices_skip_scenes_with_spheres() {
    let scene = generators::generate("mixed", 500, 1).unwrap();
    for name in GPU_INDICES {
        let spec: IndexSpec = name.parse().unwrap();
        match build_index(&spec, &scene.geometry(), TriangleKernelKind::Exact) {
            Err(BuildError::Unsupported { reason, .. }) => {
                assert!(reason.contains("triangles only"), "{reason}")
            }
            Err(e) => panic!("{name}: {e}"),
            Ok(_) => panic!("{name} built a scene with spheres"),
        }
    }
}

/// `run` with the GPU indices: `+stream` rows classified like peers (none wrong), the kernel
/// time where the adapter has timestamps, the adapter in `meta.json`.
#[test]
fn run_reports_gpu_rows() {
    let out = tempfile::tempdir().unwrap();
    Suite::run(
        "icosphere:n=2000",
        "bvh,gpu-cwbvh,gpu-bvh2,gpu-grid",
        "primary,incoherent",
        out.path(),
    )
    .with("--modes", "single,stream")
    .ok();
    let dir = out.path();
    let csv = std::fs::read_to_string(dir.join("results.csv")).unwrap();
    let mut reader = csv::Reader::from_reader(csv.as_bytes());
    let header = reader.headers().unwrap().clone();
    let col = |name: &str| {
        header
            .iter()
            .position(|h| h == name)
            .unwrap_or_else(|| panic!("no column {name}"))
    };
    let mut gpu_rows = 0;
    for row in reader.records() {
        let row = row.unwrap();
        let index = &row[col("index")];
        if index.starts_with("gpu-") {
            gpu_rows += 1;
            assert!(index.ends_with("+stream"), "{index}");
            assert_eq!(&row[col("peer_wrong")], "0", "{index}: {csv}");
            let upload: f64 = row[col("gpu_upload_ms")].parse().unwrap();
            assert!(
                upload > 0.0 && upload <= row[col("build_ms")].parse().unwrap(),
                "{index}"
            );
            let kernel = &row[col("gpu_kernel_ms")];
            assert!(
                kernel.is_empty() || kernel.parse::<f64>().unwrap() > 0.0,
                "{index}: {kernel}"
            );
        } else {
            assert!(row[col("gpu_kernel_ms")].is_empty() && row[col("gpu_upload_ms")].is_empty());
        }
    }
    assert_eq!(gpu_rows, 3 * 2, "{csv}");
    let meta = std::fs::read_to_string(dir.join("meta.json")).unwrap();
    assert!(meta.contains("\"gpu_adapter\""), "{meta}");
}

/// Without an adapter (here: a backend this build does not have), `run` skips the GPU indices
/// with one line saying why and races the rest.
#[test]
fn no_adapter_skips_gpu_indices_with_the_reason() {
    let out = tempfile::tempdir().unwrap();
    let suite = Suite::run("icosphere:n=500", "bvh,gpu-bvh2", "primary", out.path());
    let mut cmd = std::process::Command::new(env!("CARGO_BIN_EXE_accelbench"));
    cmd.args(suite.args()).env("WGPU_BACKEND", "gl");
    let output = cmd.output().unwrap();
    let text = format!(
        "{}{}",
        String::from_utf8_lossy(&output.stdout),
        String::from_utf8_lossy(&output.stderr)
    );
    assert!(output.status.success(), "{text}");
    let line = common::cli::the_line_with(&text, "no GPU adapter found");
    assert!(
        line.contains("gpu-bvh2") && line.contains("mesa-vulkan-drivers"),
        "{line}"
    );
}
