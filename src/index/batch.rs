//! How a worker traces its chunk of a batch: ray by ray ([`Index::closest_hits_chunk`], which an
//! index may trace several rays at a time), with the last hit tested first
//! ([`super::last_hit`]), or in packets of neighbouring rays ([`Index::closest_hits_packet`]).
//! Rays of a chunk are consecutive in the batch (image order for camera sets), and each chunk
//! starts with an empty last-hit cache, so results never depend on the thread count.

use super::last_hit::KernelRange;
use super::query::Query;
use super::{Index, Stats};
use crate::geometry::{Hit, Ray};
use crate::scene::Geometry;

/// Largest packet [`TraceMode::Packets`] takes.
pub const MAX_PACKET: usize = 8;

/// How a batch is traced. Every mode returns the same hits, bit for bit.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum TraceMode {
    /// One ray at a time.
    #[default]
    Single,
    /// One ray at a time, the previous ray's hit primitive tested first.
    LastHit,
    /// Packets of this many consecutive rays (4 or 8).
    Packets(usize),
}

impl TraceMode {
    /// A short label for reports: `single`, `last-hit`, `packets8`.
    pub fn label(self) -> String {
        match self {
            TraceMode::Single => "single".into(),
            TraceMode::LastHit => "last-hit".into(),
            TraceMode::Packets(n) => format!("packets{n}"),
        }
    }
}

/// Closest hits of `rays`, one [`Index::closest_hit`] per ray (`out` and `stats` as long as
/// `rays`).
#[inline]
pub fn each_closest<I: Index, G: Geometry, S: Stats>(
    index: &I,
    geom: &G,
    rays: &[Ray],
    out: &mut [Option<Hit>],
    stats: &mut [S],
) {
    for ((r, o), s) in rays.iter().zip(out.iter_mut()).zip(stats.iter_mut()) {
        *o = index.closest_hit(geom, r, s);
    }
}

/// Any-hit results of `rays`, one [`Index::any_hit`] per ray.
#[inline]
pub fn each_any<I: Index, G: Geometry, S: Stats>(
    index: &I,
    geom: &G,
    rays: &[Ray],
    out: &mut [bool],
    stats: &mut [S],
) {
    for ((r, o), s) in rays.iter().zip(out.iter_mut()).zip(stats.iter_mut()) {
        *o = index.any_hit(geom, r, s);
    }
}

/// The answers to query `Q` for one chunk traced in `mode` (`out` and `stats` as long as
/// `rays`).
pub fn trace_chunk<Q: Query, I: Index, G: Geometry, S: Stats>(
    index: &I,
    geom: &G,
    mode: TraceMode,
    rays: &[Ray],
    out: &mut [Q::Answer],
    stats: &mut [S],
) {
    match mode {
        TraceMode::Single => Q::batch::<false, _, _, _>(index, geom, rays, out, stats),
        TraceMode::LastHit => {
            let mut range = KernelRange::new(geom.clone());
            let mut last = None;
            for ((r, o), s) in rays.iter().zip(out.iter_mut()).zip(stats.iter_mut()) {
                *o = Q::last_hit(index, &mut range, r, &mut last, s);
            }
        }
        TraceMode::Packets(n) => {
            let n = n.clamp(1, MAX_PACKET);
            for ((r, o), s) in rays
                .chunks(n)
                .zip(out.chunks_mut(n))
                .zip(stats.chunks_mut(n))
            {
                Q::batch::<true, _, _, _>(index, geom, r, o, s);
            }
        }
    }
}
