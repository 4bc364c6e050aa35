//! One ray set of one scene through every built index: brute force's reference, then per index
//! (and trace mode) a counting pass and the verification of its hits, then the timed passes of
//! all of them, interleaved ([`timed_passes`]), and the result rows.

use super::contain::contained;
use super::interrupt;
use super::peer_check::{PeerCounts, classify};
use super::suite_config::{Pools, SuiteConfig};
use super::suite_result::{MismatchRecord, Note, ResultRow, SuiteResult};
use super::timing::{
    BatchHits, PassOutput, Query, Timing, counting_pass, counting_pass_in, time_pass,
};
use super::verify::{Mismatch, compare_closest};
use super::workload::RaySet;
use crate::geometry::triangle::exact::fallback_total;
use crate::geometry::{Ray, TriangleKernelKind};
use crate::index::{Counters, TraceIndex, TraceMode, is_peer};
use crate::scene::Scene;
use indicatif::ProgressBar;

/// Mismatches kept per (scene, index, set, against) for the report.
const KEEP_PER_PAIR: usize = 5;

/// A ray set of a scene and what every index's hits are checked against.
pub(super) struct SetRun<'a> {
    pub scene: &'a Scene,
    pub set: RaySet,
    pub rays: &'a [Ray],
    /// The rays brute force verifies (all, or every k-th) and its results on them.
    ref_ids: Vec<usize>,
    ref_rays: Vec<Ray>,
    ref_hits: BatchHits,
    /// The first of our indices (peers excluded): every later index is compared with it on
    /// every ray.
    first: Option<(String, BatchHits)>,
}

/// Counts one index's mismatches on one set and keeps the first few of each comparison.
struct Tally<'a> {
    scene: &'a str,
    index: &'a str,
    /// The mode traced: a mismatch names its row, `INDEX+MODE` ([`row_label`]).
    mode: TraceMode,
    set: RaySet,
    query: Query,
    count: usize,
    /// Peers only: their disagreements with brute force, classified.
    peer: Option<PeerCounts>,
}

/// A row's index label: the index's name in `single` mode, `INDEX+MODE` otherwise.
fn row_label(index: &str, mode: TraceMode) -> String {
    match mode {
        TraceMode::Single => index.to_owned(),
        m => format!("{index}+{}", m.label()),
    }
}

impl Tally<'_> {
    fn record(&mut self, against: &str, mut m: Vec<Mismatch>, res: &mut SuiteResult) {
        if self.query == Query::Any {
            m.iter_mut().for_each(|x| x.query = "any");
        }
        self.count += m.len();
        if is_peer(self.index) {
            res.peer_mismatch_total += m.len();
        } else {
            res.mismatch_total += m.len();
        }
        res.mismatches.extend(
            m.into_iter()
                .take(KEEP_PER_PAIR)
                .map(|mismatch| MismatchRecord {
                    scene: self.scene.to_owned(),
                    index: row_label(self.index, self.mode),
                    ray_set: self.set,
                    against: against.to_owned(),
                    mismatch,
                }),
        );
    }
}

impl<'a> SetRun<'a> {
    /// Traces brute force's reference on all rays, or on every k-th ray so that
    /// `sample x primitives` fits `cfg.verify_budget`, and notes the coverage.
    pub fn new(
        scene: &'a Scene,
        set: RaySet,
        rays: &'a [Ray],
        brute: &dyn TraceIndex,
        cfg: &SuiteConfig,
        pools: &Pools,
        res: &mut SuiteResult,
    ) -> SetRun<'a> {
        let cost = rays.len() as u64 * scene.len() as u64;
        let step = cost.div_ceil(cfg.verify_budget.max(1)).max(1) as usize;
        let ref_ids: Vec<usize> = (0..rays.len()).step_by(step).collect();
        let ref_rays: Vec<Ray> = ref_ids.iter().map(|&i| rays[i]).collect();
        let (_, ref_hits) = pools
            .all()
            .install(|| counting_pass(brute, set.query(), &ref_rays));
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
        SetRun {
            scene,
            set,
            rays,
            ref_ids,
            ref_rays,
            ref_hits,
            first: None,
        }
    }

    /// Compares an index's counting-pass hits with brute force's sample and with the first
    /// index; the first of our indices becomes the reference for the later ones.
    fn verify(
        &mut self,
        index: &dyn TraceIndex,
        hits: &BatchHits,
        t: &mut Tally,
        res: &mut SuiteResult,
    ) {
        let sampled: BatchHits = self.ref_ids.iter().map(|&i| hits[i]).collect();
        let mut vs_brute = compare_closest(&self.ref_rays, &self.ref_hits, &sampled);
        for m in &mut vs_brute {
            m.ray_index = self.ref_ids[m.ray_index];
        }
        if let Some(counts) = &mut t.peer {
            for m in &vs_brute {
                let ray = &self.rays[m.ray_index];
                counts.add(classify(self.scene, ray, t.query, m.expected, m.got));
            }
        }
        t.record("brute", vs_brute, res);
        match &self.first {
            Some((name, h)) => t.record(name, compare_closest(self.rays, h, hits), res),
            None if !is_peer(index.name()) => {
                self.first = Some((index.name().to_owned(), hits.clone()))
            }
            None => {}
        }
    }
}

