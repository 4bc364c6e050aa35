//! Leak test: from the centre of a closed icosphere, rays in every direction, including rays
//! aimed exactly at its vertices and edge midpoints, never escape with the watertight or the exact kernel.
use accelbench::geometry::{Ray, TriangleKernelKind};
use accelbench::index::{IndexSpec, build_index};
use accelbench::rays::incoherent_rays;
use accelbench::scene::{Scene, generators::icosphere_mesh};
use glam::{Vec3, Vec3A};

#[test]
fn watertight_and_exact_brute_force_miss_nothing_from_inside() {
    let (verts, faces) = icosphere_mesh(3);
    let tris = faces
        .iter()
        .map(|f| {
            accelbench::geometry::Triangle::new(
                verts[f[0] as usize],
                verts[f[1] as usize],
                verts[f[2] as usize],
            )
        })
        .collect();
    let scene = Scene::from_triangles("icosphere", tris);
    let mut rays: Vec<Ray> = Vec::new();
    let o = Vec3::new(0.013, -0.021, 0.007); // off-centre, so rays are not symmetric
    for v in &verts {
        rays.push(Ray::infinite(o, Vec3::from(*v) - o).unwrap());
        rays.push(Ray::infinite(Vec3::ZERO, Vec3::from(*v)).unwrap());
    }
    for f in &faces {
        for (a, b) in [(f[0], f[1]), (f[1], f[2]), (f[2], f[0])] {
            let m: Vec3A = (verts[a as usize] + verts[b as usize]) * 0.5;
            rays.push(Ray::infinite(o, Vec3::from(m) - o).unwrap());
            rays.push(Ray::infinite(Vec3::ZERO, Vec3::from(m)).unwrap());
        }
    }
    let b = accelbench::geometry::Aabb::new(Vec3A::splat(-0.3), Vec3A::splat(0.3));
    rays.extend(incoherent_rays(&b, 100_000, 9));
    for kernel in [TriangleKernelKind::Watertight, TriangleKernelKind::Exact] {
        let index = build_index(&IndexSpec::named("brute"), &scene.geometry(), kernel).unwrap();
        let mut hits = vec![None; rays.len()];
        index.closest_hits(&rays, &mut hits);
        let leaks: Vec<usize> = (0..rays.len()).filter(|&i| hits[i].is_none()).collect();
        assert!(
            leaks.is_empty(),
            "{kernel}: {} of {} rays leaked, first {:?}",
            leaks.len(),
            rays.len(),
            rays[leaks[0]]
        );
    }
}
