//! The object-safe face of a built index ([`TraceIndex`]) that the harness, the CLI and reports
//! use. The virtual call happens once per batch of rays; inside, traversal is monomorphized for
//! the index, the geometry and the stats.

use super::mode::TraceMode;
use super::own_rays::{Answers, OwnRays};
use crate::geometry::{Hit, Ray};
use crate::index::{BuildError, Counters, IndexInfo};
use crate::scene::SceneGeometry;
use std::time::Duration;

/// The object-safe face of a built index. Batch methods run in parallel on the current rayon
/// pool (`ThreadPool::install` picks the thread count); single-ray methods are for callers that
/// do per-ray work around the query (rendering).
pub trait TraceIndex: Send + Sync {
    /// Registry name (`bvh`, `grid`, ...).
    fn name(&self) -> &str;
    /// The parameters it was built with, as `key=value` pairs.
    fn params(&self) -> &str;
    fn info(&self) -> &IndexInfo;
    /// Whether the index has a batch technique of its own ([`crate::index::BatchIndex::STREAM`]).
    fn has_stream(&self) -> bool;
    /// Whether its one-query-at-a-time rows are its own ([`crate::index::BatchIndex::SINGLE`]).
    fn has_single(&self) -> bool;
    /// Whether the index traces packets as beams ([`crate::index::BatchIndex::BEAMS`]); by
    /// default not.
    fn has_beams(&self) -> bool {
        false
    }
    /// Whether the suite traces it in `mode`: `stream` only with a batch technique of its own,
    /// the beam modes only with beam traversal, the one-at-a-time modes only when they are its
    /// own.
    fn traces_in(&self, mode: TraceMode) -> bool {
        match mode {
            TraceMode::Stream => self.has_stream(),
            TraceMode::Beams(_) => self.has_beams(),
            TraceMode::Single | TraceMode::LastHit | TraceMode::Reorder => self.has_single(),
            TraceMode::Packets(_) => true,
        }
    }
    /// How many of `rays` the index refuses ([`crate::index::Index::refuses`]: it answers them
    /// as misses without tracing them) and why the first was refused; `None` when it takes all.
    fn refused(&self, rays: &[Ray]) -> Option<(usize, &'static str)>;
    /// Whether [`TraceIndex::refit`] can follow the scene's frames in place.
    fn can_refit(&self) -> bool;
    /// Moves the index to `frame`, another frame of the scene it was built on (the same
    /// primitives, same kinds and ids, at new positions), by [`crate::index::Index::refit`];
    /// `info` then describes the refitted index (its `build_time` stays the first build's).
    /// [`BuildError::Unsupported`] when the index has no refit. After any other error the
    /// index is unusable: drop it and rebuild.
    fn refit(&mut self, frame: &SceneGeometry) -> Result<(), BuildError>;
    /// The kernel time of the last batch traced, for an index on a GPU whose adapter has
    /// timestamp queries (the batch's end-to-end time includes the upload of the rays and the
    /// readback of the hits); `None` for every other index.
    fn kernel_time(&self) -> Option<Duration> {
        None
    }
    /// The batch in the index's own ray form for `mode`, made before timed passes
    /// ([`crate::index::BatchIndex::own_rays`]); `None` when it traces our `Ray` as it is.
    fn own_rays(&self, mode: TraceMode, rays: &[Ray]) -> Option<OwnRays> {
        let _ = (mode, rays);
        None
    }
    /// The answers to a batch this index made with [`TraceIndex::own_rays`], in parallel, no
    /// counting ([`crate::index::BatchIndex::trace_own`]).
    ///
    /// # Panics
    /// By default, since an index that makes no own rays is given none.
    fn trace_own(&self, own: &OwnRays, out: Answers<'_>) {
        let _ = (own, out);
        unreachable!("an index without own rays is given none");
    }
    fn closest_hit(&self, ray: &Ray) -> Option<Hit>;
    fn closest_hit_counted(&self, ray: &Ray, counters: &mut Counters) -> Option<Hit>;
    fn any_hit(&self, ray: &Ray) -> bool;
    fn any_hit_counted(&self, ray: &Ray, counters: &mut Counters) -> bool;
    /// Closest hits of a batch (`out.len() == rays.len()`) traced in `mode`, with per-ray
    /// counters (reset first) when `counters` is given.
    fn closest_hits_in(
        &self,
        mode: TraceMode,
        rays: &[Ray],
        out: &mut [Option<Hit>],
        counters: Option<&mut [Counters]>,
    );
    /// Any-hit results of a batch traced in `mode`, as [`TraceIndex::closest_hits_in`].
    fn any_hits_in(
        &self,
        mode: TraceMode,
        rays: &[Ray],
        out: &mut [bool],
        counters: Option<&mut [Counters]>,
    );
    /// [`TraceIndex::closest_hits_in`] for a batch that is an image `width` rays wide in raster
    /// order (camera rays): the packet modes then take their packets from screen tiles
    /// ([`super::tiles`]). The answers are the same; by default the width is not used.
    fn closest_hits_image(
        &self,
        mode: TraceMode,
        rays: &[Ray],
        width: usize,
        out: &mut [Option<Hit>],
        counters: Option<&mut [Counters]>,
    ) {
        let _ = width;
        self.closest_hits_in(mode, rays, out, counters);
    }
    /// [`TraceIndex::any_hits_in`] for an image `width` rays wide, as
    /// [`TraceIndex::closest_hits_image`].
    fn any_hits_image(
        &self,
        mode: TraceMode,
        rays: &[Ray],
        width: usize,
        out: &mut [bool],
        counters: Option<&mut [Counters]>,
    ) {
        let _ = width;
        self.any_hits_in(mode, rays, out, counters);
    }
    /// Closest hits of a batch (`out.len() == rays.len()`), no counting.
    fn closest_hits(&self, rays: &[Ray], out: &mut [Option<Hit>]) {
        self.closest_hits_in(TraceMode::Single, rays, out, None);
    }
    /// Any-hit results of a batch, no counting.
    fn any_hits(&self, rays: &[Ray], out: &mut [bool]) {
        self.any_hits_in(TraceMode::Single, rays, out, None);
    }
    /// Closest hits with per-ray counters.
    fn closest_hits_counted(&self, rays: &[Ray], out: &mut [Option<Hit>], c: &mut [Counters]) {
        self.closest_hits_in(TraceMode::Single, rays, out, Some(c));
    }
    /// Any-hit results with per-ray counters.
    fn any_hits_counted(&self, rays: &[Ray], out: &mut [bool], c: &mut [Counters]) {
        self.any_hits_in(TraceMode::Single, rays, out, Some(c));
    }
}
