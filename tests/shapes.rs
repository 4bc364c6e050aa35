//! Every registered index returns brute force's hits bit for bit on scenes with every primitive
//! kind (issue 10), with protocol rays, rays aimed exactly at shape vertices, edges, corners,
//! rims and apexes, and rays through the edges polygons share.

mod common;

use accelbench::geometry::{Ray, Shape};
use accelbench::index::index_names;
use accelbench::scene::{Scene, generators};
use glam::{Vec3, Vec3A};

/// Points on the features of a shape where kernels and cells are most fragile.
fn feature_points(s: &Shape) -> Vec<Vec3A> {
    match s {
        Shape::Box(b) => {
            let (c, h, m) = (b.center(), b.half_extents(), b.axes());
            vec![
                c + m * h,
                c + m * (h * Vec3A::new(1.0, -1.0, 0.0)),
                c + m * (h * Vec3A::new(0.0, 0.0, -1.0)),
            ]
        }
        Shape::ConvexPolygon(p) | Shape::ConcavePolygon(p) => {
            let v = p.vertices();
            (0..v.len())
                .flat_map(|i| [v[i], (v[i] + v[(i + 1) % v.len()]) * 0.5])
                .collect()
        }
        Shape::Cylinder(c) => vec![c.base(), c.top(), (c.base() + c.top()) * 0.5],
        Shape::Cone(c) => vec![c.apex(), c.base()],
        Shape::Ellipsoid(e) => vec![e.center() + e.axes().x_axis * e.radii().x],
    }
}

/// The kit's rays plus rays from two viewpoints at every feature point of a sample of shapes.
fn shape_rays(scene: &Scene, n: usize) -> Vec<Ray> {
    let mut rays = common::agreement_rays(scene, n);
    let b = scene.ray_set_bounds();
    let c = Vec3::from(b.center());
    let eye = c + Vec3::from(b.extent()) * Vec3::new(-0.8, 0.9, 1.2);
    for s in scene
        .shapes
        .iter()
        .step_by((scene.shapes.len() / (n / 8).max(1)).max(1))
    {
        for p in feature_points(s) {
            for o in [eye, c] {
                if let Ok(r) = Ray::infinite(o, Vec3::from(p) - o) {
                    rays.push(r);
                }
            }
        }
    }
    rays
}

#[test]
fn every_index_agrees_with_brute_force_on_all_primitive_kinds() {
    let scenes = [
        generators::generate("shapes", 1500, 7).unwrap(),
        // Dense: many overlapping shapes per cell and ray.
        generators::generate("shapes", 300, 11).unwrap(),
    ];
    for scene in &scenes {
        let kinds: std::collections::BTreeSet<_> = scene.shapes.iter().map(Shape::kind).collect();
        assert_eq!(kinds.len(), 6, "{kinds:?}");
        let rays = shape_rays(scene, 1500);
        for name in index_names() {
            common::assert_agrees(name, scene, &rays);
        }
    }
}

/// A ray through the edge two polygons of the generator share hits exactly one of them: the
/// scene-level view of the concave kernel's edge rule (brute force returns a hit, and no ray
/// at the shared edge falls through to what lies behind).
#[test]
fn rays_through_shared_polygon_edges_hit_one_of_the_pair() {
    let scene = generators::generate("shapes", 400, 5).unwrap();
    let geom = scene.geometry();
    let first_shape = (scene.triangles.len() + scene.spheres.len()) as u32;
    let pairs: Vec<usize> = (1..scene.shapes.len())
        .filter(|&i| {
            matches!(
                (&scene.shapes[i - 1], &scene.shapes[i]),
                (Shape::ConcavePolygon(_), Shape::ConcavePolygon(_))
            )
        })
        .collect();
    assert!(pairs.len() >= 40, "{}", pairs.len());
    let mut checked = 0;
    for &i in &pairs {
        let (Shape::ConcavePolygon(a), Shape::ConcavePolygon(_)) =
            (&scene.shapes[i - 1], &scene.shapes[i])
        else {
            unreachable!()
        };
        // The arrow's second edge (vertices 1 and 2) is the square's fourth.
        let (p, q) = (a.vertices()[1], a.vertices()[2]);
        for f in [0.1f32, 0.37, 0.5, 0.81] {
            let target = Vec3::from(p + (q - p) * f);
            let o = target + Vec3::from(a.normal()) * 0.3 + Vec3::new(0.01, 0.02, -0.015);
            let r = Ray::infinite(o, target - o).unwrap();
            let hits: Vec<u32> = [i - 1, i]
                .iter()
                .map(|&k| first_shape + k as u32)
                .filter(|&prim| {
                    accelbench::scene::with_geometry(
                        &geom,
                        accelbench::geometry::TriangleKernelKind::Watertight,
                        Probe { prim, ray: r },
                    )
                })
                .collect();
            assert_eq!(
                hits.len(),
                1,
                "ray {r:?} at the edge of shapes {} and {i}",
                i - 1
            );
            checked += 1;
        }
    }
    assert_eq!(checked, pairs.len() * 4);
}

/// Does `ray` hit primitive `prim` (through the scene's geometry, as indices see it)?
struct Probe {
    prim: u32,
    ray: Ray,
}

impl accelbench::scene::GeometryVisitor for Probe {
    type Output = bool;
    fn visit<G: accelbench::scene::Geometry>(self, geom: G) -> bool {
        geom.intersect(self.prim, &self.ray, self.ray.t_max)
            .is_some()
    }
}
