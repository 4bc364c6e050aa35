//! Brute force: test every primitive. The reference every other index must match.

use super::{BuildError, Index, IndexInfo, Stats};
use crate::geometry::{ClosestHit, Hit, Ray};
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

    #[inline]
    fn closest_hit<G: Geometry, S: Stats>(
        &self,
        geom: &G,
        ray: &Ray,
        stats: &mut S,
    ) -> Option<Hit> {
        let mut best = ClosestHit::new(ray.t_max);
        for prim in 0..self.len {
            stats.prim_test();
            if let Some(t) = geom.intersect(prim, ray, best.t()) {
                best.offer(t, prim);
            }
        }
        best.get()
    }

    #[inline]
    fn any_hit<G: Geometry, S: Stats>(&self, geom: &G, ray: &Ray, stats: &mut S) -> bool {
        (0..self.len).any(|prim| {
            stats.prim_test();
            geom.intersect(prim, ray, ray.t_max).is_some()
        })
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
