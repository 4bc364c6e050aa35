//! Nothing lost, no panic, nothing silently wrong (issue 47): a contender that fails is a note
//! and the run goes on.

use crate::common;
use crate::suite::{config, run_built_by};

use accelbench::geometry::triangle::Watertight;
use accelbench::geometry::{Ray, TriangleKernelKind};
use accelbench::harness::suite::SuiteResult;
use accelbench::index::{
    BatchIndex, BuildError, HitQuery, Index, IndexInfo, IndexSpec, Stats, TraceIndex,
};
use accelbench::index::{build_index, build_index_on};
use accelbench::scene::{Geometry, SceneGeometry, Triangles, generators};
use common::drop_one::{NoParams, query_skipping};

/// Brute force that panics in every trace, or with `TIMED_ONLY` only in uncounted ones (the
/// suite's timed passes; its counting passes count).
struct PanicsOnTrace<const TIMED_ONLY: bool>;

impl<const TIMED_ONLY: bool> Index for PanicsOnTrace<TIMED_ONLY> {
    type Params = NoParams;
    fn build<G: Geometry>(_: &G, _: &Self::Params) -> Result<Self, BuildError> {
        Ok(PanicsOnTrace)
    }
    fn query<Q: HitQuery, G: Geometry, S: Stats>(&self, g: &G, r: &Ray, s: &mut S) -> Q::Answer {
        let uncounted = std::any::type_name::<S>().ends_with("NoStats");
        assert!(TIMED_ONLY && !uncounted, "injected trace fault");
        query_skipping::<Q, G, S>(g, r, s, None)
    }
    fn info(&self) -> IndexInfo {
        IndexInfo::default()
    }
}

impl<const TIMED_ONLY: bool> BatchIndex for PanicsOnTrace<TIMED_ONLY> {}

/// Builds the faulty index over a scene's primitives.
type Make = dyn Fn(&SceneGeometry) -> Result<Box<dyn TraceIndex>, BuildError>;

/// The suite with `brute`, `bvh` and `faulty` on an icosphere, `faulty` built by `make` (the
/// others by the registry).
fn run_with_faulty(faulty: &str, make: &Make) -> SuiteResult {
    let scene = generators::generate("icosphere", 200, 1).unwrap();
    let cfg = config(&["brute", "bvh", faulty]);
    let build = |spec: &IndexSpec, g: &SceneGeometry| match spec.name == faulty {
        true => make(g),
        false => build_index(spec, g, TriangleKernelKind::Watertight),
    };
    run_built_by(scene, &cfg, &build)
}

fn panicking_tracer<const TIMED_ONLY: bool>(
    g: &SceneGeometry,
) -> Result<Box<dyn TraceIndex>, BuildError> {
    let geom = Triangles::<Watertight>::new(g.triangles.clone());
    let b = build_index_on::<PanicsOnTrace<TIMED_ONLY>, _>("faulty", geom, NoParams {})?;
    Ok(Box::new(b))
}

/// The one note about `name`, which must say it failed with a panic in this file.
fn failure_note(res: &SuiteResult, name: &str) -> String {
    let notes: Vec<_> = (res.notes.iter())
        .filter(|n| n.what.starts_with(&format!("index {name}")))
        .collect();
    assert_eq!(notes.len(), 1, "{:?}", res.notes);
    let reason = notes[0].reason.clone();
    assert!(
        reason.starts_with("failed: panic at tests/it/reliability.rs:"),
        "{reason}"
    );
    reason
}

/// The other indices still have their rows on both sets, verified.
fn assert_others_ran(res: &SuiteResult, failed: &str) {
    for name in ["brute", "bvh"] {
        let sets: Vec<_> = (res.rows.iter())
            .filter(|r| r.index == name)
            .map(|r| r.ray_set.as_str())
            .collect();
        assert!(
            sets.contains(&"primary") && sets.contains(&"shadow"),
            "{name}: {sets:?}"
        );
    }
    assert!(res.rows.iter().all(|r| r.index != failed));
    assert_eq!(res.mismatch_total, 0);
}

/// Runs the suite with index `faulty` made by `make` and asserts that its one failure is noted
/// with a reason ending in `reason` while the other indices ran.
fn assert_contained(make: &Make, reason: &str) {
    let res = run_with_faulty("faulty", make);
    let note = failure_note(&res, "faulty");
    assert!(note.ends_with(reason), "{note}");
    assert_others_ran(&res, "faulty");
    assert_eq!(res.failure_total, 1);
}

#[test]
fn a_panicking_build_is_a_failure_note_and_the_run_goes_on() {
    assert_contained(
        &|_| panic!("injected build fault"),
        "injected build fault (building)",
    );
}

#[test]
fn a_panicking_trace_is_a_failure_note_and_the_run_goes_on() {
    assert_contained(
        &panicking_tracer::<false>,
        "injected trace fault (counting pass)",
    );
}

#[test]
fn a_panicking_timed_pass_is_a_failure_note_and_the_run_goes_on() {
    assert_contained(
        &panicking_tracer::<true>,
        "injected trace fault (timed pass)",
    );
}

/// A peer's failure is noted but, like its mismatches, does not count against the run.
#[test]
fn a_peer_failure_is_noted_without_failing_the_run() {
    let res = run_with_faulty("obvhs-cwbvh", &|_| panic!("injected peer fault"));
    failure_note(&res, "obvhs-cwbvh");
    assert_others_ran(&res, "obvhs-cwbvh");
    assert_eq!(res.failure_total, 0);
}
