//! The parallel driver: a batch cut into chunks of [`CHUNK`] consecutive rays, each traced by
//! one rayon worker ([`super::chunk::trace_chunk`]) with its own counters or none.

use super::batch::BatchIndex;
use super::chunk::trace_chunk;
use super::mode::TraceMode;
use super::query::Query;
use super::reorder::Sorted;
use crate::geometry::Ray;
use crate::index::{Counters, NoStats};
use crate::scene::Geometry;
use rayon::prelude::*;

/// Rays per parallel work item: large enough to amortize scheduling, small enough to balance.
const CHUNK: usize = 64;

/// Answers query `Q` for a batch traced in `mode`, in parallel chunks of [`CHUNK`] rays, with
/// per-ray counters (reset first) when `counters` is given; in [`TraceMode::Reorder`] the batch
/// sorted first ([`trace_reordered`]).
pub fn trace_in_parallel<Q: Query, I: BatchIndex, G: Geometry>(
    index: &I,
    geom: &G,
    mode: TraceMode,
    rays: &[Ray],
    out: &mut [Q::Answer],
    counters: Option<&mut [Counters]>,
) {
    assert_eq!(rays.len(), out.len(), "one output per ray");
    if mode == TraceMode::Reorder {
        return trace_reordered::<Q, _, _>(index, geom, rays, out, counters);
    }
    let chunk = |(rays, out): (&[Ray], &mut [Q::Answer]), c: Option<&mut [Counters]>| match c {
        Some(c) => {
            c.fill(Counters::default());
            trace_chunk::<Q, _, _, _>(index, geom, mode, rays, out, c)
        }
        None => {
            let none = &mut [NoStats; CHUNK][..rays.len()];
            trace_chunk::<Q, _, _, _>(index, geom, mode, rays, out, none)
        }
    };
    let work = rays.par_chunks(CHUNK).zip(out.par_chunks_mut(CHUNK));
    match counters {
        Some(c) => {
            assert_eq!(rays.len(), c.len(), "one counter per ray");
            work.zip(c.par_chunks_mut(CHUNK))
                .for_each(|(w, c)| chunk(w, Some(c)));
        }
        None => work.for_each(|w| chunk(w, None)),
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
    let single = TraceMode::Single;
    match counters {
        Some(c) => {
            let mut sorted_counters = vec![Counters::default(); rays.len()];
            let sc = Some(&mut sorted_counters[..]);
            trace_in_parallel::<Q, _, _>(index, geom, single, &sorted.rays, &mut answers, sc);
            sorted.scatter(&sorted_counters, c);
        }
        None => trace_in_parallel::<Q, _, _>(index, geom, single, &sorted.rays, &mut answers, None),
    }
    sorted.scatter(&answers, out);
}
