//! The shapes of the accuracy study and their ray families.
//!
//! One shape per shape kernel, of size about `R = object_size(offset)`, tilted by a fixed
//! rotation (axis `(1, 2, 3)`, `0.7` rad) so no face, axis or plane is aligned with the world
//! axes, and centred at `(offset, offset, offset)`; computed in `f64` and rounded to `f32` once,
//! as a scene file would be. Ray targets and origins are derived from the shape's stored `f32`
//! data (the shape the kernels see), in `f64`, then rounded to `f32`.

use super::families::{
    Family, aimed, collect_rays, f64v, grazing, in_cube, object_size, sign, to_f32, unit,
};
use super::kernels::Kernel;
use super::shapes_f64::dmat;
use crate::geometry::shapes::{Cone, Cylinder, Ellipsoid, Obb, Polygon};
use crate::geometry::{Ray, Shape, ShapeError};
use crate::rays::SplitMix64;
use glam::{DMat3, DVec3, Mat3A};
use std::f64::consts::TAU;

fn tilt() -> DMat3 {
    DMat3::from_axis_angle(DVec3::new(1.0, 2.0, 3.0).normalize(), 0.7)
}

/// The shape measured by `kernel` at `offset` (see the module doc); `kernel` must be a shape
/// kernel. Every kernel's shape is valid at every offset from `0` to `1e7` (tested).
pub fn shape_at(kernel: Kernel, offset: f64) -> Result<Shape, ShapeError> {
    let r = object_size(offset);
    let c = DVec3::splat(offset);
    let at = |p: DVec3| to_f32(c + tilt() * p * r);
    let axes = Mat3A::from(tilt().as_mat3());
    let ring = |radii: &[f64]| {
        let n = radii.len();
        (0..n)
            .map(|k| {
                let a = TAU * k as f64 / n as f64;
                at(DVec3::new(a.cos(), a.sin(), 0.0) * radii[k])
            })
            .collect::<Vec<_>>()
    };
    Ok(match kernel {
        Kernel::ConvexPolygon => Shape::ConvexPolygon(Polygon::convex(ring(&[0.6; 6]))?),
        // A five-pointed star (simple, concave).
        Kernel::ConcavePolygon => Shape::ConcavePolygon(Polygon::new(ring(&[
            0.6, 0.25, 0.6, 0.25, 0.6, 0.25, 0.6, 0.25, 0.6, 0.25,
        ]))?),
        Kernel::Cylinder => Shape::Cylinder(Cylinder::new(
            at(DVec3::new(0.0, 0.0, -0.5)),
            at(DVec3::new(0.0, 0.0, 0.5)),
            (0.3 * r) as f32,
        )?),
        Kernel::Cone => Shape::Cone(Cone::new(
            at(DVec3::new(0.0, 0.0, -0.4)),
            at(DVec3::new(0.0, 0.0, 0.5)),
            (0.45 * r) as f32,
        )?),
        Kernel::Ellipsoid => Shape::Ellipsoid(Ellipsoid::new(
            at(DVec3::ZERO),
            (DVec3::new(0.6, 0.35, 0.2) * r).as_vec3().into(),
            axes,
        )?),
        _ => Shape::Box(Obb::new(
            at(DVec3::ZERO),
            (DVec3::new(0.5, 0.3, 0.4) * r).as_vec3().into(),
            axes,
        )?),
    })
}

/// The families that apply to a shape kernel: edges for shapes with edges, rims or an apex
/// (not the ellipsoid), rays from inside for solids (not the polygons).
pub fn families(kernel: Kernel) -> Vec<Family> {
    let flat = matches!(kernel, Kernel::ConvexPolygon | Kernel::ConcavePolygon);
    let smooth = kernel == Kernel::Ellipsoid;
    Family::ALL
        .into_iter()
        .filter(|f| match f {
            Family::EdgesOutside => !smooth,
            Family::EdgesInside => !smooth && !flat,
            Family::Inside => !flat,
            Family::Random | Family::Grazing => true,
        })
        .collect()
}

/// Two unit vectors completing `axis` to an orthonormal frame.
fn frame(axis: DVec3) -> (DVec3, DVec3) {
    let u = axis.any_orthonormal_vector();
    (u, axis.cross(u))
}

fn radial(axis: DVec3, rng: &mut SplitMix64) -> DVec3 {
    let (u, v) = frame(axis);
    let a = TAU * rng.next_unit();
    u * a.cos() + v * a.sin()
}

