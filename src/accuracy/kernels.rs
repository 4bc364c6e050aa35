//! The kernels under study, as data: six triangle and sphere kernels in two precisions and seven
//! shape kernels in `f32` (their `f64` mirrors are the reference), the primitives they are shot
//! at, the closest hit of one kernel over a scene, and the single-thread timing loop.

use super::kernels_f64::Ray64;
use super::shapes_f64;
use crate::geometry::real::{KernelRay, Real};
use crate::geometry::reference::{self, Reference};
use crate::geometry::shapes::{cone, cylinder, ellipsoid, obb, polygon};
use crate::geometry::sphere::{intersect_algebraic, intersect_geometric};
use crate::geometry::triangle::{
    Exact, MollerTrumbore, Parametric, PlaneEdges, RealKernel, Watertight,
};
use crate::geometry::{Ray, Shape, Sphere, Triangle, TriangleKernel};
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
    /// Exact decisions: `f64` filter, exact fallback (`f32` only: it has no `f64` mirror).
    Exact,
    SphereAlgebraic,
    SphereGeometric,
    /// Oriented box, slab method (`shapes::obb::intersect_slabs`).
    BoxSlabs,
    /// Oriented box, the three front-facing planes (`shapes::obb::intersect_front_planes`).
    BoxFrontPlanes,
    ConvexPolygon,
    ConcavePolygon,
    Cylinder,
    Cone,
    Ellipsoid,
}

impl Kernel {
    /// Every kernel: the triangle and sphere kernels, then [`Kernel::SHAPES`].
    pub const ALL: [Kernel; 14] = {
        let first = [
            Kernel::PlaneEdges,
            Kernel::Parametric,
            Kernel::MollerTrumbore,
            Kernel::Watertight,
            Kernel::Exact,
            Kernel::SphereAlgebraic,
            Kernel::SphereGeometric,
        ];
        let mut all = [Kernel::PlaneEdges; 14];
        let mut i = 0;
        while i < all.len() {
            all[i] = if i < first.len() {
                first[i]
            } else {
                Kernel::SHAPES[i - first.len()]
            };
            i += 1;
        }
        all
    };

    /// The shape kernels (measured in `f32` against their `f64` mirrors).
    pub const SHAPES: [Kernel; 7] = [
        Kernel::BoxSlabs,
        Kernel::BoxFrontPlanes,
        Kernel::ConvexPolygon,
        Kernel::ConcavePolygon,
        Kernel::Cylinder,
        Kernel::Cone,
        Kernel::Ellipsoid,
    ];

    pub fn name(self) -> &'static str {
        match self {
            Kernel::PlaneEdges => "plane-edges",
            Kernel::Parametric => "parametric",
            Kernel::MollerTrumbore => "moller-trumbore",
            Kernel::Watertight => "watertight",
            Kernel::Exact => "exact",
            Kernel::SphereAlgebraic => "sphere-algebraic",
            Kernel::SphereGeometric => "sphere-geometric",
            Kernel::BoxSlabs => "box-slabs",
            Kernel::BoxFrontPlanes => "box-front-planes",
            Kernel::ConvexPolygon => "convex-polygon",
            Kernel::ConcavePolygon => "concave-polygon",
            Kernel::Cylinder => "cylinder",
            Kernel::Cone => "cone",
            Kernel::Ellipsoid => "ellipsoid",
        }
    }

    pub fn is_sphere(self) -> bool {
        matches!(self, Kernel::SphereAlgebraic | Kernel::SphereGeometric)
    }

    pub fn is_shape(self) -> bool {
        Kernel::SHAPES.contains(&self)
    }

    pub fn is_triangle(self) -> bool {
        !self.is_sphere() && !self.is_shape()
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
    /// Shapes of the kind of `kernel`, which is both what is measured and what its `f64` mirror
    /// (the reference) follows.
    Shapes {
        shapes: Vec<Shape>,
        kernel: Kernel,
    },
}

