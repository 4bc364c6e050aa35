//! Scoring a kernel against the exact reference: the reference closest hit of a ray, and the
//! tallies behind the false-miss, false-hit and wrong-primitive rates and the `t` errors.

use super::kernels::{Precision, Prims};
use crate::geometry::Ray;
use crate::geometry::reference::Reference;

/// The reference closest hit of a ray over all primitives.
#[derive(Debug, Clone, Copy)]
pub enum RefClosest {
    Hit { t: f64, prim: usize },
    Miss,
    Unverifiable,
}

pub fn reference_closest(prims: &Prims, spheres: &[(glam::DVec3, f64)], ray: &Ray) -> RefClosest {
    let o = glam::Vec3::from(ray.origin).as_dvec3();
    let d = glam::Vec3::from(ray.dir).as_dvec3();
    let dn = d / d.length();
    let mut best: Option<(f64, usize)> = None;
    for (i, &(c, r)) in spheres.iter().enumerate() {
        // Conservative cull: the line passes farther than the bounding radius (with slack for
        // the f64 rounding of this test).
        let oc = c - o;
        let dist = oc.cross(dn).length();
        if dist > r * (1.0 + 1e-9) + 1e-9 * oc.length() {
            continue;
        }
        match prims.reference(i, ray) {
            Reference::Unverifiable => return RefClosest::Unverifiable,
            Reference::Miss => {}
            Reference::Hit(t) => {
                if best.is_none_or(|(bt, _)| t < bt) {
                    best = Some((t, i));
                }
            }
        }
    }
    match best {
        Some((t, prim)) => RefClosest::Hit { t, prim },
        None => RefClosest::Miss,
    }
}

/// Counts of one kernel variant on one batch.
#[derive(Debug, Clone, Copy, Default)]
pub struct Tally {
    pub rays: usize,
    pub unverifiable: usize,
    pub ref_hits: usize,
    pub ref_misses: usize,
    pub false_misses: usize,
    pub false_hits: usize,
    pub wrong: usize,
    pub err_sum: f64,
    pub err_max: f64,
    pub err_n: usize,
    /// Edge functions the exact kernel decided by its exact fallback (zero for other kernels).
    pub fallbacks: u64,
    /// Primitive tests made (three edge functions each for triangles).
    pub tests: u64,
}

impl Tally {
    pub fn merge(mut self, o: Tally) -> Tally {
        self.rays += o.rays;
        self.unverifiable += o.unverifiable;
        self.ref_hits += o.ref_hits;
        self.ref_misses += o.ref_misses;
        self.false_misses += o.false_misses;
        self.false_hits += o.false_hits;
        self.wrong += o.wrong;
        self.err_sum += o.err_sum;
        self.err_max = self.err_max.max(o.err_max);
        self.err_n += o.err_n;
        self.fallbacks += o.fallbacks;
        self.tests += o.tests;
        self
    }

    /// Scores one kernel answer (its primitive and `t`, computed in `precision`) against the
    /// reference. Another primitive than the reference's is a tie, not wrong, when its exact `t`
    /// equals the reference's to within `1e-12 t`, or, for an `f32` kernel, rounds to the same
    /// `f32`: an `f32` result cannot order two distances closer than that, and the suite's tie
    /// rule (lowest id at equal `t`) then decides.
    pub fn score(
        &mut self,
        prims: &Prims,
        ray: &Ray,
        r: RefClosest,
        got: Option<(usize, f64)>,
        precision: Precision,
    ) {
        self.rays += 1;
        match (r, got) {
            (RefClosest::Unverifiable, _) => self.unverifiable += 1,
            (RefClosest::Miss, None) => self.ref_misses += 1,
            (RefClosest::Miss, Some(_)) => {
                self.ref_misses += 1;
                self.false_hits += 1;
            }
            (RefClosest::Hit { .. }, None) => {
                self.ref_hits += 1;
                self.false_misses += 1;
            }
            (RefClosest::Hit { t, prim }, Some((p, tk))) => {
                self.ref_hits += 1;
                // Another primitive is right only when the reference has it tied at `t`.
                let tied = p == prim
                    || matches!(prims.reference(p, ray),
                        Reference::Hit(tp) if (tp - t).abs() <= 1e-12 * t.abs()
                            || (precision == Precision::F32 && tp as f32 == t as f32));
                if !tied {
                    self.wrong += 1;
                    return;
                }
                let err = if t != 0.0 {
                    (tk - t).abs() / t.abs()
                } else {
                    tk.abs()
                };
                self.err_sum += err;
                self.err_max = self.err_max.max(err);
                self.err_n += 1;
            }
        }
    }
}

