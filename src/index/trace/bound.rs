//! A built index bound to the geometry it was built on ([`BoundIndex`], built by
//! [`build_index_on`]): the object-safe [`TraceIndex`] of the harness, whose batch calls trace in
//! parallel ([`super::parallel`]).

use super::batch::BatchIndex;
use super::mode::TraceMode;
use super::own_rays::{Answers, OwnRays};
use super::parallel::trace_in_parallel;
use super::trace_index::TraceIndex;
use crate::geometry::{Hit, Ray};
use crate::index::{AnyHit, BuildError, Closest, Counters, Index, IndexInfo, NoStats};
use crate::scene::{FromScene, Geometry, SceneGeometry};
use std::time::Instant;

/// Builds index `I` over a concrete geometry (for tests and benches that want static types),
/// after checking its estimate against the memory budget ([`crate::index::build_budget`]).
pub fn build_index_on<I: Index, G: Geometry>(
    name: &str,
    geom: G,
    params: I::Params,
) -> Result<BoundIndex<I, G>, BuildError> {
    if geom.is_empty() {
        return Err(BuildError::EmptyScene);
    }
    if let Some(need) = I::estimated_build_bytes(geom.len(), &params) {
        crate::index::build_budget::ensure_fits(name, geom.len(), need)?;
    }
    let ((index, build_time), peak) = crate::heap_meter::peak_during(|| {
        let start = Instant::now();
        let index = I::build(&geom, &params);
        (index, start.elapsed())
    });
    let index = index?;
    let mut info = index.info();
    info.build_time = build_time;
    if !I::FOREIGN_HEAP {
        info.peak_build_bytes = Some(peak);
    }
    Ok(BoundIndex {
        reframe: None,
        params: toml::to_string(&params)
            .unwrap_or_default()
            .trim()
            .replace('\n', ","),
        name: name.to_owned(),
        index,
        geom,
        info,
    })
}

/// A built index with the geometry it was built on.
pub struct BoundIndex<I: Index, G: Geometry> {
    pub index: I,
    pub geom: G,
    name: String,
    params: String,
    info: IndexInfo,
    /// How to make `G` over another frame of the scene, for [`TraceIndex::refit`]; `None`
    /// for geometries not made from a scene ([`BoundIndex::movable`] sets it).
    reframe: Option<fn(&SceneGeometry) -> G>,
}

impl<I: Index, G: FromScene> BoundIndex<I, G> {
    /// The index able to follow its scene's frames ([`TraceIndex::refit`]).
    pub fn movable(self) -> Self {
        BoundIndex {
            reframe: Some(G::from_scene),
            ..self
        }
    }
}

impl<I: BatchIndex, G: Geometry> TraceIndex for BoundIndex<I, G> {
    fn name(&self) -> &str {
        &self.name
    }
    fn params(&self) -> &str {
        &self.params
    }
    fn info(&self) -> &IndexInfo {
        &self.info
    }
    fn has_stream(&self) -> bool {
        I::STREAM
    }
    fn has_single(&self) -> bool {
        I::SINGLE
    }
    fn has_beams(&self) -> bool {
        I::BEAMS
    }
    fn refused(&self, rays: &[Ray]) -> Option<(usize, &'static str)> {
        let mut why = None;
        let count = rays
            .iter()
            .filter_map(I::refuses)
            .inspect(|w| {
                why.get_or_insert(*w);
            })
            .count();
        why.map(|w| (count, w))
    }
    fn can_refit(&self) -> bool {
        I::REFIT && self.reframe.is_some()
    }
    fn refit(&mut self, frame: &SceneGeometry) -> Result<(), BuildError> {
        let reframe = self
            .reframe
            .filter(|_| I::REFIT)
            .ok_or_else(|| BuildError::Unsupported {
                index: self.name.clone(),
                reason: "it has no refit; rebuild it".into(),
            })?;
        let geom = reframe(frame);
        self.index.refit(&geom)?;
        self.geom = geom;
        self.info = IndexInfo {
            build_time: self.info.build_time,
            ..self.index.info()
        };
        Ok(())
    }
    fn own_rays(&self, mode: TraceMode, rays: &[Ray]) -> Option<OwnRays> {
        self.index.own_rays(mode, rays)
    }
    fn trace_own(&self, own: &OwnRays, out: Answers<'_>) {
        self.index.trace_own(own, out);
    }
    fn closest_hit(&self, ray: &Ray) -> Option<Hit> {
        self.index.closest_hit(&self.geom, ray, &mut NoStats)
    }
    fn closest_hit_counted(&self, ray: &Ray, counters: &mut Counters) -> Option<Hit> {
        self.index.closest_hit(&self.geom, ray, counters)
    }
    fn any_hit(&self, ray: &Ray) -> bool {
        self.index.any_hit(&self.geom, ray, &mut NoStats)
    }
    fn any_hit_counted(&self, ray: &Ray, counters: &mut Counters) -> bool {
        self.index.any_hit(&self.geom, ray, counters)
    }
    fn closest_hits_in(
        &self,
        mode: TraceMode,
        rays: &[Ray],
        out: &mut [Option<Hit>],
        counters: Option<&mut [Counters]>,
    ) {
        trace_in_parallel::<Closest, _, _>(
            &self.index,
            &self.geom,
            mode,
            rays,
            None,
            out,
            counters,
        );
    }
    fn closest_hits_image(
        &self,
        mode: TraceMode,
        rays: &[Ray],
        width: usize,
        out: &mut [Option<Hit>],
        counters: Option<&mut [Counters]>,
    ) {
        let (index, geom) = (&self.index, &self.geom);
        trace_in_parallel::<Closest, _, _>(index, geom, mode, rays, Some(width), out, counters);
    }
    fn any_hits_in(
        &self,
        mode: TraceMode,
        rays: &[Ray],
        out: &mut [bool],
        counters: Option<&mut [Counters]>,
    ) {
        trace_in_parallel::<AnyHit, _, _>(&self.index, &self.geom, mode, rays, None, out, counters);
    }
    fn any_hits_image(
        &self,
        mode: TraceMode,
        rays: &[Ray],
        width: usize,
        out: &mut [bool],
        counters: Option<&mut [Counters]>,
    ) {
        let (index, geom) = (&self.index, &self.geom);
        trace_in_parallel::<AnyHit, _, _>(index, geom, mode, rays, Some(width), out, counters);
    }
}
