//! The stress suite (`accelbench stress`): corner-case scenes and rays run on every registered
//! index, which must return brute force's hits bit for bit, never panic and always answer; the
//! boundary checks for bad rays; and the shadow-ray self-intersection study.

pub mod boundary;
pub mod cases;
pub mod report;
pub mod self_intersection;

use crate::geometry::{Hit, TriangleKernelKind};
use crate::harness::contain::panic_message;
use crate::harness::verify::{Mismatch, compare_with_expected};
use crate::index::{BuildError, IndexSpec, TraceIndex, build_index, index_names};
use crate::scene::SceneGeometry;
use cases::Case;
use self_intersection::SpawnRow;
use serde::Serialize;
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::sync::Arc;
use std::sync::mpsc;
use std::time::Duration;

/// What to run.
#[derive(Debug, Clone)]
pub struct StressConfig {
    /// Primitives of the generated scenes.
    pub prims: usize,
    /// Rays per case.
    pub rays: usize,
    /// Surface points per configuration of the self-intersection study.
    pub spawn_points: usize,
    /// An index that gives no answer within this time on one case fails it ("never loop").
    pub timeout: Duration,
}

impl StressConfig {
    pub fn full() -> StressConfig {
        StressConfig {
            prims: 5_000,
            rays: 20_000,
            spawn_points: 20_000,
            timeout: Duration::from_secs(300),
        }
    }

    pub fn quick() -> StressConfig {
        StressConfig {
            prims: 1_000,
            rays: 2_000,
            spawn_points: 2_000,
            timeout: Duration::from_secs(120),
        }
    }
}

/// One case on one index.
#[derive(Debug, Clone, Serialize)]
pub struct CaseResult {
    pub case: String,
    pub index: String,
    pub rays: usize,
    pub mismatches: usize,
    /// The first mismatch with the ray's bits, or the build error, panic or timeout.
    pub first_failure: String,
    pub passed: bool,
}

/// Everything `accelbench stress` reports.
#[derive(Debug, Clone)]
pub struct StressSummary {
    pub cases: Vec<CaseResult>,
    pub boundary: Vec<boundary::BoundaryCheck>,
    pub self_intersection: Vec<SpawnRow>,
}

impl StressSummary {
    /// Failed cases of indices not in `tolerated`, and failed boundary checks (as case rows).
    pub fn failures(&self, tolerated: &[&str]) -> Vec<CaseResult> {
        let mut out: Vec<CaseResult> = self
            .cases
            .iter()
            .filter(|c| !c.passed && !tolerated.contains(&c.index.as_str()))
            .cloned()
            .collect();
        out.extend(self.boundary.iter().filter_map(|b| {
            let e = b.outcome.as_ref().err()?;
            Some(CaseResult {
                case: b.name.clone(),
                index: "-".into(),
                rays: 0,
                mismatches: 0,
                first_failure: e.clone(),
                passed: false,
            })
        }));
        out
    }
}

/// Compares `index` with brute force's closest hits `expected` on the case's rays: closest hits
/// bit for bit, and any-hit equal to "brute force found a hit".
fn check(case: &Case, expected: &[Option<Hit>], index: &dyn TraceIndex) -> Vec<Mismatch> {
    compare_with_expected(index, &case.rays, expected)
}

/// How [`run_one`] builds an index (the registry's [`build_index`], or a test double).
type Builder =
    fn(&IndexSpec, &SceneGeometry, TriangleKernelKind) -> Result<Box<dyn TraceIndex>, BuildError>;

/// Runs one index on one case in its own thread, with a time limit.
fn run_one(
    case: &Arc<Case>,
    expected: &Arc<Vec<Option<Hit>>>,
    name: &str,
    timeout: Duration,
    build: Builder,
) -> CaseResult {
    let (tx, rx) = mpsc::channel();
    let (c, e) = (Arc::clone(case), Arc::clone(expected));
    let index_name = name.to_owned();
    // The caller's thread count (`--threads`) carries over to the watchdog thread's own pool.
    let threads = rayon::current_num_threads();
    std::thread::spawn(move || {
        let result = catch_unwind(AssertUnwindSafe(|| {
            let spec = IndexSpec::named(&index_name);
            let run = || {
                let index = build(&spec, &c.scene, c.kernel)?;
                Ok::<_, BuildError>(check(&c, &e, index.as_ref()))
            };
            match rayon::ThreadPoolBuilder::new().num_threads(threads).build() {
                Ok(pool) => pool.install(run),
                Err(_) => run(),
            }
        }));
        let _ = tx.send(result);
    });
    let (mismatches, first_failure) = match rx.recv_timeout(timeout) {
        Ok(Ok(Ok(m))) => (
            m.len(),
            m.first().map(|m| m.to_string()).unwrap_or_default(),
        ),
        Ok(Ok(Err(e))) => (0, format!("build failed: {e}")),
        Ok(Err(panic)) => (0, format!("panicked: {}", panic_message(&*panic))),
        Err(_) => (
            0,
            format!(
                "no answer within {} s (an endless loop?)",
                timeout.as_secs()
            ),
        ),
    };
    CaseResult {
        case: case.name.to_owned(),
        index: name.to_owned(),
        rays: case.rays.len(),
        mismatches,
        passed: first_failure.is_empty(),
        first_failure,
    }
}

