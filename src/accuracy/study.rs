//! The time-against-error study: every kernel in `f32` and `f64`, on every ray family, at every
//! offset, measured against the exact reference (false misses, false hits, wrong primitives,
//! relative `t` error) and timed (ns per primitive test).

use super::families::{Family, icosphere_at, object_size, sphere_rays, spheres_at, triangle_rays};
use super::kernels_f64::{self as k64, Ray64};
use super::reference::{self, Reference};
use crate::geometry::sphere::{intersect_algebraic, intersect_geometric};
use crate::geometry::triangle::{MollerTrumbore, Parametric, PlaneEdges, Watertight};
use crate::geometry::{Ray, Sphere, Triangle, TriangleKernel};
use rayon::prelude::*;
use serde::Serialize;
use std::hint::black_box;
use std::time::Instant;

/// Which kernel.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Kernel {
    PlaneEdges,
    Parametric,
    MollerTrumbore,
    Watertight,
    SphereAlgebraic,
    SphereGeometric,
}

impl Kernel {
    pub const ALL: [Kernel; 6] = [
        Kernel::PlaneEdges,
        Kernel::Parametric,
        Kernel::MollerTrumbore,
        Kernel::Watertight,
        Kernel::SphereAlgebraic,
        Kernel::SphereGeometric,
    ];

    pub fn name(self) -> &'static str {
        match self {
            Kernel::PlaneEdges => "plane-edges",
            Kernel::Parametric => "parametric",
            Kernel::MollerTrumbore => "moller-trumbore",
            Kernel::Watertight => "watertight",
            Kernel::SphereAlgebraic => "sphere-algebraic",
            Kernel::SphereGeometric => "sphere-geometric",
        }
    }

    pub fn is_sphere(self) -> bool {
        matches!(self, Kernel::SphereAlgebraic | Kernel::SphereGeometric)
    }
}

/// Arithmetic precision of a kernel.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Precision {
    F32,
    F64,
}

impl Precision {
    pub fn name(self) -> &'static str {
        match self {
            Precision::F32 => "f32",
            Precision::F64 => "f64",
        }
    }
}

/// What to run.
#[derive(Debug, Clone)]
pub struct AccuracyConfig {
    /// Rays per family and offset.
    pub rays: usize,
    /// Translations from the origin (scene units, on every axis).
    pub offsets: Vec<f64>,
    /// Subdivision level of the icosphere mesh (`20 * 4^level` triangles).
    pub icosphere_level: u32,
    /// Timing repeats per kernel and family (best is kept); 0 skips timing (`ns_per_test` NaN).
    pub timing_repeats: usize,
    pub seed: u64,
}

impl AccuracyConfig {
    /// The command line's default: offsets `0, 1e0 .. 1e7`.
    pub fn full(rays: usize) -> AccuracyConfig {
        let mut offsets = vec![0.0];
        offsets.extend((0..=7).map(|e| 10f64.powi(e)));
        AccuracyConfig {
            rays,
            offsets,
            icosphere_level: 2,
            timing_repeats: 3,
            seed: 7,
        }
    }

    /// A small configuration (tests, `--quick`).
    pub fn quick(rays: usize) -> AccuracyConfig {
        AccuracyConfig {
            offsets: vec![0.0, 1e3, 1e5, 1e7],
            icosphere_level: 1,
            timing_repeats: 1,
            ..AccuracyConfig::full(rays)
        }
    }
}