/// Whether brute force is too slow to time on this set (noted in the result if so).
fn brute_over_budget(
    run: &SetRun,
    index: &dyn TraceIndex,
    cfg: &SuiteConfig,
    res: &mut SuiteResult,
) -> bool {
    let prims = run.scene.len() as u64;
    if index.name() != "brute" || run.rays.len() as u64 * prims <= cfg.brute_timing_budget {
        return false;
    }
    res.note(
        run.scene,
        format!("brute on {}", run.set.name()),
        format!(
            "skipped: {} rays x {} primitives is over the brute-force budget of {}",
            run.rays.len(),
            prims,
            cfg.brute_timing_budget
        ),
    );
    true
}

/// Runs every built index on one ray set and appends its rows to `res`. First each index is
/// counted and verified in every mode of `cfg.modes` that applies to the set and to the index
/// ([`TraceIndex::traces_in`]); then all of them are timed together ([`timed_passes`]). An
/// index that panics in a counting or timed pass gets a failure note instead of rows, and is
/// returned. A SIGINT ([`interrupt::requested`]) stops the set within a slice of a counting
/// pass (or of brute force's reference) or before the next timed pass, and the set gives no rows (its timings would be
/// incomplete) and marks the result [`SuiteResult::interrupted`], which ends the run.
pub(super) fn run_set<'a>(
    mut run: SetRun<'a>,
    built: &'a [Box<dyn TraceIndex>],
    cfg: &SuiteConfig,
    pools: &Pools,
    progress: &ProgressBar,
    res: &mut SuiteResult,
) -> Vec<&'a dyn TraceIndex> {
    let mut entries = Vec::new();
    let mut failed = Vec::new();
    for index in built {
        if interrupt::requested() {
            res.interrupted = true;
            return failed;
        }
        let index = index.as_ref();
        progress.set_message(format!(
            "{}: {} {}",
            run.scene.name,
            run.set.name(),
            index.name()
        ));
        if brute_over_budget(&run, index, cfg, res) {
            progress.inc(1);
            continue;
        }
        if let Some((n, why)) = index.refused(run.rays) {
            let what = format!("index {} on {}", index.name(), run.set.name());
            let reason = format!(
                "{n} of {} rays not traced (answered as misses, judged like any result): {why}",
                run.rays.len()
            );
            res.note(run.scene, what, reason);
        }
        let first = entries.len();
        // A panic can only come from the index's trace, before that mode's verification: what
        // the earlier modes recorded stays (their hits were verified). The first mode traced is
        // verified against brute force and the first index; the later ones against it, ray by
        // ray.
        let counted = contained(|| {
            let mut reference: Option<(TraceMode, BatchHits)> = None;
            let set = run.set;
            for &mode in cfg
                .modes
                .iter()
                .filter(|m| applies(**m, set) && index.traces_in(**m))
            {
                let entry = count_mode(&mut run, index, mode, reference.as_ref(), pools, res);
                reference.get_or_insert_with(|| (mode, entry.hits.clone()));
                entries.push(entry);
            }
        });
        if let Err(p) = counted {
            entries.truncate(first);
            note_failed(&run, index, &format!("{p} (counting pass)"), res);
            failed.push(index);
        }
        progress.inc(1);
    }
    progress.set_message(format!("{}: {} timing", run.scene.name, run.set.name()));
    let timings = timed_passes(&run, &mut entries, cfg, pools, res);
    if interrupt::requested() {
        res.interrupted = true;
        return failed;
    }
    for (entry, timings) in entries.into_iter().zip(timings) {
        if let Some(p) = entry.failed {
            note_failed(&run, entry.index, &format!("{p} (timed pass)"), res);
            failed.push(entry.index);
            continue;
        }
        let counts = SetCounts {
            total: entry.total,
            hits: entry.hits.iter().flatten().count(),
            mismatches: entry.tally.count,
            exact_fallbacks: entry.exact_fallbacks,
            peer: entry.tally.peer,
        };
        let label = row_label(entry.index.name(), entry.mode);
        for (threads, timing) in timings {
            let mut row = result_row(&run, entry.index, &counts, threads, timing, cfg);
            row.index.clone_from(&label);
            row.mode = entry.mode.label();
            res.rows.push(row);
        }
    }
    failed
}

