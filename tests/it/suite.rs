//! The suite: verification catches an index that drops a primitive (and names the ray), the
//! report's CSV has the promised columns and parses, and `accelbench run --quick` runs end to end.

use crate::common;

use crate::common::temp::temp_path;
use accelbench::camera::Camera;
use accelbench::geometry::triangle::Watertight;
use accelbench::geometry::{Ray, Triangle, TriangleKernelKind};
use accelbench::harness::suite::{
    IndexBuilder, ResultRow, Shard, SuiteConfig, SuiteResult, run_suite_with,
};
use accelbench::harness::workload::{RaySet, SetSizes};
use accelbench::index::{IndexSpec, TraceIndex, build_index, build_index_on};
use accelbench::scene::{Scene, Triangles, generators};
use common::drop_one::{DROPPED, DropOne};
use indicatif::ProgressBar;

pub(crate) fn config(indices: &[&str]) -> SuiteConfig {
    SuiteConfig {
        indices: indices.iter().map(|n| IndexSpec::named(n)).collect(),
        sets: vec![RaySet::Primary, RaySet::Shadow],
        threads: vec![1, 2],
        sizes: SetSizes {
            primary_side: 48,
            incoherent: 500,
            ao_fraction: 0.05,
        },
        repeats: 2,
        kernel: TriangleKernelKind::Watertight,
        verify_budget: u64::MAX,
        brute_timing_budget: u64::MAX,
        timed: true,
        shard: Shard::WHOLE,
        modes: vec![accelbench::index::TraceMode::Single],
    }
}

/// The suite on one scene with the indices `build` makes.
pub(crate) fn run_built_by(scene: Scene, cfg: &SuiteConfig, build: IndexBuilder) -> SuiteResult {
    run_suite_with(&[scene], cfg, &ProgressBar::hidden(), build, &mut |_, _| {}).unwrap()
}

#[test]
fn verification_reports_a_dropped_primitive_with_its_ray() {
    let scene = generators::generate("icosphere", 200, 1).unwrap();
    let cfg = config(&["brute", "drop-one"]);
    let build = |spec: &IndexSpec, g: &accelbench::scene::SceneGeometry| {
        if spec.name == "drop-one" {
            let geom = Triangles::<Watertight>::new(g.triangles.clone());
            let b = build_index_on::<DropOne, _>("drop-one", geom, Default::default())?;
            Ok(Box::new(b) as Box<dyn TraceIndex>)
        } else {
            build_index(spec, g, TriangleKernelKind::Watertight)
        }
    };
    let res = run_built_by(scene, &cfg, &build);
    let bad: Vec<&ResultRow> = res.rows.iter().filter(|r| r.mismatches > 0).collect();
    assert!(!bad.is_empty(), "the dropped primitive went unnoticed");
    assert!(bad.iter().all(|r| r.index == "drop-one"));
    assert!(
        res.rows
            .iter()
            .any(|r| r.index == "brute" && r.mismatches == 0)
    );
    let m = &res.mismatches[0];
    assert_eq!(m.index, "drop-one");
    assert_eq!(m.mismatch.expected.map(|h| h.prim), Some(DROPPED));
    // The record carries the ray's exact bits, and they replay to the same ray.
    let b = m.mismatch.ray_bits.map(f32::from_bits);
    let replay = Ray::new(
        glam::Vec3::new(b[0], b[1], b[2]),
        glam::Vec3::new(b[4], b[5], b[6]),
        b[3],
        b[7],
    )
    .unwrap();
    let brute = build_index(
        &IndexSpec::named("brute"),
        &generators::generate("icosphere", 200, 1)
            .unwrap()
            .geometry(),
        TriangleKernelKind::Watertight,
    )
    .unwrap();
    assert_eq!(brute.closest_hit(&replay).map(|h| h.prim), Some(DROPPED));
    assert!(
        m.mismatch
            .to_string()
            .contains(&format!("{:08x}", m.mismatch.ray_bits[0]))
    );
}

#[test]
fn every_registered_index_agrees_in_the_suite() {
    let scene = generators::generate("mixed", 600, 2).unwrap();
    let names = accelbench::index::index_names();
    let mut cfg = config(&names);
    cfg.sets = RaySet::ALL.to_vec();
    cfg.threads = vec![2];
    let res =
        accelbench::harness::suite::run_suite(&[scene], &cfg, &ProgressBar::hidden()).unwrap();
    assert_eq!(res.mismatch_total, 0, "{:?}", res.mismatches.first());
    // Triangle-only peers (features `embree`, `tinybvh`) and GPU indices (`gpu`) skip this
    // scene with spheres.
    let skipped = res
        .notes
        .iter()
        .filter(|n| {
            n.reason
                .starts_with("skipped: the peer tests triangles only")
                || n.reason
                    .starts_with("skipped: the GPU shaders test triangles only")
        })
        .count();
    assert_eq!(res.notes.len(), skipped, "{:?}", res.notes);
    assert_eq!(res.rows.len(), (names.len() - skipped) * RaySet::ALL.len());
}

