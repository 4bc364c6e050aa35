//! The suite (`accelbench run` and `accelbench verify`): every requested index on every scene and
//! ray set, a counting pass and a timed pass per thread count, and hit verification.
//!
//! Per scene: each index is built once (on all threads) and reused by every ray set. Per ray set
//! and index: one counting pass (statistics, untimed), then per thread count a timed pass of
//! `repeats` runs (median and spread), the runs of the set's indices taking turns (see
//! [`super::suite_set`]). Verification compares, bit for bit:
//! - every index with brute force, on every ray when `rays x primitives` fits the verification
//!   budget, else on a deterministic sample (every k-th ray) that fits it;
//! - every index with the first of our indices in the list (peers, [`is_peer`], excluded), on every
//!   ray (so all indices agree pairwise);
//! - every timed pass with the same index's counting pass.
//!
//! A contender's failure is contained: a build error, or a panic while building or tracing it
//! ([`super::contain`]), becomes a note on that contender (`failed: panic at ...`), counted in
//! [`SuiteResult::failure_total`] when it is ours, and the run goes on without it.
//!
//! A SIGINT ([`super::interrupt`]) stops the run at the next index's counting pass or timed
//! pass (or ray set, or scene): the result then holds the sets finished so far (the set in
//! progress gives no rows) and says [`SuiteResult::interrupted`].

use super::contain::contained;
use super::interrupt;
pub use super::shard::Shard;
use super::suite_config::Pools;
pub use super::suite_config::SuiteConfig;
pub use super::suite_result::{MismatchRecord, Note, ResultRow, SuiteResult};
use super::suite_set::{SetRun, run_set};
use super::workload::{self, RaySet};
use crate::geometry::TriangleKernelKind;
use crate::index::{BuildError, IndexSpec, TraceIndex, build_index, is_peer};
use crate::scene::{Scene, SceneGeometry};
use indicatif::ProgressBar;

/// Builds the index a spec names over a scene's primitives.
pub type IndexBuilder<'a> =
    &'a dyn Fn(&IndexSpec, &SceneGeometry) -> Result<Box<dyn TraceIndex>, BuildError>;

/// Called once per scene after all its ray sets, with the indices built for it (in list order),
/// e.g. to render pictures with them; never inside a timed pass.
pub type SceneHook<'a> = &'a mut (dyn FnMut(&Scene, &[&dyn TraceIndex]) + Send);

/// Runs the suite on `scenes` with the registry's indices. Fails only when the run cannot start
/// (thread pools); index failures and mismatches are reported in the result.
pub fn run_suite(
    scenes: &[Scene],
    cfg: &SuiteConfig,
    progress: &ProgressBar,
) -> Result<SuiteResult, rayon::ThreadPoolBuildError> {
    let kernel = cfg.kernel;
    run_suite_with(
        scenes,
        cfg,
        progress,
        &|s, g| build_index(s, g, kernel),
        &mut |_, _| {},
    )
}

/// [`run_suite`] with indices built by `build` (tests inject faulty indices this way).
pub fn run_suite_with(
    scenes: &[Scene],
    cfg: &SuiteConfig,
    progress: &ProgressBar,
    build: IndexBuilder,
    after_scene: SceneHook,
) -> Result<SuiteResult, rayon::ThreadPoolBuildError> {
    let pools = Pools::new(&cfg.threads)?;
    let mut res = SuiteResult::default();
    let n = cfg.indices.len();
    let items = (0..scenes.len())
        .flat_map(|s| (0..n).map(move |i| (s, i)))
        .filter(|&(s, i)| cfg.shard.takes(s, i, n))
        .count();
    progress.set_length((items * cfg.sets.len()) as u64);
    for (pos, scene) in scenes.iter().enumerate() {
        let specs: Vec<&IndexSpec> = (cfg.indices.iter().enumerate())
            .filter(|(i, _)| cfg.shard.takes(pos, *i, n))
            .map(|(_, s)| s)
            .collect();
        if specs.is_empty() {
            continue;
        }
        if interrupt::requested() {
            res.interrupted = true;
            break;
        }
        let built = run_scene(scene, &specs, cfg, &pools, progress, build, &mut res);
        if res.interrupted {
            break;
        }
        let refs: Vec<&dyn TraceIndex> = built.iter().map(|b| b.as_ref()).collect();
        if let Err(p) = contained(|| pools.all().install(|| after_scene(scene, &refs))) {
            res.note(scene, "pictures".into(), format!("failed: {p}"));
        }
    }
    progress.finish_and_clear();
    Ok(res)
}

