//! Our rays written into Embree's `RTCRay` / `RTCRayHit` in whole 16-byte lanes.
//!
//! Embree's single-ray kernels load the origin with `tnear` and the direction with `time` as one
//! 16-byte vector each. A vector load that spans several narrower stores cannot be served by
//! store forwarding and waits for the stores to reach the cache; built field by field (an 8-byte
//! store of `dir_x, dir_y`, then `dir_z`, then `time`), that stall cost the suite's `embree` 20%
//! of its speed on primary rays against writing each lane with one store (bunny, 1024 x 1024, one
//! thread). So every lane here is written with one 16-byte store.
//!
//! Embree takes origin and direction coordinates up to ±[`FLT_LARGE`] (its `RayK::valid`,
//! which its checked builds assert, aborting the process: Debian's is one). A ray past that is
//! written as [`INACTIVE`], which Embree traces as an empty segment: no hit, not occluded.

use crate::geometry::Ray;
use embree3::{INVALID_ID, RayHit};
use glam::{Vec3A, Vec4};
use std::mem::{MaybeUninit, offset_of, size_of};

/// `RTCRay` (12 four-byte fields: origin, `tnear`, direction, `time`, `tfar`, `mask`, `id`,
/// `flags`) as three lanes.
pub(super) type RayLanes = [Vec4; 3];
/// A ray as the peer's own rays keep it for the timed passes ([`record`]): the lanes of
/// [`RayLanes`] that differ from ray to ray, origin with `tnear` and direction with `tfar` in
/// `time`'s place, 32 bytes (a `.rays` record's layout, as `tools/embree_standalone.c` reads
/// it).
pub(super) type RayRecord = [Vec4; 2];
/// `RTCRayHit`: the ray's three lanes, then `RTCHit` (`Ng`, `u`, `v`, `primID`, `geomID`,
/// `instID[1]`) as two.
type RayHitLanes = [Vec4; 5];

// The lanes below follow the field order of Embree 3's `RTCRay` and `RTCHit` (rtcore_ray.h),
// both 16-byte aligned.
const _: () = {
    use embree3::sys::{RTCHit, RTCRay};
    assert!(size_of::<RTCRay>() == size_of::<RayLanes>());
    assert!(size_of::<RayHit>() == size_of::<RayHitLanes>());
    assert!(align_of::<RTCRay>() >= align_of::<Vec4>());
    assert!(offset_of!(RTCRay, tnear) == 12 && offset_of!(RTCRay, dir_x) == 16);
    assert!(offset_of!(RTCRay, time) == 28 && offset_of!(RTCRay, tfar) == 32);
    assert!(offset_of!(RTCRay, mask) == 36 && offset_of!(RTCRay, flags) == 44);
    assert!(offset_of!(RayHit, hit) == 48);
    assert!(offset_of!(RTCHit, u) == 12 && offset_of!(RTCHit, v) == 16);
    assert!(offset_of!(RTCHit, primID) == 20 && offset_of!(RTCHit, geomID) == 24);
    assert!(offset_of!(RTCHit, instID) == 28);
};

/// A four-byte field holding the bits of a `u32`, as a lane element.
#[inline(always)]
fn bits(x: u32) -> f32 {
    f32::from_bits(x)
}

/// Our ray's three `RTCRay` lanes: `[t_min, t_max]` as `[tnear, tfar]`, time 0, every mask bit
/// set, id and flags 0; [`INACTIVE`] for a ray out of Embree's range.
#[inline(always)]
pub(super) fn ray_lanes(ray: &Ray) -> RayLanes {
    if !in_range(ray) {
        return INACTIVE;
    }
    [
        ray.origin.extend(ray.t_min),
        ray.dir.extend(0.0),
        Vec4::new(ray.t_max, bits(u32::MAX), 0.0, 0.0),
    ]
}

/// `ray` as a [`RayRecord`] (its range check applied, as in [`ray_lanes`]).
pub(super) fn record(ray: &Ray) -> RayRecord {
    let [o, d, t] = ray_lanes(ray);
    [o, d.with_w(t.x)]
}

/// The [`RayLanes`] of a [`RayRecord`]: `tfar` moved to its lane, time 0, every mask bit set,
/// id and flags 0.
#[inline(always)]
pub(super) fn record_lanes(r: &RayRecord) -> RayLanes {
    [
        r[0],
        r[1].with_w(0.0),
        Vec4::new(r[1].w, bits(u32::MAX), 0.0, 0.0),
    ]
}

/// Embree's `FLT_LARGE` (`common/math/constants.h`): the largest origin or direction
/// coordinate it takes.
pub(super) const FLT_LARGE: f32 = 1.844e18;

