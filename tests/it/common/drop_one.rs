//! A faulty index for tests of the verification: brute force that never reports one primitive.

use accelbench::geometry::{Hit, Ray};
use accelbench::index::{BatchIndex, BuildError, Index, IndexInfo, Stats};
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
    fn closest_hit<G: Geometry, S: Stats>(&self, g: &G, ray: &Ray, s: &mut S) -> Option<Hit> {
        closest_skipping(g, ray, s, Some(DROPPED))
    }
    fn any_hit<G: Geometry, S: Stats>(&self, g: &G, ray: &Ray, s: &mut S) -> bool {
        self.closest_hit(g, ray, s).is_some()
    }
    fn info(&self) -> IndexInfo {
        IndexInfo::default()
    }
}

/// Brute force's closest hit of `ray` over every primitive but `skip`, counting each test.
pub fn closest_skipping<G: Geometry, S: Stats>(
    g: &G,
    ray: &Ray,
    s: &mut S,
    skip: Option<u32>,
) -> Option<Hit> {
    let mut best: Option<Hit> = None;
    for prim in (0..g.len() as u32).filter(|&p| Some(p) != skip) {
        s.prim_test();
        if let Some(t) = g.intersect(prim, ray, ray.t_max) {
            let h = Hit { t, prim };
            if best.is_none_or(|b| h.is_closer_than(&b)) {
                best = Some(h);
            }
        }
    }
    best
}

impl BatchIndex for DropOne {}
