//! How the tracing machinery asks an index each query kind ([`Query`]): the batch techniques
//! and the last-hit function that answer [`Closest`] and [`AnyHit`], so the chunk code and the
//! parallel driver trace both with one generic body. One query at a time needs nothing here:
//! it is [`crate::index::Index::query`] itself ([`batch::each`]).

use super::batch::BatchIndex;
use super::last_hit::{self, KernelRange};
use crate::geometry::Ray;
use crate::index::{AnyHit, Closest, HitQuery, Index, Stats};
use crate::scene::Geometry;

/// A query kind with the [`BatchIndex`] methods and the last-hit function that answer it.
pub trait Query: HitQuery {
    /// A chunk of a batch with the index's own batch technique
    /// ([`BatchIndex::closest_hits_stream`] or `any_hits_stream`), or with `PACKET` one packet
    /// ([`BatchIndex::closest_hits_packet`] or `any_hits_packet`).
    fn batch<const PACKET: bool, I: BatchIndex, G: Geometry, S: Stats>(
        i: &I,
        g: &G,
        rays: &[Ray],
        out: &mut [Self::Answer],
        stats: &mut [S],
    );
    /// One packet traced as a beam ([`BatchIndex::closest_hits_beam`] or `any_hits_beam`).
    fn beam<I: BatchIndex, G: Geometry, S: Stats>(
        i: &I,
        g: &G,
        rays: &[Ray],
        out: &mut [Self::Answer],
        stats: &mut [S],
    );
    /// One packet in packet mode `mode` ([`super::TraceMode::Packets`]: [`Query::batch`] with
    /// `PACKET`; [`super::TraceMode::Beams`]: [`Query::beam`]).
    #[inline]
    fn packet<I: BatchIndex, G: Geometry, S: Stats>(
        beams: bool,
        i: &I,
        g: &G,
        rays: &[Ray],
        out: &mut [Self::Answer],
        stats: &mut [S],
    ) {
        if beams {
            Self::beam(i, g, rays, out, stats)
        } else {
            Self::batch::<true, _, _, _>(i, g, rays, out, stats)
        }
    }
    /// One ray with the last-hit cache ([`last_hit::closest_hit`] or [`last_hit::any_hit`]).
    fn last_hit<I: Index, G: Geometry, S: Stats>(
        i: &I,
        range: &mut KernelRange<G>,
        ray: &Ray,
        last: &mut Option<u32>,
        stats: &mut S,
    ) -> Self::Answer;
}

/// `impl Query for $kind`: the [`BatchIndex`] methods and the last-hit function that answer it.
macro_rules! answered_by {
    ($kind:ty, $chunk:ident, $packet:ident, $beam:ident, $last_hit:path) => {
        impl Query for $kind {
            #[inline]
            fn batch<const PACKET: bool, I: BatchIndex, G: Geometry, S: Stats>(
                i: &I,
                g: &G,
                r: &[Ray],
                o: &mut [Self::Answer],
                s: &mut [S],
            ) {
                if PACKET {
                    i.$packet(g, r, o, s)
                } else {
                    i.$chunk(g, r, o, s)
                }
            }
            #[inline]
            fn beam<I: BatchIndex, G: Geometry, S: Stats>(
                i: &I,
                g: &G,
                r: &[Ray],
                o: &mut [Self::Answer],
                s: &mut [S],
            ) {
                i.$beam(g, r, o, s)
            }
            #[inline]
            fn last_hit<I: Index, G: Geometry, S: Stats>(
                i: &I,
                g: &mut KernelRange<G>,
                r: &Ray,
                l: &mut Option<u32>,
                s: &mut S,
            ) -> Self::Answer {
                $last_hit(i, g, r, l, s)
            }
        }
    };
}

answered_by!(
    Closest,
    closest_hits_stream,
    closest_hits_packet,
    closest_hits_beam,
    last_hit::closest_hit
);
answered_by!(
    AnyHit,
    any_hits_stream,
    any_hits_packet,
    any_hits_beam,
    last_hit::any_hit
);