fn pick(rng: &mut SplitMix64, n: usize) -> usize {
    (rng.next_u64() % n as u64) as usize
}

/// A random point of the surface and the outward normal there (the polygon's plane normal).
fn surface_point(shape: &Shape, rng: &mut SplitMix64) -> (DVec3, DVec3) {
    match shape {
        Shape::Box(b) => {
            let (c, h, a) = (f64v(b.center()), f64v(b.half_extents()), dmat(b.axes()));
            let i = pick(rng, 3);
            let s = sign(rng);
            let mut l =
                (DVec3::new(rng.next_unit(), rng.next_unit(), rng.next_unit()) * 2.0 - 1.0) * h;
            l[i] = s * h[i];
            (c + a * l, a.col(i) * s)
        }
        Shape::ConvexPolygon(p) | Shape::ConcavePolygon(p) => {
            let v: Vec<DVec3> = p.vertices().iter().map(|&v| f64v(v)).collect();
            let k = 1 + pick(rng, v.len() - 2);
            let (mut b1, mut b2) = (rng.next_unit(), rng.next_unit());
            if b1 + b2 > 1.0 {
                (b1, b2) = (1.0 - b1, 1.0 - b2);
            }
            let q = v[0] + (v[k] - v[0]) * b1 + (v[k + 1] - v[0]) * b2;
            (q, f64v(p.normal()))
        }
        Shape::Cylinder(c) => {
            let (base, axis) = (f64v(c.base()), f64v(c.axis()));
            let (h, r) = (c.height() as f64, c.radius() as f64);
            let u = radial(axis, rng);
            if rng.next_unit() < 0.5 {
                (base + axis * (h * rng.next_unit()) + u * r, u)
            } else {
                let top = rng.next_unit() < 0.5;
                let q = base + axis * if top { h } else { 0.0 } + u * (r * rng.next_unit().sqrt());
                (q, if top { axis } else { -axis })
            }
        }
        Shape::Cone(c) => {
            let (apex, axis) = (f64v(c.apex()), f64v(c.axis()));
            let (h, r) = (c.height() as f64, c.radius() as f64);
            let u = radial(axis, rng);
            if rng.next_unit() < 0.5 {
                let z = h * rng.next_unit();
                let n = (u * h - axis * r).normalize();
                (apex + axis * z + u * (z * r / h), n)
            } else {
                (apex + axis * h + u * (r * rng.next_unit().sqrt()), axis)
            }
        }
        Shape::Ellipsoid(e) => {
            let (c, radii, a) = (f64v(e.center()), f64v(e.radii()), dmat(e.axes()));
            let s = unit(rng);
            (c + a * (radii * s), (a * (s / radii)).normalize())
        }
    }
}

/// A random point of an edge, corner, rim or apex; `None` for the ellipsoid (it has none).
fn edge_point(shape: &Shape, rng: &mut SplitMix64) -> Option<DVec3> {
    Some(match shape {
        Shape::Box(b) => {
            let (c, h, a) = (f64v(b.center()), f64v(b.half_extents()), dmat(b.axes()));
            let mut l = DVec3::new(sign(rng), sign(rng), sign(rng)) * h;
            if rng.next_unit() < 0.75 {
                // An edge: one coordinate free.
                let i = pick(rng, 3);
                l[i] = (2.0 * rng.next_unit() - 1.0) * h[i];
            }
            c + a * l
        }
        Shape::ConvexPolygon(p) | Shape::ConcavePolygon(p) => {
            let v = p.vertices();
            let k = pick(rng, v.len());
            let (a, b) = (f64v(v[k]), f64v(v[(k + 1) % v.len()]));
            if rng.next_unit() < 1.0 / 3.0 {
                a
            } else {
                a + (b - a) * rng.next_unit()
            }
        }
        Shape::Cylinder(c) => {
            let (base, axis) = (f64v(c.base()), f64v(c.axis()));
            let z = if rng.next_unit() < 0.5 {
                0.0
            } else {
                c.height() as f64
            };
            base + axis * z + radial(axis, rng) * c.radius() as f64
        }
        Shape::Cone(c) => {
            let (apex, axis) = (f64v(c.apex()), f64v(c.axis()));
            if rng.next_unit() < 0.25 {
                apex
            } else {
                apex + axis * c.height() as f64 + radial(axis, rng) * c.radius() as f64
            }
        }
        Shape::Ellipsoid(_) => return None,
    })
}

