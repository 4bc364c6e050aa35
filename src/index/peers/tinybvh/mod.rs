//! tinybvh (Jacco Bikker's single-header C++ library, version 1.6.8 in `third_party/tinybvh`,
//! compiled with our C shim `shim.cpp` by `build.rs`; feature `tinybvh`) as a peer behind our
//! [`Index`] trait: `tinybvh-bvh8`, its `BVH8_CPU` layout (8-wide nodes traversed with AVX2,
//! leaves of up to 4 triangles tested four at a time), built by tinybvh's reference binned SAH
//! builder and converted as `BVH8_CPU::Build` does.
//!
//! tinybvh tests the triangles itself, so its hits are not bit for bit ours (the suite classifies
//! disagreements, `harness::peer_check`). What it offers and what it lacks:
//! - closest hit through `BVH8_CPU::Intersect`, any hit through `BVH8_CPU::IsOccluded` (which
//!   stops at the first hit it finds);
//! - no `t_min`: tinybvh's `Ray` has no near distance and accepts hits at `t > 0`, so a ray
//!   with `t_min > 0` can get a hit before `t_min` (the protocol's sets start at 0);
//! - the build uses tinybvh's own job system when the calling rayon pool has more than one
//!   thread (and the scene at least 50,000 triangles, tinybvh's `MT_BUILD_THRESHOLD`), and one
//!   thread otherwise, so a one-thread pool measures a one-thread build;
//! - no counters: the index is [`IndexInfo::uncounted`];
//! - rays as the caller gives them (not normalized, `t` in the direction's units), where
//!   tinybvh's own assume `t <= 1e30` and unit directions: the shim (`shim.cpp`) keeps such rays
//!   out of the empty child slots of tinybvh's nodes (boxes at 1e30 that a ray with
//!   `t_max = inf` or a short direction can reach, and that crash the traversal) by lowering
//!   the ray's `t` below them, which loses no hit in front of them, and refuses the rays whose
//!   coordinates overflow tinybvh's ray check ([`Index::refuses`]);
//! - memory: the block array the traversal reads is the resident figure; the trees `BVH8_CPU`
//!   keeps beside it are `kept_bytes`, and the build's peak is counted through tinybvh's
//!   allocation hooks.

use super::triangle_peer::{LibraryFigures, library_query, peer_triangles};
use crate::geometry::{Hit, Ray};
use crate::index::build_budget::per_primitive;
use crate::index::{BatchIndex, BuildError, HitQuery, Index, IndexInfo, Stats};
use crate::scene::Geometry;
use glam::Vec3A;
use serde::{Deserialize, Serialize};

/// `tinybvh-bvh8` has no parameters.
#[derive(Debug, Clone, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TinyBvhParams {}

/// The shim's closest hit (`AccelbenchTinyHit`): `prim` is `u32::MAX` when there is none.
#[repr(C)]
struct ShimHit {
    t: f32,
    prim: u32,
}

/// The origin's and direction's lanes as the shim reads them: 16-byte aligned, four floats
/// each (the fourth ignored).
#[inline(always)]
fn lanes(ray: &Ray) -> (*const f32, *const f32) {
    let lane = |v: &Vec3A| (v as *const Vec3A).cast::<f32>();
    (lane(&ray.origin), lane(&ray.dir))
}

/// tinybvh's `BVH8_CPU` with the meter of its allocations, opaque (owned by the C++ side).
#[repr(C)]
struct Bvh8Cpu {
    _opaque: [u8; 0],
}

unsafe extern "C" {
    fn accelbench_tinybvh_build(verts: *const f32, tris: u32, threaded: i32) -> *mut Bvh8Cpu;
    fn accelbench_tinybvh_info(
        h: *const Bvh8Cpu,
        nodes: *mut u32,
        leaves: *mut u32,
        bytes: *mut u64,
        other_bytes: *mut u64,
        peak_bytes: *mut u64,
    );
    fn accelbench_tinybvh_intersect(
        h: *const Bvh8Cpu,
        origin: *const f32,
        dir: *const f32,
        t_max: f32,
    ) -> ShimHit;
    fn accelbench_tinybvh_occluded(
        h: *const Bvh8Cpu,
        origin: *const f32,
        dir: *const f32,
        t_max: f32,
    ) -> i32;
    fn accelbench_tinybvh_refuses(origin: *const f32, dir: *const f32, t_max: f32) -> i32;
    fn accelbench_tinybvh_free(h: *mut Bvh8Cpu);
}

/// Peak build bytes per triangle held to the memory budget (`Index::estimated_build_bytes`):
/// the 48-byte vertex copy handed to tinybvh plus what tinybvh's hooks counted. Measured with
/// `info --indices` (2026-12-03, one and two build threads alike): 435 on the bunny, 452 on the
/// icosphere (20,480 and 1,310,720), 461 to 463 on soup (20,000 and 100,000), 485 on slivers
/// (50,000); this is the largest with a margin of 15%.
pub const TINYBVH_BUILD_BYTES_PER_PRIM: usize = 560;

/// `tinybvh-bvh8`. The `BVH8_CPU` holds its own copy of every node and triangle (interleaved
/// 256-byte nodes and 192-byte four-triangle leaves), so it outlives the vertex array it was
/// built from.
pub struct TinyBvh8 {
    bvh: *mut Bvh8Cpu,
    /// Its `memory_bytes` are the `BVH8_CPU` block array's, as tinybvh allocates it; the peak
    /// is the vertex copy's plus tinybvh's allocations at their peak.
    figures: LibraryFigures,
    /// Inner and leaf nodes of the 8-wide tree.
    nodes: usize,
    leaves: usize,
    /// What tinybvh holds beside the block array: the binary and 8-wide trees it was converted
    /// from, which `BVH8_CPU` keeps.
    kept_bytes: usize,
}

