//! Watertightness: rays shot from inside closed meshes (an icosphere and the closed room),
//! translated far from the origin, must all hit something. Counted per triangle kernel (with
//! brute force's any-hit query) and, for the watertight kernel, by the closest-hit query of every
//! other registered index.

use super::families::{full_offsets, icosphere_at, object_size};
use crate::geometry::{Ray, Triangle, TriangleKernelKind};
use crate::index::{BuildError, IndexSpec, TraceIndex, build_index, index_names};
use crate::rays::SplitMix64;
use crate::scene::{SceneGeometry, generators::room};
use glam::{DVec3, Vec3, Vec3A};
use serde::Serialize;
use std::sync::Arc;

/// What to run.
#[derive(Debug, Clone)]
pub struct WatertightConfig {
    /// Rays per mesh and offset.
    pub rays: usize,
    pub offsets: Vec<f64>,
    /// Kernels counted with brute force.
    pub kernels: Vec<TriangleKernelKind>,
    /// Also run the watertight kernel through every registered index.
    pub every_index: bool,
    pub seed: u64,
}

impl WatertightConfig {
    /// Offsets `0, 1e0 .. 1e7`, every kernel, every index.
    pub fn full(rays: usize) -> WatertightConfig {
        WatertightConfig {
            rays,
            offsets: full_offsets(),
            kernels: TriangleKernelKind::ALL.to_vec(),
            every_index: true,
            seed: 11,
        }
    }
}

/// Misses of one kernel through one index on one mesh at one offset.
#[derive(Debug, Clone, Serialize)]
pub struct LeakRow {
    pub mesh: String,
    pub offset: f64,
    pub kernel: TriangleKernelKind,
    pub index: String,
    pub rays: usize,
    pub misses: usize,
    pub miss_rate: f64,
    /// Of `rays`, those aimed exactly at a vertex or an edge midpoint, and their misses.
    pub aimed_rays: usize,
    pub aimed_misses: usize,
}

/// A closed mesh and a point well inside it.
pub struct ClosedMesh {
    pub name: &'static str,
    pub triangles: Vec<Triangle>,
    pub inside: DVec3,
}

/// The closed meshes at `offset`: an icosphere (level 2) of radius `R` and the room `[0,1]^3`
/// (about 300 triangles) scaled to side `2R`, both centred at `(offset, offset, offset)`
/// (`R` as in [`object_size`]).
pub fn closed_meshes(offset: f64) -> Vec<ClosedMesh> {
    let r = object_size(offset);
    let place = |v: Vec3A| {
        let p = DVec3::splat(offset) + (Vec3::from(v).as_dvec3() - 0.5) * (2.0 * r);
        Vec3A::from(p.as_vec3())
    };
    let room = room(300)
        .iter()
        .map(|t| Triangle::new(place(t.v[0]), place(t.v[1]), place(t.v[2])))
        .collect();
    vec![
        ClosedMesh {
            name: "icosphere",
            triangles: icosphere_at(2, offset),
            inside: DVec3::splat(offset),
        },
        ClosedMesh {
            name: "room",
            triangles: room,
            inside: DVec3::splat(offset),
        },
    ]
}

