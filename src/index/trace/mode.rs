//! The ways a batch can be traced ([`TraceMode`]), the two families the verdict compares within
//! ([`ModeFamily`]), and their labels.

/// Largest packet [`TraceMode::Packets`] takes.
pub const MAX_PACKET: usize = 16;

/// How a batch is traced. Every mode of every index of ours returns the same hits, bit for bit.
///
/// What a mode may do: [`TraceMode::Single`] and [`TraceMode::LastHit`] answer one query at a
/// time (one ray's walk finishes before the next ray's starts; nothing is shared between rays
/// but the last-hit cache); [`TraceMode::Stream`], [`TraceMode::Packets`] and [`TraceMode::Beams`]
/// may trace several rays of a chunk at once (interleaved or lockstep walks, SIMD across rays);
/// [`TraceMode::Reorder`] may change the order of the batch's rays, and answers each one query at
/// a time.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum TraceMode {
    /// One query at a time: [`crate::index::Index::closest_hit`] / `any_hit` per ray.
    #[default]
    Single,
    /// The index's own way to trace a batch of independent rays ([`crate::index::BatchIndex::STREAM`]).
    Stream,
    /// One ray at a time, the previous ray's hit primitive tested first.
    LastHit,
    /// Packets of this many neighbouring rays (4, 8 or 16; [`super::tiles`] says which).
    Packets(usize),
    /// The same packets as [`TraceMode::Packets`], traced as beams: the first active ray
    /// decides a node, an interval (frustum) test culls for the whole packet
    /// ([`crate::index::BatchIndex::BEAMS`]; only indices with the technique are traced so).
    Beams(usize),
    /// The batch sorted by a coherence key, then one query at a time in that order
    /// ([`super::reorder`]); the sort is part of the mode's time.
    Reorder,
}

/// The two families the verdict compares within: one query at a time, or a batch.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum ModeFamily {
    /// `single` and `last-hit`.
    OneAtATime,
    /// `stream`, the packet and beam modes and `reorder`.
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
            TraceMode::Beams(n) => format!("beams{n}"),
            TraceMode::Reorder => "reorder".into(),
        }
    }

    /// A mode from its label (`single`, `stream`, `last-hit`, `packets4`, `packets8`,
    /// `packets16`, `beams4`, `beams8`, `beams16`, `reorder`).
    pub fn parse(s: &str) -> Result<TraceMode, String> {
        match s.trim() {
            "single" => Ok(TraceMode::Single),
            "stream" => Ok(TraceMode::Stream),
            "last-hit" => Ok(TraceMode::LastHit),
            "packets4" => Ok(TraceMode::Packets(4)),
            "packets8" => Ok(TraceMode::Packets(8)),
            "packets16" => Ok(TraceMode::Packets(16)),
            "beams4" => Ok(TraceMode::Beams(4)),
            "beams8" => Ok(TraceMode::Beams(8)),
            "beams16" => Ok(TraceMode::Beams(16)),
            "reorder" => Ok(TraceMode::Reorder),
            other => Err(format!(
                "unknown trace mode '{other}': choose from single, stream, last-hit, packets4, \
                 packets8, packets16, beams4, beams8, beams16, reorder"
            )),
        }
    }

    /// The verdict's family of this mode.
    pub fn family(self) -> ModeFamily {
        match self {
            TraceMode::Single | TraceMode::LastHit => ModeFamily::OneAtATime,
            TraceMode::Stream
            | TraceMode::Packets(_)
            | TraceMode::Beams(_)
            | TraceMode::Reorder => ModeFamily::Batch,
        }
    }
}
