//! Intel Embree 3 (the system library, through the `embree3` crate; feature `embree`) as a peer
//! behind our [`Index`] trait: `embree` (build quality medium, `RTC_SCENE_FLAG_ROBUST`, i.e.
//! watertight traversal, the fair match for our default exact kernel) and `embree-fast` (the
//! same without the robust flag: Embree's default). One `rtcIntersect1` per closest-hit query,
//! one `rtcOccluded1` per any-hit query, the ray written as Embree loads it ([`rtc_ray`]); the
//! timed passes of the `single` mode take the batch in Embree's ray layout, made before the
//! clock starts ([`BatchIndex::own_rays`]). In the `stream` mode each chunk of the batch is one
//! `rtcIntersect1M` / `rtcOccluded1M` ray stream ([`stream`]); in the packet modes
//! (`embree+packets16`) each packet of the harness is one `rtcIntersect16` / `rtcOccluded16`
//! ([`rtc_packet`]). `embree-p16` ([`packet16`]) traces the robust scene 16 consecutive rays
//! at a time.
//!
//! Embree tests the triangles itself, so its hits are not bit for bit ours: the suite classifies
//! each disagreement with brute force as a tie or wrong (`harness::peer_check`). Embree counts
//! nothing, so the index is [`IndexInfo::uncounted`]. Triangle scenes only
//! ([`BuildError::Unsupported`] otherwise).

mod device;
mod packet16;
mod rtc_packet;
mod rtc_ray;
mod stream;

use super::triangle_peer::{LibraryFigures, library_query, peer_triangles};
use crate::geometry::{Hit, Ray};
use crate::index::build_budget::{per_primitive, stopped};
use crate::index::trace::parallel::each_chunk;
use crate::index::{
    Answers, BatchIndex, BuildError, HitQuery, Index, IndexInfo, OwnRays, Stats, TraceMode,
};
use crate::scene::Geometry;
use device::MonitoredDevice;
use embree3::{
    BufferUsage, BuildQuality, Format, GeometryKind, INVALID_ID, IntersectContext, RayHit, Scene,
    SceneFlags,
};
use rtc_ray::{RayLanes, RayRecord};
use serde::{Deserialize, Serialize};
use std::mem::MaybeUninit;

/// Embree's peak build heap per primitive for the estimate, in bytes: its memory monitor
/// reported 147 to 175 B per primitive (soup, icosphere, bunny, slivers; every quality).
pub(super) const EMBREE_BUILD_BYTES_PER_PRIM: usize = 200;

pub use packet16::EmbreeP16;

/// Embree's BVH build quality (`RTC_BUILD_QUALITY_*`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum EmbreeQuality {
    Low,
    #[default]
    Medium,
    High,
}

impl EmbreeQuality {
    fn rtc(self) -> BuildQuality {
        match self {
            EmbreeQuality::Low => BuildQuality::LOW,
            EmbreeQuality::Medium => BuildQuality::MEDIUM,
            EmbreeQuality::High => BuildQuality::HIGH,
        }
    }
}

/// Parameters of `embree` and `embree-fast`.
#[derive(Debug, Clone, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct EmbreeParams {
    /// Build quality (default `medium`).
    pub quality: EmbreeQuality,
}

/// An Embree scene of one triangle mesh whose primitive ids are our scene ids. `ROBUST` sets
/// `RTC_SCENE_FLAG_ROBUST`.
pub struct EmbreePeer<const ROBUST: bool> {
    scene: Scene<'static>,
    /// Its `memory_bytes` are what Embree held after the commit (its memory-monitor callback:
    /// allocations minus frees, vertex and index buffers included), its peak the most Embree
    /// held at once during the build (the same monitor).
    figures: LibraryFigures,
    /// Embree's build threads (`threads=N` of the device: the calling rayon pool's size).
    build_threads: usize,
}

/// `embree`: robust (watertight) traversal.
pub type Embree = EmbreePeer<true>;
/// `embree-fast`: Embree's default (non-robust) traversal.
pub type EmbreeFast = EmbreePeer<false>;

impl<const ROBUST: bool> EmbreePeer<ROBUST> {
    const NAME: &'static str = if ROBUST { "embree" } else { "embree-fast" };

