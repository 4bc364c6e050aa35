//! A faulty index for tests of the verification: brute force that never reports one primitive.

use accelbench::geometry::Ray;
use accelbench::index::kit::prim_test;
use accelbench::index::{BatchIndex, BuildError, HitQuery, Index, IndexInfo, Stats};
use accelbench::scene::Geometry;

#[derive(Debug, Clone, Default, serde::Serialize, serde::Deserialize)]
pub struct NoParams {}

/// Brute force that never reports primitive `DROPPED`: the injected fault.
pub struct DropOne;
pub const DROPPED: u32 = 17;

impl Index for DropOne {
    type Params = NoParams;
    fn build<G: Geometry>(_: &G, _: &Self::Params) -> Result<Self, BuildError> {
        Ok(DropOne)
    }
    fn query<Q: HitQuery, G: Geometry, S: Stats>(&self, g: &G, r: &Ray, s: &mut S) -> Q::Answer {
        query_skipping::<Q, G, S>(g, r, s, Some(DROPPED))
    }
    fn info(&self) -> IndexInfo {
        IndexInfo::default()
    }
}

/// Brute force's answer to query `Q` for `ray` over every primitive but `skip`, counting each
/// test.
pub fn query_skipping<Q: HitQuery, G: Geometry, S: Stats>(
    g: &G,
    ray: &Ray,
    s: &mut S,
    skip: Option<u32>,
) -> Q::Answer {
    let mut found = Q::start(ray);
    for prim in (0..g.len() as u32).filter(|&p| Some(p) != skip) {
        if prim_test::test::<Q, G, S>(&mut found, g, prim, ray, s) {
            break;
        }
    }
    Q::answer(found)
}

impl BatchIndex for DropOne {}
