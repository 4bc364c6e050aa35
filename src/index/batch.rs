//! How a worker traces its chunk of a batch, in one of the [`TraceMode`]s: one query at a time
//! ([`Index::closest_hit`] per ray), with the index's own batch technique
//! ([`Index::closest_hits_stream`]), with the last hit tested first ([`super::last_hit`]), or in
//! packets of neighbouring rays ([`Index::closest_hits_packet`]).
//! Rays of a chunk are consecutive in the batch (image order for camera sets), and each chunk
//! starts with an empty last-hit cache, so results never depend on the thread count.

use super::last_hit::KernelRange;
use super::query::Query;
use super::{Index, Stats};
use crate::geometry::{Hit, Ray};
use crate::scene::Geometry;

/// Largest packet [`TraceMode::Packets`] takes.
pub const MAX_PACKET: usize = 8;

/// How a batch is traced. Every mode of every index of ours returns the same hits, bit for bit.
///
/// What a mode may do: [`TraceMode::Single`] and [`TraceMode::LastHit`] answer one query at a
/// time (one ray's walk finishes before the next ray's starts; nothing is shared between rays
/// but the last-hit cache); [`TraceMode::Stream`] and [`TraceMode::Packets`] may trace several
/// rays of a chunk at once (interleaved or lockstep walks, SIMD across rays).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum TraceMode {
    /// One query at a time: [`Index::closest_hit`] / [`Index::any_hit`] per ray.
    #[default]
    Single,
    /// The index's own way to trace a batch of independent rays ([`Index::STREAM`]).
    Stream,
    /// One ray at a time, the previous ray's hit primitive tested first.
    LastHit,
    /// Packets of this many consecutive rays (4 or 8).
    Packets(usize),
}

/// The two families the verdict compares within: one query at a time, or a batch.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum ModeFamily {
    /// `single` and `last-hit`.
    OneAtATime,
    /// `stream` and the packet modes.
    Batch,
}

impl ModeFamily {
    /// `one at a time` or `batch`.
    pub fn label(self) -> &'static str {
        match self {
            ModeFamily::OneAtATime => "one at a time",
            ModeFamily::Batch => "batch",
        }
    }
}

impl TraceMode {
    /// A short label for reports and the `mode` column: `single`, `stream`, `last-hit`,
    /// `packets8`; [`TraceMode::parse`] reads it back.
    pub fn label(self) -> String {
        match self {
            TraceMode::Single => "single".into(),
            TraceMode::Stream => "stream".into(),
            TraceMode::LastHit => "last-hit".into(),
            TraceMode::Packets(n) => format!("packets{n}"),
        }
    }

    /// A mode from its label (`single`, `stream`, `last-hit`, `packets4`, `packets8`).
    pub fn parse(s: &str) -> Result<TraceMode, String> {
        match s.trim() {
            "single" => Ok(TraceMode::Single),
            "stream" => Ok(TraceMode::Stream),
            "last-hit" => Ok(TraceMode::LastHit),
            "packets4" => Ok(TraceMode::Packets(4)),
            "packets8" => Ok(TraceMode::Packets(8)),
            other => Err(format!(
                "unknown trace mode '{other}': choose from single, stream, last-hit, packets4, packets8"
            )),
        }
    }

    /// The verdict's family of this mode.
    pub fn family(self) -> ModeFamily {
        match self {
            TraceMode::Single | TraceMode::LastHit => ModeFamily::OneAtATime,
            TraceMode::Stream | TraceMode::Packets(_) => ModeFamily::Batch,
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
        TraceMode::Single => Q::each(index, geom, rays, out, stats),
        TraceMode::Stream => Q::batch::<false, _, _, _>(index, geom, rays, out, stats),
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
