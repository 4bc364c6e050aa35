//! How a worker traces its chunk of a batch, in one of the [`TraceMode`]s: one query at a time
//! ([`crate::index::Index::closest_hit`] per ray), with the index's own batch technique
//! ([`BatchIndex::closest_hits_stream`]), with the last hit tested first ([`super::last_hit`]),
//! or in packets of neighbouring rays ([`BatchIndex::closest_hits_packet`], or as beams:
//! [`BatchIndex::closest_hits_beam`]).
//! Rays of a chunk are consecutive in the batch (image order for camera sets), and each chunk
//! starts with an empty last-hit cache, so results never depend on the thread count.

use super::batch::{BatchIndex, each};
use super::last_hit::KernelRange;
use super::mode::{MAX_PACKET, TraceMode};
use super::query::Query;
use crate::geometry::Ray;
use crate::index::Stats;
use crate::scene::Geometry;

/// The answers to query `Q` for one chunk traced in `mode` (`out` and `stats` as long as
/// `rays`).
pub fn trace_chunk<Q: Query, I: BatchIndex, G: Geometry, S: Stats>(
    index: &I,
    geom: &G,
    mode: TraceMode,
    rays: &[Ray],
    out: &mut [Q::Answer],
    stats: &mut [S],
) {
    match mode {
        // A chunk of a reordered batch is already in coherence order (see `super::reorder`).
        TraceMode::Single | TraceMode::Reorder => each::<Q, _, _, _>(index, geom, rays, out, stats),
        TraceMode::Stream => Q::batch::<false, _, _, _>(index, geom, rays, out, stats),
        TraceMode::LastHit => {
            let mut range = KernelRange::new(geom.clone());
            let mut last = None;
            for ((r, o), s) in rays.iter().zip(out.iter_mut()).zip(stats.iter_mut()) {
                *o = Q::last_hit(index, &mut range, r, &mut last, s);
            }
        }
        TraceMode::Packets(n) | TraceMode::Beams(n) => {
            let beams = matches!(mode, TraceMode::Beams(_));
            let n = n.clamp(1, MAX_PACKET);
            for ((r, o), s) in rays
                .chunks(n)
                .zip(out.chunks_mut(n))
                .zip(stats.chunks_mut(n))
            {
                Q::packet(beams, index, geom, r, o, s);
            }
        }
    }
}
