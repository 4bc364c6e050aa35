//! The scene's geometries ([`Triangles`], [`Mixed`], [`WithShapes`]) implementing the traits
//! of `geometry_traits.rs`, and [`with_geometry`], which picks one for a scene. Monomorphized
//! per primitive mix and triangle kernel, so a triangle-only scene never pays for a sphere
//! branch and the kernel choice costs no dispatch.

use super::accept::{accept, accept_lanes};
use super::geometry_traits::{Geometry, ShapeQueries};
use crate::geometry::clip::triangle_clipped_bounds;
use crate::geometry::overlap::{sphere_overlaps_box, triangle_overlaps_box};
use crate::geometry::sphere::intersect_algebraic;
use crate::geometry::triangle::lanes::TriangleBlock;
use crate::geometry::triangle::{Exact, MollerTrumbore, Parametric, PlaneEdges, Watertight};
use crate::geometry::{Aabb, Ray, Shape, Sphere, Triangle, TriangleKernel, TriangleKernelKind};
use glam::Vec3A;
use std::marker::PhantomData;
use std::sync::Arc;

/// Extent of a triangle along `dir` (see [`ShapeQueries::extent_along`]).
#[inline]
fn triangle_extent(t: &Triangle, dir: Vec3A) -> (f32, f32) {
    let d = t.v.map(|v| dir.dot(v));
    (d[0].min(d[1]).min(d[2]), d[0].max(d[1]).max(d[2]))
}

/// A triangle's own plane (see [`ShapeQueries::own_plane`]).
fn triangle_plane(t: &Triangle) -> Option<(Vec3A, f32)> {
    let n = t.normal();
    (n != Vec3A::ZERO).then(|| (n, n.dot(t.v[0])))
}

/// Scene primitives shared (cheap to clone) by every index built on one scene.
#[derive(Debug, Clone, Default)]
pub struct SceneGeometry {
    pub triangles: Arc<[Triangle]>,
    pub spheres: Arc<[Sphere]>,
    pub shapes: Arc<[Shape]>,
    /// The scene's instances when it has `[[instance]]` entries (for `tlas`; every other index
    /// traces the flattened primitives above).
    pub instances: Option<Arc<super::instances::InstanceSet>>,
}

