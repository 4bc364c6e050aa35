//! Timed and counting passes over a batch of rays. Counting never runs inside a timed pass.

use crate::geometry::{Hit, Ray};
use crate::index::{Counters, TraceIndex, TraceMode};
use std::time::{Duration, Instant};

/// What a batch asks: the closest hit, or only whether anything is hit (occlusion).
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Query {
    Closest,
    Any,
}

/// Median and spread (max - min) of repeated timings.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Timing {
    pub median: Duration,
    pub spread: Duration,
    pub repeats: usize,
}

impl Timing {
    /// Rays per second at the median.
    pub fn rays_per_sec(&self, rays: usize) -> f64 {
        rays as f64 / self.median.as_secs_f64().max(1e-12)
    }
}

/// Runs `f` `repeats` times (at least once) and returns the median and spread.
pub fn time_repeated(repeats: usize, mut f: impl FnMut()) -> Timing {
    let samples: Vec<Duration> = (0..repeats.max(1))
        .map(|_| {
            let start = Instant::now();
            f();
            start.elapsed()
        })
        .collect();
    summarize(samples)
}

/// Median and spread of non-empty samples.
fn summarize(mut samples: Vec<Duration>) -> Timing {
    samples.sort();
    let repeats = samples.len();
    Timing {
        median: samples[repeats / 2],
        spread: samples[repeats - 1] - samples[0],
        repeats,
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

/// The timed pass: runs the batch `repeats` times on the current rayon pool, no counting.
pub fn timed_pass(
    index: &dyn TraceIndex,
    query: Query,
    rays: &[Ray],
    repeats: usize,
) -> (Timing, BatchHits) {
    timed_pass_in(index, query, TraceMode::Single, rays, repeats)
}

/// [`timed_pass`] with the batch traced in `mode` (last hit first, packets).
pub fn timed_pass_in(
    index: &dyn TraceIndex,
    query: Query,
    mode: TraceMode,
    rays: &[Ray],
    repeats: usize,
) -> (Timing, BatchHits) {
    match query {
        Query::Closest => {
            let mut out = vec![None; rays.len()];
            let t = time_repeated(repeats, || {
                index.closest_hits_in(mode, rays, &mut out, None)
            });
            (t, out)
        }
        Query::Any => {
            let mut out = vec![false; rays.len()];
            let t = time_repeated(repeats, || index.any_hits_in(mode, rays, &mut out, None));
            (t, occluded(&out))
        }
    }
}

/// The counting pass: per-ray counters and the results, untimed.
pub fn counting_pass(
    index: &dyn TraceIndex,
    query: Query,
    rays: &[Ray],
) -> (Vec<Counters>, BatchHits) {
    counting_pass_in(index, query, TraceMode::Single, rays)
}

/// [`counting_pass`] with the batch traced in `mode`.
pub fn counting_pass_in(
    index: &dyn TraceIndex,
    query: Query,
    mode: TraceMode,
    rays: &[Ray],
) -> (Vec<Counters>, BatchHits) {
    let mut counters = vec![Counters::default(); rays.len()];
    match query {
        Query::Closest => {
            let mut out = vec![None; rays.len()];
            index.closest_hits_in(mode, rays, &mut out, Some(&mut counters));
            (counters, out)
        }
        Query::Any => {
            let mut out = vec![false; rays.len()];
            index.any_hits_in(mode, rays, &mut out, Some(&mut counters));
            (counters, occluded(&out))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn median_and_spread() {
        let ms = Duration::from_millis;
        let t = summarize(vec![ms(5), ms(1), ms(9), ms(3), ms(4)]);
        assert_eq!((t.median, t.spread, t.repeats), (ms(4), ms(8), 5));
        let mut calls = 0;
        assert_eq!(time_repeated(0, || calls += 1).repeats, 1);
        assert_eq!(calls, 1);
    }
}