    /// The scene of `geom`'s triangles, errors naming the index `name`.
    fn build_named<G: Geometry>(
        geom: &G,
        params: &EmbreeParams,
        name: &str,
    ) -> Result<Self, BuildError> {
        let tris = peer_triangles(geom, name)?;
        let failed = |what: &str, e: embree3::Error| BuildError::Failed {
            index: name.to_owned(),
            message: format!("Embree {what} failed ({e:?})"),
        };
        let build_threads = rayon::current_num_threads();
        let device = MonitoredDevice::new(build_threads).map_err(|e| failed("device", e))?;
        let mut mesh = device
            .device
            .create_geometry(GeometryKind::TRIANGLE)
            .map_err(|e| failed("triangle geometry", e))?;
        let n = tris.len();
        mesh.set_new_buffer::<[f32; 3]>(BufferUsage::VERTEX, 0, Format::FLOAT3, 12, 3 * n)
            .map_err(|e| failed("vertex buffer", e))?
            .iter_mut()
            .zip(tris.iter().flat_map(|t| t.v))
            .for_each(|(dst, v)| *dst = v.to_array());
        mesh.set_new_buffer::<[u32; 3]>(BufferUsage::INDEX, 0, Format::UINT3, 12, n)
            .map_err(|e| failed("index buffer", e))?
            .iter_mut()
            .enumerate()
            // `peer_triangles` guarantees 3 * n < u32::MAX.
            .for_each(|(i, dst)| *dst = [0, 1, 2].map(|k| (3 * i + k) as u32));
        mesh.set_build_quality(params.quality.rtc());
        let mesh = mesh.commit();
        let flags = if ROBUST {
            SceneFlags::ROBUST
        } else {
            SceneFlags::NONE
        };
        let mut scene = device
            .device
            .create_scene()
            .map_err(|e| failed("scene", e))?;
        scene.set_flags(flags);
        scene.set_build_quality(params.quality.rtc());
        scene.attach_geometry(&mesh);
        drop(mesh);
        scene.commit();
        let error = device.device.get_error();
        if let Some(bytes) = device.refused_at() {
            let reached = bytes.saturating_add(crate::heap_meter::held_bytes());
            return Err(stopped(name, reached, "try quality=low"));
        }
        if error != embree3::Error::NONE {
            return Err(failed("scene commit", error));
        }
        Ok(EmbreePeer {
            figures: LibraryFigures {
                triangles: n,
                memory_bytes: device.held_bytes(),
                peak_build_bytes: device.peak_bytes(),
            },
            scene,
            build_threads,
        })
    }
}

impl<const ROBUST: bool> EmbreePeer<ROBUST> {
    /// Embree's closest hit of a ray given as its `RTCRay` lanes: one `rtcIntersect1`.
    #[inline(always)]
    fn intersect(&self, ctx: &mut IntersectContext, lanes: &RayLanes) -> Option<Hit> {
        let mut slot = MaybeUninit::<RayHit>::uninit();
        let rh = rtc_ray::init_ray_hit(&mut slot, lanes);
        self.scene.intersect(ctx, rh);
        (rh.hit.geomID != INVALID_ID).then_some(Hit {
            t: rh.ray.tfar,
            prim: rh.hit.primID,
        })
    }

    /// Whether Embree finds anything on a ray given as its `RTCRay` lanes: one
    /// `rtcOccluded1`.
    #[inline(always)]
    fn occluded(&self, ctx: &mut IntersectContext, lanes: &RayLanes) -> bool {
        let mut slot = MaybeUninit::uninit();
        self.scene
            .occluded(ctx, rtc_ray::init_ray(&mut slot, lanes))
    }
}

impl<const ROBUST: bool> Index for EmbreePeer<ROBUST> {
    type Params = EmbreeParams;
    const FOREIGN_HEAP: bool = true;

    fn build<G: Geometry>(geom: &G, params: &EmbreeParams) -> Result<Self, BuildError> {
        Self::build_named(geom, params, Self::NAME)
    }

    fn estimated_build_bytes(prims: usize, _: &EmbreeParams) -> Option<usize> {
        per_primitive(prims, EMBREE_BUILD_BYTES_PER_PRIM)
    }

    fn refuses(ray: &Ray) -> Option<&'static str> {
        rtc_ray::refusal(ray)
    }

    /// The library's two calls below ([`library_query`]).
    #[inline]
    fn query<Q: HitQuery, G: Geometry, S: Stats>(&self, g: &G, r: &Ray, _: &mut S) -> Q::Answer {
        library_query::<Q, _, _>(self, g, r)
    }

    #[inline]
    fn closest_hit<G: Geometry, S: Stats>(&self, _: &G, ray: &Ray, _: &mut S) -> Option<Hit> {
        let ctx = &mut IntersectContext::incoherent();
        self.intersect(ctx, &rtc_ray::ray_lanes(ray))
    }

    #[inline]
    fn any_hit<G: Geometry, S: Stats>(&self, _: &G, ray: &Ray, _: &mut S) -> bool {
        let ctx = &mut IntersectContext::incoherent();
        self.occluded(ctx, &rtc_ray::ray_lanes(ray))
    }

    fn info(&self) -> IndexInfo {
        IndexInfo {
            extra: vec![("build_threads".into(), self.build_threads as f64)],
            ..self.figures.info()
        }
    }
}