pub fn rate(n: usize, of: usize) -> f64 {
    if of == 0 { 0.0 } else { n as f64 / of as f64 }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Triangle;
    use glam::Vec3;

    #[test]
    fn scores_misses_hits_wrong_primitives_and_errors() {
        // Two parallel triangles at z = 2 and z = 3 over the same square corner.
        let tri = |z: f32| Triangle::from_corners([0.0, 0.0, z], [4.0, 0.0, z], [0.0, 4.0, z]);
        let prims = Prims::Tris(vec![tri(2.0), tri(3.0)]);
        let spheres: Vec<_> = (0..2).map(|i| prims.bounding_sphere(i)).collect();
        let ray = Ray::infinite(Vec3::new(1.0, 1.0, 0.0), Vec3::Z).unwrap();
        let r = reference_closest(&prims, &spheres, &ray);
        assert!(matches!(r, RefClosest::Hit { prim: 0, t } if t == 2.0));
        let mut tally = Tally::default();
        tally.score(&prims, &ray, r, None, Precision::F32);
        tally.score(&prims, &ray, r, Some((1, 3.0)), Precision::F32);
        tally.score(
            &prims,
            &ray,
            r,
            Some((0, 2.0 * (1.0 + 1e-6))),
            Precision::F32,
        );
        let away = Ray::infinite(Vec3::new(1.0, 1.0, 0.0), -Vec3::Z).unwrap();
        let miss = reference_closest(&prims, &spheres, &away);
        tally.score(&prims, &away, miss, Some((0, 1.0)), Precision::F32);
        assert_eq!((tally.rays, tally.ref_hits, tally.ref_misses), (4, 3, 1));
        assert_eq!(
            (tally.false_misses, tally.wrong, tally.false_hits),
            (1, 1, 1)
        );
        assert!((tally.err_max - 1e-6).abs() < 1e-12);
        assert_eq!(rate(1, 4), 0.25);
        assert_eq!(rate(1, 0), 0.0);
    }

    #[test]
    fn another_primitive_at_the_same_f32_distance_is_a_tie_for_f32_kernels_only() {
        // Triangle 0 lies in z = 2, triangle 1 in z = 2 + x / 2: a ray up through x = 2^-30
        // meets 0 at t = 2 and 1 at t = 2 + 2^-31, which rounds to the same `f32`.
        let corners = |z0: f32, z1: f32| {
            Triangle::from_corners([0.0, 0.0, z0], [4.0, 0.0, z1], [0.0, 4.0, z0])
        };
        let prims = Prims::Tris(vec![corners(2.0, 2.0), corners(2.0, 4.0)]);
        let spheres: Vec<_> = (0..2).map(|i| prims.bounding_sphere(i)).collect();
        let ray = Ray::infinite(Vec3::new(2f32.powi(-30), 1.0, 0.0), Vec3::Z).unwrap();
        let r = reference_closest(&prims, &spheres, &ray);
        assert!(matches!(r, RefClosest::Hit { prim: 0, t } if t == 2.0));
        let mut f32_tally = Tally::default();
        f32_tally.score(&prims, &ray, r, Some((1, 2.0)), Precision::F32);
        assert_eq!(f32_tally.wrong, 0);
        let mut f64_tally = Tally::default();
        f64_tally.score(&prims, &ray, r, Some((1, 2.0)), Precision::F64);
        assert_eq!(f64_tally.wrong, 1);
    }
}