/// Rays from near `mesh.inside` (within `0.05 R`): first aimed exactly at every vertex and edge
/// midpoint (in `f32`; `min(n/2, 6 * triangles)` of them), then uniform directions, `n` in all.
pub fn inside_rays(mesh: &ClosedMesh, offset: f64, n: usize, seed: u64) -> Vec<Ray> {
    let mut rng = SplitMix64::new(seed);
    let r = object_size(offset);
    let mut origin = || {
        let j = DVec3::new(rng.next_unit(), rng.next_unit(), rng.next_unit()) * 2.0 - 1.0;
        (mesh.inside + j * (0.05 * r)).as_vec3()
    };
    let mut rays = Vec::with_capacity(n);
    'targets: for t in &mesh.triangles {
        for k in 0..3 {
            for target in [t.v[k], (t.v[k] + t.v[(k + 1) % 3]) * 0.5] {
                if rays.len() >= n / 2 {
                    break 'targets;
                }
                let o = origin();
                rays.extend(Ray::infinite(o, Vec3::from(target) - o).ok());
            }
        }
    }
    let mut rng2 = SplitMix64::new(seed ^ 0x5555);
    while rays.len() < n {
        let w = 1.0 - 2.0 * rng2.next_unit();
        let phi = std::f64::consts::TAU * rng2.next_unit();
        let s = (1.0 - w * w).max(0.0).sqrt();
        let d = DVec3::new(s * phi.cos(), s * phi.sin(), w);
        rays.extend(Ray::infinite(origin(), d.as_vec3()).ok());
    }
    rays
}

/// Per ray: no closest hit.
fn closest_misses(index: &dyn TraceIndex, rays: &[Ray]) -> Vec<bool> {
    let mut hits = vec![None; rays.len()];
    index.closest_hits(rays, &mut hits);
    hits.iter().map(|h| h.is_none()).collect()
}

/// Per ray: no hit at all, by the any-hit query (brute force stops at the first hit, about
/// twice as fast from inside a closed mesh).
fn any_misses(index: &dyn TraceIndex, rays: &[Ray]) -> Vec<bool> {
    let mut any = vec![false; rays.len()];
    index.any_hits(rays, &mut any);
    any.iter().map(|a| !a).collect()
}

/// Runs the watertightness study: one row per mesh, offset, kernel (brute force) and, for the
/// watertight kernel, per registered index.
pub fn run(config: &WatertightConfig) -> Result<Vec<LeakRow>, BuildError> {
    let mut rows = Vec::new();
    for (oi, &offset) in config.offsets.iter().enumerate() {
        for mesh in closed_meshes(offset) {
            let rays = inside_rays(&mesh, offset, config.rays, config.seed ^ oi as u64);
            let geom = SceneGeometry {
                triangles: Arc::from(mesh.triangles.as_slice()),
                ..SceneGeometry::default()
            };
            let aimed = rays
                .len()
                .min(config.rays / 2)
                .min(6 * mesh.triangles.len());
            let mut row = |kernel, index: &dyn TraceIndex, missed: Vec<bool>| {
                let m = missed.iter().filter(|&&x| x).count();
                rows.push(LeakRow {
                    mesh: mesh.name.to_owned(),
                    offset,
                    kernel,
                    index: index.name().to_owned(),
                    rays: rays.len(),
                    misses: m,
                    miss_rate: m as f64 / rays.len().max(1) as f64,
                    aimed_rays: aimed,
                    aimed_misses: missed[..aimed].iter().filter(|&&x| x).count(),
                });
            };
            for &k in &config.kernels {
                let brute = build_index(&IndexSpec::named("brute"), &geom, k)?;
                row(k, brute.as_ref(), any_misses(brute.as_ref(), &rays));
            }
            if config.every_index {
                let k = TriangleKernelKind::Watertight;
                for name in index_names().into_iter().filter(|n| *n != "brute") {
                    let index = build_index(&IndexSpec::named(name), &geom, k)?;
                    row(k, index.as_ref(), closest_misses(index.as_ref(), &rays));
                }
            }
        }
    }
    Ok(rows)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rays_start_inside_and_aim_at_vertices_first() {
        let meshes = closed_meshes(1e5);
        assert_eq!(meshes.len(), 2);
        let rays = inside_rays(&meshes[0], 1e5, 1000, 1);
        assert_eq!(rays.len(), 1000);
        let v = meshes[0].triangles[0].v[0];
        let hits_vertex = (rays[0].origin + rays[0].dir) - v;
        assert!(hits_vertex.abs().max_element() <= 0.05, "{hits_vertex:?}");
    }
}
