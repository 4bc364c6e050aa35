//! Brute force: test every primitive. The reference every other index must match.

use crate::geometry::{ClosestHit, Hit, Ray};
use crate::index::build_budget::per_primitive;
use crate::index::kit::{prim_test, ray_queries};
use crate::index::{BatchIndex, BuildError, Index, IndexInfo, Stats};
use crate::scene::Geometry;
use serde::{Deserialize, Serialize};

/// Brute force has no structure, only the primitive count.
#[derive(Debug, Clone)]
pub struct BruteForce {
    len: u32,
}

/// Brute force takes no parameters.
#[derive(Debug, Clone, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BruteParams {}

/// Every primitive tested, in id order.
#[inline]
fn closest<G: Geometry, S: Stats>(b: &BruteForce, g: &G, r: &Ray, s: &mut S) -> Option<Hit> {
    let mut best = ClosestHit::new(r.t_max);
    for prim in 0..b.len {
        prim_test::closest(&mut best, g, prim, r, s);
    }
    best.get()
}

/// Whether any primitive is hit, stopping at the first.
#[inline]
fn any<G: Geometry, S: Stats>(b: &BruteForce, geom: &G, ray: &Ray, stats: &mut S) -> bool {
    (0..b.len).any(|prim| prim_test::any(geom, prim, ray, stats))
}

impl Index for BruteForce {
    type Params = BruteParams;

    fn build<G: Geometry>(geom: &G, _params: &BruteParams) -> Result<Self, BuildError> {
        if geom.is_empty() {
            return Err(BuildError::EmptyScene);
        }
        Ok(BruteForce {
            len: geom.len() as u32,
        })
    }

    ray_queries!(closest, any, |index| index);

    /// Nothing per primitive: brute force stores only the count.
    fn estimated_build_bytes(prims: usize, _: &BruteParams) -> Option<usize> {
        per_primitive(prims, 0)
    }

    fn info(&self) -> IndexInfo {
        IndexInfo {
            nodes: 1,
            leaves: 1,
            depth: 1,
            memory_bytes: 0,
            prim_refs: self.len as usize,
            ..IndexInfo::default()
        }
    }
}

impl BatchIndex for BruteForce {}