impl Prims {
    pub fn len(&self) -> usize {
        match self {
            Prims::Tris(t) => t.len(),
            Prims::Spheres(s) => s.len(),
            Prims::Shapes { shapes, .. } => shapes.len(),
        }
    }

    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    pub fn reference(&self, prim: usize, ray: &Ray) -> Reference {
        match self {
            Prims::Tris(t) => reference::triangle(&t[prim], ray),
            Prims::Spheres(s) => reference::sphere(&s[prim], ray),
            Prims::Shapes { shapes, kernel } => {
                shapes_f64::reference(*kernel == Kernel::BoxFrontPlanes, &shapes[prim], ray)
            }
        }
    }

    /// Centre and radius of a sphere around the primitive.
    pub fn bounding_sphere(&self, prim: usize) -> (glam::DVec3, f64) {
        let b = match self {
            Prims::Tris(t) => t[prim].bounds(),
            Prims::Spheres(s) => s[prim].bounds(),
            Prims::Shapes { shapes, .. } => shapes[prim].bounds(),
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
            (Prims::Shapes { shapes, .. }, Precision::F32) => {
                shape_f32(kernel, &shapes[i], ray, f32::INFINITY).map(f64::from)
            }
            (Prims::Shapes { shapes, .. }, Precision::F64) => {
                let mut doubt = shapes_f64::Doubt::default();
                shapes_f64::mirror(
                    kernel == Kernel::BoxFrontPlanes,
                    &shapes[i],
                    r64,
                    f64::INFINITY,
                    &mut doubt,
                )
            }
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
        Kernel::Exact => Exact::intersect,
        _ => Watertight::intersect,
    }
}

fn tri_f64(k: Kernel) -> TriF64 {
    match k {
        Kernel::PlaneEdges => PlaneEdges::intersect_in,
        Kernel::Parametric => Parametric::intersect_in,
        Kernel::MollerTrumbore => MollerTrumbore::intersect_in,
        _ => Watertight::intersect_in,
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
        Kernel::SphereGeometric => intersect_geometric,
        _ => intersect_algebraic,
    }
}

/// The shape kernel `kernel` in `f32` (the box takes either of its two kernels; every other
/// shape its one shared kernel).
#[inline(always)]
pub fn shape_f32(kernel: Kernel, shape: &Shape, ray: &Ray, t_max: f32) -> Option<f32> {
    match (kernel, shape) {
        (Kernel::BoxFrontPlanes, Shape::Box(b)) => obb::intersect_front_planes(b, ray, t_max),
        _ => shape.intersect(ray, t_max),
    }
}

/// The triangle or sphere kernel variants, in both precisions (the exact kernel in `f32` only).
pub fn variants(spheres: bool) -> Vec<(Kernel, Precision)> {
    Kernel::ALL
        .into_iter()
        .filter(|k| {
            if spheres {
                k.is_sphere()
            } else {
                k.is_triangle()
            }
        })
        .flat_map(|k| {
            let f64_mirror = k != Kernel::Exact;
            [(k, Precision::F32)]
                .into_iter()
                .chain(f64_mirror.then_some((k, Precision::F64)))
        })
        .collect()
}

/// Each timed repeat runs the rays over the primitives as many times as it takes to make at
/// least this many tests (a single shape and a thousand rays would be too short to time).
pub const MIN_TIMED_TESTS: usize = 200_000;

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
    let tests = rays.len() * prims.len();
    let passes = MIN_TIMED_TESTS.div_ceil(tests);
    let mut best = f64::INFINITY;
    for _ in 0..repeats {
        let start = Instant::now();
        let hits: usize = (0..passes)
            .map(|_| one_pass(kernel, precision, prims, rays, &r64))
            .sum();
        black_box(hits);
        let ns = start.elapsed().as_nanos() as f64 / (passes * tests) as f64;
        best = best.min(ns);
    }
    best
}

