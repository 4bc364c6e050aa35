//! Every registered index returns brute force's hits bit for bit on scenes with every primitive
//! kind (issue 10), with protocol rays, rays aimed exactly at shape vertices, edges, corners,
//! rims and apexes, and rays through the edges polygons share.

use crate::common;

use crate::common::temp::temp_path;
use accelbench::geometry::{Ray, Shape};
use accelbench::index::{index_names, is_peer};
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
        // Our indices must agree; the obvhs peers (index::is_peer) lose some hits by design of
        // their own box tests and are checked in tests/it/obvhs_peer.rs.
        for name in index_names().into_iter().filter(|n| !is_peer(n)) {
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
    fn visit<G: accelbench::scene::FromScene>(self, geom: G) -> bool {
        geom.intersect(self.prim, &self.ray, self.ray.t_max)
            .is_some()
    }
}

/// The overlap tests grids, octrees and kd-trees store shapes by are conservative where it
/// matters: the point where the shared kernel reports a hit lies in a cell that the shape's
/// `overlaps_box` accepts, for every kind; and the exact tests (boxes, polygons) do reject some
/// cells their bounds touch.
#[test]
fn hit_points_lie_in_cells_the_overlap_test_accepts() {
    let scene = generators::generate("shapes", 800, 3).unwrap();
    let rays = common::agreement_rays(&scene, 3000);
    let geom = scene.geometry();
    let first_shape = (scene.triangles.len() + scene.spheres.len()) as u32;
    let report = accelbench::scene::with_geometry(
        &geom,
        accelbench::geometry::TriangleKernelKind::Watertight,
        CellCheck {
            bounds: scene.bounds(),
            cells: 12,
            first: first_shape,
            rays,
        },
    );
    assert!(report.hits > 2000, "{report:?}");
    assert_eq!(report.missing, Vec::<String>::new());
    assert!(report.rejected_by_exact_test > 100, "{report:?}");
}

#[derive(Debug)]
struct CellReport {
    hits: usize,
    missing: Vec<String>,
    rejected_by_exact_test: usize,
}

struct CellCheck {
    bounds: accelbench::geometry::Aabb,
    cells: usize,
    first: u32,
    rays: Vec<Ray>,
}

impl accelbench::scene::GeometryVisitor for CellCheck {
    type Output = CellReport;
    fn visit<G: accelbench::scene::FromScene>(self, geom: G) -> CellReport {
        use accelbench::geometry::Aabb;
        let size = self.bounds.extent() / self.cells as f32;
        let cell = |i: [usize; 3]| {
            let lo = self.bounds.min + size * Vec3A::new(i[0] as f32, i[1] as f32, i[2] as f32);
            Aabb::new(lo, lo + size)
        };
        let mut report = CellReport {
            hits: 0,
            missing: Vec::new(),
            rejected_by_exact_test: 0,
        };
        for prim in self.first..geom.len() as u32 {
            for r in &self.rays {
                let Some(t) = geom.intersect(prim, r, r.t_max) else {
                    continue;
                };
                report.hits += 1;
                let p = r.at(t);
                let rel = (p - self.bounds.min) / size;
                let i = rel
                    .to_array()
                    .map(|x| (x.max(0.0) as usize).min(self.cells - 1));
                if !geom.overlaps_box(prim, &cell(i)) {
                    report
                        .missing
                        .push(format!("prim {prim} at {p:?} ray {r:?}"));
                }
            }
            // Cells the bounds touch but the exact tests reject.
            let b = geom.bounds(prim);
            for x in 0..self.cells {
                for y in 0..self.cells {
                    for z in 0..self.cells {
                        let c = cell([x, y, z]);
                        if b.overlaps(&c) && !geom.overlaps_box(prim, &c) {
                            report.rejected_by_exact_test += 1;
                        }
                    }
                }
            }
        }
        report
    }
}

/// The shapes scene renders (Phong, shadows) to byte-identical PNGs through every one of our
/// indices.
#[test]
fn shapes_scene_renders_identically_through_every_index() {
    use accelbench::geometry::TriangleKernelKind;
    use accelbench::index::{IndexSpec, build_index};
    use accelbench::render::{RenderOptions, render_shaded};
    let scene = generators::generate("shapes", 300, 3).unwrap();
    let opts = RenderOptions::new(40, 40);
    let mut first = None;
    for name in index_names().into_iter().filter(|n| !is_peer(n)) {
        let index = build_index(
            &IndexSpec::named(name),
            &scene.geometry(),
            TriangleKernelKind::Watertight,
        )
        .unwrap();
        let img = render_shaded(&scene, index.as_ref(), &opts).unwrap();
        let (_dir, p) = temp_path("s.png");
        img.write_png(&p).unwrap();
        let bytes = std::fs::read(&p).unwrap();
        match &first {
            None => first = Some(bytes),
            Some(b) => assert!(*b == bytes, "{name} renders a different image"),
        }
    }
}
