//! The kernels under study, as data: six kernels in two precisions, the primitives they are shot
//! at, the closest hit of one kernel over a scene, and the single-thread timing loop.

use super::kernels_f64::{self as k64, Ray64};
use super::reference::{self, Reference};
use crate::geometry::sphere::{intersect_algebraic, intersect_geometric};
use crate::geometry::triangle::{MollerTrumbore, Parametric, PlaneEdges, Watertight};
use crate::geometry::{Ray, Sphere, Triangle, TriangleKernel};
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

/// The primitives a family is shot at.
pub enum Prims {
    Tris(Vec<Triangle>),
    Spheres(Vec<Sphere>),
}

impl Prims {
    pub fn len(&self) -> usize {
        match self {
            Prims::Tris(t) => t.len(),
            Prims::Spheres(s) => s.len(),
        }
    }

    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    pub fn reference(&self, prim: usize, ray: &Ray) -> Reference {
        match self {
            Prims::Tris(t) => reference::triangle(&t[prim], ray),
            Prims::Spheres(s) => reference::sphere(&s[prim], ray),
        }
    }

    /// Centre and radius of a sphere around the primitive.
    pub fn bounding_sphere(&self, prim: usize) -> (glam::DVec3, f64) {
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

/// Closest hit `(prim, t)` of a kernel over all primitives (ties to the lowest primitive).
pub fn kernel_closest(
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

/// The kernel variants that apply to a primitive kind.
pub fn variants(spheres: bool) -> Vec<(Kernel, Precision)> {
    Kernel::ALL
        .into_iter()
        .filter(|k| k.is_sphere() == spheres)
        .flat_map(|k| [(k, Precision::F32), (k, Precision::F64)])
        .collect()
}

/// Best-of-`repeats` nanoseconds per test of one variant over `rays x prims`, single thread.
pub fn time_variant(
    kernel: Kernel,
    precision: Precision,
    prims: &Prims,
    rays: &[Ray],
    repeats: usize,
) -> f64 {
    if repeats == 0 || rays.is_empty() || prims.is_empty() {
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