/// Runs every case on every registered index (brute force too: its any-hit must agree with its
/// closest hit), the boundary checks and the self-intersection study.
pub fn run(config: &StressConfig) -> Result<StressSummary, BuildError> {
    let mut results = Vec::new();
    for case in cases::all_cases(config.prims, config.rays) {
        let brute = build_index(&IndexSpec::named("brute"), &case.scene, case.kernel)?;
        let mut expected = vec![None; case.rays.len()];
        brute.closest_hits(&case.rays, &mut expected);
        let (case, expected) = (Arc::new(case), Arc::new(expected));
        for name in index_names() {
            results.push(run_one(&case, &expected, name, config.timeout, build_index));
        }
    }
    Ok(StressSummary {
        cases: results,
        boundary: boundary::run(),
        self_intersection: self_intersection::run(config.spawn_points)?,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Ray;
    use crate::geometry::triangle::Watertight;
    use crate::index::{BatchIndex, HitQuery, Index, IndexInfo, Stats, build_index_on};
    use crate::scene::{Geometry, Triangles};

    /// A broken index: brute force that never tests the first half of the primitives.
    struct SkipsHalf(u32);

    #[derive(Debug, Clone, Default, serde::Serialize, serde::Deserialize)]
    struct NoParams {}

    impl Index for SkipsHalf {
        type Params = NoParams;
        fn build<G: Geometry>(geom: &G, _: &Self::Params) -> Result<Self, BuildError> {
            Ok(SkipsHalf(geom.len() as u32))
        }
        fn query<Q: HitQuery, G: Geometry, S: Stats>(
            &self,
            g: &G,
            r: &Ray,
            s: &mut S,
        ) -> Q::Answer {
            let mut found = Q::start(r);
            for p in self.0 / 2..self.0 {
                if crate::index::kit::prim_test::test::<Q, G, S>(&mut found, g, p, r, s) {
                    break;
                }
            }
            Q::answer(found)
        }
        fn info(&self) -> IndexInfo {
            IndexInfo::default()
        }
    }

    impl BatchIndex for SkipsHalf {}

    fn broken(
        _: &IndexSpec,
        g: &SceneGeometry,
        _: TriangleKernelKind,
    ) -> Result<Box<dyn TraceIndex>, BuildError> {
        let geom = Triangles::<Watertight>::new(g.triangles.clone());
        Ok(Box::new(build_index_on::<SkipsHalf, _>(
            "skips-half",
            geom,
            Default::default(),
        )?))
    }

    fn panics(
        _: &IndexSpec,
        _: &SceneGeometry,
        _: TriangleKernelKind,
    ) -> Result<Box<dyn TraceIndex>, BuildError> {
        panic!("deliberate")
    }

    fn hangs(
        s: &IndexSpec,
        g: &SceneGeometry,
        k: TriangleKernelKind,
    ) -> Result<Box<dyn TraceIndex>, BuildError> {
        std::thread::sleep(Duration::from_secs(3));
        build_index(s, g, k)
    }

    #[test]
    fn mismatches_panics_and_hangs_are_reported_as_failures() {
        let case = cases::all_cases(200, 300)
            .into_iter()
            .find(|c| c.name == "vertices-and-edges")
            .unwrap();
        let brute = build_index(&IndexSpec::named("brute"), &case.scene, case.kernel).unwrap();
        let mut expected = vec![None; case.rays.len()];
        brute.closest_hits(&case.rays, &mut expected);
        let (case, expected) = (Arc::new(case), Arc::new(expected));
        let t = Duration::from_secs(60);
        let ok = run_one(&case, &expected, "brute", t, build_index);
        assert!(ok.passed, "{ok:?}");
        let bad = run_one(&case, &expected, "skips-half", t, broken);
        assert!(!bad.passed && bad.mismatches > 0, "{bad:?}");
        assert!(
            bad.first_failure.contains("bits ["),
            "{}",
            bad.first_failure
        );
        let p = run_one(&case, &expected, "panics", t, panics);
        assert!(p.first_failure.contains("panicked: deliberate"), "{p:?}");
        let h = run_one(&case, &expected, "hangs", Duration::from_millis(200), hangs);
        assert!(h.first_failure.contains("no answer within"), "{h:?}");
    }
}
