//! The suite (`accelbench run` and `accelbench verify`): every requested index on every scene and
//! ray set, a counting pass and a timed pass per thread count, and hit verification.
//!
//! Per scene: each index is built once (on all threads) and reused by every ray set. Per ray set
//! and index: one counting pass (statistics, untimed), then per thread count a timed pass of
//! `repeats` runs (median and spread). Verification compares, bit for bit:
//! - every index with brute force, on every ray when `rays x primitives` fits the verification
//!   budget, else on a deterministic sample (every k-th ray) that fits it;
//! - every index with the first of our indices in the list (peers, [`is_peer`], excluded), on every
//!   ray (so all indices agree pairwise);
//! - every timed pass with the same index's counting pass.

use super::timing::{BatchHits, Query, Timing, counting_pass, timed_pass};
use super::verify::{Mismatch, compare_closest};
use super::workload::{self, RaySet, SetSizes};
use crate::geometry::{Ray, TriangleKernelKind};
use crate::index::{BuildError, Counters, IndexSpec, TraceIndex, build_index, is_peer};
use crate::scene::{Scene, SceneGeometry};
use indicatif::ProgressBar;
use serde::{Deserialize, Serialize};

/// What to run.
#[derive(Debug, Clone, Serialize)]
pub struct SuiteConfig {
    #[serde(serialize_with = "specs_as_strings")]
    pub indices: Vec<IndexSpec>,
    pub sets: Vec<RaySet>,
    pub threads: Vec<usize>,
    pub sizes: SetSizes,
    /// Timed runs per (index, set, threads); the median is reported.
    pub repeats: usize,
    pub kernel: TriangleKernelKind,
    /// Brute-force verification covers every ray while `rays x primitives` is at most this;
    /// beyond it, a deterministic sample of that cost.
    pub verify_budget: u64,
    /// Brute force is timed as an index only while `rays x primitives` is at most this.
    pub brute_timing_budget: u64,
    /// `false` for `accelbench verify`: no timed passes, no rows.
    pub timed: bool,
}

fn specs_as_strings<S: serde::Serializer>(v: &[IndexSpec], s: S) -> Result<S::Ok, S::Error> {
    s.collect_seq(v.iter().map(|x| x.to_string()))
}

/// One row of `results.csv`: scene x index x ray set x threads.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct ResultRow {
    pub scene: String,
    pub primitives: usize,
    pub index: String,
    pub params: String,
    pub ray_set: String,
    pub rays: usize,
    pub threads: usize,
    pub build_ms: f64,
    pub memory_bytes: usize,
    pub trace_ms_median: f64,
    pub trace_ms_spread: f64,
    pub mrays_per_s: f64,
    pub mtests_per_s: f64,
    pub prim_tests_per_ray: f64,
    pub node_visits_per_ray: f64,
    pub box_tests_per_ray: f64,
    /// Rays with a hit (closest-hit sets) or occluded (any-hit sets).
    pub hits: usize,
    /// Rays on which this index disagreed with brute force, the first index or itself.
    pub mismatches: usize,
    /// Rays compared with brute force (all rays, or the sample's size).
    pub brute_verified_rays: usize,
    pub query: String,
    pub kernel: String,
    pub repeats: usize,
}

/// A mismatch with where it happened.
#[derive(Debug, Clone)]
pub struct MismatchRecord {
    pub scene: String,
    pub index: String,
    pub ray_set: RaySet,
    /// What it was compared with: `brute`, another index's name, or `counting-pass`.
    pub against: String,
    pub mismatch: Mismatch,
}

/// Something the suite did not run, and why.
#[derive(Debug, Clone, Serialize)]
pub struct Note {
    pub scene: String,
    pub what: String,
    pub reason: String,
}

/// Everything a run produced.
#[derive(Debug, Default)]
pub struct SuiteResult {
    pub rows: Vec<ResultRow>,
    /// Mismatch counts per (scene, index, set, against) are in the rows; the first few of each
    /// are kept here with the ray's bits.
    pub mismatches: Vec<MismatchRecord>,
    /// Mismatching results of our indices: any fails the run.
    pub mismatch_total: usize,
    /// Mismatching results of peer indices ([`crate::index::Kind::Peer`]): reported, not a failure.
    pub peer_mismatch_total: usize,
    pub notes: Vec<Note>,
    /// Per scene and set: how brute-force verification covered the rays.
    pub verification: Vec<Note>,
}

/// Mismatches kept per (scene, index, set, against) for the report.
const KEEP_PER_PAIR: usize = 5;

/// A rayon pool per thread count, built once per run.
struct Pools(Vec<(usize, rayon::ThreadPool)>);

impl Pools {
    fn new(threads: &[usize]) -> Result<Pools, rayon::ThreadPoolBuildError> {
        let mut v = Vec::new();
        for &t in threads {
            v.push((t, rayon::ThreadPoolBuilder::new().num_threads(t).build()?));
        }
        Ok(Pools(v))
    }
}

/// Builds the index a spec names over a scene's primitives.
pub type IndexBuilder<'a> =
    &'a dyn Fn(&IndexSpec, &SceneGeometry) -> Result<Box<dyn TraceIndex>, BuildError>;

