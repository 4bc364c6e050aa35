//! One ray set of one scene through every built index: brute force's reference, then per index
//! (and trace mode) a counting pass and the verification of its hits, then the timed passes of
//! all of them, interleaved ([`timed_passes`]), and the result rows.

use super::contain::contained;
use super::interrupt;
use super::peer_check::{PeerCounts, classify};
use super::set_row::{SetCounts, result_row, row_label};
use super::suite_config::{Pools, SuiteConfig};
use super::suite_result::{MismatchRecord, Note, SuiteResult};
use super::timing::{
    BatchHits, PassOutput, Query, TimedBatch, Timing, counting_pass, counting_pass_in, time_pass,
};
use super::verify::{Mismatch, compare_closest};
use super::workload::RaySet;
use crate::geometry::Ray;
use crate::geometry::triangle::exact::fallback_total;
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
    /// The set's width as an image, for the packet modes' tiles ([`RaySet::image_width`]).
    fn width(&self) -> Option<usize> {
        self.set.image_width(self.rays.len())
    }

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
            mode: entry.mode,
            total: entry.total,
            hits: entry.hits.iter().flatten().count(),
            mismatches: entry.tally.count,
            exact_fallbacks: entry.exact_fallbacks,
            peer: entry.tally.peer,
            brute_verified_rays: run.ref_ids.len(),
        };
        for timed in timings {
            let (scene, set, rays) = (run.scene, run.set, run.rays.len());
            res.rows.push(result_row(
                scene,
                set,
                rays,
                entry.index,
                &counts,
                timed,
                cfg,
            ));
        }
    }
    failed
}

/// Notes that `index` panicked on this set (`p`: [`contained`]'s message and the pass).
fn note_failed(run: &SetRun, index: &dyn TraceIndex, p: &str, res: &mut SuiteResult) {
    let what = format!("index {} on {}", index.name(), run.set.name());
    res.fail(run.scene, index.name(), what, format!("failed: {p}"));
}

/// Whether the suite traces `set` in `mode`: packets and beams only on the coherent sets.
fn applies(mode: TraceMode, set: RaySet) -> bool {
    match mode {
        TraceMode::Packets(_) | TraceMode::Beams(_) => set.is_coherent(),
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
        .install(|| counting_pass_in(index, query, mode, run.rays, run.width()));
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
    // Each entry's rays made ready (its own ray form, where it has one) before any clock starts.
    let batches: Vec<TimedBatch> = entries
        .iter()
        .map(|e| TimedBatch::new(e.index, e.mode, run.rays, run.width()))
        .collect();
    let mut timings = vec![Vec::new(); entries.len()];
    for (threads, pool) in &pools.0 {
        let mut samples = vec![Vec::with_capacity(repeats); entries.len()];
        let mut kernels = vec![Vec::new(); entries.len()];
        for pass in 1..=repeats {
            let each = entries.iter_mut().zip(&batches);
            for (((entry, batch), samples), kernels) in each.zip(&mut samples).zip(&mut kernels) {
                if interrupt::requested() {
                    return timings;
                }
                if entry.failed.is_some() {
                    continue;
                }
                let timed = contained(|| pool.install(|| time_pass(entry.index, batch, &mut out)));
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
