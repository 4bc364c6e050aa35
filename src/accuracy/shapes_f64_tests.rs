//! Tests of the `f64` shape mirrors against hand-computed and `f32` kernel answers.

use super::*;
use crate::accuracy::kernels::Kernel;
use crate::geometry::shapes::obb;
use crate::geometry::test_support::ray;
use glam::{Mat3A, Vec3};

/// [`super::reference`] for the kernel `k`.
fn reference(k: Kernel, s: &Shape, r: &Ray) -> Reference {
    super::reference(k == Kernel::BoxFrontPlanes, s, r)
}

/// [`super::mirror`] for the kernel `k`.
fn mirror(k: Kernel, s: &Shape, r: &Ray64, t_max: f64, d: &mut Doubt) -> Option<f64> {
    super::mirror(k == Kernel::BoxFrontPlanes, s, r, t_max, d)
}

fn shapes() -> Vec<(Kernel, Shape)> {
    let tilt = Mat3A::from_axis_angle(Vec3::new(1.0, 2.0, 3.0).normalize(), 0.7);
    let b = Obb::new(Vec3A::new(0.2, 0.1, 4.0), Vec3A::new(0.7, 0.5, 0.9), tilt).unwrap();
    let square = |z: f32| {
        vec![
            Vec3A::new(-1.0, -1.0, z),
            Vec3A::new(1.0, -1.0, z),
            Vec3A::new(1.0, 1.0, z),
            Vec3A::new(-1.0, 1.0, z),
        ]
    };
    let mut ell = square(4.0);
    ell.insert(2, Vec3A::new(0.0, 0.0, 4.0));
    vec![
        (Kernel::BoxSlabs, Shape::Box(b)),
        (Kernel::BoxFrontPlanes, Shape::Box(b)),
        (
            Kernel::ConvexPolygon,
            Shape::ConvexPolygon(Polygon::convex(square(4.0)).unwrap()),
        ),
        (
            Kernel::ConcavePolygon,
            Shape::ConcavePolygon(Polygon::new(ell).unwrap()),
        ),
        (
            Kernel::Cylinder,
            Shape::Cylinder(
                Cylinder::new(Vec3A::new(0.0, -0.5, 3.0), Vec3A::new(0.3, 0.6, 5.0), 0.8).unwrap(),
            ),
        ),
        (
            Kernel::Cone,
            Shape::Cone(
                Cone::new(Vec3A::new(0.1, 0.0, 3.0), Vec3A::new(-0.2, 0.3, 5.0), 1.0).unwrap(),
            ),
        ),
        (
            Kernel::Ellipsoid,
            Shape::Ellipsoid(
                Ellipsoid::new(Vec3A::new(0.0, 0.2, 4.0), Vec3A::new(1.0, 0.6, 0.4), tilt).unwrap(),
            ),
        ),
    ]
}

fn f32_kernel(k: Kernel, s: &Shape, r: &Ray) -> Option<f32> {
    match (k, s) {
        (Kernel::BoxFrontPlanes, Shape::Box(b)) => obb::intersect_front_planes(b, r, r.t_max),
        _ => s.intersect(r, r.t_max),
    }
}

/// On rays well away from every edge, rim and tangent each mirror agrees with its `f32`
/// original on hit or miss, to `f32` precision on `t`, and is certain of its answer.
#[test]
fn mirrors_agree_with_the_f32_kernels_on_easy_rays() {
    let mut hits = [0usize; 7];
    let mut misses = [0usize; 7];
    for (i, (k, s)) in shapes().iter().enumerate() {
        for (o, d) in [
            ([0.05, 0.1, 0.0], [0.0, 0.0, 1.0]),
            ([0.0, 0.0, 0.0], [0.03, 0.05, 1.0]),
            ([0.1, -0.1, 9.0], [0.01, 0.02, -1.0]),
            ([5.0, 5.0, 0.0], [0.0, 0.0, 1.0]),
            ([0.0, 0.0, 0.0], [0.0, 0.0, -1.0]),
            ([-4.0, 0.1, 4.1], [1.0, 0.0, 0.0]),
        ] {
            let r = ray(o, d);
            let a = f32_kernel(*k, s, &r);
            let mut doubt = Doubt::default();
            let b = mirror(*k, s, &Ray64::from_ray(&r), f64::INFINITY, &mut doubt);
            assert!(!doubt.0, "{k:?} doubts an easy ray {o:?} {d:?}");
            assert_eq!(
                a.is_some(),
                b.is_some(),
                "{k:?} {o:?} {d:?}: {a:?} vs {b:?}"
            );
            if let (Some(a), Some(b)) = (a, b) {
                assert!((a as f64 - b).abs() <= 1e-5 * b.abs(), "{k:?}: {a} vs {b}");
                hits[i] += 1;
            } else {
                misses[i] += 1;
            }
        }
    }
    assert!(hits.iter().all(|&h| h >= 2), "{hits:?}");
    assert!(misses.iter().all(|&m| m >= 2), "{misses:?}");
}

