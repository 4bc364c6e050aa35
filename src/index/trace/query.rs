//! The two questions a batch asks of an index, as types: [`Closest`] (the closest hit) and
//! [`AnyHit`] (whether anything is hit), so the batch code, the last-hit cache and the registry
//! trace both with one generic body.

use super::batch::{self, BatchIndex};
use super::last_hit::{self, KernelRange};
use crate::geometry::{Hit, Ray};
use crate::index::{Index, Stats};
use crate::scene::Geometry;

/// A query kind: its answer per ray and the [`Index`] and [`BatchIndex`] methods that produce
/// it.
pub trait Query: Send + Sync + 'static {
    /// One ray's answer (`Option<Hit>` or `bool`).
    type Answer: Copy + Send + Sync;
    /// A chunk of a batch one query at a time ([`Index::closest_hit`] or `any_hit` per ray).
    fn each<I: Index, G: Geometry, S: Stats>(
        i: &I,
        g: &G,
        rays: &[Ray],
        out: &mut [Self::Answer],
        stats: &mut [S],
    );
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
    /// One ray with the last-hit cache ([`last_hit::closest_hit`] or [`last_hit::any_hit`]).
    fn last_hit<I: Index, G: Geometry, S: Stats>(
        i: &I,
        range: &mut KernelRange<G>,
        ray: &Ray,
        last: &mut Option<u32>,
        stats: &mut S,
    ) -> Self::Answer;
}

/// The closest hit (primitive and `t`), or `None`.
pub enum Closest {}

/// Whether any primitive is hit (shadow rays).
pub enum AnyHit {}

/// `impl Query for $kind`: the [`Index`] methods and the last-hit function that answer it.
macro_rules! answered_by {
    ($kind:ty, $answer:ty, $each:path, $chunk:ident, $packet:ident, $last_hit:path) => {
        impl Query for $kind {
            type Answer = $answer;
            #[inline]
            fn each<I: Index, G: Geometry, S: Stats>(
                i: &I,
                g: &G,
                r: &[Ray],
                o: &mut [Self::Answer],
                s: &mut [S],
            ) {
                $each(i, g, r, o, s)
            }
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
    Option<Hit>,
    batch::each_closest,
    closest_hits_stream,
    closest_hits_packet,
    last_hit::closest_hit
);
answered_by!(
    AnyHit,
    bool,
    batch::each_any,
    any_hits_stream,
    any_hits_packet,
    last_hit::any_hit
);
