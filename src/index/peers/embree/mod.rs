//! Intel Embree 3 (the system library, through the `embree3` crate; feature `embree`) as a peer
//! behind our [`Index`] trait: `embree` (build quality medium, `RTC_SCENE_FLAG_ROBUST`, i.e.
//! watertight traversal, the fair match for our default exact kernel) and `embree-fast` (the
//! same without the robust flag: Embree's default). One `rtcIntersect1` per closest-hit query,
//! one `rtcOccluded1` per any-hit query, the ray written as Embree loads it ([`rtc_ray`]); in the
//! `stream` mode each chunk of the batch is one `rtcIntersect1M` / `rtcOccluded1M` ray stream
//! ([`stream`]).
//! `embree-p16` ([`packet16`]) traces the robust scene 16 consecutive rays at a time.
//!
//! Embree tests the triangles itself, so its hits are not bit for bit ours: the suite classifies
//! each disagreement with brute force as a tie or wrong (`harness::peer_check`). Embree counts
//! nothing, so the index is [`IndexInfo::uncounted`]. Triangle scenes only
//! ([`BuildError::Unsupported`] otherwise).

mod device;
mod packet16;
mod rtc_ray;
mod stream;

use super::triangle_peer::{library_query, peer_triangles};
use crate::geometry::{Hit, Ray};
use crate::index::build_budget::{per_primitive, stopped};
use crate::index::{BatchIndex, BuildError, HitQuery, Index, IndexInfo, Stats};
use crate::scene::Geometry;
use device::MonitoredDevice;
use embree3::{
    BufferUsage, BuildQuality, Format, GeometryKind, INVALID_ID, IntersectContext, RayHit, Scene,
    SceneFlags,
};
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
    /// Bytes Embree held after the commit (its memory-monitor callback: allocations minus
    /// frees, vertex and index buffers included).
    memory_bytes: usize,
    /// The most bytes Embree held at once during the build (the same monitor).
    peak_build_bytes: usize,
    triangles: usize,
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
            memory_bytes: device.held_bytes(),
            peak_build_bytes: device.peak_bytes(),
            scene,
            triangles: n,
            build_threads,
        })
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
        let mut slot = MaybeUninit::<RayHit>::uninit();
        let rh = rtc_ray::init_ray_hit(&mut slot, ray);
        self.scene
            .intersect(&mut IntersectContext::incoherent(), rh);
        (rh.hit.geomID != INVALID_ID).then_some(Hit {
            t: rh.ray.tfar,
            prim: rh.hit.primID,
        })
    }

    #[inline]
    fn any_hit<G: Geometry, S: Stats>(&self, _: &G, ray: &Ray, _: &mut S) -> bool {
        let mut slot = MaybeUninit::uninit();
        let r = rtc_ray::init_ray(&mut slot, ray);
        self.scene.occluded(&mut IntersectContext::incoherent(), r)
    }

    fn info(&self) -> IndexInfo {
        IndexInfo {
            memory_bytes: self.memory_bytes,
            peak_build_bytes: Some(self.peak_build_bytes),
            prim_refs: self.triangles,
            uncounted: true,
            extra: vec![("build_threads".into(), self.build_threads as f64)],
            ..IndexInfo::default()
        }
    }
}

impl<const ROBUST: bool> BatchIndex for EmbreePeer<ROBUST> {
    const STREAM: bool = true;

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
