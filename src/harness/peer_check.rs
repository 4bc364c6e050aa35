//! What a peer's disagreement with brute force means. Peers (obvhs, Embree, tinybvh) traverse,
//! and some test triangles, their own way, so their hits differ from ours on some rays; each such
//! ray is classified here, the one place that does it, with the exact reference of
//! [`crate::geometry::reference`] (exact hit/miss, `t` in double-double):
//! - **tie**: both hit, `t` within `1e-6 t` of each other (a shared edge or vertex, or the same
//!   hit with the peer's own rounding of `t`), or both hit primitives the reference puts at the
//!   same exact `t`;
//! - **t off**: the peer hits brute force's primitive, but its `t` is more than `1e-6 t` away
//!   (Embree's reciprocal approximation on grazing rays): the right surface, an imprecise
//!   distance;
//! - **wrong**: the reference contradicts the peer: it reports a hit that is not there, or it
//!   misses or passes a hit of brute force that is there and exactly closer;
//! - otherwise the reference sides with the peer (brute force's kernel was the wrong one).
//!
//! Shapes other than triangles and spheres have no exact reference: a hit on one is taken at
//! the `t` reported.

use super::timing::Query;
use crate::geometry::reference::{self, Reference};
use crate::geometry::{Hit, Ray};
use crate::scene::Scene;

/// Largest relative difference of two hits' `t` that still makes them a tie.
pub const TIE_REL_T: f64 = 1e-6;

/// How one peer result that differs from brute force's is judged.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Verdict {
    Tie,
    TOff,
    Wrong,
    /// The reference confirms the peer's answer and refutes brute force's.
    PeerRight,
}

/// Ties, imprecise `t` and wrong results of one peer on one ray set (among the
/// brute-force-verified rays).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct PeerCounts {
    pub ties: usize,
    pub t_off: usize,
    pub wrong: usize,
}

impl PeerCounts {
    pub fn add(&mut self, v: Verdict) {
        match v {
            Verdict::Tie => self.ties += 1,
            Verdict::TOff => self.t_off += 1,
            Verdict::Wrong => self.wrong += 1,
            Verdict::PeerRight => {}
        }
    }
}

fn near(a: f64, b: f64) -> bool {
    (a - b).abs() <= TIE_REL_T * a.abs().max(b.abs())
}

/// The exact reference for primitive `prim` of `scene` (ids: triangles, spheres, shapes).
fn truth(scene: &Scene, prim: u32, ray: &Ray) -> Reference {
    let i = prim as usize;
    let (nt, ns) = (scene.triangles.len(), scene.spheres.len());
    if i < nt {
        reference::triangle(&scene.triangles[i], ray)
    } else if i < nt + ns {
        reference::sphere(&scene.spheres[i - nt], ray)
    } else {
        Reference::Unverifiable
    }
}

/// The exact `t` at which `ray` meets `hit.prim` inside `[t_min, t_max]`, `None` when it does
/// not or when that `t` rounds past `f32`'s range (the hit contract: a hit has a finite `t`, so
/// a distance beyond `f32::MAX` is a miss); the reported `t` when the reference cannot decide.
fn real_t(scene: &Scene, ray: &Ray, hit: &Hit) -> Option<f64> {
    match truth(scene, hit.prim, ray) {
        Reference::Hit(t) => {
            (t >= ray.t_min as f64 && t <= ray.t_max as f64 && (t as f32).is_finite()).then_some(t)
        }
        Reference::Miss => None,
        Reference::Unverifiable => Some(hit.t as f64),
    }
}

/// Whether any primitive of `scene` really meets `ray` inside `[t_min, t_max]`.
fn really_occluded(scene: &Scene, ray: &Ray) -> bool {
    (0..scene.len() as u32).any(|prim| real_t(scene, ray, &Hit { t: f32::NAN, prim }).is_some())
}

