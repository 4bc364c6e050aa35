//! The parallel driver: a batch cut into chunks of [`CHUNK`] consecutive rays, each traced by
//! one rayon worker ([`super::chunk::trace_chunk`]) with its own counters or none.

use super::batch::BatchIndex;
use super::chunk::trace_chunk;
use super::mode::TraceMode;
use super::query::Query;
use crate::geometry::Ray;
use crate::index::{Counters, NoStats};
use crate::scene::Geometry;
use rayon::prelude::*;

/// Rays per parallel work item: large enough to amortize scheduling, small enough to balance.
const CHUNK: usize = 64;

/// Answers query `Q` for a batch traced in `mode`, in parallel chunks of [`CHUNK`] rays, with
/// per-ray counters (reset first) when `counters` is given. The rays stay in their order
/// ([`TraceMode::Reorder`] is [`super::reorder`], which calls this with the sorted batch).
pub fn trace_in_parallel<Q: Query, I: BatchIndex, G: Geometry>(
    index: &I,
    geom: &G,
    mode: TraceMode,
    rays: &[Ray],
    out: &mut [Q::Answer],
    counters: Option<&mut [Counters]>,
) {
    assert_eq!(rays.len(), out.len(), "one output per ray");
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