/// Whether Embree takes `ray` (every origin and direction coordinate within ±[`FLT_LARGE`]):
/// one compare of the lanes and a mask, no horizontal maximum (this runs once per ray).
#[inline(always)]
pub(super) fn in_range(ray: &Ray) -> bool {
    let largest = ray.origin.abs().max(ray.dir.abs());
    largest.cmple(Vec3A::splat(FLT_LARGE)).all()
}

/// Why Embree refuses `ray`, for `Index::refuses`.
pub(super) fn refusal(ray: &Ray) -> Option<&'static str> {
    (!in_range(ray)).then_some(
        "a coordinate of its origin or direction is beyond ±1.844e18, the largest Embree takes \
         (its checked builds abort on such rays)",
    )
}

/// A ray Embree takes and finds nothing on: `tfar < tnear` (a stream's inactive ray), so no
/// hit, and `tfar` stays -1 (not the -inf that marks an occluded ray).
const INACTIVE: RayLanes = [
    Vec4::ZERO,
    Vec4::new(1.0, 0.0, 0.0, 0.0),
    Vec4::new(-1.0, f32::from_bits(u32::MAX), 0.0, 0.0),
];

/// `slot` initialized as Embree's ray of `lanes` (see [`ray_lanes`]).
#[inline(always)]
pub(super) fn init_ray<'a>(
    slot: &'a mut MaybeUninit<embree3::Ray>,
    lanes: &RayLanes,
) -> &'a mut embree3::Ray {
    // SAFETY: `RTCRay` is `repr(C)`, 16-byte aligned and 48 bytes of `f32`/`u32` fields in the
    // lanes' order (checked above), so the write initializes every field, and every bit pattern
    // is a valid value of those fields.
    unsafe {
        slot.as_mut_ptr().cast::<RayLanes>().write(*lanes);
        slot.assume_init_mut()
    }
}

/// `slot` initialized as Embree's ray of `lanes` (see [`ray_lanes`]) with no hit yet (`geomID`
/// and `instID` invalid).
#[inline(always)]
pub(super) fn init_ray_hit<'a>(
    slot: &'a mut MaybeUninit<RayHit>,
    lanes: &RayLanes,
) -> &'a mut RayHit {
    let [o, d, t] = *lanes;
    let none = bits(INVALID_ID);
    let lanes: RayHitLanes = [o, d, t, Vec4::ZERO, Vec4::new(0.0, none, none, none)];
    // SAFETY: as in `init_ray`: `RTCRayHit` is `RTCRay` then `RTCHit`, 80 bytes of 16-byte
    // aligned `f32`/`u32` fields in the lanes' order (checked above).
    unsafe {
        slot.as_mut_ptr().cast::<RayHitLanes>().write(lanes);
        slot.assume_init_mut()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lanes_land_in_embree_fields() {
        let (origin, dir): ([f32; 3], [f32; 3]) = ([1.0, 2.0, 3.0], [-4.0, 5.0, -6.0]);
        let ray = Ray::new(origin.into(), dir.into(), 0.5, 7.0).unwrap();
        let mut slot = MaybeUninit::new(RayHit::from(embree3::Ray::new(
            [0.0; 3], [1.0; 3], 9.0, 9.0, 9.0, 0, 9,
        )));
        let rh = init_ray_hit(&mut slot, &ray_lanes(&ray));
        let r = rh.ray;
        assert_eq!([r.org_x, r.org_y, r.org_z, r.tnear], [1.0, 2.0, 3.0, 0.5]);
        assert_eq!(
            [r.dir_x, r.dir_y, r.dir_z, r.time, r.tfar],
            [-4.0, 5.0, -6.0, 0.0, 7.0]
        );
        assert_eq!([r.mask, r.id, r.flags], [u32::MAX, 0, 0]);
        let h = rh.hit;
        assert_eq!([h.geomID, h.instID[0]], [INVALID_ID, INVALID_ID]);
        let mut slot = MaybeUninit::new(embree3::Ray::new([0.0; 3], [1.0; 3], 9.0, 9.0, 9.0, 0, 9));
        let plain = init_ray(&mut slot, &ray_lanes(&ray));
        assert_eq!(plain.tfar.to_bits(), 7.0f32.to_bits());
        for ray in [
            ray,
            Ray::new([2e18; 3].into(), dir.into(), 0.5, 7.0).unwrap(),
        ] {
            let via_record = record_lanes(&record(&ray)).map(|l| l.to_array().map(f32::to_bits));
            let direct = ray_lanes(&ray).map(|l| l.to_array().map(f32::to_bits));
            assert_eq!(via_record, direct);
        }
        assert_eq!([plain.mask, plain.id, plain.flags], [u32::MAX, 0, 0]);
    }
}
