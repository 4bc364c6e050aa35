//! The scenes and ray families of the accuracy study: a closed icosphere mesh and a handful of
//! spheres, placed at a translation `offset` from the origin, and rays that are random, aimed
//! exactly at shared vertices and edges, or grazing.
//!
//! Placement: the objects have size `R = max(1, offset * 1e-4)` (scene units), so that at the
//! far offsets the object still spans at least `1e3` ulps of its coordinates and remains a
//! closed, non-degenerate shape. Everything is computed in `f64` and rounded to `f32` once, as a
//! scene file would be.

use crate::geometry::{Ray, Sphere, Triangle};
use crate::rays::SplitMix64;
use crate::scene::generators::icosphere_mesh;
use glam::{DVec3, Vec3, Vec3A};
use serde::Serialize;

/// A family of rays. For the shapes (see `shape_families`) the edge families aim at box edges
/// and corners, polygon edges and vertices, the rims of cylinders and cones and the cone's apex.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Family {
    /// Origins on a sphere of radius `3R` around the object, aimed at uniform points of a box
    /// `1.2R` around it (about half hit).
    Random,
    /// Aimed exactly at the `f32` vertices and edge midpoints of the closed mesh from outside
    /// (origins as in `Random`; triangles only: spheres have no edges). A leak shows as a wrong
    /// (far-side) primitive; a ray touching a silhouette vertex is an exact hit.
    EdgesOutside,
    /// The same targets from near the centre (within `0.1R`): every ray must hit; a miss is a
    /// leak.
    EdgesInside,
    /// Nearly parallel to the surface: at angles log-uniform in `[1e-6, 1e-1]` rad to a
    /// triangle's plane, or passing a sphere's centre at `r (1 - delta)`, `delta` log-uniform in
    /// `[1e-7, 1e-1]`; for the shapes, at such angles to the surface's tangent plane at a
    /// random surface point.
    Grazing,
    /// From inside a solid shape (a ball around its middle) in uniform random directions: every
    /// ray must hit (the exit). Shapes only.
    Inside,
}

impl Family {
    pub const ALL: [Family; 5] = [
        Family::Random,
        Family::EdgesOutside,
        Family::EdgesInside,
        Family::Grazing,
        Family::Inside,
    ];

    /// The families of the triangle mesh and the spheres.
    pub const MESH: [Family; 4] = [
        Family::Random,
        Family::EdgesOutside,
        Family::EdgesInside,
        Family::Grazing,
    ];

    /// `true` for the families aimed at mesh vertices and edges (none for spheres).
    pub fn is_edges(self) -> bool {
        matches!(self, Family::EdgesOutside | Family::EdgesInside)
    }

    pub fn name(self) -> &'static str {
        match self {
            Family::Random => "random",
            Family::EdgesOutside => "edges-outside",
            Family::EdgesInside => "edges-inside",
            Family::Grazing => "grazing",
            Family::Inside => "inside",
        }
    }
}

/// The study's translations from the origin: `0, 1e0 .. 1e7`.
pub fn full_offsets() -> Vec<f64> {
    [0.0]
        .into_iter()
        .chain((0..=7).map(|e| 10f64.powi(e)))
        .collect()
}

/// The object size at a translation (see the module doc).
pub fn object_size(offset: f64) -> f64 {
    (offset * 1e-4).max(1.0)
}

pub(super) fn to_f32(p: DVec3) -> Vec3A {
    Vec3A::from(p.as_vec3())
}

pub(super) fn f64v(p: Vec3A) -> DVec3 {
    Vec3::from(p).as_dvec3()
}

/// The point `(offset, offset, offset) + R * p`, rounded to `f32`.
fn place(p: DVec3, offset: f64) -> Vec3A {
    to_f32(DVec3::splat(offset) + p * object_size(offset))
}

