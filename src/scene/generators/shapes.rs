//! A seeded field of every primitive kind: triangles, spheres, oriented boxes, convex and
//! concave polygons, capped cylinders and cones, ellipsoids.

use super::random::{per_object, point, unit_vector};
use crate::geometry::shapes::{Cone, Cylinder, Ellipsoid, Obb, Polygon};
use crate::geometry::{Shape, Sphere, Triangle};
use crate::rays::SplitMix64;
use crate::scene::Scene;
use glam::{Mat3A, Vec3A};

/// About `n` primitives in the unit cube, cycling through eight slots: a triangle, a sphere, a
/// box, a convex polygon (regular 3- to 8-gon), a pair of polygons sharing an edge (a concave
/// arrow and a square, both by the concave kernel, so rays through the shared edge test the
/// edge rule), a cylinder, a cone and an ellipsoid. Random centres, orientations and sizes of
/// about `0.6 / cbrt(n)`, like the sphere field. Kinds are stored as the scene orders them
/// (triangles, spheres, shapes), each in generation order.
pub fn shape_field(name: &str, n: usize, seed: u64) -> Scene {
    let mut rng = SplitMix64::new(seed);
    let r0 = per_object(0.6, n);
    let mut scene = Scene {
        name: name.to_owned(),
        ..Scene::default()
    };
    for i in 0..n {
        let c = point(&mut rng);
        let size = r0 * (0.5 + 0.5 * rng.next_unit() as f32);
        let rot = Mat3A::from_axis_angle(
            unit_vector(&mut rng).into(),
            (std::f64::consts::TAU * rng.next_unit()) as f32,
        );
        let place = |x: f32, y: f32| c + rot * Vec3A::new(x, y, 0.0) * size;
        let axis = rot.z_axis * size;
        let built = match i % 8 {
            0 => {
                scene.triangles.push(Triangle::new(
                    place(-1.0, -0.7),
                    place(1.0, -0.5),
                    place(0.1, 1.0),
                ));
                continue;
            }
            1 => {
                scene.spheres.push(Sphere::new(c, size));
                continue;
            }
            2 => Obb::new(c, Vec3A::new(1.0, 0.6, 0.3) * size, rot).map(Shape::Box),
            3 => {
                let k = 3 + (rng.next_u64() % 6) as usize;
                let verts = (0..k)
                    .map(|j| {
                        let a = std::f32::consts::TAU * j as f32 / k as f32;
                        place(a.cos(), a.sin())
                    })
                    .collect();
                Polygon::convex(verts).map(Shape::ConvexPolygon)
            }
            4 => {
                let arrow = [
                    (-1.0, -0.5),
                    (0.0, -0.5),
                    (0.0, 0.5),
                    (-1.0, 0.5),
                    (-0.6, 0.0),
                ];
                let square = [(0.0, -0.5), (1.0, -0.5), (1.0, 0.5), (0.0, 0.5)];
                let poly = |pts: &[(f32, f32)]| {
                    Polygon::new(pts.iter().map(|&(x, y)| place(x, y)).collect())
                        .map(Shape::ConcavePolygon)
                };
                poly(&arrow).and_then(|a| {
                    scene.shapes.push(a);
                    poly(&square)
                })
            }
            5 => Cylinder::new(c - axis, c + axis, size * 0.4).map(Shape::Cylinder),
            6 => Cone::new(c - axis, c + axis, size * 0.6).map(Shape::Cone),
            _ => Ellipsoid::new(c, Vec3A::new(1.0, 0.5, 0.25) * size, rot).map(Shape::Ellipsoid),
        };
        scene
            .shapes
            .push(built.expect("generated shapes have positive sizes and unit frames"));
    }
    scene
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_kind_is_present_and_seeded() {
        let s = shape_field("shapes", 80, 3);
        let kinds: std::collections::BTreeSet<_> = s.shapes.iter().map(Shape::kind).collect();
        assert_eq!(kinds.len(), 6, "{kinds:?}");
        assert_eq!(
            (s.triangles.len(), s.spheres.len(), s.shapes.len()),
            (10, 10, 70)
        );
        assert_eq!(shape_field("shapes", 80, 3).shapes, s.shapes);
        assert_ne!(shape_field("shapes", 80, 4).shapes, s.shapes);
        assert!(s.validate().is_ok());
    }
}