/// Notes that `index` panicked on this set (`p`: [`contained`]'s message and the pass).
fn note_failed(run: &SetRun, index: &dyn TraceIndex, p: &str, res: &mut SuiteResult) {
    let what = format!("index {} on {}", index.name(), run.set.name());
    res.fail(run.scene, index.name(), what, format!("failed: {p}"));
}

/// Whether the suite traces `set` in `mode`: packets only on the coherent sets.
fn applies(mode: TraceMode, set: RaySet) -> bool {
    match mode {
        TraceMode::Packets(_) => set.is_coherent(),
        _ => true,
    }
}

/// One index in one trace mode on the set, counted and verified, waiting to be timed.
struct Entry<'a> {
    index: &'a dyn TraceIndex,
    mode: TraceMode,
    /// The counting pass's answers.
    hits: BatchHits,
    total: Counters,
    /// Edge functions the exact kernel's fallback decided during the counting pass.
    exact_fallbacks: u64,
    tally: Tally<'a>,
    /// Set when a timed pass panicked: the entry is timed no further and gets no rows.
    failed: Option<String>,
}

/// The counting pass of one index in one mode and its verification: the index's first mode
/// (and every mode of a peer) against brute force and the first index, our later modes against
/// the first mode's answers `reference`.
fn count_mode<'a>(
    run: &mut SetRun<'a>,
    index: &'a dyn TraceIndex,
    mode: TraceMode,
    reference: Option<&(TraceMode, BatchHits)>,
    pools: &Pools,
    res: &mut SuiteResult,
) -> Entry<'a> {
    let query = run.set.query();
    let fallbacks_before = fallback_total();
    let (counters, hits) = pools
        .all()
        .install(|| counting_pass_in(index, query, mode, run.rays));
    let exact_fallbacks = fallback_total() - fallbacks_before;
    let mut tally = Tally {
        scene: &run.scene.name,
        index: index.name(),
        mode,
        set: run.set,
        query,
        count: 0,
        peer: is_peer(index.name()).then(PeerCounts::default),
    };
    // A peer's every mode is judged against brute force (its wrong results are classified per
    // row, so a wrong mode of a peer never wins); ours are held to their first mode ray by ray.
    // After a SIGINT the pass (or brute force's reference) may be cut short: nothing is judged,
    // and `run_set` gives the set no rows.
    match reference {
        _ if interrupt::requested() => {}
        Some((m, r)) if !is_peer(index.name()) => {
            tally.record(&m.label(), compare_closest(run.rays, r, &hits), res)
        }
        _ => run.verify(index, &hits, &mut tally, res),
    }
    Entry {
        index,
        mode,
        hits,
        total: counters.iter().copied().sum(),
        exact_fallbacks,
        tally,
        failed: None,
    }
}