impl SceneGeometry {
    pub fn len(&self) -> usize {
        self.triangles.len() + self.spheres.len() + self.shapes.len()
    }

    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Unit geometric normal of primitive `prim` at the surface point `p` (for the final hit
    /// only); zero for a degenerate triangle. Not oriented toward the ray.
    pub fn normal_at(&self, prim: u32, p: Vec3A) -> Vec3A {
        normal_of(&self.triangles, &self.spheres, &self.shapes, prim, p)
    }
}

/// Unit geometric normal of primitive `prim` (ids: triangles, then spheres, then shapes) at the
/// surface point `p`, for the final hit only; zero for a degenerate triangle. Not oriented
/// toward the ray.
pub fn normal_of(
    tris: &[Triangle],
    spheres: &[Sphere],
    shapes: &[Shape],
    prim: u32,
    p: Vec3A,
) -> Vec3A {
    let i = prim as usize;
    let (nt, ns) = (tris.len(), spheres.len());
    if i < nt {
        tris[i].normal()
    } else if i < nt + ns {
        spheres[i - nt].normal_at(p)
    } else {
        shapes[i - nt - ns].normal_at(p)
    }
}

/// Triangle-only geometry with kernel `K`.
#[derive(Debug, Clone)]
pub struct Triangles<K: TriangleKernel> {
    pub tris: Arc<[Triangle]>,
    kernel: PhantomData<K>,
}

impl<K: TriangleKernel> Triangles<K> {
    pub fn new(tris: Arc<[Triangle]>) -> Self {
        Triangles {
            tris,
            kernel: PhantomData,
        }
    }
}

impl<K: TriangleKernel> Geometry for Triangles<K> {
    #[inline]
    fn len(&self) -> usize {
        self.tris.len()
    }
    #[inline]
    fn bounds(&self, prim: u32) -> Aabb {
        self.tris[prim as usize].bounds()
    }
    #[inline]
    fn intersect(&self, prim: u32, ray: &Ray, t_max: f32) -> Option<f32> {
        let tri = &self.tris[prim as usize];
        accept(K::intersect(tri, ray, ray.t_max), tri.bounds(), ray, t_max)
    }
    /// The kernel's lane form decides what it can and its hits go through [`accept_lanes`];
    /// undecided lanes take the scalar kernel and [`accept`], as in [`Geometry::intersect`].
    /// A block the lane form decided to be all misses (most blocks a ray tests) skips the
    /// clamp.
    #[inline(always)]
    fn intersect_block(&self, block: &TriangleBlock, ray: &Ray, t_max: f32) -> (u32, [f32; 4]) {
        let lanes = K::intersect_lanes(&block.tris, ray);
        if lanes.hit | lanes.scalar == 0 {
            return (0, [0.0; 4]);
        }
        let mut out = accept_lanes(lanes.hit, lanes.t, &block.tris, ray, t_max);
        let mut todo = lanes.scalar;
        while todo != 0 {
            let i = todo.trailing_zeros() as usize;
            todo &= todo - 1;
            let tri = block.tris.triangle(i);
            if let Some(t) = accept(K::intersect(&tri, ray, ray.t_max), tri.bounds(), ray, t_max) {
                out.0 |= 1 << i;
                out.1[i] = t;
            }
        }
        out
    }
}

impl<K: TriangleKernel> ShapeQueries for Triangles<K> {
    fn overlaps_box(&self, prim: u32, cell: &Aabb) -> bool {
        triangle_overlaps_box(&self.tris[prim as usize], cell)
    }
    fn clipped_bounds(&self, prim: u32, cell: &Aabb) -> Aabb {
        triangle_clipped_bounds(&self.tris[prim as usize], cell)
    }
    fn extent_along(&self, prim: u32, dir: Vec3A) -> (f32, f32) {
        triangle_extent(&self.tris[prim as usize], dir)
    }
    fn own_plane(&self, prim: u32) -> Option<(Vec3A, f32)> {
        triangle_plane(&self.tris[prim as usize])
    }
    fn normal(&self, prim: u32, _ray: &Ray, _t: f32) -> Vec3A {
        self.tris[prim as usize].normal()
    }
    fn block_triangle(&self, prim: u32) -> Option<Triangle> {
        Some(self.tris[prim as usize])
    }
    fn triangles_only(&self) -> Option<&[Triangle]> {
        Some(&self.tris)
    }
}

/// Triangles (ids `0..n_tri`) and spheres (ids `n_tri..`), triangle kernel `K`, spheres by the
/// stable algebraic kernel.
#[derive(Debug, Clone)]
pub struct Mixed<K: TriangleKernel> {
    pub tris: Arc<[Triangle]>,
    pub spheres: Arc<[Sphere]>,
    kernel: PhantomData<K>,
}

impl<K: TriangleKernel> Mixed<K> {
    pub fn new(tris: Arc<[Triangle]>, spheres: Arc<[Sphere]>) -> Self {
        Mixed {
            tris,
            spheres,
            kernel: PhantomData,
        }
    }
}

impl<K: TriangleKernel> Geometry for Mixed<K> {
    #[inline]
    fn len(&self) -> usize {
        self.tris.len() + self.spheres.len()
    }
    #[inline]
    fn bounds(&self, prim: u32) -> Aabb {
        let i = prim as usize;
        match self.tris.get(i) {
            Some(t) => t.bounds(),
            None => self.spheres[i - self.tris.len()].bounds(),
        }
    }
    #[inline]
    fn intersect(&self, prim: u32, ray: &Ray, t_max: f32) -> Option<f32> {
        let i = prim as usize;
        match self.tris.get(i) {
            Some(tri) => accept(K::intersect(tri, ray, ray.t_max), tri.bounds(), ray, t_max),
            None => {
                let s = &self.spheres[i - self.tris.len()];
                accept(
                    intersect_algebraic(s, ray, ray.t_max),
                    s.bounds(),
                    ray,
                    t_max,
                )
            }
        }
    }
}

impl<K: TriangleKernel> ShapeQueries for Mixed<K> {
    fn overlaps_box(&self, prim: u32, cell: &Aabb) -> bool {
        let i = prim as usize;
        match self.tris.get(i) {
            Some(t) => triangle_overlaps_box(t, cell),
            None => sphere_overlaps_box(&self.spheres[i - self.tris.len()], cell),
        }
    }
    fn clipped_bounds(&self, prim: u32, cell: &Aabb) -> Aabb {
        let i = prim as usize;
        match self.tris.get(i) {
            Some(t) => triangle_clipped_bounds(t, cell),
            None => self.spheres[i - self.tris.len()]
                .bounds()
                .intersection(*cell),
        }
    }
    fn normal(&self, prim: u32, ray: &Ray, t: f32) -> Vec3A {
        let i = prim as usize;
        match self.tris.get(i) {
            Some(tri) => tri.normal(),
            None => self.spheres[i - self.tris.len()].normal_at(ray.at(t)),
        }
    }
}

/// Triangles (ids `0..n_tri`), spheres (then `n_sph` ids) and shapes (the rest): triangle kernel
/// `K`, spheres by the stable algebraic kernel, shapes by their kind's kernel
/// ([`Shape::intersect`]). Only scenes with shapes use it, so the others never pay for the
/// shape branch.
#[derive(Debug, Clone)]
pub struct WithShapes<K: TriangleKernel> {
    pub tris: Arc<[Triangle]>,
    pub spheres: Arc<[Sphere]>,
    pub shapes: Arc<[Shape]>,
    kernel: PhantomData<K>,
}

impl<K: TriangleKernel> WithShapes<K> {
    pub fn new(tris: Arc<[Triangle]>, spheres: Arc<[Sphere]>, shapes: Arc<[Shape]>) -> Self {
        WithShapes {
            tris,
            spheres,
            shapes,
            kernel: PhantomData,
        }
    }