const COLUMNS: &[&str] = &[
    "scene",
    "primitives",
    "index",
    "params",
    "ray_set",
    "rays",
    "threads",
    "build_ms",
    "memory_bytes",
    "trace_ms_median",
    "trace_ms_spread",
    "mrays_per_s",
    "mtests_per_s",
    "prim_tests_per_ray",
    "node_visits_per_ray",
    "box_tests_per_ray",
    "hits",
    "mismatches",
    "peer_ties",
    "peer_t_off",
    "peer_wrong",
];

#[test]
fn quick_run_end_to_end_writes_the_report() {
    let (_dir, out) = temp_path("report");
    common::cli::accelbench_ok(&[
        "run",
        "--quick",
        "--quiet",
        "--scenes",
        "icosphere:n=800,soup:n=600,seed=2",
        "--out",
        out.to_str().unwrap(),
    ]);
    for f in ["results.csv", "meta.json", "summary.md", "mrays_shadow.svg"] {
        assert!(out.join(f).exists(), "{f} missing");
    }
    let mut r = csv::Reader::from_path(out.join("results.csv")).unwrap();
    let header: Vec<String> = r.headers().unwrap().iter().map(str::to_owned).collect();
    for c in COLUMNS {
        assert!(
            header.iter().any(|h| h == c),
            "column {c} missing: {header:?}"
        );
    }
    let rows: Vec<ResultRow> = r.deserialize().collect::<Result<_, _>>().unwrap();
    let scenes: std::collections::HashSet<_> = rows.iter().map(|r| r.scene.as_str()).collect();
    assert_eq!(scenes.len(), 2, "{scenes:?}");
    assert!(rows.iter().all(|r| r.rays > 0));
    // Ours must match brute force; peers (Embree and tinybvh with `--features peers`) use their
    // own triangle tests, and their ties are reported, not failed.
    assert!(
        rows.iter()
            .filter(|r| !accelbench::index::is_peer(r.index.split('+').next().unwrap()))
            .all(|r| r.mismatches == 0)
    );
    let meta: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("meta.json")).unwrap()).unwrap();
    assert!(meta["git_revision"].is_string() && meta["cores"].as_u64().unwrap() >= 1);
    let md = std::fs::read_to_string(out.join("summary.md")).unwrap();
    assert!(md.contains("Verification: passed"), "{md}");
}

#[test]
fn bad_run_arguments_fail_with_a_message() {
    for (args, expect) in [
        (vec!["run", "--indices", "nope"], "unknown index"),
        (vec!["run", "--scenes", "nope"], "unknown scene"),
        (vec!["run", "--threads", "0"], "thread count"),
        (vec!["verify", "--indices", "brute:x=1"], "unknown field"),
    ] {
        common::cli::accelbench_fails(&args, &[expect]);
    }
}

/// A triangle with a corner exactly at the protocol camera's eye makes two of its edge
/// functions exactly zero on every primary ray, which only the exact kernel's fallback decides:
/// the suite reports a positive fallback share for each of our indices with `--kernel exact`,
/// none for peers (their own triangle tests) and none with other kernels.
#[test]
fn exact_kernel_fallback_share_is_reported_per_index() {
    let mut scene = generators::generate("icosphere", 200, 1).unwrap();
    let bounds = scene.ray_set_bounds();
    scene.reference_bounds = Some(bounds);
    let eye = glam::Vec3A::from(Camera::protocol(&bounds, 48, 48).unwrap().eye_f32());
    let to_centre = bounds.center() - eye;
    let side = to_centre.any_orthonormal_vector() * to_centre.length() * 0.05;
    scene.triangles.push(Triangle::new(
        eye,
        eye + to_centre * 0.5 + side,
        eye + to_centre * 0.5 - side,
    ));
    let mut cfg = config(&["brute", "bvh", "obvhs-bvh2"]);
    cfg.sets = vec![RaySet::Primary];
    cfg.threads = vec![1];
    cfg.repeats = 1;
    for kernel in [TriangleKernelKind::Exact, TriangleKernelKind::Watertight] {
        cfg.kernel = kernel;
        let res = accelbench::harness::suite::run_suite(
            std::slice::from_ref(&scene),
            &cfg,
            &ProgressBar::hidden(),
        )
        .unwrap();
        assert_eq!(res.rows.len(), 3);
        for r in &res.rows {
            let counted = kernel == TriangleKernelKind::Exact && r.index != "obvhs-bvh2";
            if counted {
                assert!(r.exact_fallback_rate > 0.0, "{r:?}");
            } else {
                assert!(r.exact_fallback_rate.is_nan(), "{r:?}");
            }
        }
    }
}

