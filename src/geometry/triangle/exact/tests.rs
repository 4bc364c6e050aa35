//! The exact kernel against the accuracy study's exact reference (Shewchuk's `orient3d` on
//! exact `f64` differences) on rays built to sit on, or one ulp beside, edges and vertices.

use super::*;
use crate::geometry::expansion;
use crate::geometry::reference::{self, Reference};
use crate::geometry::test_support::unit_floats as lcg;
use glam::Vec3;

/// The `f32` `steps` ulps away from `x` (toward +inf for positive `steps`).
fn ulps(x: f32, steps: i32) -> f32 {
    let mut y = x;
    for _ in 0..steps.abs() {
        y = if steps > 0 {
            y.next_up()
        } else {
            y.next_down()
        };
    }
    y
}

/// Asserts the kernel's line decision equals the reference's (when the reference can certify
/// it and the hit is clearly in front of the origin); returns how many were compared.
fn check(tri: &Triangle, ray: &Ray) -> usize {
    let got = Exact::intersect(tri, ray, f32::INFINITY);
    match reference::triangle(tri, ray) {
        Reference::Unverifiable => 0,
        Reference::Miss => {
            // A reference miss behind the origin can be a kernel hit at t = 0 after rounding.
            assert!(
                got.is_none_or(|t| t == 0.0),
                "{tri:?} {ray:?}: got {got:?}, exact miss"
            );
            1
        }
        Reference::Hit(t) => {
            assert!(
                got.is_some() || t == 0.0,
                "{tri:?} {ray:?}: exact hit at {t}, got miss"
            );
            1
        }
    }
}

fn random_triangle(next: &mut impl FnMut() -> f32, scale: f32, offset: Vec3A) -> Triangle {
    let mut p = || offset + Vec3A::new(next(), next(), next()) * scale;
    Triangle::new(p(), p(), p())
}

#[test]
fn rays_at_and_one_ulp_beside_vertices_and_edges_decide_exactly() {
    let mut next = lcg(7);
    let mut compared = 0;
    for offset in [0.0, 1.0, 1e3, 1e5, 1e7] {
        for _ in 0..300 {
            let tri = random_triangle(&mut next, 1.0, Vec3A::splat(offset));
            let o = Vec3::splat(offset) + Vec3::new(next(), next(), -3.0 - next());
            let (a, b) = (tri.v[0], tri.v[1]);
            let f = next();
            let targets = [a, b, a + (b - a) * f, a + (b - a) * 0.5];
            for target in targets {
                let dir = Vec3::from(target) - o;
                for (dx, dy) in [(0, 0), (1, 0), (-1, 0), (0, 1), (0, -1), (2, -2)] {
                    let d = Vec3::new(ulps(dir.x, dx), ulps(dir.y, dy), dir.z);
                    let Ok(ray) = Ray::infinite(o, d) else {
                        continue;
                    };
                    compared += check(&tri, &ray);
                }
            }
        }
    }
    assert!(compared > 30_000, "{compared} compared");
}

#[test]
fn axis_aligned_rays_through_exact_vertices_and_edges() {
    // Integer corners: rays along z through grid points land exactly on edges and vertices,
    // where every edge function sign is zero or tiny and the filter cannot decide.
    let tri = Triangle::from_corners([0.0, 0.0, 2.0], [4.0, 0.0, 2.0], [0.0, 4.0, 2.0]);
    let before = fallback_count();
    for x in -1..=5 {
        for y in -1..=5 {
            for (dx, dy) in [(0, 0), (1, 0), (-1, 0), (0, 1), (0, -1)] {
                let o = Vec3::new(ulps(x as f32, dx), ulps(y as f32, dy), 0.0);
                let ray = Ray::infinite(o, Vec3::Z).unwrap();
                check(&tri, &ray);
                let (x, y) = (o.x as f64, o.y as f64);
                let (sum, err) = expansion::two_sum(x, y); // x + y = sum + err exactly
                let inside = x >= 0.0 && y >= 0.0 && (sum < 4.0 || (sum == 4.0 && err <= 0.0));
                assert_eq!(
                    Exact::intersect(&tri, &ray, f32::INFINITY).is_some(),
                    inside,
                    "{o}"
                );
            }
        }
    }
    assert!(fallback_count() > before, "the fallback was never taken");
}