/// One line of `accuracy.csv`: a kernel in one precision on one family at one offset.
#[derive(Debug, Clone, Serialize)]
pub struct AccuracyRow {
    pub kernel: Kernel,
    pub precision: Precision,
    pub family: Family,
    pub offset: f64,
    /// Object size at this offset (scene units).
    pub object_size: f64,
    pub rays: usize,
    /// Rays the reference could not certify (left out of every rate).
    pub unverifiable: usize,
    /// Rays the exact reference says hit something.
    pub reference_hits: usize,
    pub false_misses: usize,
    pub false_hits: usize,
    pub wrong_primitives: usize,
    /// `false_misses / reference_hits` (leaks).
    pub false_miss_rate: f64,
    /// `false_hits / reference misses`.
    pub false_hit_rate: f64,
    /// `wrong_primitives / reference_hits`.
    pub wrong_primitive_rate: f64,
    /// `|t - t_ref| / t_ref` over rays where kernel and reference hit the same primitive (or a
    /// tied one).
    pub max_rel_t_error: f64,
    pub mean_rel_t_error: f64,
    /// Nanoseconds per primitive test on this family at the first offset, single thread, best
    /// of `timing_repeats` (NaN when not timed).
    pub ns_per_test: f64,
}

/// The primitives a family is shot at.
enum Prims {
    Tris(Vec<Triangle>),
    Spheres(Vec<Sphere>),
}

impl Prims {
    fn len(&self) -> usize {
        match self {
            Prims::Tris(t) => t.len(),
            Prims::Spheres(s) => s.len(),
        }
    }

    fn reference(&self, prim: usize, ray: &Ray) -> Reference {
        match self {
            Prims::Tris(t) => reference::triangle(&t[prim], ray),
            Prims::Spheres(s) => reference::sphere(&s[prim], ray),
        }
    }

    /// Centre and radius of a sphere around the primitive.
    fn bounding_sphere(&self, prim: usize) -> (glam::DVec3, f64) {
        let b = match self {
            Prims::Tris(t) => t[prim].bounds(),
            Prims::Spheres(s) => s[prim].bounds(),
        };
        let (lo, hi) = (
            glam::Vec3::from(b.min).as_dvec3(),
            glam::Vec3::from(b.max).as_dvec3(),
        );
        ((lo + hi) * 0.5, (hi - lo).length() * 0.5)
    }
}

/// The reference closest hit of a ray over all primitives.
#[derive(Debug, Clone, Copy)]
enum RefClosest {
    Hit { t: f64, prim: usize },
    Miss,
    Unverifiable,
}

