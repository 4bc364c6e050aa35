//! The parallel driver: a batch cut into chunks of [`CHUNK`] consecutive rays, each traced by
//! one rayon worker ([`super::chunk::trace_chunk`]) with its own counters or none. A batch that
//! is an image of known width, traced in packets, is cut into bands of [`BAND_ROWS`] image rows
//! instead, each traced in packets from screen tiles ([`super::tiles::trace_band`]).

use super::batch::BatchIndex;
use super::chunk::trace_chunk;
use super::mode::TraceMode;
use super::query::Query;
use super::reorder::Sorted;
use super::tiles::{BAND_ROWS, trace_band};
use crate::geometry::Ray;
use crate::index::{Counters, NoStats, Stats};
use crate::scene::Geometry;
use rayon::prelude::*;

/// Rays per parallel work item: large enough to amortize scheduling, small enough to balance.
const CHUNK: usize = 64;

/// Answers query `Q` for a batch traced in `mode`, in parallel chunks of [`CHUNK`] rays, with
/// per-ray counters (reset first) when `counters` is given. `width`: the batch is an image of
/// this many columns in raster order (camera rays), whose packets then come from tiles. In
/// [`TraceMode::Reorder`] the batch is sorted first ([`trace_reordered`]).
pub fn trace_in_parallel<Q: Query, I: BatchIndex, G: Geometry>(
    index: &I,
    geom: &G,
    mode: TraceMode,
    rays: &[Ray],
    width: Option<usize>,
    out: &mut [Q::Answer],
    counters: Option<&mut [Counters]>,
) {
    assert_eq!(rays.len(), out.len(), "one output per ray");
    if mode == TraceMode::Reorder {
        return trace_reordered::<Q, _, _>(index, geom, rays, out, counters);
    }
    let tiled = match (mode, width) {
        (TraceMode::Packets(n), Some(w)) if w > 0 => Some((n, w, false)),
        (TraceMode::Beams(n), Some(w)) if w > 0 => Some((n, w, true)),
        _ => None,
    };
    let item = tiled.map_or(CHUNK, |(_, w, _)| BAND_ROWS * w);
    let work = rays.par_chunks(item).zip(out.par_chunks_mut(item));
    match counters {
        Some(c) => {
            assert_eq!(rays.len(), c.len(), "one counter per ray");
            work.zip(c.par_chunks_mut(item))
                .for_each(|((rays, out), c)| {
                    c.fill(Counters::default());
                    trace_item::<Q, _, _, _>(index, geom, mode, tiled, rays, out, c)
                });
        }
        // A vector of the zero-sized `NoStats` allocates nothing.
        None => work.for_each(|(rays, out)| {
            let none = &mut vec![NoStats; rays.len()];
            trace_item::<Q, _, _, _>(index, geom, mode, tiled, rays, out, none)
        }),
    }
}

/// `trace` run on each chunk of [`CHUNK`] consecutive records of a batch and its answers, in
/// parallel on the current rayon pool: the driver of a batch in an index's own ray form
/// ([`super::BatchIndex::trace_own`]), cut as [`trace_in_parallel`] cuts a batch of `Ray`s.
pub fn each_chunk<T: Sync, A: Send>(
    records: &[T],
    out: &mut [A],
    trace: impl Fn(&[T], &mut [A]) + Sync,
) {
    assert_eq!(records.len(), out.len(), "one output per ray");
    records
        .par_chunks(CHUNK)
        .zip(out.par_chunks_mut(CHUNK))
        .for_each(|(records, out)| trace(records, out));
}

/// One work item: a band of an image in tiles (`tiled`: the packet size, the image width and
/// whether the packets are traced as beams), or a chunk in `mode`.
fn trace_item<Q: Query, I: BatchIndex, G: Geometry, S: Stats>(
    index: &I,
    geom: &G,
    mode: TraceMode,
    tiled: Option<(usize, usize, bool)>,
    rays: &[Ray],
    out: &mut [Q::Answer],
    stats: &mut [S],
) {
    match tiled {
        Some((n, w, beams)) => {
            trace_band::<Q, _, _, _>(index, geom, (n, beams), w, rays, out, stats)
        }
        None => trace_chunk::<Q, _, _, _>(index, geom, mode, rays, out, stats),
    }
}

/// The batch in coherence order ([`super::reorder`]): sorted, traced in `single` mode, and its
/// answers and counters put back at their rays' places.
fn trace_reordered<Q: Query, I: BatchIndex, G: Geometry>(
    index: &I,
    geom: &G,
    rays: &[Ray],
    out: &mut [Q::Answer],
    counters: Option<&mut [Counters]>,
) {
    let sorted = Sorted::new(rays);
    let mut answers = vec![Q::Answer::default(); rays.len()];
    let (single, sorted_rays) = (TraceMode::Single, &sorted.rays);
    match counters {
        Some(c) => {
            let mut sorted_counters = vec![Counters::default(); rays.len()];
            let sc = Some(&mut sorted_counters[..]);
            trace_in_parallel::<Q, _, _>(index, geom, single, sorted_rays, None, &mut answers, sc);
            sorted.scatter(&sorted_counters, c);
        }
        None => {
            trace_in_parallel::<Q, _, _>(index, geom, single, sorted_rays, None, &mut answers, None)
        }
    }
    sorted.scatter(&answers, out);
}
