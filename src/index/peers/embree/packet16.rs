//! `embree-p16`: the robust Embree scene of `embree` traced 16 consecutive rays at a time with
//! `rtcIntersect16` / `rtcOccluded16`, to show what Embree's packets give on coherent rays.
//!
//! Its rows are stream rows only (`embree-p16+stream`, [`BatchIndex::SINGLE`] is false: its single
//! rays would be `embree`'s). The harness hands every worker chunks of consecutive rays
//! ([`BatchIndex::closest_hits_stream`]); a
//! chunk is cut into packets of 16 (the last one of a batch shorter, its missing lanes switched
//! off in the valid mask). Primary rays are row-major, and chunks (64 rays) and rows (a multiple
//! of 16 pixels at the protocol's sizes) start on a multiple of 16, so a packet is a segment of
//! one image row. Single rays (`--modes single,last-hit,packets8`, renders) go through
//! `rtcIntersect1` as in `embree`.
//!
//! Embree's packet kernels test the triangles with the same robust algorithm, lane by lane, but
//! are not bound by our hit contract: disagreements with brute force are classified like every
//! peer's (`harness::peer_check`).

use super::rtc_ray::{in_range, refusal};
use super::{Embree, EmbreeParams};
use crate::geometry::{Hit, Ray};
use crate::index::{BatchIndex, BuildError, HitQuery, Index, IndexInfo, Stats};
use crate::scene::Geometry;
use embree3::{Hit16, INVALID_ID, IntersectContext, Ray16, RayHit16, ValidMask, ValidMaskN};

/// Rays per packet.
const LANES: usize = 16;

/// `embree-p16`.
pub struct EmbreeP16(Embree);

/// A valid mask as `rtcIntersect16` reads it: 64-byte aligned, lane `i` active for `i < n`.
#[repr(C, align(64))]
struct Valid16(ValidMaskN<LANES>);

impl Valid16 {
    fn first(n: usize) -> Valid16 {
        Valid16(ValidMaskN::new(std::array::from_fn(|i| {
            if i < n {
                ValidMask::Valid
            } else {
                ValidMask::Invalid
            }
        })))
    }
}

/// Writes `rays` (at most 16) into the first lanes of `packet` as Embree rays (`[t_min, t_max]`
/// as `[tnear, tfar]`, time 0, every mask bit set); lanes past them keep what they held. A ray
/// out of Embree's range becomes an empty segment at the origin (`tfar` -1 < `tnear` 0), which
/// Embree skips ([`super::rtc_ray`]).
#[inline(always)]
fn set_rays(packet: &mut Ray16, rays: &[Ray]) {
    for (i, r) in rays.iter().enumerate() {
        if !in_range(r) {
            packet.org_x[i] = 0.0;
            packet.org_y[i] = 0.0;
            packet.org_z[i] = 0.0;
            packet.tnear[i] = 0.0;
            packet.dir_x[i] = 1.0;
            packet.dir_y[i] = 0.0;
            packet.dir_z[i] = 0.0;
            packet.tfar[i] = -1.0;
            continue;
        }
        packet.org_x[i] = r.origin.x;
        packet.org_y[i] = r.origin.y;
        packet.org_z[i] = r.origin.z;
        packet.tnear[i] = r.t_min;
        packet.dir_x[i] = r.dir.x;
        packet.dir_y[i] = r.dir.y;
        packet.dir_z[i] = r.dir.z;
        packet.tfar[i] = r.t_max;
    }
}

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
        let mut packet = RayHit16 {
            ray: Ray16::empty(),
            hit: Hit16::new(),
        };
        let mut context = IntersectContext::coherent();
        for (rays, out) in rays.chunks(LANES).zip(out.chunks_mut(LANES)) {
            set_rays(&mut packet.ray, rays);
            packet.hit.geomID = [INVALID_ID; LANES];
            packet.hit.instID = [[INVALID_ID; LANES]];
            let valid = Valid16::first(rays.len());
            self.0
                .scene
                .intersect16(&mut context, &mut packet, &valid.0);
            for (i, o) in out.iter_mut().enumerate() {
                *o = (packet.hit.geomID[i] != INVALID_ID).then_some(Hit {
                    t: packet.ray.tfar[i],
                    prim: packet.hit.primID[i],
                });
            }
        }
    }

    fn any_hits_stream<G: Geometry, S: Stats>(
        &self,
        _: &G,
        rays: &[Ray],
        out: &mut [bool],
        _: &mut [S],
    ) {
        let mut packet = Ray16::empty();
        let mut context = IntersectContext::coherent();
        for (rays, out) in rays.chunks(LANES).zip(out.chunks_mut(LANES)) {
            set_rays(&mut packet, rays);
            let valid = Valid16::first(rays.len());
            self.0.scene.occluded16(&mut context, &mut packet, &valid.0);
            // `rtcOccluded16` sets `tfar` to -inf on the rays it finds blocked.
            for (o, &t) in out.iter_mut().zip(&packet.tfar) {
                *o = t == f32::NEG_INFINITY;
            }
        }
    }
}
