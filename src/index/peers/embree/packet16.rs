//! `embree-p16`: the robust Embree scene of `embree` traced 16 consecutive rays at a time with
//! `rtcIntersect16` / `rtcOccluded16` ([`super::rtc_packet`]), the form Embree's packets had in
//! the suite before the packet modes took screen tiles (a row segment of the image instead of a
//! 4 x 4 tile): `embree+packets16` makes the same calls on the harness's packets.
//!
//! Its rows are stream rows only (`embree-p16+stream`, [`BatchIndex::SINGLE`] is false: its single
//! rays would be `embree`'s). The harness hands every worker chunks of consecutive rays
//! ([`BatchIndex::closest_hits_stream`]); a
//! chunk is cut into packets of 16 (the last one of a batch shorter, its missing lanes switched
//! off in the valid mask). Primary rays are row-major, and chunks (64 rays) and rows (a multiple
//! of 16 pixels at the protocol's sizes) start on a multiple of 16, so a packet is a segment of
//! one image row. Single rays (`--modes single,last-hit,packets8`, renders) go through
//! `rtcIntersect1` as in `embree`.

use super::rtc_packet::{any_hits, closest_hits};
use super::rtc_ray::refusal;
use super::{Embree, EmbreeParams};
use crate::geometry::{Hit, Ray};
use crate::index::{BatchIndex, BuildError, HitQuery, Index, IndexInfo, Stats};
use crate::scene::Geometry;

/// `embree-p16`.
pub struct EmbreeP16(Embree);

impl Index for EmbreeP16 {
    type Params = EmbreeParams;
    const FOREIGN_HEAP: bool = true;

    fn build<G: Geometry>(geom: &G, params: &EmbreeParams) -> Result<Self, BuildError> {
        Embree::build_named(geom, params, "embree-p16").map(EmbreeP16)
    }

    fn estimated_build_bytes(prims: usize, params: &EmbreeParams) -> Option<usize> {
        Embree::estimated_build_bytes(prims, params)
    }

    fn refuses(ray: &Ray) -> Option<&'static str> {
        refusal(ray)
    }

    // Single rays (the last-hit cache) go to the robust scene's `rtcIntersect1`/`rtcOccluded1`.
    #[inline]
    fn query<Q: HitQuery, G: Geometry, S: Stats>(&self, g: &G, r: &Ray, s: &mut S) -> Q::Answer {
        self.0.query::<Q, G, S>(g, r, s)
    }

    fn info(&self) -> IndexInfo {
        self.0.info()
    }
}

impl BatchIndex for EmbreeP16 {
    const STREAM: bool = true;
    const SINGLE: bool = false;

    fn closest_hits_stream<G: Geometry, S: Stats>(
        &self,
        _: &G,
        rays: &[Ray],
        out: &mut [Option<Hit>],
        _: &mut [S],
    ) {
        closest_hits(&self.0.scene, rays, out);
    }

    fn any_hits_stream<G: Geometry, S: Stats>(
        &self,
        _: &G,
        rays: &[Ray],
        out: &mut [bool],
        _: &mut [S],
    ) {
        any_hits(&self.0.scene, rays, out);
    }
}
