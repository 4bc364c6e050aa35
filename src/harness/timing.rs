//! Timed and counting passes over a batch of rays. Counting never runs inside a timed pass.

use crate::geometry::{Hit, Ray};
use crate::index::trace::tiles;
use crate::index::{Answers, Counters, OwnRays, TraceIndex, TraceMode};
use std::time::{Duration, Instant};

/// What a batch asks: the closest hit, or only whether anything is hit (occlusion).
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Query {
    Closest,
    Any,
}

/// Median, spread (max - min) and the median's confidence interval
/// ([`super::median_interval`]) of repeated timings.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Timing {
    pub median: Duration,
    pub spread: Duration,
    /// The interval of the median: `fastest <= median <= slowest`.
    pub fastest: Duration,
    pub slowest: Duration,
    pub repeats: usize,
    /// The median of the GPU kernel times of the same passes
    /// ([`crate::index::TraceIndex::kernel_time`]), for GPU indices with timestamps.
    pub kernel: Option<Duration>,
}

impl Timing {
    /// Rays per second at the median.
    pub fn rays_per_sec(&self, rays: usize) -> f64 {
        rays as f64 / self.median.as_secs_f64().max(1e-12)
    }

    /// Median, spread and interval of non-empty samples.
    pub fn of(mut samples: Vec<Duration>) -> Timing {
        samples.sort();
        let repeats = samples.len();
        let (fastest, slowest) = super::median_interval::of_sorted(&samples);
        Timing {
            median: samples[repeats / 2],
            spread: samples[repeats - 1] - samples[0],
            fastest,
            slowest,
            repeats,
            kernel: None,
        }
    }

    /// The timing with the median of `kernel` (one per pass, where every pass had one).
    pub fn with_kernel(self, mut kernel: Vec<Duration>) -> Timing {
        kernel.sort();
        Timing {
            kernel: (!kernel.is_empty() && kernel.len() == self.repeats)
                .then(|| kernel[kernel.len() / 2]),
            ..self
        }
    }
}

/// Results of one batch: closest hits (for `Any`, a hit with `t = NaN` stands for "occluded").
pub type BatchHits = Vec<Option<Hit>>;

fn occluded(any: &[bool]) -> BatchHits {
    any.iter()
        .map(|&a| {
            a.then_some(Hit {
                t: f32::NAN,
                prim: u32::MAX,
            })
        })
        .collect()
}

/// The timed pass: runs the batch ray by ray `repeats` times (at least once) on the current
/// rayon pool, no counting. Returns the median and spread, and the last run's answers.
pub fn timed_pass(
    index: &dyn TraceIndex,
    query: Query,
    rays: &[Ray],
    repeats: usize,
) -> (Timing, BatchHits) {
    let mut out = PassOutput::new(query, rays.len());
    let batch = TimedBatch::new(index, TraceMode::Single, rays, None);
    let samples = (0..repeats.max(1))
        .map(|_| time_pass(index, &batch, &mut out))
        .collect();
    (Timing::of(samples), out.hits())
}

/// Where a timed pass writes its answers, allocated once for all the passes over one batch
/// (so a pass allocates nothing).
pub enum PassOutput {
    Closest(Vec<Option<Hit>>),
    Any(Vec<bool>),
}

impl PassOutput {
    /// Room for the answers to `query` on `rays` rays.
    pub fn new(query: Query, rays: usize) -> PassOutput {
        match query {
            Query::Closest => PassOutput::Closest(vec![None; rays]),
            Query::Any => PassOutput::Any(vec![false; rays]),
        }
    }

    /// The last pass's answers.
    pub fn hits(&self) -> BatchHits {
        match self {
            PassOutput::Closest(out) => out.clone(),
            PassOutput::Any(out) => occluded(out),
        }
    }
}

/// Closest hits of `rays` in `mode`, as an image of `width` columns when given.
fn closest_in(
    index: &dyn TraceIndex,
    mode: TraceMode,
    rays: &[Ray],
    width: Option<usize>,
    out: &mut [Option<Hit>],
    c: Option<&mut [Counters]>,
) {
    match width {
        Some(w) => index.closest_hits_image(mode, rays, w, out, c),
        None => index.closest_hits_in(mode, rays, out, c),
    }
}

/// Any-hit results of `rays` in `mode`, as an image of `width` columns when given.
fn any_in(
    index: &dyn TraceIndex,
    mode: TraceMode,
    rays: &[Ray],
    width: Option<usize>,
    out: &mut [bool],
    c: Option<&mut [Counters]>,
) {
    match width {
        Some(w) => index.any_hits_image(mode, rays, w, out, c),
        None => index.any_hits_in(mode, rays, out, c),
    }
}

/// A batch made ready for the timed passes of one index in one mode, before any clock starts:
/// its image width when it is an image in raster order (the packet modes then take packets from
/// screen tiles, [`tiles`]), and the index's own form of its rays where the index has one
/// ([`TraceIndex::own_rays`]: a peer library's ray records).
pub struct TimedBatch<'a> {
    rays: &'a [Ray],
    mode: TraceMode,
    width: Option<usize>,
    own: Option<OwnRays>,
}