fn reference_closest(prims: &Prims, spheres: &[(glam::DVec3, f64)], ray: &Ray) -> RefClosest {
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

/// Closest hit `(prim, t)` of a kernel over all primitives (ties to the lowest primitive).
fn kernel_closest(
    kernel: Kernel,
    precision: Precision,
    prims: &Prims,
    ray: &Ray,
    r64: &Ray64,
) -> Option<(usize, f64)> {
    let mut best: Option<(usize, f64)> = None;
    for i in 0..prims.len() {
        let t = match (prims, precision) {
            (Prims::Tris(t), Precision::F32) => {
                tri_f32(kernel)(&t[i], ray, f32::INFINITY).map(f64::from)
            }
            (Prims::Tris(t), Precision::F64) => tri_f64(kernel)(&t[i], r64, f64::INFINITY),
            (Prims::Spheres(s), Precision::F32) => {
                sphere_f32(kernel)(&s[i], ray, f32::INFINITY).map(f64::from)
            }
            (Prims::Spheres(s), Precision::F64) => sphere_f64(kernel)(&s[i], r64, f64::INFINITY),
        };
        if let Some(t) = t
            && best.is_none_or(|(_, bt)| t < bt)
        {
            best = Some((i, t));
        }
    }
    best
}

type TriF32 = fn(&Triangle, &Ray, f32) -> Option<f32>;
type TriF64 = fn(&Triangle, &Ray64, f64) -> Option<f64>;
type SphF32 = fn(&Sphere, &Ray, f32) -> Option<f32>;
type SphF64 = fn(&Sphere, &Ray64, f64) -> Option<f64>;

fn tri_f32(k: Kernel) -> TriF32 {
    match k {
        Kernel::PlaneEdges => PlaneEdges::intersect,
        Kernel::Parametric => Parametric::intersect,
        Kernel::MollerTrumbore => MollerTrumbore::intersect,
        _ => Watertight::intersect,
    }
}

fn tri_f64(k: Kernel) -> TriF64 {
    match k {
        Kernel::PlaneEdges => k64::plane_edges,
        Kernel::Parametric => k64::parametric,
        Kernel::MollerTrumbore => k64::moller_trumbore,
        _ => k64::watertight,
    }
}

fn sphere_f32(k: Kernel) -> SphF32 {
    match k {
        Kernel::SphereGeometric => intersect_geometric,
        _ => intersect_algebraic,
    }
}

fn sphere_f64(k: Kernel) -> SphF64 {
    match k {
        Kernel::SphereGeometric => k64::sphere_geometric,
        _ => k64::sphere_algebraic,
    }
}

/// Counts of one kernel variant on one batch.
#[derive(Debug, Clone, Copy, Default)]
struct Tally {
    rays: usize,
    unverifiable: usize,
    ref_hits: usize,
    ref_misses: usize,
    false_misses: usize,
    false_hits: usize,
    wrong: usize,
    err_sum: f64,
    err_max: f64,
    err_n: usize,
}

impl Tally {
    fn merge(mut self, o: Tally) -> Tally {
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
        self
    }

    /// Scores one kernel answer against the reference.
    fn score(&mut self, prims: &Prims, ray: &Ray, r: RefClosest, got: Option<(usize, f64)>) {
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
                        Reference::Hit(tp) if (tp - t).abs() <= 1e-12 * t.abs());
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

fn rate(n: usize, of: usize) -> f64 {
    if of == 0 { 0.0 } else { n as f64 / of as f64 }
}

/// The kernel variants that apply to a primitive kind.
fn variants(spheres: bool) -> Vec<(Kernel, Precision)> {
    Kernel::ALL
        .into_iter()
        .filter(|k| k.is_sphere() == spheres)
        .flat_map(|k| [(k, Precision::F32), (k, Precision::F64)])
        .collect()
}

/// Best-of-`repeats` nanoseconds per test of one variant over `rays x prims`, single thread.
fn time_variant(
    kernel: Kernel,
    precision: Precision,
    prims: &Prims,
    rays: &[Ray],
    repeats: usize,
) -> f64 {
    if repeats == 0 || rays.is_empty() || prims.len() == 0 {
        return f64::NAN;
    }
    let r64: Vec<Ray64> = rays.iter().map(Ray64::from_ray).collect();
    let mut best = f64::INFINITY;
    for _ in 0..repeats {
        let start = Instant::now();
        let hits = match (prims, precision) {
            (Prims::Tris(t), Precision::F32) => count_hits(t, rays, |p, r| match kernel {
                Kernel::PlaneEdges => PlaneEdges::intersect(p, r, f32::INFINITY).is_some(),
                Kernel::Parametric => Parametric::intersect(p, r, f32::INFINITY).is_some(),
                Kernel::MollerTrumbore => MollerTrumbore::intersect(p, r, f32::INFINITY).is_some(),
                _ => Watertight::intersect(p, r, f32::INFINITY).is_some(),
            }),
            (Prims::Tris(t), Precision::F64) => count_hits(t, &r64, |p, r| match kernel {
                Kernel::PlaneEdges => k64::plane_edges(p, r, f64::INFINITY).is_some(),
                Kernel::Parametric => k64::parametric(p, r, f64::INFINITY).is_some(),
                Kernel::MollerTrumbore => k64::moller_trumbore(p, r, f64::INFINITY).is_some(),
                _ => k64::watertight(p, r, f64::INFINITY).is_some(),
            }),
            (Prims::Spheres(s), Precision::F32) => count_hits(s, rays, |p, r| match kernel {
                Kernel::SphereGeometric => intersect_geometric(p, r, f32::INFINITY).is_some(),
                _ => intersect_algebraic(p, r, f32::INFINITY).is_some(),
            }),
            (Prims::Spheres(s), Precision::F64) => count_hits(s, &r64, |p, r| match kernel {
                Kernel::SphereGeometric => k64::sphere_geometric(p, r, f64::INFINITY).is_some(),
                _ => k64::sphere_algebraic(p, r, f64::INFINITY).is_some(),
            }),
        };
        black_box(hits);
        let ns = start.elapsed().as_nanos() as f64 / (rays.len() * prims.len()) as f64;
        best = best.min(ns);
    }
    best
}

/// Every ray against every primitive. The kernel is chosen by a `match` inside the closure
/// (the same arm every time, so perfectly predicted), and every kernel is inlined the same way.
#[inline(never)]
fn count_hits<P, R>(prims: &[P], rays: &[R], f: impl Fn(&P, &R) -> bool) -> usize {
    let mut n = 0;
    for r in rays {
        for p in prims {
            n += f(black_box(p), r) as usize;
        }
    }
    n
}

/// Runs the study: one row per kernel, precision, family and offset.
pub fn run(config: &AccuracyConfig) -> Vec<AccuracyRow> {
    let mut rows = Vec::new();
    for family in Family::ALL {
        for spheres in [false, true] {
            if spheres && family == Family::EdgesVertices {
                continue;
            }
            let mut timings: Vec<f64> = Vec::new();
            for (oi, &offset) in config.offsets.iter().enumerate() {
                let seed = config.seed ^ (oi as u64) << 32;
                let (prims, rays) = if spheres {
                    let s = spheres_at(offset);
                    let rays = sphere_rays(family, &s, offset, config.rays, seed);
                    (Prims::Spheres(s), rays)
                } else {
                    let t = icosphere_at(config.icosphere_level, offset);
                    let rays = triangle_rays(family, &t, offset, config.rays, seed);
                    (Prims::Tris(t), rays)
                };
                let vars = variants(spheres);
                if oi == 0 {
                    timings = vars
                        .iter()
                        .map(|&(k, p)| time_variant(k, p, &prims, &rays, config.timing_repeats))
                        .collect();
                }
                let bsph: Vec<_> = (0..prims.len()).map(|i| prims.bounding_sphere(i)).collect();
                let tallies = rays
                    .par_iter()
                    .fold(
                        || vec![Tally::default(); vars.len()],
                        |mut acc, ray| {
                            let r = reference_closest(&prims, &bsph, ray);
                            let r64 = Ray64::from_ray(ray);
                            for (slot, &(k, p)) in acc.iter_mut().zip(&vars) {
                                let got = kernel_closest(k, p, &prims, ray, &r64);
                                slot.score(&prims, ray, r, got);
                            }
                            acc
                        },
                    )
                    .reduce(
                        || vec![Tally::default(); vars.len()],
                        |a, b| a.into_iter().zip(b).map(|(x, y)| x.merge(y)).collect(),
                    );
                for ((&(kernel, precision), t), &ns) in vars.iter().zip(tallies).zip(&timings) {
                    rows.push(AccuracyRow {
                        kernel,
                        precision,
                        family,
                        offset,
                        object_size: object_size(offset),
                        rays: t.rays,
                        unverifiable: t.unverifiable,
                        reference_hits: t.ref_hits,
                        false_misses: t.false_misses,
                        false_hits: t.false_hits,
                        wrong_primitives: t.wrong,
                        false_miss_rate: rate(t.false_misses, t.ref_hits),
                        false_hit_rate: rate(t.false_hits, t.ref_misses),
                        wrong_primitive_rate: rate(t.wrong, t.ref_hits),
                        max_rel_t_error: t.err_max,
                        mean_rel_t_error: if t.err_n == 0 {
                            0.0
                        } else {
                            t.err_sum / t.err_n as f64
                        },
                        ns_per_test: ns,
                    });
                }
            }
        }
    }
    rows
}
