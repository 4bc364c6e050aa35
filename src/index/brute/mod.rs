//! Brute force: test every primitive. The reference every other index must match.

use crate::geometry::Ray;
use crate::index::build_budget::per_primitive;
use crate::index::kit::prim_test;
use crate::index::{BatchIndex, BuildError, HitQuery, Index, IndexInfo, Stats};
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

    /// Every primitive tested, in id order (an any-hit query stops at the first hit).
    #[inline]
    fn query<Q: HitQuery, G: Geometry, S: Stats>(&self, g: &G, r: &Ray, s: &mut S) -> Q::Answer {
        let mut found = Q::start(r);
        for prim in 0..self.len {
            if prim_test::test::<Q, G, S>(&mut found, g, prim, r, s) {
                break;
            }
        }
        Q::answer(found)
    }

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
