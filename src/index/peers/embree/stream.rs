//! `embree+stream` and `embree-fast+stream`: a chunk of the batch handed to Embree as one ray
//! stream, `rtcIntersect1M` / `rtcOccluded1M` over an array of rays, so Embree may trace it as
//! it likes best (its stream code repacks coherent rays into packets). The context says
//! coherent when the chunk looks like camera rays (the test `bvh4`/`bvh8` use to pick their
//! lockstep walk, `walk::coherent`), incoherent otherwise.
//!
//! The rays are written as in single-ray calls ([`super::rtc_ray`]), in a stack array of at most
//! [`STREAM`] rays: no allocation per chunk.

use super::rtc_ray::{init_ray, init_ray_hit, ray_lanes};
use crate::geometry::{Hit, Ray};
use crate::index::kit::box_tree::stream::coherent;
use embree3::sys::{RTCRay, RTCRayHit, rtcIntersect1M, rtcOccluded1M};
use embree3::{AsIntersectContext, INVALID_ID, IntersectContext, RayHit, Scene};
use std::mem::{MaybeUninit, size_of};

/// Rays per stream call (the harness's chunks are at most this long; longer ones are cut).
const STREAM: usize = 64;

fn context(rays: &[Ray]) -> IntersectContext {
    match coherent(rays) {
        true => IntersectContext::coherent(),
        false => IntersectContext::incoherent(),
    }
}

/// Closest hits of `rays` through `rtcIntersect1M`.
pub(super) fn closest_hits(scene: &Scene, rays: &[Ray], out: &mut [Option<Hit>]) {
    let mut slots = [const { MaybeUninit::<RayHit>::uninit() }; STREAM];
    for (rays, out) in rays.chunks(STREAM).zip(out.chunks_mut(STREAM)) {
        for (slot, ray) in slots.iter_mut().zip(rays) {
            init_ray_hit(slot, &ray_lanes(ray));
        }
        let mut ctx = context(rays);
        // SAFETY: the first `rays.len()` slots are initialized `RTCRayHit`s (16-byte aligned,
        // checked in `rtc_ray`), laid out `size_of::<RayHit>()` apart; the scene is committed.
        unsafe {
            rtcIntersect1M(
                scene.handle(),
                ctx.as_mut_context_ptr(),
                slots.as_mut_ptr().cast::<RTCRayHit>(),
                rays.len() as u32,
                size_of::<RayHit>(),
            );
        }
        for (o, slot) in out.iter_mut().zip(&slots) {
            // SAFETY: initialized above, written by Embree.
            let rh = unsafe { slot.assume_init_ref() };
            *o = (rh.hit.geomID != INVALID_ID).then_some(Hit {
                t: rh.ray.tfar,
                prim: rh.hit.primID,
            });
        }
    }
}

/// Any-hit results of `rays` through `rtcOccluded1M` (it sets `tfar` to -inf on occluded rays).
pub(super) fn any_hits(scene: &Scene, rays: &[Ray], out: &mut [bool]) {
    let mut slots = [const { MaybeUninit::<embree3::Ray>::uninit() }; STREAM];
    for (rays, out) in rays.chunks(STREAM).zip(out.chunks_mut(STREAM)) {
        for (slot, ray) in slots.iter_mut().zip(rays) {
            init_ray(slot, &ray_lanes(ray));
        }
        let mut ctx = context(rays);
        // SAFETY: as in `closest_hits`, with `RTCRay`s.
        unsafe {
            rtcOccluded1M(
                scene.handle(),
                ctx.as_mut_context_ptr(),
                slots.as_mut_ptr().cast::<RTCRay>(),
                rays.len() as u32,
                size_of::<embree3::Ray>(),
            );
        }
        for (o, slot) in out.iter_mut().zip(&slots) {
            // SAFETY: initialized above, written by Embree.
            *o = unsafe { slot.assume_init_ref() }.tfar == f32::NEG_INFINITY;
        }
    }
}