    /// Which primitive `prim` is.
    #[inline(always)]
    fn prim(&self, prim: u32) -> Prim<'_> {
        let i = prim as usize;
        let (nt, ns) = (self.tris.len(), self.spheres.len());
        if i < nt {
            Prim::Triangle(&self.tris[i])
        } else if i < nt + ns {
            Prim::Sphere(&self.spheres[i - nt])
        } else {
            Prim::Shape(&self.shapes[i - nt - ns])
        }
    }
}

/// A primitive of a [`WithShapes`] geometry.
enum Prim<'a> {
    Triangle(&'a Triangle),
    Sphere(&'a Sphere),
    Shape(&'a Shape),
}

impl<K: TriangleKernel> Geometry for WithShapes<K> {
    #[inline]
    fn len(&self) -> usize {
        self.tris.len() + self.spheres.len() + self.shapes.len()
    }
    #[inline]
    fn bounds(&self, prim: u32) -> Aabb {
        match self.prim(prim) {
            Prim::Triangle(t) => t.bounds(),
            Prim::Sphere(s) => s.bounds(),
            Prim::Shape(s) => s.bounds(),
        }
    }
    #[inline]
    fn intersect(&self, prim: u32, ray: &Ray, t_max: f32) -> Option<f32> {
        match self.prim(prim) {
            Prim::Triangle(t) => accept(K::intersect(t, ray, ray.t_max), t.bounds(), ray, t_max),
            Prim::Sphere(s) => accept(
                intersect_algebraic(s, ray, ray.t_max),
                s.bounds(),
                ray,
                t_max,
            ),
            Prim::Shape(s) => accept(s.intersect(ray, ray.t_max), s.bounds(), ray, t_max),
        }
    }
}

impl<K: TriangleKernel> ShapeQueries for WithShapes<K> {
    fn overlaps_box(&self, prim: u32, cell: &Aabb) -> bool {
        match self.prim(prim) {
            Prim::Triangle(t) => triangle_overlaps_box(t, cell),
            Prim::Sphere(s) => sphere_overlaps_box(s, cell),
            Prim::Shape(s) => s.overlaps_box(cell),
        }
    }
    fn normal(&self, prim: u32, ray: &Ray, t: f32) -> Vec3A {
        match self.prim(prim) {
            Prim::Triangle(t) => t.normal(),
            Prim::Sphere(s) => s.normal_at(ray.at(t)),
            Prim::Shape(s) => s.normal_at(ray.at(t)),
        }
    }
}

/// Something to run on a concrete geometry type (closures cannot be generic).
pub trait GeometryVisitor {
    type Output;
    fn visit<G: FromScene>(self, geom: G) -> Self::Output;
}

/// A geometry [`with_geometry`] makes from a scene's primitives: the same type over another
/// frame of the same scene (its primitives moved, their kinds and ids kept) is
/// [`FromScene::from_scene`] of that frame.
pub trait FromScene: Geometry {
    fn from_scene(data: &SceneGeometry) -> Self;
}

impl<K: TriangleKernel> FromScene for Triangles<K> {
    fn from_scene(data: &SceneGeometry) -> Self {
        Triangles::new(data.triangles.clone())
    }
}

impl<K: TriangleKernel> FromScene for Mixed<K> {
    fn from_scene(data: &SceneGeometry) -> Self {
        Mixed::new(data.triangles.clone(), data.spheres.clone())
    }
}

impl<K: TriangleKernel> FromScene for WithShapes<K> {
    fn from_scene(data: &SceneGeometry) -> Self {
        WithShapes::new(
            data.triangles.clone(),
            data.spheres.clone(),
            data.shapes.clone(),
        )
    }
}

/// Runs `v` on the geometry type that fits the scene: scenes with shapes get [`WithShapes`],
/// triangle-only scenes [`Triangles`], others [`Mixed`]; the triangle kernel is fixed at
/// compile time inside.
pub fn with_geometry<V: GeometryVisitor>(
    data: &SceneGeometry,
    kernel: TriangleKernelKind,
    v: V,
) -> V::Output {
    fn pick<K: TriangleKernel, V: GeometryVisitor>(data: &SceneGeometry, v: V) -> V::Output {
        if !data.shapes.is_empty() {
            v.visit(WithShapes::<K>::new(
                data.triangles.clone(),
                data.spheres.clone(),
                data.shapes.clone(),
            ))
        } else if data.spheres.is_empty() {
            v.visit(Triangles::<K>::new(data.triangles.clone()))
        } else {
            v.visit(Mixed::<K>::new(
                data.triangles.clone(),
                data.spheres.clone(),
            ))
        }
    }
    match kernel {
        TriangleKernelKind::PlaneEdges => pick::<PlaneEdges, V>(data, v),
        TriangleKernelKind::Parametric => pick::<Parametric, V>(data, v),
        TriangleKernelKind::MollerTrumbore => pick::<MollerTrumbore, V>(data, v),
        TriangleKernelKind::Watertight => pick::<Watertight, V>(data, v),
        TriangleKernelKind::Exact => pick::<Exact, V>(data, v),
    }
}