/// The closed unit icosphere of `level` scaled by `R` and translated by `offset` on every axis.
/// Shared vertices stay bit-identical, so the mesh stays closed.
pub fn icosphere_at(level: u32, offset: f64) -> Vec<Triangle> {
    let (v, f) = icosphere_mesh(level);
    let placed: Vec<Vec3A> = v.iter().map(|&p| place(f64v(p), offset)).collect();
    f.iter()
        .map(|&[a, b, c]| Triangle::new(placed[a as usize], placed[b as usize], placed[c as usize]))
        .collect()
}

/// Nine spheres: radius `0.3R` at the corners `(+-0.5R)^3` and `0.15R` at the centre.
pub fn spheres_at(offset: f64) -> Vec<Sphere> {
    let r = object_size(offset);
    let mut s: Vec<Sphere> = (0..8)
        .map(|i| {
            let c = DVec3::new(
                if i & 1 == 0 { -0.5 } else { 0.5 },
                if i & 2 == 0 { -0.5 } else { 0.5 },
                if i & 4 == 0 { -0.5 } else { 0.5 },
            );
            Sphere::new(place(c, offset), (0.3 * r) as f32)
        })
        .collect();
    s.push(Sphere::new(place(DVec3::ZERO, offset), (0.15 * r) as f32));
    s
}

pub(super) fn unit(rng: &mut SplitMix64) -> DVec3 {
    let w = 1.0 - 2.0 * rng.next_unit();
    let phi = std::f64::consts::TAU * rng.next_unit();
    let s = (1.0 - w * w).max(0.0).sqrt();
    DVec3::new(s * phi.cos(), s * phi.sin(), w)
}

pub(super) fn in_cube(rng: &mut SplitMix64) -> DVec3 {
    DVec3::new(rng.next_unit(), rng.next_unit(), rng.next_unit()) * 2.0 - 1.0
}

pub(super) fn log_uniform(rng: &mut SplitMix64, lo: f64, hi: f64) -> f64 {
    (lo.ln() + rng.next_unit() * (hi.ln() - lo.ln())).exp()
}

/// A ray from `o` towards `target` (both already `f32`), direction rounded from `f64`.
pub(super) fn aimed(o: Vec3A, target: Vec3A) -> Option<Ray> {
    let d = f64v(target) - f64v(o);
    Ray::infinite(Vec3::from(o), d.as_vec3()).ok()
}

/// `-1` or `1`, even odds.
pub(super) fn sign(rng: &mut SplitMix64) -> f64 {
    if rng.next_unit() < 0.5 { -1.0 } else { 1.0 }
}

/// A grazing ray through `q`: at an angle log-uniform in `[1e-6, 1e-1]` rad to the plane with
/// unit normal `normal`, from either side, starting `2 size` before `q`.
pub(super) fn grazing(rng: &mut SplitMix64, q: DVec3, normal: DVec3, size: f64) -> Option<Ray> {
    let tangent = normal.cross(unit(rng)).normalize_or_zero();
    let angle = log_uniform(rng, 1e-6, 1e-1);
    let d = tangent * angle.cos() + normal * (sign(rng) * angle.sin());
    let o = q - d * (2.0 * size);
    Ray::infinite(o.as_vec3(), d.as_vec3()).ok()
}

/// Up to `n` rays from `attempt` (which fails on a degenerate ray), giving up after `4n + 16`
/// attempts.
pub(super) fn collect_rays(n: usize, mut attempt: impl FnMut() -> Option<Ray>) -> Vec<Ray> {
    let mut rays = Vec::with_capacity(n);
    for _ in 0..4 * n + 16 {
        if rays.len() >= n {
            break;
        }
        rays.extend(attempt());
    }
    rays
}

/// The primitives of the study's objects as the families aim at them: which families reach
/// them, and a ray of each such family but `Random` (which aims at the object's box, whatever
/// its primitives, in [`family_rays`]).
pub trait FamilyTarget: Sized {
    /// Whether `family` has rays for these primitives (`Random` always does).
    fn has(family: Family) -> bool;
    /// A ray of `family` (one [`Self::has`], not `Random`) at a random one of `prims`, placed
    /// at `offset`; `None` for a degenerate ray.
    fn aimed_at(prims: &[Self], family: Family, rng: &mut SplitMix64, offset: f64) -> Option<Ray>;
}