/// One hand-checked hit per mirror, and one ray through an edge, rim or tangent that the
/// reference must call unverifiable.
#[test]
fn hand_checked_cases() {
    let check = |k: Kernel, s: Shape, r: Ray, t: f64| {
        let Reference::Hit(got) = reference(k, &s, &r) else {
            panic!("{k:?}: {:?}", reference(k, &s, &r))
        };
        assert!((got - t).abs() <= 1e-12 * t, "{k:?}: {got} vs {t}");
    };
    // Unit cube at (0, 0, 5) turned 90 degrees about z (still the same cube): from the
    // origin along +z it enters z = 4.5; from inside it exits at y = 0.5.
    let cube = Shape::Box(
        Obb::new(
            Vec3A::new(0.0, 0.0, 5.0),
            Vec3A::splat(0.5),
            Mat3A::from_rotation_z(std::f32::consts::FRAC_PI_2),
        )
        .unwrap(),
    );
    for k in [Kernel::BoxSlabs, Kernel::BoxFrontPlanes] {
        check(k, cube.clone(), ray([0.1, 0.2, 0.0], [0.0, 0.0, 2.0]), 2.25);
        check(k, cube.clone(), ray([0.0, 0.0, 5.0], [0.0, 1.0, 0.0]), 0.5);
        // Touching only the edge x = 0.5, z = 4.5 of the axis-aligned cube (the line
        // x - z = -4 of the plane y = 0).
        let aligned = Shape::Box(
            Obb::new(
                Vec3A::new(0.0, 0.0, 5.0),
                Vec3A::splat(0.5),
                Mat3A::IDENTITY,
            )
            .unwrap(),
        );
        assert_eq!(
            reference(k, &aligned, &ray([-1.0, 0.0, 3.0], [1.0, 0.0, 1.0])),
            Reference::Unverifiable,
            "{k:?}"
        );
    }
    // The square |x|, |y| <= 1 at z = 4, as a convex and as a concave polygon: a hit at
    // t = 4, a miss beside it, and a ray through its edge x = 1: unverifiable.
    let square = vec![
        Vec3A::new(-1.0, -1.0, 4.0),
        Vec3A::new(1.0, -1.0, 4.0),
        Vec3A::new(1.0, 1.0, 4.0),
        Vec3A::new(-1.0, 1.0, 4.0),
    ];
    let convex = Shape::ConvexPolygon(Polygon::convex(square.clone()).unwrap());
    let concave = Shape::ConcavePolygon(Polygon::new(square).unwrap());
    for (k, s) in [
        (Kernel::ConvexPolygon, convex),
        (Kernel::ConcavePolygon, concave),
    ] {
        check(k, s.clone(), ray([0.5, 0.25, 0.0], [0.0, 0.0, 1.0]), 4.0);
        assert_eq!(
            reference(k, &s, &ray([3.0, 0.5, 4.0], [0.0, 0.0, 1.0])),
            Reference::Miss,
            "{k:?}: beside"
        );
        assert_eq!(
            reference(k, &s, &ray([1.0, 0.5, 0.0], [0.0, 0.0, 1.0])),
            Reference::Unverifiable,
            "{k:?}"
        );
    }
    // Cylinder of radius 1 around z from z = 2 to z = 6: the side at x = -1 from x = -5
    // (t = 4), the bottom cap from below (t = 2), a line touching only the rim: unverifiable.
    let cyl = Shape::Cylinder(
        Cylinder::new(Vec3A::new(0.0, 0.0, 2.0), Vec3A::new(0.0, 0.0, 6.0), 1.0).unwrap(),
    );
    check(
        Kernel::Cylinder,
        cyl.clone(),
        ray([-5.0, 0.0, 3.0], [1.0, 0.0, 0.0]),
        4.0,
    );
    check(
        Kernel::Cylinder,
        cyl.clone(),
        ray([0.5, 0.0, 0.0], [0.0, 0.0, 1.0]),
        2.0,
    );
    assert_eq!(
        reference(
            Kernel::Cylinder,
            &cyl,
            &ray([-2.0, 0.0, 3.0], [1.0, 0.0, -1.0])
        ),
        Reference::Unverifiable
    );
    // Cone with apex (0, 0, 2), base radius 2 at z = 4 (slope 1): along -x at z = 3 the side
    // is at x = 1 (t = 4 from x = 5); straight up the axis, the base at t = 4; through the
    // apex exactly: unverifiable.
    let cone =
        Shape::Cone(Cone::new(Vec3A::new(0.0, 0.0, 4.0), Vec3A::new(0.0, 0.0, 2.0), 2.0).unwrap());
    check(
        Kernel::Cone,
        cone.clone(),
        ray([5.0, 0.0, 3.0], [-1.0, 0.0, 0.0]),
        4.0,
    );
    check(
        Kernel::Cone,
        cone.clone(),
        ray([0.0, 0.5, 8.0], [0.0, 0.0, -1.0]),
        4.0,
    );
    assert_eq!(
        reference(Kernel::Cone, &cone, &ray([-0.5, 0.0, 1.0], [0.5, 0.0, 1.0])),
        Reference::Unverifiable
    );
    // Ellipsoid radii (2, 1, 0.5) at (0, 0, 5): along +z at x = 1 it enters at
    // z = 5 - 0.5 sqrt(3/4); along x at y = 1 exactly tangent: unverifiable.
    let e = Shape::Ellipsoid(
        Ellipsoid::new(
            Vec3A::new(0.0, 0.0, 5.0),
            Vec3A::new(2.0, 1.0, 0.5),
            Mat3A::IDENTITY,
        )
        .unwrap(),
    );
    check(
        Kernel::Ellipsoid,
        e.clone(),
        ray([1.0, 0.0, 0.0], [0.0, 0.0, 1.0]),
        5.0 - 0.5 * 0.75f64.sqrt(),
    );
    assert_eq!(
        reference(
            Kernel::Ellipsoid,
            &e,
            &ray([-5.0, 1.0, 5.0], [1.0, 0.0, 0.0])
        ),
        Reference::Unverifiable
    );
}
