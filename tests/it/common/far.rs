//! A closed mesh far from the coordinate origin, where the overlap padding (1e-5 of the
//! coordinates, about 100 units at 1e7) is wider than the cells an adaptive structure would
//! make near the origin, and rays from inside it (every one must hit).

use accelbench::geometry::{Ray, Triangle, TriangleKernelKind};
use accelbench::index::{IndexSpec, build_index};
use accelbench::scene::{Scene, generators};
use glam::{Vec3, Vec3A};

/// The centre of the far sphere, about 1.2e7 from the origin.
pub const FAR_CENTRE: [f32; 3] = [1.0e7, -6.0e6, 3.0e6];

/// A closed icosphere of 20,480 triangles and radius 1000 centred at [`FAR_CENTRE`].
pub fn far_icosphere() -> Scene {
    let c = Vec3A::from(FAR_CENTRE);
    let tris = generators::icosphere(5)
        .into_iter()
        .map(|t| {
            Triangle::new(
                t.v[0] * 1000.0 + c,
                t.v[1] * 1000.0 + c,
                t.v[2] * 1000.0 + c,
            )
        })
        .collect();
    Scene::from_triangles("far_icosphere", tris)
}

/// `n` rays from points up to 900 units from the centre in spread directions (deterministic).
pub fn rays_from_inside(n: usize) -> Vec<Ray> {
    let c = Vec3::from(FAR_CENTRE);
    (0..n)
        .map(|i| {
            let f = i as f32 + 0.5;
            // Golden-angle spiral directions, origins on a smaller shifted spiral.
            let z = 1.0 - 2.0 * f / n as f32;
            let a = f * 2.399_963;
            let r = (1.0 - z * z).sqrt();
            let dir = Vec3::new(r * a.cos(), r * a.sin(), z);
            let o = c + Vec3::new((a * 0.7).sin(), (a * 1.3).cos(), z + 0.1).normalize_or_zero()
                * (900.0 * (i % 7) as f32 / 7.0);
            Ray::infinite(o, dir).unwrap()
        })
        .collect()
}

/// Asserts that `spec` builds on the far sphere and that every ray from inside hits, with brute
/// force's hits (the caller also runs `assert_agrees`, which checks every kernel).
pub fn assert_all_hit_from_inside(spec: &str, rays: &[Ray]) {
    let scene = far_icosphere();
    let spec: IndexSpec = spec.parse().unwrap();
    let index = build_index(&spec, &scene.geometry(), TriangleKernelKind::Exact)
        .unwrap_or_else(|e| panic!("{spec} on the far sphere: {e}"));
    let mut hits = vec![None; rays.len()];
    index.closest_hits(rays, &mut hits);
    let missed = hits.iter().filter(|h| h.is_none()).count();
    assert_eq!(
        missed,
        0,
        "{spec}: {missed} of {} rays from inside miss",
        rays.len()
    );
}