/// Called once per scene after all its ray sets, with the indices built for it (in list order),
/// e.g. to render pictures with them; never inside a timed pass.
pub type SceneHook<'a> = &'a mut (dyn FnMut(&Scene, &[&dyn TraceIndex]) + Send);

/// Runs the suite on `scenes` with the registry's indices. Fails only when the run cannot start
/// (thread pools); index build errors and mismatches are reported in the result.
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
    progress.set_length((scenes.len() * cfg.sets.len() * cfg.indices.len()) as u64);
    for scene in scenes {
        let built = run_scene(scene, cfg, &pools, progress, build, &mut res);
        let refs: Vec<&dyn TraceIndex> = built.iter().map(|b| b.as_ref()).collect();
        pools
            .0
            .last()
            .unwrap()
            .1
            .install(|| after_scene(scene, &refs));
    }
    progress.finish_and_clear();
    Ok(res)
}

fn note(res: &mut SuiteResult, scene: &Scene, what: String, reason: String) {
    res.notes.push(Note {
        scene: scene.name.clone(),
        what,
        reason,
    });
}

fn run_scene(
    scene: &Scene,
    cfg: &SuiteConfig,
    pools: &Pools,
    progress: &ProgressBar,
    build: IndexBuilder,
    res: &mut SuiteResult,
) -> Vec<Box<dyn TraceIndex>> {
    let geom = scene.geometry();
    let mut built: Vec<Box<dyn TraceIndex>> = Vec::new();
    for spec in &cfg.indices {
        progress.set_message(format!("{}: building {spec}", scene.name));
        match build(spec, &geom) {
            Ok(i) => built.push(i),
            Err(e) => {
                note(
                    res,
                    scene,
                    format!("index {spec}"),
                    format!("build failed: {e}"),
                );
                progress.inc(cfg.sets.len() as u64);
            }
        }
    }
    let brute = build_index(&IndexSpec::named("brute"), &geom, cfg.kernel)
        .expect("brute force builds on every valid scene");
    let prims = scene.len() as u64;

    // Primary rays and hits feed the secondary sets; hits come from the first built index
    // (every index returns the same hits; verification checks that separately).
    let primary = match workload::primary(scene, &cfg.sizes) {
        Ok(r) => r,
        Err(e) => {
            note(res, scene, "all ray sets".into(), format!("camera: {e}"));
            return built;
        }
    };
    let needs_primary_hits = cfg.sets.iter().any(|s| s.is_secondary());
    let primary_hits = if needs_primary_hits {
        let tracer: &dyn TraceIndex = built
            .iter()
            .find(|b| b.name() != "brute" && !is_peer(b.name()))
            .map_or(brute.as_ref(), |b| b.as_ref());
        let mut h = vec![None; primary.len()];
        pools
            .0
            .last()
            .unwrap()
            .1
            .install(|| tracer.closest_hits(&primary, &mut h));
        h
    } else {
        Vec::new()
    };

    for &set in &cfg.sets {
        let rays = match set {
            RaySet::Primary => primary.clone(),
            RaySet::Incoherent => workload::incoherent(scene, &cfg.sizes),
            s => workload::secondary(s, scene, &cfg.sizes, &primary, &primary_hits),
        };
        if rays.is_empty() {
            note(
                res,
                scene,
                format!("ray set {}", set.name()),
                "skipped: no primary hit to start from (or no light the hit surfaces face)".into(),
            );
            progress.inc(built.len() as u64);
            continue;
        }
        run_set(
            scene,
            set,
            &rays,
            &built,
            brute.as_ref(),
            prims,
            cfg,
            pools,
            progress,
            res,
        );
    }
    built
}

/// The rays brute force verifies (all, or every k-th) and their reference results.
fn brute_reference(
    brute: &dyn TraceIndex,
    query: Query,
    rays: &[Ray],
    prims: u64,
    budget: u64,
    pools: &Pools,
) -> (Vec<usize>, BatchHits) {
    let cost = rays.len() as u64 * prims;
    let step = cost.div_ceil(budget.max(1)).max(1) as usize;
    let ids: Vec<usize> = (0..rays.len()).step_by(step).collect();
    let sample: Vec<Ray> = ids.iter().map(|&i| rays[i]).collect();
    let pool = &pools.0.last().unwrap().1;
    let (_, hits) = pool.install(|| counting_pass(brute, query, &sample));
    (ids, hits)
}