/// Origins of the `Random` and `EdgesOutside` rays: on the sphere of radius `3R`.
fn outside(rng: &mut SplitMix64, offset: f64) -> Vec3A {
    place(unit(rng) * 3.0, offset)
}

/// A random one of `prims`.
fn pick<'p, P>(prims: &'p [P], rng: &mut SplitMix64) -> &'p P {
    &prims[(rng.next_u64() % prims.len() as u64) as usize]
}

/// Up to `n` rays of `family` for the object of `prims` (placed at `offset`), from `seed`; none
/// for a family the primitives do not have ([`FamilyTarget::has`]).
pub fn family_rays<P: FamilyTarget>(
    family: Family,
    prims: &[P],
    offset: f64,
    n: usize,
    seed: u64,
) -> Vec<Ray> {
    let mut rng = SplitMix64::new(seed);
    if !P::has(family) {
        return Vec::new();
    }
    collect_rays(n, || match family {
        Family::Random => {
            let o = outside(&mut rng, offset);
            aimed(o, place(in_cube(&mut rng) * 1.2, offset))
        }
        _ => P::aimed_at(prims, family, &mut rng, offset),
    })
}

/// The closed mesh: every family but `Inside`.
impl FamilyTarget for Triangle {
    fn has(family: Family) -> bool {
        family != Family::Inside
    }

    fn aimed_at(tris: &[Self], family: Family, rng: &mut SplitMix64, offset: f64) -> Option<Ray> {
        let t = pick(tris, rng);
        if family.is_edges() {
            let k = (rng.next_u64() % 6) as usize;
            // Vertices, or edge midpoints computed in f32 as a renderer would.
            let target = if k < 3 {
                t.v[k]
            } else {
                (t.v[k - 3] + t.v[(k - 2) % 3]) * 0.5
            };
            let o = if family == Family::EdgesOutside {
                outside(rng, offset)
            } else {
                place(in_cube(rng) * 0.1, offset)
            };
            return aimed(o, target);
        }
        // Grazing.
        let v = t.v.map(f64v);
        let n = (v[1] - v[0]).cross(v[2] - v[0]).normalize_or_zero();
        let (b1, b2) = (rng.next_unit(), rng.next_unit());
        let (b1, b2) = if b1 + b2 > 1.0 {
            (1.0 - b1, 1.0 - b2)
        } else {
            (b1, b2)
        };
        let q = v[0] + (v[1] - v[0]) * b1 + (v[2] - v[0]) * b2;
        grazing(rng, q, n, object_size(offset))
    }
}

/// The spheres: `Random` and `Grazing` (no edges; `Inside` is for the shapes).
impl FamilyTarget for Sphere {
    fn has(family: Family) -> bool {
        matches!(family, Family::Random | Family::Grazing)
    }

    fn aimed_at(spheres: &[Self], _: Family, rng: &mut SplitMix64, _: f64) -> Option<Ray> {
        let s = pick(spheres, rng);
        let c = f64v(s.center);
        let r = s.radius as f64;
        let d = unit(rng);
        let side = d.cross(unit(rng)).normalize_or_zero();
        let b = r * (1.0 - log_uniform(rng, 1e-7, 1e-1));
        let o = c + side * b - d * (3.0 * r);
        Ray::infinite(o.as_vec3(), d.as_vec3()).ok()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn families_give_the_requested_rays_at_every_offset() {
        for offset in [0.0, 1e3, 1e7] {
            let tris = icosphere_at(1, offset);
            let spheres = spheres_at(offset);
            for f in Family::MESH {
                assert_eq!(family_rays(f, &tris, offset, 50, 1).len(), 50, "{f:?}");
                let expected = if f.is_edges() { 0 } else { 50 };
                assert_eq!(family_rays(f, &spheres, offset, 50, 1).len(), expected);
            }
            // The placed mesh is non-degenerate.
            assert!(tris.iter().all(|t| !t.is_degenerate()), "offset {offset}");
        }
        assert_eq!(object_size(1e7), 1e3);
    }
}