/// [`one_pass`] for a triangle kernel other than `Exact`, in the precision of `rays` (each call
/// inlined: no function pointer in the timed loop).
fn triangle_hits<R: KernelRay>(kernel: Kernel, tris: &[Triangle], rays: &[R]) -> usize {
    let far = R::Scalar::INFINITY;
    count_hits(tris, rays, |p, r| match kernel {
        Kernel::PlaneEdges => PlaneEdges::intersect_in(p, r, far).is_some(),
        Kernel::Parametric => Parametric::intersect_in(p, r, far).is_some(),
        Kernel::MollerTrumbore => MollerTrumbore::intersect_in(p, r, far).is_some(),
        _ => Watertight::intersect_in(p, r, far).is_some(),
    })
}

/// [`one_pass`] for a sphere kernel in the precision of `rays`.
fn sphere_hits<R: KernelRay>(kernel: Kernel, spheres: &[Sphere], rays: &[R]) -> usize {
    let far = R::Scalar::INFINITY;
    count_hits(spheres, rays, |p, r| match kernel {
        Kernel::SphereGeometric => intersect_geometric(p, r, far).is_some(),
        _ => intersect_algebraic(p, r, far).is_some(),
    })
}

/// Every ray against every primitive once; the number of hits.
fn one_pass(
    kernel: Kernel,
    precision: Precision,
    prims: &Prims,
    rays: &[Ray],
    r64: &[Ray64],
) -> usize {
    match (prims, precision) {
        (Prims::Tris(t), Precision::F32) if kernel == Kernel::Exact => {
            count_hits(t, rays, |p, r| {
                Exact::intersect(p, r, f32::INFINITY).is_some()
            })
        }
        (Prims::Tris(t), Precision::F32) => triangle_hits(kernel, t, rays),
        (Prims::Tris(t), Precision::F64) => triangle_hits(kernel, t, r64),
        (Prims::Spheres(s), Precision::F32) => sphere_hits(kernel, s, rays),
        (Prims::Spheres(s), Precision::F64) => sphere_hits(kernel, s, r64),
        (Prims::Shapes { shapes, .. }, Precision::F32) => time_shapes(kernel, shapes, rays),
        (Prims::Shapes { shapes, .. }, Precision::F64) => count_hits(shapes, r64, |p, r| {
            let mut doubt = shapes_f64::Doubt::default();
            shapes_f64::mirror(
                kernel == Kernel::BoxFrontPlanes,
                p,
                r,
                f64::INFINITY,
                &mut doubt,
            )
            .is_some()
        }),
    }
}

/// The `f32` shape kernel over every ray and shape, each kernel called directly on its own
/// shape type (as the indices call it, without the [`Shape`] dispatch).
fn time_shapes(kernel: Kernel, shapes: &[Shape], rays: &[Ray]) -> usize {
    macro_rules! each {
        ($variant:ident, $f:path) => {{
            let typed: Vec<_> = shapes
                .iter()
                .filter_map(|s| match s {
                    Shape::$variant(x) => Some(x.clone()),
                    _ => None,
                })
                .collect();
            count_hits(&typed, rays, |p, r| $f(p, r, f32::INFINITY).is_some())
        }};
    }
    match kernel {
        Kernel::BoxFrontPlanes => each!(Box, obb::intersect_front_planes),
        Kernel::ConvexPolygon => each!(ConvexPolygon, polygon::intersect_convex),
        Kernel::ConcavePolygon => each!(ConcavePolygon, polygon::intersect_concave),
        Kernel::Cylinder => each!(Cylinder, cylinder::intersect),
        Kernel::Cone => each!(Cone, cone::intersect),
        Kernel::Ellipsoid => each!(Ellipsoid, ellipsoid::intersect),
        Kernel::BoxSlabs => each!(Box, obb::intersect_slabs),
        _ => count_hits(shapes, rays, |p, r| {
            shape_f32(kernel, p, r, f32::INFINITY).is_some()
        }),
    }
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
