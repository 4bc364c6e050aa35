//! tinybvh (Jacco Bikker's single-header C++ library, through the `tinybvh-rs` crate; feature
//! `tinybvh`) as a peer behind our [`Index`] trait: `tinybvh-bvh8`, its `BVH8_CPU` layout
//! (8-wide nodes traversed with AVX2, leaves of up to 4 triangles tested four at a time),
//! converted from its binned SAH build with leaves split to at most 4 triangles
//! (`split_leaves(4)`, which the conversion requires).
//!
//! tinybvh tests the triangles itself, so its hits are not bit for bit ours (the suite classifies
//! disagreements, `harness::peer_check`). Limits, from the binding's source (tinybvh-rs
//! 0.1.0-beta.3, `src/cxx_ffi.rs`, over tinybvh 1.6.8):
//! - no `t_min`: tinybvh's `Ray` has no near distance and accepts hits at `t > 0`, so a ray
//!   with `t_min > 0` can get a hit before `t_min` (the protocol's sets start at 0);
//! - no any-hit entry point: tinybvh has `BVH8_CPU::IsOccluded`, but the binding binds only
//!   `Intersect`, so any-hit queries run the closest-hit traversal and test whether it found
//!   something (tinybvh's own occlusion query could stop at the first hit found);
//! - no build thread control: tinybvh's `BVH::threadedBuild` is not bound, so the binned build
//!   runs on all cores above 50,000 triangles (`MT_BUILD_THRESHOLD`) and on one below, whatever
//!   pool calls it: its build time on one thread is not measured;
//! - no counters: the index is [`IndexInfo::uncounted`].
//!
//! The binding's build script compiles only its own C++ file, so reaching these through a shim
//! of ours would mean a second compilation of tinybvh (a build script and C++ toolchain step of
//! our own) and reading the binding's private pointer: not done.
//!
//! Rays are built here, not by tinybvh's `Ray` constructor, because that one normalizes the
//! direction (its `t` would then be in other units than ours).

use super::triangle_peer::peer_triangles;
use crate::geometry::{Hit, Ray};
use crate::index::{BuildError, Index, IndexInfo, Stats};
use crate::scene::Geometry;
use serde::{Deserialize, Serialize};
use tinybvh_rs::{Intersector, bvh, bvh8_cpu, mbvh};

/// `tinybvh-bvh8` has no parameters.
#[derive(Debug, Clone, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TinyBvhParams {}

/// tinybvh's `BVH8_CPU`. After `ConvertFrom` it holds its own copy of every node and triangle
/// (interleaved 256-byte nodes and 192-byte four-triangle leaves), so it outlives the binary
/// BVH, the 8-wide intermediate and the vertex array it was made from.
struct Bvh8Cpu(bvh8_cpu::BVH);

// SAFETY: after the build the C++ object is only read: `Intersect` is a `const` method that
// reads the node and leaf blocks and writes only the ray passed in, so shared use from several
// threads is sound, and the object owns its memory (nothing ties it to the building thread).
unsafe impl Send for Bvh8Cpu {}
unsafe impl Sync for Bvh8Cpu {}

/// `tinybvh-bvh8`.
pub struct TinyBvh8 {
    bvh: Bvh8Cpu,
    triangles: usize,
    /// Inner and leaf nodes of the 8-wide tree.
    nodes: usize,
    leaves: usize,
    /// Bytes of the `BVH8_CPU` block array, sized as tinybvh allocates it (see [`block_bytes`]).
    memory_bytes: usize,
}

/// tinybvh's `RAY_MASK_INTERSECT_ALL` (the mask field sits in the origin's padding).
const MASK_ALL: u32 = 0xFFFF;

/// `1/x` as tinybvh computes a ray's reciprocal direction (`tinybvh_safercp`): `+-1e30` for
/// `|x| <= 1e-12`.
#[inline(always)]
fn safe_rcp(x: f32) -> f32 {
    if x.abs() > 1e-12 {
        1.0 / x
    } else if x >= 0.0 {
        tinybvh_rs::INFINITE
    } else {
        -tinybvh_rs::INFINITE
    }
}

/// Our ray as tinybvh's, direction not normalized (so `t` is in our units), the best distance
/// starting at `t_max` (tinybvh keeps hits with `t` below it).
#[inline(always)]
fn tiny_ray(ray: &Ray) -> tinybvh_rs::Ray {
    let hit = tinybvh_rs::Intersection {
        t: ray.t_max,
        u: 0.0,
        v: 0.0,
        prim: u32::MAX,
    };
    tinybvh_rs::Ray {
        origin: ray.origin.to_array(),
        padding_0: MASK_ALL,
        dir: ray.dir.to_array(),
        padding_1: 0,
        r_d: ray.dir.to_array().map(safe_rcp),
        padding_2: 0,
        hit,
    }
}

/// Bytes tinybvh allocates for a `BVH8_CPU` block array: a 256-byte block per node of the
/// 8-wide tree and a 192-byte block per leaf (`BVH8_CPU::ConvertFrom`).
fn block_bytes(nodes: usize, leaves: usize) -> usize {
    nodes * 256 + leaves * 192
}

impl Index for TinyBvh8 {
    type Params = TinyBvhParams;

    fn build<G: Geometry>(geom: &G, _: &TinyBvhParams) -> Result<Self, BuildError> {
        let name = "tinybvh-bvh8";
        let tris = peer_triangles(geom, name)?;
        let failed = |e: tinybvh_rs::Error| BuildError::Failed {
            index: name.to_owned(),
            message: format!("tinybvh: {e}"),
        };
        let verts: Vec<[f32; 4]> = tris
            .iter()
            .flat_map(|t| t.v.map(|v| [v.x, v.y, v.z, 0.0]))
            .collect();
        let mut binary = bvh::BVH::new(verts.as_slice().into()).map_err(failed)?;
        binary.split_leaves(4);
        let wide = mbvh::BVH::new(&binary);
        let nodes = wide.nodes().len();
        let leaves = wide.leaf_count(0) as usize;
        let bvh = bvh8_cpu::BVH::new(&wide).map_err(failed)?;
        Ok(TinyBvh8 {
            bvh: Bvh8Cpu(bvh),
            triangles: tris.len(),
            nodes,
            leaves,
            memory_bytes: block_bytes(nodes, leaves),
        })
    }

    #[inline]
    fn closest_hit<G: Geometry, S: Stats>(&self, _: &G, ray: &Ray, _: &mut S) -> Option<Hit> {
        let mut r = tiny_ray(ray);
        self.bvh.0.intersect(&mut r);
        (r.hit.t < ray.t_max).then_some(Hit {
            t: r.hit.t,
            prim: r.hit.prim,
        })
    }

    #[inline]
    fn any_hit<G: Geometry, S: Stats>(&self, geom: &G, ray: &Ray, stats: &mut S) -> bool {
        self.closest_hit(geom, ray, stats).is_some()
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reciprocal_matches_tinybvh() {
        assert_eq!(safe_rcp(2.0), 0.5);
        assert_eq!(safe_rcp(-4.0), -0.25);
        assert_eq!(safe_rcp(0.0), 1e30);
        assert_eq!(safe_rcp(-0.0), 1e30);
        assert_eq!(safe_rcp(-1e-13), -1e30);
    }
}