/// Runs `specs` (this shard's share of the indices) on every ray set of `scene`.
fn run_scene(
    scene: &Scene,
    specs: &[&IndexSpec],
    cfg: &SuiteConfig,
    pools: &Pools,
    progress: &ProgressBar,
    build: IndexBuilder,
    res: &mut SuiteResult,
) -> Vec<Box<dyn TraceIndex>> {
    let geom = scene.geometry();
    let mut built: Vec<Box<dyn TraceIndex>> = Vec::new();
    for spec in specs {
        progress.set_message(format!("{}: building {spec}", scene.name));
        let what = format!("index {spec}");
        match contained(|| build(spec, &geom)) {
            Ok(Ok(i)) => {
                built.push(i);
                continue;
            }
            Ok(Err(BuildError::Unsupported { reason, .. })) => {
                res.note(scene, what, format!("skipped: {reason}"))
            }
            Ok(Err(e @ BuildError::OverBudget { .. })) => {
                res.note(scene, what, format!("skipped: {e}"))
            }
            Ok(Err(e)) => res.fail(scene, &spec.name, what, format!("build failed: {e}")),
            Err(p) => res.fail(scene, &spec.name, what, format!("failed: {p} (building)")),
        }
        progress.inc(cfg.sets.len() as u64);
    }
    let brute = match contained(|| build_index(&IndexSpec::named("brute"), &geom, cfg.kernel)) {
        Ok(Ok(b)) => b,
        Ok(Err(e)) => {
            res.fail(
                scene,
                "brute",
                "reference brute".into(),
                format!("build failed: {e}"),
            );
            return built;
        }
        Err(p) => {
            let reason = format!("failed: {p} (building)");
            res.fail(scene, "brute", "reference brute".into(), reason);
            return built;
        }
    };

    // Primary rays and hits feed the secondary sets; hits come from the first built index
    // (every index returns the same hits; verification checks that separately).
    let primary = match workload::primary(scene, &cfg.sizes) {
        Ok(r) => r,
        Err(e) => {
            res.note(scene, "all ray sets".into(), format!("camera: {e}"));
            return built;
        }
    };
    let needs_primary_hits = cfg.sets.iter().any(|s| s.is_secondary());
    let primary_hits = if needs_primary_hits {
        match primary_hits(scene, &primary, &mut built, brute.as_ref(), pools, res) {
            Some(h) => h,
            None => return built,
        }
    } else {
        Vec::new()
    };

    for &set in &cfg.sets {
        if interrupt::requested() {
            res.interrupted = true;
            return built;
        }
        let rays = match set {
            RaySet::Primary => primary.clone(),
            RaySet::Incoherent => workload::incoherent(scene, &cfg.sizes),
            s if s.is_secondary() => {
                workload::secondary(s, scene, &cfg.sizes, &primary, &primary_hits)
            }
            s => match workload::camera_model_set(scene, &cfg.sizes, camera_kind(s)) {
                Ok(r) => r,
                Err(e) => {
                    let what = format!("ray set {}", s.name());
                    res.note(scene, what, format!("camera: {e}"));
                    progress.inc(built.len() as u64);
                    continue;
                }
            },
        };
        if rays.is_empty() {
            let reason = match primary_hits.iter().flatten().count() {
                0 => "skipped: no primary hit to start from".to_owned(),
                n => format!(
                    "skipped: none of the {n} primary hits starts a ray: their surfaces have no \
                     finite normal (zero area, or coordinates so large that it overflows f32) or \
                     face away from every light"
                ),
            };
            res.note(scene, format!("ray set {}", set.name()), reason);
            progress.inc(built.len() as u64);
            continue;
        }
        progress.set_message(format!(
            "{}: {} brute-force reference",
            scene.name,
            set.name()
        ));
        let failed = contained(|| {
            let run = SetRun::new(scene, set, &rays, brute.as_ref(), cfg, pools, res);
            let failed = run_set(run, &built, cfg, pools, progress, res);
            let gone = |b: &dyn TraceIndex| failed.iter().any(|&f| std::ptr::addr_eq(f, b));
            built
                .iter()
                .map(|b| gone(b.as_ref()))
                .collect::<Vec<bool>>()
        });
        match failed {
            // The contenders that panicked on this set are left out of the later ones.
            Ok(gone) => {
                let mut gone = gone.into_iter();
                built.retain(|_| !gone.next().unwrap_or(false));
            }
            Err(p) => {
                let what = format!("ray set {}", set.name());
                res.fail(
                    scene,
                    "brute",
                    what,
                    format!("failed: {p} (brute force's reference or the verification)"),
                );
            }
        }
    }
    built
}

/// The primary hits the secondary sets start from, traced by the first of our indices (every
/// index returns the same hits; verification checks that separately), or by brute force when
/// none was built. An index that panics is noted, dropped from `built`, and the next one traces;
/// `None` when brute force itself panics (noted).
fn primary_hits(
    scene: &Scene,
    primary: &[crate::geometry::Ray],
    built: &mut Vec<Box<dyn TraceIndex>>,
    brute: &dyn TraceIndex,
    pools: &Pools,
    res: &mut SuiteResult,
) -> Option<Vec<Option<crate::geometry::Hit>>> {
    loop {
        let pos = (built.iter()).position(|b| b.name() != "brute" && !is_peer(b.name()));
        let tracer = pos.map_or(brute, |p| built[p].as_ref());
        let traced = contained(|| {
            let mut h = vec![None; primary.len()];
            pools.all().install(|| tracer.closest_hits(primary, &mut h));
            h
        });
        match traced {
            Ok(h) => return Some(h),
            Err(p) => {
                let what = format!("index {} on primary", tracer.name());
                res.fail(
                    scene,
                    tracer.name(),
                    what,
                    format!("failed: {p} (tracing primary)"),
                );
                built.remove(pos?);
            }
        }
    }
}

/// Builds every index of `specs` on a tiny scene, so bad names and parameters fail before a long
/// run starts. An index this machine cannot run ([`BuildError::Unsupported`], e.g. a GPU
/// index without an adapter) passes: each scene then skips it with the reason.
pub fn check_specs(specs: &[IndexSpec], kernel: TriangleKernelKind) -> Result<(), BuildError> {
    let probe = crate::scene::generators::generate("icosphere", 100, 1).expect("built-in");
    for s in specs {
        match build_index(s, &probe.geometry(), kernel) {
            Ok(_) | Err(BuildError::Unsupported { .. }) => {}
            Err(e) => return Err(e),
        }
    }
    Ok(())
}

/// The camera model of a set that is neither the primary, the incoherent nor a secondary set.
fn camera_kind(set: RaySet) -> crate::camera::ModelKind {
    set.camera_model()
        .expect("every set but primary, incoherent and the secondary ones is a camera set")
}