/// The timed passes of every entry at every thread count, or one untimed entry at the largest
/// count when the run does not time. The repeats are interleaved: every entry's first pass,
/// then every entry's second, and so on, each timing's median and spread taken over its own
/// passes. On a shared machine whose speed drifts over seconds, a slow phase then falls on
/// every contender alike instead of on one index's run of repeats, which keeps the ratios
/// between indices of one run steadier. Each entry's last pass at each thread count is checked
/// against its counting pass.
fn timed_passes(
    run: &SetRun,
    entries: &mut [Entry],
    cfg: &SuiteConfig,
    pools: &Pools,
    res: &mut SuiteResult,
) -> Vec<Vec<(usize, Option<Timing>)>> {
    if !cfg.timed {
        let threads = cfg.threads.last().copied().unwrap_or(1);
        return entries.iter().map(|_| vec![(threads, None)]).collect();
    }
    let repeats = cfg.repeats.max(1);
    let mut out = PassOutput::new(run.set.query(), run.rays.len());
    let mut timings = vec![Vec::new(); entries.len()];
    for (threads, pool) in &pools.0 {
        let mut samples = vec![Vec::with_capacity(repeats); entries.len()];
        let mut kernels = vec![Vec::new(); entries.len()];
        for pass in 1..=repeats {
            for ((entry, samples), kernels) in
                entries.iter_mut().zip(&mut samples).zip(&mut kernels)
            {
                if interrupt::requested() {
                    return timings;
                }
                if entry.failed.is_some() {
                    continue;
                }
                let timed = contained(|| {
                    pool.install(|| time_pass(entry.index, entry.mode, run.rays, &mut out))
                });
                match timed {
                    Ok(t) => {
                        samples.push(t);
                        kernels.extend(entry.index.kernel_time());
                    }
                    Err(p) => {
                        entry.failed = Some(p);
                        continue;
                    }
                }
                if pass == repeats {
                    let timed = out.hits();
                    let m = compare_closest(run.rays, &entry.hits, &timed);
                    entry.tally.record("counting-pass", m, res);
                }
            }
        }
        for ((timing, samples), kernels) in timings.iter_mut().zip(samples).zip(kernels) {
            let timed = (!samples.is_empty()).then(|| Timing::of(samples).with_kernel(kernels));
            timing.push((*threads, timed));
        }
    }
    timings
}

/// What the counting pass and verification found for one index on one set.
struct SetCounts {
    total: Counters,
    hits: usize,
    mismatches: usize,
    /// Edge functions the exact kernel's fallback decided during the counting pass.
    exact_fallbacks: u64,
    peer: Option<PeerCounts>,
}

fn result_row(
    run: &SetRun,
    index: &dyn TraceIndex,
    c: &SetCounts,
    threads: usize,
    timing: Option<Timing>,
    cfg: &SuiteConfig,
) -> ResultRow {
    let n = run.rays.len() as f64;
    let info = index.info();
    // Indices that count nothing (Embree, tinybvh) get NaN ("–" in the summary), not 0.
    let counted = |v: f64| if info.uncounted { f64::NAN } else { v };
    let secs = |d: std::time::Duration| d.as_secs_f64();
    let [median, spread, fastest, slowest] = timing.map_or([f64::NAN; 4], |t| {
        [t.median, t.spread, t.fastest, t.slowest].map(secs)
    });
    ResultRow {
        scene: run.scene.name.clone(),
        primitives: run.scene.len(),
        index: index.name().to_owned(),
        params: index.params().to_owned(),
        mode: TraceMode::Single.label(),
        ray_set: run.set.name().to_owned(),
        rays: run.rays.len(),
        threads,
        build_ms: info.build_time.as_secs_f64() * 1e3,
        memory_bytes: info.memory_bytes,
        peak_build_bytes: info.peak_build_bytes,
        trace_ms_median: median * 1e3,
        trace_ms_spread: spread * 1e3,
        mrays_per_s: n / median / 1e6,
        mrays_ci_low: n / slowest / 1e6,
        mrays_ci_high: n / fastest / 1e6,
        mtests_per_s: counted(c.total.prim_tests as f64 / median / 1e6),
        prim_tests_per_ray: counted(c.total.prim_tests as f64 / n),
        node_visits_per_ray: counted(c.total.node_visits as f64 / n),
        box_tests_per_ray: counted(c.total.box_tests as f64 / n),
        hits: c.hits,
        mismatches: c.mismatches,
        brute_verified_rays: run.ref_ids.len(),
        query: match run.set.query() {
            Query::Closest => "closest",
            Query::Any => "any",
        }
        .into(),
        kernel: cfg.kernel.name().into(),
        repeats: if cfg.timed { cfg.repeats } else { 0 },
        exact_fallback_rate: if cfg.kernel == TriangleKernelKind::Exact && !is_peer(index.name()) {
            c.exact_fallbacks as f64 / (3 * c.total.prim_tests.max(1)) as f64
        } else {
            f64::NAN
        },
        peer_ties: c.peer.map(|p| p.ties),
        peer_t_off: c.peer.map(|p| p.t_off),
        peer_wrong: c.peer.map(|p| p.wrong),
        gpu_kernel_ms: timing.and_then(|t| t.kernel).map(|k| secs(k) * 1e3),
        gpu_upload_ms: info.upload_time.map(|u| secs(u) * 1e3),
    }
}
