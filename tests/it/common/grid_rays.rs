//! Rays along and from a grid layout's cell boundaries (the uniform grid's, and each level of
//! the two-level grid's).

use accelbench::geometry::Ray;
use accelbench::index::grid::Layout;
use glam::Vec3;

/// Rays exactly on a grid layout's own cell boundary planes (and edges), axis-parallel with +-0.0
/// components, from outside and starting on a boundary inside.
pub fn boundary_rays(l: &Layout) -> Vec<Ray> {
    let mut rays = Vec::new();
    let b = l.bounds;
    let out = (b.extent().length() + 1.0) * 2.0;
    for a in 0..3 {
        let (u, v) = ((a + 1) % 3, (a + 2) % 3);
        // Every few planes on the two other axes: the ray runs along an edge of four cells.
        for &pu in l.planes[u].iter().step_by(2) {
            for &pv in l.planes[v].iter().step_by(3) {
                for sign in [1.0f32, -1.0] {
                    for zero in [0.0f32, -0.0] {
                        let mut o = [0.0f32; 3];
                        o[u] = pu;
                        o[v] = pv;
                        let mut d = [zero; 3];
                        d[a] = sign;
                        // From outside the grid.
                        o[a] = b.center()[a] - sign * out;
                        rays.push(Ray::infinite(Vec3::from(o), Vec3::from(d)).unwrap());
                        // Starting on a boundary plane inside.
                        let mid = l.planes[a][l.planes[a].len() / 2];
                        o[a] = mid;
                        rays.push(Ray::infinite(Vec3::from(o), Vec3::from(d)).unwrap());
                    }
                }
            }
        }
    }
    // Oblique rays starting on cell corners.
    for (i, &px) in l.planes[0].iter().enumerate() {
        let py = l.planes[1][i % l.planes[1].len()];
        let pz = l.planes[2][(i * 7) % l.planes[2].len()];
        for d in [Vec3::new(0.3, -0.5, 0.8), Vec3::new(-1.0, 1.0, 1.0)] {
            rays.push(Ray::infinite(Vec3::new(px, py, pz), d).unwrap());
        }
    }
    rays
}