#[allow(clippy::too_many_arguments)]
fn run_set(
    scene: &Scene,
    set: RaySet,
    rays: &[Ray],
    built: &[Box<dyn TraceIndex>],
    brute: &dyn TraceIndex,
    prims: u64,
    cfg: &SuiteConfig,
    pools: &Pools,
    progress: &ProgressBar,
    res: &mut SuiteResult,
) {
    let query = set.query();
    progress.set_message(format!(
        "{}: {} brute-force reference",
        scene.name,
        set.name()
    ));
    let (ref_ids, ref_hits) = brute_reference(brute, query, rays, prims, cfg.verify_budget, pools);
    let ref_rays: Vec<Ray> = ref_ids.iter().map(|&i| rays[i]).collect();
    res.verification.push(Note {
        scene: scene.name.clone(),
        what: set.name().into(),
        reason: if ref_ids.len() == rays.len() {
            format!("all {} rays checked against brute force", rays.len())
        } else {
            format!(
                "a sample of {} of {} rays (one in {}) checked against brute force",
                ref_ids.len(),
                rays.len(),
                rays.len().div_ceil(ref_ids.len())
            )
        },
    });
    let all_pool = &pools.0.last().unwrap().1;
    let mut first: Option<(String, BatchHits)> = None;
    for index in built {
        progress.set_message(format!("{}: {} {}", scene.name, set.name(), index.name()));
        let is_brute = index.name() == "brute";
        if is_brute && rays.len() as u64 * prims > cfg.brute_timing_budget {
            note(
                res,
                scene,
                format!("brute on {}", set.name()),
                format!(
                    "skipped: {} rays x {} primitives is over the brute-force budget of {}",
                    rays.len(),
                    prims,
                    cfg.brute_timing_budget
                ),
            );
            progress.inc(1);
            continue;
        }
        let (counters, hits) = all_pool.install(|| counting_pass(index.as_ref(), query, rays));
        let mut mismatches = 0usize;
        let mut record = |against: &str, mut m: Vec<Mismatch>, res: &mut SuiteResult| {
            if query == Query::Any {
                m.iter_mut().for_each(|x| x.query = "any");
            }
            mismatches += m.len();
            if is_peer(index.name()) {
                res.peer_mismatch_total += m.len();
            } else {
                res.mismatch_total += m.len();
            }
            res.mismatches
                .extend(
                    m.into_iter()
                        .take(KEEP_PER_PAIR)
                        .map(|mismatch| MismatchRecord {
                            scene: scene.name.clone(),
                            index: index.name().to_owned(),
                            ray_set: set,
                            against: against.to_owned(),
                            mismatch,
                        }),
                );
        };
        let sampled: BatchHits = ref_ids.iter().map(|&i| hits[i]).collect();
        let mut vs_brute = compare_closest(&ref_rays, &ref_hits, &sampled);
        for m in &mut vs_brute {
            m.ray_index = ref_ids[m.ray_index];
        }
        record("brute", vs_brute, res);
        // The first of our indices is the one all others are compared with on every ray.
        match &first {
            Some((name, h)) => record(name, compare_closest(rays, h, &hits), res),
            None if !is_peer(index.name()) => first = Some((index.name().to_owned(), hits.clone())),
            None => {}
        }
        let total: Counters = counters.iter().copied().sum();
        let timings: Vec<(usize, Option<Timing>)> = if cfg.timed {
            pools
                .0
                .iter()
                .map(|(t, pool)| {
                    let (timing, timed_hits) =
                        pool.install(|| timed_pass(index.as_ref(), query, rays, cfg.repeats));
                    record(
                        "counting-pass",
                        compare_closest(rays, &hits, &timed_hits),
                        res,
                    );
                    (*t, Some(timing))
                })
                .collect()
        } else {
            vec![(cfg.threads.last().copied().unwrap_or(1), None)]
        };
        let n = rays.len() as f64;
        let info = index.info();
        let hit_count = hits.iter().flatten().count();
        for (threads, timing) in timings {
            let (median, spread) = timing.map_or((f64::NAN, f64::NAN), |t| {
                (t.median.as_secs_f64(), t.spread.as_secs_f64())
            });
            res.rows.push(ResultRow {
                scene: scene.name.clone(),
                primitives: scene.len(),
                index: index.name().to_owned(),
                params: index.params().to_owned(),
                ray_set: set.name().to_owned(),
                rays: rays.len(),
                threads,
                build_ms: info.build_time.as_secs_f64() * 1e3,
                memory_bytes: info.memory_bytes,
                trace_ms_median: median * 1e3,
                trace_ms_spread: spread * 1e3,
                mrays_per_s: n / median / 1e6,
                mtests_per_s: total.prim_tests as f64 / median / 1e6,
                prim_tests_per_ray: total.prim_tests as f64 / n,
                node_visits_per_ray: total.node_visits as f64 / n,
                box_tests_per_ray: total.box_tests as f64 / n,
                hits: hit_count,
                mismatches,
                brute_verified_rays: ref_ids.len(),
                query: match query {
                    Query::Closest => "closest",
                    Query::Any => "any",
                }
                .into(),
                kernel: cfg.kernel.name().into(),
                repeats: if cfg.timed { cfg.repeats } else { 0 },
            });
        }
        progress.inc(1);
    }
}

/// Builds every index of `specs` on a tiny scene, so bad names and parameters fail before a long
/// run starts.
pub fn check_specs(specs: &[IndexSpec], kernel: TriangleKernelKind) -> Result<(), BuildError> {
    let probe = crate::scene::generators::generate("icosphere", 100, 1).expect("built-in");
    for s in specs {
        build_index(s, &probe.geometry(), kernel)?;
    }
    Ok(())
}