/// Judges a peer's result `got` where brute force returned `expected` (they differ). For
/// [`Query::Any`] a `Some` means "occluded"; deciding it scans every primitive of the scene with
/// the reference, which is affordable because disagreements are rare. A closest hit whose `t`
/// is not a finite number (`embree-fast` returns NaN on some rays with tiny directions) is
/// wrong.
pub fn classify(
    scene: &Scene,
    ray: &Ray,
    query: Query,
    expected: Option<Hit>,
    got: Option<Hit>,
) -> Verdict {
    if query == Query::Any {
        return if got.is_some() == really_occluded(scene, ray) {
            Verdict::PeerRight
        } else {
            Verdict::Wrong
        };
    }
    if got.is_some_and(|g| !g.t.is_finite()) {
        return Verdict::Wrong;
    }
    if let (Some(e), Some(g)) = (expected, got)
        && near(e.t as f64, g.t as f64)
    {
        return Verdict::Tie;
    }
    let peer_t = match got {
        Some(g) => match real_t(scene, ray, &g) {
            Some(t) => Some(t),
            None => return Verdict::Wrong,
        },
        None => None,
    };
    let brute_t = expected.and_then(|e| real_t(scene, ray, &e));
    match (brute_t, peer_t) {
        (Some(_), None) => Verdict::Wrong,
        (Some(b), Some(p)) if b < p => Verdict::Wrong,
        (Some(b), Some(p)) if b == p => {
            if expected.map(|e| e.prim) == got.map(|g| g.prim) {
                Verdict::TOff
            } else {
                Verdict::Tie
            }
        }
        _ => Verdict::PeerRight,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Triangle;
    use glam::Vec3;

    /// Two triangles in the planes z = 1 and z = 2 across the z axis, ray from the origin up z.
    fn setup() -> (Scene, Ray) {
        let tri = |z: f32| Triangle::from_corners([-1.0, -1.0, z], [1.0, -1.0, z], [0.0, 1.0, z]);
        let scene = Scene::from_triangles("two", vec![tri(1.0), tri(2.0)]);
        (scene, Ray::infinite(Vec3::ZERO, Vec3::Z).unwrap())
    }

    fn hit(prim: u32, t: f32) -> Option<Hit> {
        Some(Hit { t, prim })
    }

    #[test]
    fn closest_hit_verdicts() {
        let (s, r) = setup();
        let c = |e, g| classify(&s, &r, Query::Closest, e, g);
        // Same distance, other primitive or the peer's rounding: a tie.
        assert_eq!(c(hit(0, 1.0), hit(1, 1.0)), Verdict::Tie);
        assert_eq!(c(hit(0, 1.0), hit(0, 1.0 + 1e-7)), Verdict::Tie);
        // The right triangle at an imprecise distance.
        assert_eq!(c(hit(0, 1.0), hit(0, 1.0 + 1e-5)), Verdict::TOff);
        // The peer misses the near triangle, skips to the far one, or invents a hit.
        assert_eq!(c(hit(0, 1.0), None), Verdict::Wrong);
        assert_eq!(c(hit(0, 1.0), hit(1, 2.0)), Verdict::Wrong);
        assert_eq!(c(None, hit(0, 1.0)), Verdict::PeerRight);
        assert_eq!(c(hit(1, 2.0), hit(0, 1.0)), Verdict::PeerRight);
        assert_eq!(c(hit(0, 1.0), hit(1, 0.5)), Verdict::Wrong);
    }

    /// A hit needs a finite `t`: a NaN distance is wrong, and so is a hit whose exact distance
    /// (1e40 along a direction of length 1e-40) is beyond `f32`, where brute force misses.
    #[test]
    fn a_hit_without_a_finite_t_is_wrong() {
        let (s, r) = setup();
        let c = |r: &Ray, e, g| classify(&s, r, Query::Closest, e, g);
        assert_eq!(c(&r, hit(0, 1.0), hit(0, f32::NAN)), Verdict::Wrong);
        assert_eq!(c(&r, None, hit(1, f32::NAN)), Verdict::Wrong);
        let far = Ray::infinite(Vec3::ZERO, Vec3::new(0.0, 0.0, 1e-40)).unwrap();
        assert_eq!(c(&far, None, hit(0, f32::MAX)), Verdict::Wrong);
        assert_eq!(c(&far, None, hit(0, f32::INFINITY)), Verdict::Wrong);
    }

    #[test]
    fn any_hit_verdicts() {
        let (s, r) = setup();
        let occluded = hit(u32::MAX, f32::NAN);
        assert_eq!(classify(&s, &r, Query::Any, occluded, None), Verdict::Wrong);
        let away = Ray::infinite(Vec3::ZERO, -Vec3::Z).unwrap();
        assert_eq!(
            classify(&s, &away, Query::Any, None, occluded),
            Verdict::Wrong
        );
        assert_eq!(
            classify(&s, &away, Query::Any, occluded, None),
            Verdict::PeerRight
        );
    }

    #[test]
    fn counts_add_up() {
        let mut c = PeerCounts::default();
        [
            Verdict::Tie,
            Verdict::Wrong,
            Verdict::Tie,
            Verdict::PeerRight,
        ]
        .into_iter()
        .for_each(|v| c.add(v));
        assert_eq!(
            c,
            PeerCounts {
                ties: 2,
                t_off: 0,
                wrong: 1
            }
        );
    }
}