// SAFETY: after the build the C++ object is only read: `Intersect` and `IsOccluded` are `const`
// methods that read the node and leaf blocks and write only the ray passed in, so shared use from
// several threads is sound, and the object owns its memory (nothing ties it to the building
// thread).
unsafe impl Send for TinyBvh8 {}
unsafe impl Sync for TinyBvh8 {}

impl Drop for TinyBvh8 {
    fn drop(&mut self) {
        // SAFETY: `bvh` came from `accelbench_tinybvh_build`, non-null, and is freed only here.
        unsafe { accelbench_tinybvh_free(self.bvh) }
    }
}

impl Index for TinyBvh8 {
    type Params = TinyBvhParams;
    /// tinybvh allocates outside our heap; the shim counts its allocations through tinybvh's
    /// hooks (`BVHContext`), and the peak in [`IndexInfo`] is theirs plus the vertex copy.
    const FOREIGN_HEAP: bool = true;

    fn build<G: Geometry>(geom: &G, _: &TinyBvhParams) -> Result<Self, BuildError> {
        let name = "tinybvh-bvh8";
        let tris = peer_triangles(geom, name)?;
        let verts: Vec<[f32; 4]> = tris
            .iter()
            .flat_map(|t| t.v.map(|v| [v.x, v.y, v.z, 0.0]))
            .collect();
        let count = u32::try_from(tris.len()).map_err(|_| BuildError::Failed {
            index: name.to_owned(),
            message: format!("{} triangles: tinybvh takes at most 2^32 - 1", tris.len()),
        })?;
        let threaded = i32::from(rayon::current_num_threads() > 1);
        // SAFETY: `verts` holds 3 vertices of 4 floats per triangle and outlives the call.
        let bvh = unsafe { accelbench_tinybvh_build(verts.as_ptr().cast(), count, threaded) };
        if bvh.is_null() {
            return Err(BuildError::Failed {
                index: name.to_owned(),
                message: "tinybvh's build failed (out of memory?)".into(),
            });
        }
        let (mut nodes, mut leaves) = (0u32, 0u32);
        let (mut bytes, mut kept, mut peak) = (0u64, 0u64, 0u64);
        // SAFETY: `bvh` is a live build; the outputs are valid for writes.
        unsafe {
            accelbench_tinybvh_info(
                bvh,
                &mut nodes,
                &mut leaves,
                &mut bytes,
                &mut kept,
                &mut peak,
            )
        };
        Ok(TinyBvh8 {
            bvh,
            figures: LibraryFigures {
                triangles: tris.len(),
                memory_bytes: bytes as usize,
                peak_build_bytes: std::mem::size_of_val(verts.as_slice()) + peak as usize,
            },
            nodes: nodes as usize,
            leaves: leaves as usize,
            kept_bytes: kept as usize,
        })
    }

    fn estimated_build_bytes(prims: usize, _: &TinyBvhParams) -> Option<usize> {
        per_primitive(prims, TINYBVH_BUILD_BYTES_PER_PRIM)
    }

    /// Rays whose coordinates overflow tinybvh's ray check (a sum of the origin, direction and
    /// `t`, NaN when components near 3.4e38 of both signs meet), on which it exits the process.
    fn refuses(ray: &Ray) -> Option<&'static str> {
        let (o, d) = lanes(ray);
        // SAFETY: `o` and `d` point at 16-byte aligned lanes of four floats.
        let refused = unsafe { accelbench_tinybvh_refuses(o, d, ray.t_max) };
        (refused != 0).then_some(
            "its coordinates overflow tinybvh's ray check (the sum of origin, direction and t is \
             NaN), on which tinybvh exits the process",
        )
    }

    /// The library's two calls below ([`library_query`]).
    #[inline]
    fn query<Q: HitQuery, G: Geometry, S: Stats>(&self, g: &G, r: &Ray, _: &mut S) -> Q::Answer {
        library_query::<Q, _, _>(self, g, r)
    }

    #[inline]
    fn closest_hit<G: Geometry, S: Stats>(&self, _: &G, ray: &Ray, _: &mut S) -> Option<Hit> {
        let (o, d) = lanes(ray);
        // SAFETY: a live build; `o` and `d` point at 16-byte aligned lanes of four floats.
        let hit = unsafe { accelbench_tinybvh_intersect(self.bvh, o, d, ray.t_max) };
        (hit.prim != u32::MAX).then_some(Hit {
            t: hit.t,
            prim: hit.prim,
        })
    }

    #[inline]
    fn any_hit<G: Geometry, S: Stats>(&self, _: &G, ray: &Ray, _: &mut S) -> bool {
        let (o, d) = lanes(ray);
        // SAFETY: a live build; `o` and `d` point at 16-byte aligned lanes of four floats.
        unsafe { accelbench_tinybvh_occluded(self.bvh, o, d, ray.t_max) != 0 }
    }

    fn info(&self) -> IndexInfo {
        IndexInfo {
            nodes: self.nodes,
            leaves: self.leaves,
            extra: vec![("kept_bytes".into(), self.kept_bytes as f64)],
            ..self.figures.info()
        }
    }
}

impl BatchIndex for TinyBvh8 {}