/// An index that records the name of every uncounted batch it traces (the suite's timed
/// passes) in a shared log, and otherwise is the index it wraps.
struct Logged {
    inner: Box<dyn TraceIndex>,
    log: std::sync::Arc<std::sync::Mutex<Vec<String>>>,
}

impl Logged {
    fn note(&self, counted: bool) {
        if !counted {
            self.log.lock().unwrap().push(self.inner.name().to_owned());
        }
    }
}

impl TraceIndex for Logged {
    fn name(&self) -> &str {
        self.inner.name()
    }
    fn params(&self) -> &str {
        self.inner.params()
    }
    fn info(&self) -> &accelbench::index::IndexInfo {
        self.inner.info()
    }
    fn has_stream(&self) -> bool {
        self.inner.has_stream()
    }
    fn has_single(&self) -> bool {
        self.inner.has_single()
    }
    fn has_beams(&self) -> bool {
        self.inner.has_beams()
    }
    fn refused(&self, rays: &[Ray]) -> Option<(usize, &'static str)> {
        self.inner.refused(rays)
    }
    fn can_refit(&self) -> bool {
        self.inner.can_refit()
    }
    fn refit(
        &mut self,
        frame: &accelbench::scene::SceneGeometry,
    ) -> Result<(), accelbench::index::BuildError> {
        self.inner.refit(frame)
    }
    fn closest_hit(&self, ray: &Ray) -> Option<accelbench::geometry::Hit> {
        self.inner.closest_hit(ray)
    }
    fn closest_hit_counted(
        &self,
        ray: &Ray,
        c: &mut accelbench::index::Counters,
    ) -> Option<accelbench::geometry::Hit> {
        self.inner.closest_hit_counted(ray, c)
    }
    fn any_hit(&self, ray: &Ray) -> bool {
        self.inner.any_hit(ray)
    }
    fn any_hit_counted(&self, ray: &Ray, c: &mut accelbench::index::Counters) -> bool {
        self.inner.any_hit_counted(ray, c)
    }
    fn closest_hits_in(
        &self,
        mode: accelbench::index::TraceMode,
        rays: &[Ray],
        out: &mut [Option<accelbench::geometry::Hit>],
        counters: Option<&mut [accelbench::index::Counters]>,
    ) {
        self.note(counters.is_some());
        self.inner.closest_hits_in(mode, rays, out, counters)
    }
    fn any_hits_in(
        &self,
        mode: accelbench::index::TraceMode,
        rays: &[Ray],
        out: &mut [bool],
        counters: Option<&mut [accelbench::index::Counters]>,
    ) {
        self.note(counters.is_some());
        self.inner.any_hits_in(mode, rays, out, counters)
    }
}

/// The timed passes of a set's indices take turns (the first pass of each, then the second of
/// each, ...) at each thread count, so a slow phase of the machine does not fall on one index
/// alone; every index still gets its repeats, and the rows carry them.
#[test]
fn timed_passes_of_a_set_are_interleaved_across_indices() {
    let scene = generators::generate("icosphere", 200, 1).unwrap();
    let mut cfg = config(&["bvh", "bvh8", "grid"]);
    cfg.sets = vec![RaySet::Primary];
    cfg.threads = vec![1, 2];
    cfg.repeats = 3;
    let log = std::sync::Arc::new(std::sync::Mutex::new(Vec::new()));
    let build = |spec: &IndexSpec, g: &accelbench::scene::SceneGeometry| {
        let inner = build_index(spec, g, TriangleKernelKind::Watertight)?;
        let log = log.clone();
        Ok(Box::new(Logged { inner, log }) as Box<dyn TraceIndex>)
    };
    let res = run_built_by(scene, &cfg, &build);
    let one_round = ["bvh", "bvh8", "grid"];
    let expected: Vec<&str> = one_round.repeat(3 * 2);
    assert_eq!(*log.lock().unwrap(), expected);
    assert_eq!(res.rows.len(), 3 * 2);
    assert!(res.rows.iter().all(|r| r.repeats == 3 && r.mismatches == 0));
    assert!(res.rows.iter().all(|r| r.mrays_per_s.is_finite()));
}