impl<const ROBUST: bool> BatchIndex for EmbreePeer<ROBUST> {
    const STREAM: bool = true;

    /// In `single` mode, the batch as 32-byte records of Embree's ray ([`rtc_ray::record`], the
    /// range check applied): a timed pass then writes each record's two lanes and a third of
    /// constants into the call's `RTCRayHit`, as `tools/embree_standalone.c` does with the
    /// protocol's records.
    fn own_rays(&self, mode: TraceMode, rays: &[Ray]) -> Option<OwnRays> {
        let records = || rays.iter().map(rtc_ray::record).collect::<Vec<RayRecord>>();
        (mode == TraceMode::Single).then(|| OwnRays::new(records()))
    }

    /// One `rtcIntersect1` / `rtcOccluded1` per record, one intersect context per chunk.
    fn trace_own(&self, own: &OwnRays, out: Answers<'_>) {
        let records = own.records::<RayRecord>();
        match out {
            Answers::Closest(out) => each_chunk(records, out, |records, out| {
                let ctx = &mut IntersectContext::incoherent();
                for (r, o) in records.iter().zip(out) {
                    *o = self.intersect(ctx, &rtc_ray::record_lanes(r));
                }
            }),
            Answers::Any(out) => each_chunk(records, out, |records, out| {
                let ctx = &mut IntersectContext::incoherent();
                for (r, o) in records.iter().zip(out) {
                    *o = self.occluded(ctx, &rtc_ray::record_lanes(r));
                }
            }),
        }
    }

    /// A packet of the harness (at most 16 neighbouring rays: a screen tile of a camera set) as
    /// one `rtcIntersect16` ([`rtc_packet`]).
    fn closest_hits_packet<G: Geometry, S: Stats>(
        &self,
        _: &G,
        rays: &[Ray],
        out: &mut [Option<Hit>],
        _: &mut [S],
    ) {
        rtc_packet::closest_hits(&self.scene, rays, out);
    }

    fn any_hits_packet<G: Geometry, S: Stats>(
        &self,
        _: &G,
        rays: &[Ray],
        out: &mut [bool],
        _: &mut [S],
    ) {
        rtc_packet::any_hits(&self.scene, rays, out);
    }

    /// The chunk as one Embree ray stream ([`stream`]).
    fn closest_hits_stream<G: Geometry, S: Stats>(
        &self,
        _: &G,
        rays: &[Ray],
        out: &mut [Option<Hit>],
        _: &mut [S],
    ) {
        stream::closest_hits(&self.scene, rays, out);
    }

    fn any_hits_stream<G: Geometry, S: Stats>(
        &self,
        _: &G,
        rays: &[Ray],
        out: &mut [bool],
        _: &mut [S],
    ) {
        stream::any_hits(&self.scene, rays, out);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::TriangleKernelKind;
    use crate::index::{IndexSpec, build_index};
    use glam::Vec3;

    /// The timed passes' own rays answer as the counting pass's `Ray`s do, ray for ray, for
    /// closest and any hits, a ray out of Embree's range included; other modes make none.
    #[test]
    fn own_rays_answer_as_rays_do() {
        let scene = crate::scene::generators::generate("icosphere", 500, 1).unwrap();
        let spec = IndexSpec::named("embree");
        let index = build_index(&spec, &scene.geometry(), TriangleKernelKind::Exact).unwrap();
        let mut rays: Vec<Ray> = (0..300)
            .map(|i| {
                let a = i as f32 * 0.37;
                let origin = Vec3::new(3.0 * a.cos(), 3.0 * a.sin(), (i % 7) as f32 - 3.0);
                let target = Vec3::new((a * 3.1).sin(), (a * 1.7).cos(), (a * 0.9).sin()) * 0.8;
                Ray::new(origin, target - origin, 0.0, f32::INFINITY).unwrap()
            })
            .collect();
        rays.push(Ray::new(Vec3::splat(2e18), -Vec3::ONE, 0.0, f32::INFINITY).unwrap());
        assert!(index.own_rays(TraceMode::Stream, &rays).is_none());
        let own = index.own_rays(TraceMode::Single, &rays).unwrap();
        let mut closest = vec![None; rays.len()];
        index.trace_own(&own, Answers::Closest(&mut closest));
        let expected: Vec<_> = rays.iter().map(|r| index.closest_hit(r)).collect();
        assert_eq!(closest, expected);
        assert!(closest.iter().flatten().count() > 100);
        assert_eq!(closest.last(), Some(&None));
        let mut any = vec![true; rays.len()];
        index.trace_own(&own, Answers::Any(&mut any));
        let expected: Vec<_> = rays.iter().map(|r| index.any_hit(r)).collect();
        assert_eq!(any, expected);
    }
}