#[test]
fn shared_edges_and_vertices_are_hit_by_both_triangles() {
    // Two triangles sharing the diagonal of a square; a fan of six around a vertex.
    let p = |x: f32, y: f32| Vec3A::new(x, y, 1.0);
    let square = [
        Triangle::new(p(0.1, 0.3), p(1.7, 0.2), p(1.3, 1.9)),
        Triangle::new(p(0.1, 0.3), p(1.3, 1.9), p(-0.2, 1.1)),
    ];
    let mut next = lcg(3);
    for _ in 0..2000 {
        let f = next();
        let (a, c) = (square[0].v[0], square[0].v[2]);
        let target = a + (c - a) * f;
        let o = Vec3::new(next() * 4.0 - 2.0, next() * 4.0 - 2.0, -2.0);
        let ray = Ray::infinite(o, Vec3::from(target) - o).unwrap();
        let hits = square.map(|t| Exact::intersect(&t, &ray, f32::INFINITY).is_some());
        assert!(hits[0] || hits[1], "leak through the shared edge: {ray:?}");
        for t in &square {
            check(t, &ray);
        }
    }
}

#[test]
fn degenerate_parallel_and_in_plane_rays_miss() {
    let line = Triangle::new(Vec3A::ZERO, Vec3A::X, Vec3A::X * 2.0);
    let through = Ray::infinite(Vec3::new(1.0, 0.0, -1.0), Vec3::Z).unwrap();
    assert_eq!(Exact::intersect(&line, &through, f32::INFINITY), None);
    let tri = Triangle::new(Vec3A::ZERO, Vec3A::X, Vec3A::Y);
    let in_plane = Ray::infinite(Vec3::new(-1.0, 0.25, 0.0), Vec3::X).unwrap();
    assert_eq!(Exact::intersect(&tri, &in_plane, f32::INFINITY), None);
    let parallel = Ray::infinite(Vec3::new(-1.0, 0.25, 1.0), Vec3::X).unwrap();
    assert_eq!(Exact::intersect(&tri, &parallel, f32::INFINITY), None);
}

#[test]
fn exact_edge_sign_matches_orient3d_where_differences_are_exact() {
    let mut next = lcg(11);
    for _ in 0..5000 {
        let v = |n: &mut dyn FnMut() -> f32| Vec3A::new(n() * 8.0, n() * 8.0, n() * 8.0);
        let (p, q) = (v(&mut next), v(&mut next));
        let o = Vec3::new(next(), next(), next()) * 8.0;
        // Aim at a point of the edge p q so the sign is often zero or tiny.
        let target = p + (q - p) * (next() * 2.0 - 0.5);
        let Ok(ray) = Ray::infinite(o, Vec3::from(target) - o) else {
            continue;
        };
        let f = |x: Vec3A| [x.x as f64, x.y as f64, x.z as f64];
        let (o64, d64) = (f(ray.origin), f(ray.dir));
        let sub = |x: [f64; 3]| [x[0] - o64[0], x[1] - o64[1], x[2] - o64[2]];
        let c = |x: [f64; 3]| robust::Coord3D {
            x: x[0],
            y: x[1],
            z: x[2],
        };
        let want = robust::orient3d(c(d64), c(sub(f(p))), c(sub(f(q))), c([0.0; 3]));
        let want = (want > 0.0) as i32 - (want < 0.0) as i32;
        assert_eq!(exact_edge_sign(p, q, &ray), Some(want), "{p} {q} {ray:?}");
    }
}