impl<'a> TimedBatch<'a> {
    /// `rays` ready for `index`'s timed passes in `mode`; `width`: the batch is an image this
    /// many rays wide in raster order.
    pub fn new(
        index: &dyn TraceIndex,
        mode: TraceMode,
        rays: &'a [Ray],
        width: Option<usize>,
    ) -> TimedBatch<'a> {
        TimedBatch {
            rays,
            mode,
            width,
            own: index.own_rays(mode, rays),
        }
    }
}

/// One timed pass: `batch` traced once by `index` (the index it was made for) on the current
/// rayon pool, no counting, the answers left in `out` (whose query it answers). Returns the
/// wall time. Never inlined, so that a profile names the timed region.
#[inline(never)]
pub fn time_pass(index: &dyn TraceIndex, batch: &TimedBatch, out: &mut PassOutput) -> Duration {
    let start = Instant::now();
    match (&batch.own, out) {
        (Some(own), PassOutput::Closest(out)) => index.trace_own(own, Answers::Closest(out)),
        (Some(own), PassOutput::Any(out)) => index.trace_own(own, Answers::Any(out)),
        (None, out) => trace_into(index, batch.mode, batch.rays, batch.width, out, 0, None),
    }
    start.elapsed()
}

/// Traces `rays` in `mode` (as an image of `width` columns when given) into the answers
/// `from..from + rays.len()` of `out`, for `out`'s query, counting into `c` when given.
fn trace_into(
    index: &dyn TraceIndex,
    mode: TraceMode,
    rays: &[Ray],
    width: Option<usize>,
    out: &mut PassOutput,
    from: usize,
    c: Option<&mut [Counters]>,
) {
    let to = from + rays.len();
    match out {
        PassOutput::Closest(out) => closest_in(index, mode, rays, width, &mut out[from..to], c),
        PassOutput::Any(out) => any_in(index, mode, rays, width, &mut out[from..to], c),
    }
}

/// The counting pass: per-ray counters and the results, untimed.
pub fn counting_pass(
    index: &dyn TraceIndex,
    query: Query,
    rays: &[Ray],
) -> (Vec<Counters>, BatchHits) {
    counting_pass_in(index, query, TraceMode::Single, rays, None)
}

/// Rays per slice of a counting pass: between slices the pass checks for a SIGINT.
const COUNTING_SLICE: usize = 1 << 14;

/// [`counting_pass`] with the batch traced in `mode` (as an image `width` rays wide in raster
/// order when given), in slices of [`COUNTING_SLICE`] rays (of whole bands of
/// [`tiles::BAND_ROWS`] rows for an image, so that its packets are the timed passes' tiles: at
/// least one band). A SIGINT ([`super::interrupt::requested`]) stops it
/// before the next slice, leaving the rest of the answers unset: a caller that installed the
/// handler checks it after the pass and drops what the pass returned. (The timed passes are
/// not cut: each is one call, so that nothing but tracing is timed.)
pub fn counting_pass_in(
    index: &dyn TraceIndex,
    query: Query,
    mode: TraceMode,
    rays: &[Ray],
    width: Option<usize>,
) -> (Vec<Counters>, BatchHits) {
    let slice = match width {
        Some(w) => (COUNTING_SLICE / (tiles::BAND_ROWS * w)).max(1) * tiles::BAND_ROWS * w,
        None => COUNTING_SLICE,
    };
    let mut counters = vec![Counters::default(); rays.len()];
    let slices = rays.chunks(slice).zip(counters.chunks_mut(slice));
    let mut out = PassOutput::new(query, rays.len());
    for (k, (rays, c)) in slices.enumerate() {
        if super::interrupt::requested() {
            break;
        }
        trace_into(index, mode, rays, width, &mut out, k * slice, Some(c));
    }
    let hits = match out {
        PassOutput::Closest(out) => out,
        PassOutput::Any(out) => occluded(&out),
    };
    (counters, hits)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn median_and_spread() {
        let ms = Duration::from_millis;
        let t = Timing::of(vec![ms(5), ms(1), ms(9), ms(3), ms(4)]);
        assert_eq!((t.median, t.spread, t.repeats), (ms(4), ms(8), 5));
        // Five samples: the interval is the whole range.
        assert_eq!((t.fastest, t.slowest), (ms(1), ms(9)));
        let t = Timing::of((1..=9).rev().map(ms).collect());
        assert_eq!((t.median, t.fastest, t.slowest), (ms(5), ms(2), ms(8)));
    }

    /// Zero repeats still time one pass, and the pass's answers are the index's.
    #[test]
    fn a_timed_pass_runs_at_least_once_and_keeps_its_answers() {
        use crate::geometry::TriangleKernelKind;
        use crate::index::{IndexSpec, build_index};
        let scene = crate::scene::generators::generate("icosphere", 100, 1).unwrap();
        let brute = build_index(
            &IndexSpec::named("brute"),
            &scene.geometry(),
            TriangleKernelKind::Exact,
        )
        .unwrap();
        let ray = Ray::new(
            glam::Vec3::new(0.0, 0.0, -10.0),
            glam::Vec3::Z,
            0.0,
            f32::INFINITY,
        )
        .unwrap();
        let (t, hits) = timed_pass(brute.as_ref(), Query::Closest, &[ray], 0);
        assert_eq!(t.repeats, 1);
        assert_eq!(hits, vec![brute.closest_hit(&ray)]);
        assert!(hits[0].is_some());
        let (_, any) = timed_pass(brute.as_ref(), Query::Any, &[ray], 2);
        assert!(any[0].is_some_and(|h| h.t.is_nan()));
    }
}