/// A ball inside a solid shape (centre, radius); `None` for the polygons.
fn inner_ball(shape: &Shape) -> Option<(DVec3, f64)> {
    Some(match shape {
        Shape::Box(b) => (
            f64v(b.center()),
            0.5 * b.half_extents().min_element() as f64,
        ),
        Shape::Cylinder(c) => {
            let (h, r) = (c.height() as f64, c.radius() as f64);
            (
                f64v(c.base()) + f64v(c.axis()) * (0.5 * h),
                0.5 * r.min(0.5 * h),
            )
        }
        Shape::Cone(c) => {
            let (h, r) = (c.height() as f64, c.radius() as f64);
            // At 0.7 h from the apex: 0.3 h from the base, 0.7 r h / |(h, r)| from the side.
            let to_side = 0.7 * r * h / h.hypot(r);
            (
                f64v(c.apex()) + f64v(c.axis()) * (0.7 * h),
                0.5 * to_side.min(0.3 * h),
            )
        }
        Shape::Ellipsoid(e) => (f64v(e.center()), 0.5 * e.radii().min_element() as f64),
        Shape::ConvexPolygon(_) | Shape::ConcavePolygon(_) => return None,
    })
}

/// Rays of `family` for `shape` (placed at `offset`): `n` rays, or none when the family does
/// not apply to the shape (see [`families`]).
pub fn shape_rays(family: Family, shape: &Shape, offset: f64, n: usize, seed: u64) -> Vec<Ray> {
    let mut rng = SplitMix64::new(seed);
    let r = object_size(offset);
    let bounds = shape.bounds();
    let centre = f64v(bounds.center());
    let half = f64v(bounds.extent()) * 0.5;
    let ball = inner_ball(shape);
    let edges = !matches!(shape, Shape::Ellipsoid(_));
    let applies = match family {
        Family::EdgesOutside => edges,
        Family::EdgesInside => edges && ball.is_some(),
        Family::Inside => ball.is_some(),
        Family::Random | Family::Grazing => true,
    };
    if !applies {
        return Vec::new();
    }
    let inside = |rng: &mut SplitMix64| {
        let (c, radius) = ball.unwrap_or((centre, 0.0));
        to_f32(c + in_cube(rng) * (radius / 3f64.sqrt()))
    };
    collect_rays(n, || {
        let outside = to_f32(centre + unit(&mut rng) * (3.0 * r));
        match family {
            Family::Random => aimed(outside, to_f32(centre + in_cube(&mut rng) * half * 1.2)),
            Family::EdgesOutside => {
                edge_point(shape, &mut rng).and_then(|t| aimed(outside, to_f32(t)))
            }
            Family::EdgesInside => {
                let o = inside(&mut rng);
                edge_point(shape, &mut rng).and_then(|t| aimed(o, to_f32(t)))
            }
            Family::Inside => {
                let o = inside(&mut rng);
                Ray::infinite(o.into(), unit(&mut rng).as_vec3()).ok()
            }
            Family::Grazing => {
                let (q, normal) = surface_point(shape, &mut rng);
                grazing(&mut rng, q, normal, r)
            }
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_shape_is_valid_and_gets_its_families_at_every_offset() {
        for k in Kernel::SHAPES {
            for offset in super::super::families::full_offsets() {
                let shape = shape_at(k, offset).unwrap_or_else(|e| panic!("{k:?} {offset}: {e}"));
                let fams = families(k);
                for f in Family::ALL {
                    let expected = if fams.contains(&f) { 40 } else { 0 };
                    let rays = shape_rays(f, &shape, offset, 40, 3);
                    assert_eq!(rays.len(), expected, "{k:?} {f:?} at {offset}");
                }
                // Rays from inside start inside: the kernel finds the exit for every one.
                if fams.contains(&Family::Inside) {
                    for ray in shape_rays(Family::Inside, &shape, offset, 40, 3) {
                        assert!(
                            shape.intersect(&ray, f32::INFINITY).is_some(),
                            "{k:?} {ray:?}"
                        );
                    }
                }
            }
        }
        assert_eq!(families(Kernel::Ellipsoid).len(), 3);
        assert_eq!(families(Kernel::ConcavePolygon).len(), 3);
        assert_eq!(families(Kernel::Cone).len(), 5);
    }
}
