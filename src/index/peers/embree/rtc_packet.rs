//! Embree's 16-ray packet calls, `rtcIntersect16` / `rtcOccluded16` over at most 16 rays at a
//! time ([`closest_hits`], [`any_hits`]): the packet modes of `embree` and `embree-fast`
//! (`embree+packets16`, a packet of the harness each call) and `embree-p16`'s stream (runs of
//! 16 consecutive rays, [`super::packet16`]).
//!
//! Embree's packet kernels test the triangles with the same robust algorithm, lane by lane, but
//! are not bound by our hit contract: disagreements with brute force are classified like every
//! peer's (`harness::peer_check`).

use super::rtc_ray::in_range;
use crate::geometry::{Hit, Ray};
use embree3::{Hit16, INVALID_ID, IntersectContext, Ray16, RayHit16, Scene, ValidMask, ValidMaskN};

/// Rays per packet.
const LANES: usize = 16;

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

/// Closest hits of `rays` in packets of 16 consecutive rays (`rtcIntersect16`, the last packet's
/// missing lanes switched off), with a coherent context.
pub(super) fn closest_hits(scene: &Scene, rays: &[Ray], out: &mut [Option<Hit>]) {
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
        scene.intersect16(&mut context, &mut packet, &valid.0);
        for (i, o) in out.iter_mut().enumerate() {
            *o = (packet.hit.geomID[i] != INVALID_ID).then_some(Hit {
                t: packet.ray.tfar[i],
                prim: packet.hit.primID[i],
            });
        }
    }
}

/// Any-hit results of `rays` in packets of 16 (`rtcOccluded16`), as [`closest_hits`].
pub(super) fn any_hits(scene: &Scene, rays: &[Ray], out: &mut [bool]) {
    let mut packet = Ray16::empty();
    let mut context = IntersectContext::coherent();
    for (rays, out) in rays.chunks(LANES).zip(out.chunks_mut(LANES)) {
        set_rays(&mut packet, rays);
        let valid = Valid16::first(rays.len());
        scene.occluded16(&mut context, &mut packet, &valid.0);
        // `rtcOccluded16` sets `tfar` to -inf on the rays it finds blocked.
        for (o, &t) in out.iter_mut().zip(&packet.tfar) {
            *o = t == f32::NEG_INFINITY;
        }
    }
}
