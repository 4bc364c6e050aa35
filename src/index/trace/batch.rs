//! How an index traces several rays at a time ([`BatchIndex`]): its own batch technique
//! (`stream`) and packets of neighbouring rays, by default one [`Index`] query per ray
//! ([`each`]). A trait apart from [`Index`], so the query trait imports
//! nothing of the tracing machinery.

use super::mode::TraceMode;
use super::own_rays::{Answers, OwnRays};
use crate::geometry::{Hit, Ray};
use crate::index::{AnyHit, Closest, HitQuery, Index, Stats};
use crate::scene::Geometry;

/// An index's batch techniques. Every index implements it (`impl BatchIndex for X {}` keeps
/// the defaults); one with a technique of its own overrides the methods and sets the flags.
pub trait BatchIndex: Index {
    /// Whether the index has a batch technique of its own ([`BatchIndex::closest_hits_stream`] is
    /// overridden): the suite then gives it `INDEX+stream` rows. An index without one has no
    /// stream row; the verdict lets its one-at-a-time row stand for it.
    const STREAM: bool = false;

    /// Whether one-query-at-a-time rows of the index measure anything of its own: `false` for
    /// an index that exists only as a batch technique over another index's single rays
    /// (`embree-p16`), which then gets only `+stream` rows.
    const SINGLE: bool = true;

    /// Whether the index traces packets as beams ([`BatchIndex::closest_hits_beam`] is
    /// overridden): the suite then gives it `INDEX+beams16` rows (and `beams4`, `beams8`). An
    /// index without beams gets no beam row.
    const BEAMS: bool = false;

    /// The batch `rays` in the index's own ray form for tracing in `mode` ([`super::own_rays`]),
    /// made before the timed passes so that they time the index's calls and not the conversion;
    /// `None` (the default) when the index traces our `Ray` as it is in that mode. A peer whose
    /// library reads rays of its own layout has one.
    fn own_rays(&self, mode: TraceMode, rays: &[Ray]) -> Option<OwnRays> {
        let _ = (mode, rays);
        None
    }

    /// The answers to a batch made by [`BatchIndex::own_rays`] (one per record), traced in
    /// parallel on the current rayon pool ([`super::parallel::each_chunk`]), no counting: the
    /// same answers as the batch's rays traced in the mode the records were made for.
    ///
    /// # Panics
    /// By default, since an index that makes no own rays is never given any.
    fn trace_own(&self, own: &OwnRays, out: Answers<'_>) {
        let _ = (own, out);
        unreachable!("an index without own rays is given none");
    }

    /// Closest hits of a chunk of consecutive rays of a batch (the harness's parallel work item,
    /// at most 64 rays; image order for camera sets; `out` and `stats` as long as `rays`) with
    /// the index's own batch technique ([`super::TraceMode::Stream`]). By default
    /// [`Index::closest_hit`] per ray; an index that traces several rays at a time (interleaved
    /// walks in `bvh4`/`bvh8`, Embree's 16-ray packets in `embree-p16`) overrides it and sets
    /// [`BatchIndex::STREAM`].
    #[inline]
    fn closest_hits_stream<G: Geometry, S: Stats>(
        &self,
        geom: &G,
        rays: &[Ray],
        out: &mut [Option<Hit>],
        stats: &mut [S],
    ) {
        each::<Closest, _, _, _>(self, geom, rays, out, stats);
    }

    /// Any-hit results of a chunk, as [`BatchIndex::closest_hits_stream`].
    #[inline]
    fn any_hits_stream<G: Geometry, S: Stats>(
        &self,
        geom: &G,
        rays: &[Ray],
        out: &mut [bool],
        stats: &mut [S],
    ) {
        each::<AnyHit, _, _, _>(self, geom, rays, out, stats);
    }

    /// Closest hits of a packet of neighbouring rays (at most [`super::MAX_PACKET`]; `out` and `stats`
    /// as long as `rays`). By default ray by ray; an index with packet traversal overrides it.
    #[inline]
    fn closest_hits_packet<G: Geometry, S: Stats>(
        &self,
        geom: &G,
        rays: &[Ray],
        out: &mut [Option<Hit>],
        stats: &mut [S],
    ) {
        each::<Closest, _, _, _>(self, geom, rays, out, stats);
    }

    /// Any-hit results of a packet, as [`BatchIndex::closest_hits_packet`].
    #[inline]
    fn any_hits_packet<G: Geometry, S: Stats>(
        &self,
        geom: &G,
        rays: &[Ray],
        out: &mut [bool],
        stats: &mut [S],
    ) {
        each::<AnyHit, _, _, _>(self, geom, rays, out, stats);
    }

    /// Closest hits of a packet (as [`BatchIndex::closest_hits_packet`]) traced as a beam
    /// ([`super::TraceMode::Beams`]). By default ray by ray; an index with beam traversal
    /// overrides it and sets [`BatchIndex::BEAMS`].
    #[inline]
    fn closest_hits_beam<G: Geometry, S: Stats>(
        &self,
        geom: &G,
        rays: &[Ray],
        out: &mut [Option<Hit>],
        stats: &mut [S],
    ) {
        each::<Closest, _, _, _>(self, geom, rays, out, stats);
    }

    /// Any-hit results of a packet traced as a beam, as [`BatchIndex::closest_hits_beam`].
    #[inline]
    fn any_hits_beam<G: Geometry, S: Stats>(
        &self,
        geom: &G,
        rays: &[Ray],
        out: &mut [bool],
        stats: &mut [S],
    ) {
        each::<AnyHit, _, _, _>(self, geom, rays, out, stats);
    }
}

/// Answers to query `Q` for `rays`, one [`Index::query`] per ray (`out` and `stats` as long as
/// `rays`).
#[inline]
pub fn each<Q: HitQuery, I: Index, G: Geometry, S: Stats>(
    index: &I,
    geom: &G,
    rays: &[Ray],
    out: &mut [Q::Answer],
    stats: &mut [S],
) {
    for ((r, o), s) in rays.iter().zip(out.iter_mut()).zip(stats.iter_mut()) {
        *o = index.query::<Q, G, S>(geom, r, s);
    }
}
