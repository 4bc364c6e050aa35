//! The scalar kernel's answers for the lanes of a block ([`scalar_lanes`]): what an undecided
//! lane gets, and the reference the lane forms are tested against ([`LaneTally`]).

use super::TriangleKernel;
#[cfg(test)]
use super::lanes::LaneHits;
use super::lanes::TriangleLanes;

/// The scalar kernel's answers for the four lanes (the reference the lane forms are tested
/// against, and what an undecided lane gets).
pub fn scalar_lanes<K: TriangleKernel>(
    lanes: &TriangleLanes,
    ray: &crate::geometry::Ray,
) -> [Option<f32>; 4] {
    std::array::from_fn(|i| K::intersect(&lanes.triangle(i), ray, ray.t_max))
}

/// What the lane-form tests saw: decided hits and misses, lanes left to the scalar kernel, and
/// blocks whose every lane was a decided miss (among them the blocks the lane forms' early exit
/// returns: every lane missed by its signs).
#[cfg(test)]
#[derive(Debug, Default)]
pub struct LaneTally {
    pub hits: usize,
    pub misses: usize,
    pub undecided: usize,
    pub all_missed: usize,
}

#[cfg(test)]
impl LaneTally {
    /// Asserts that every lane `got` decided equals the scalar kernel `K` bit for bit (hit or
    /// miss, and `t`), and counts the outcomes.
    pub fn check<K: TriangleKernel>(
        &mut self,
        got: &LaneHits,
        lanes: &TriangleLanes,
        ray: &crate::geometry::Ray,
    ) {
        self.all_missed += usize::from(got.hit | got.scalar == 0);
        for (i, w) in scalar_lanes::<K>(lanes, ray).iter().enumerate() {
            if got.scalar >> i & 1 == 1 {
                self.undecided += 1;
                continue;
            }
            let g = (got.hit >> i & 1 == 1).then_some(got.t[i]);
            assert_eq!(g.map(f32::to_bits), w.map(f32::to_bits), "lane {i} {ray:?}");
            if g.is_some() {
                self.hits += 1
            } else {
                self.misses += 1
            }
        }
    }

    /// Asserts that the test reached every outcome: over 10,000 hits and misses, over 100
    /// undecided lanes and over 1,000 blocks of misses only.
    pub fn assert_all_outcomes(&self) {
        assert!(
            self.hits > 10_000
                && self.misses > 10_000
                && self.undecided > 100
                && self.all_missed > 1_000,
            "{self:?}"
        );
    }
}

/// Points uniform in the cube `[-scale / 2, scale / 2]^3`, from a fixed seed.
#[cfg(test)]
pub fn points(seed: u64) -> impl FnMut(f32) -> glam::Vec3A {
    let mut unit = crate::geometry::test_support::unit_floats(seed);
    move |scale| glam::Vec3A::new(unit(), unit(), unit()) * scale - scale / 2.0
}

/// Round `round` of a lane-form test: four triangles of random corners at `scale` (from
/// `point`), and the lanes of the first `1 + round % 4` of them.
#[cfg(test)]
pub fn random_block(
    point: &mut impl FnMut(f32) -> glam::Vec3A,
    scale: f32,
    round: usize,
) -> ([crate::geometry::Triangle; 4], TriangleLanes) {
    let tris: [crate::geometry::Triangle; 4] = std::array::from_fn(|_| {
        crate::geometry::Triangle::new(point(scale), point(scale), point(scale))
    });
    let lanes = TriangleLanes::new(&tris[..1 + round % 4]);
    (tris, lanes)
}

/// The origin of round `round`'s ray: every seventh round in the plane of the first triangle
/// (edge functions near zero), the others a random point at eight times `scale`.
#[cfg(test)]
pub fn ray_origin(
    point: &mut dyn FnMut(f32) -> glam::Vec3A,
    tris: &[crate::geometry::Triangle; 4],
    scale: f32,
    round: usize,
) -> glam::Vec3A {
    match round % 7 {
        0 => tris[0].v[0] * 2.0 - tris[0].v[1],
        _ => point(scale * 8.0),
    }
}

/// The point a round's ray aims at, by `round % 5`: corner `corner` of the first triangle, the
/// midpoint of its edge 1-2, a point beyond corner 0 outside the triangle (often no lane is
/// hit), or a point inside it.
#[cfg(test)]
pub fn ray_target(
    tris: &[crate::geometry::Triangle; 4],
    round: usize,
    corner: usize,
) -> glam::Vec3A {
    let v = tris[0].v;
    match round % 5 {
        0 => v[corner],
        1 => (v[1] + v[2]) * 0.5,
        2 => v[0] * 2.0 - (v[1] + v[2]) * 0.5,
        _ => v[0] * 0.3 + v[1] * 0.3 + v[2] * 0.4,
    }
}

/// Decided lanes of `lane_form` equal the scalar kernel `K` bit for bit over 40,000 rounds:
/// round `r` draws a block at scale `scales[r % scales.len()]` ([`random_block`], points from
/// `seed`) and the ray `aim(point, &tris, scale, r)` (`None`: no ray this round), and
/// [`LaneTally::check`]s the answers; then every outcome must have occurred.
#[cfg(test)]
pub fn check_decided_lanes<K: TriangleKernel>(
    seed: u64,
    scales: &[f32],
    mut aim: impl FnMut(
        &mut dyn FnMut(f32) -> glam::Vec3A,
        &[crate::geometry::Triangle; 4],
        f32,
        usize,
    ) -> Option<crate::geometry::Ray>,
    lane_form: impl Fn(&TriangleLanes, &crate::geometry::Ray) -> LaneHits,
) {
    let mut point = points(seed);
    let mut tally = LaneTally::default();
    for round in 0..40_000 {
        let scale = scales[round % scales.len()];
        let (tris, lanes) = random_block(&mut point, scale, round);
        let Some(ray) = aim(&mut point, &tris, scale, round) else {
            continue;
        };
        tally.check::<K>(&lane_form(&lanes, &ray), &lanes, &ray);
    }
    tally.assert_all_outcomes();
}
