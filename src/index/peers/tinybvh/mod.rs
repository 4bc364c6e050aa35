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
//! - no counters: the index is [`IndexInfo::uncounted`].

use super::triangle_peer::peer_triangles;
use crate::geometry::{Hit, Ray};
use crate::index::{BatchIndex, BuildError, Index, IndexInfo, Stats};
use crate::scene::Geometry;
use serde::{Deserialize, Serialize};

/// `tinybvh-bvh8` has no parameters.
#[derive(Debug, Clone, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TinyBvhParams {}

/// tinybvh's `BVH8_CPU`, opaque (owned by the C++ side).
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
    );
    fn accelbench_tinybvh_intersect(
        h: *const Bvh8Cpu,
        origin: *const f32,
        dir: *const f32,
        t_max: f32,
        t: *mut f32,
        prim: *mut u32,
    ) -> i32;
    fn accelbench_tinybvh_occluded(
        h: *const Bvh8Cpu,
        origin: *const f32,
        dir: *const f32,
        t_max: f32,
    ) -> i32;
    fn accelbench_tinybvh_free(h: *mut Bvh8Cpu);
}

/// `tinybvh-bvh8`. The `BVH8_CPU` holds its own copy of every node and triangle (interleaved
/// 256-byte nodes and 192-byte four-triangle leaves), so it outlives the vertex array it was
/// built from.
pub struct TinyBvh8 {
    bvh: *mut Bvh8Cpu,
    triangles: usize,
    /// Inner and leaf nodes of the 8-wide tree.
    nodes: usize,
    leaves: usize,
    /// Bytes of the `BVH8_CPU` block array, as tinybvh allocates it.
    memory_bytes: usize,
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
    /// tinybvh allocates with C++ `new`, unseen by the heap meter: its peak is not measured.
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
        let (mut nodes, mut leaves, mut bytes) = (0u32, 0u32, 0u64);
        // SAFETY: `bvh` is a live build; the outputs are valid for writes.
        unsafe { accelbench_tinybvh_info(bvh, &mut nodes, &mut leaves, &mut bytes) };
        Ok(TinyBvh8 {
            bvh,
            triangles: tris.len(),
            nodes: nodes as usize,
            leaves: leaves as usize,
            memory_bytes: bytes as usize,
        })
    }

    #[inline]
    fn closest_hit<G: Geometry, S: Stats>(&self, _: &G, ray: &Ray, _: &mut S) -> Option<Hit> {
        let (o, d) = (ray.origin.to_array(), ray.dir.to_array());
        let (mut t, mut prim) = (0.0, 0);
        // SAFETY: a live build; `o` and `d` hold 3 floats; the outputs are valid for writes.
        let hit = unsafe {
            accelbench_tinybvh_intersect(
                self.bvh,
                o.as_ptr(),
                d.as_ptr(),
                ray.t_max,
                &mut t,
                &mut prim,
            )
        };
        (hit != 0).then_some(Hit { t, prim })
    }

    #[inline]
    fn any_hit<G: Geometry, S: Stats>(&self, _: &G, ray: &Ray, _: &mut S) -> bool {
        let (o, d) = (ray.origin.to_array(), ray.dir.to_array());
        // SAFETY: a live build; `o` and `d` hold 3 floats.
        unsafe { accelbench_tinybvh_occluded(self.bvh, o.as_ptr(), d.as_ptr(), ray.t_max) != 0 }
    }

    fn info(&self) -> IndexInfo {
        IndexInfo {
            nodes: self.nodes,
            leaves: self.leaves,
            memory_bytes: self.memory_bytes,
            prim_refs: self.triangles,
            uncounted: true,
            ..IndexInfo::default()
        }
    }
}

impl BatchIndex for TinyBvh8 {}
