//! Self-intersection of shadow rays: (a) a `t_min` epsilon against (b) the origin offset of
//! Wächter and Binder ([`crate::rays::spawn::offset_origin`]), measured at several scene scales
//! and offsets.
//!
//! The scene (in local units): a tilted ground square `[0,1]^2` (two triangles, normal not on an
//! axis) and an occluder square over half of it, parallel at height `GAP = 1e-4` (a real contact,
//! like an object resting almost on the floor), scaled by `scale` and translated by `offset` on
//! every axis. Surface points come from rays hitting the ground from below, from 4 scene sizes
//! away (so they carry the usual rounding), and shadow rays leave towards a directional light.
//! - self-hit: the shadow ray hits the ground it leaves;
//! - missed contact: the point is under the occluder (by exact local geometry, away from its
//!   border) but the shadow ray does not hit the occluder.

use crate::geometry::triangle::Watertight;
use crate::geometry::{Ray, Triangle, TriangleKernel, TriangleKernelKind};
use crate::index::{BuildError, IndexSpec, build_index};
use crate::rays::SplitMix64;
use crate::rays::spawn::{SpawnMethod, offset_origin};
use crate::scene::SceneGeometry;
use glam::{DVec3, Vec3, Vec3A};
use serde::Serialize;
use std::sync::Arc;

/// Height of the occluder over the ground, in local units (relative to the scene size).
pub const GAP: f64 = 1e-4;

/// `(scale, offset)` pairs measured: scales `1e-3 .. 1e4` at the origin, then far offsets with
/// the scene large enough that the gap spans at least a few ulps.
pub const CONFIGS: &[(f64, f64)] = &[
    (1e-3, 0.0),
    (1.0, 0.0),
    (1e3, 0.0),
    (1e4, 0.0),
    (10.0, 1e3),
    (1e3, 1e5),
    (1e5, 1e7),
];

/// The methods compared: epsilons (relative to the scene size) and the offset.
pub const METHODS: &[SpawnMethod] = &[
    SpawnMethod::Epsilon(1e-7),
    SpawnMethod::Epsilon(1e-6),
    SpawnMethod::Epsilon(1e-5),
    SpawnMethod::Epsilon(1e-4),
    SpawnMethod::Epsilon(1e-3),
    SpawnMethod::Offset,
];

/// Results of one method at one scale and offset.
#[derive(Debug, Clone, Serialize)]
pub struct SpawnRow {
    pub scale: f64,
    pub offset: f64,
    pub method: String,
    pub points: usize,
    pub self_hits: usize,
    pub self_hit_rate: f64,
    /// Points whose shadow ray must hit the occluder.
    pub contacts: usize,
    pub missed_contacts: usize,
    pub missed_contact_rate: f64,
}

pub fn method_name(m: SpawnMethod) -> String {
    match m {
        SpawnMethod::Epsilon(e) => format!("epsilon {e:e}"),
        SpawnMethod::Offset => "offset".to_owned(),
    }
}

/// The local frame: `e1, e2` span the ground, `e3` is its normal (none on an axis).
fn frame() -> [DVec3; 3] {
    let e3 = DVec3::new(0.3, 0.8, 0.52).normalize();
    let e1 = e3.cross(DVec3::X).normalize();
    let e2 = e3.cross(e1);
    [e1, e2, e3]
}

struct Setup {
    frame: [DVec3; 3],
    scale: f64,
    offset: f64,
}

impl Setup {
    fn point(&self, u: f64, v: f64, w: f64) -> DVec3 {
        let [e1, e2, e3] = self.frame;
        DVec3::splat(self.offset) + (e1 * u + e2 * v + e3 * w) * self.scale
    }
    fn p32(&self, u: f64, v: f64, w: f64) -> Vec3A {
        Vec3A::from(self.point(u, v, w).as_vec3())
    }
    fn vector(&self, l: DVec3) -> Vec3 {
        let [e1, e2, e3] = self.frame;
        (e1 * l.x + e2 * l.y + e3 * l.z).as_vec3()
    }
    fn quad(&self, u1: f64, w: f64) -> [Triangle; 2] {
        let p = |u, v| self.p32(u, v, w);
        [
            Triangle::new(p(0.0, 0.0), p(u1, 0.0), p(u1, 1.0)),
            Triangle::new(p(0.0, 0.0), p(u1, 1.0), p(0.0, 1.0)),
        ]
    }
}

/// Measures every method at `(scale, offset)` on `points` surface points.
pub fn measure(
    scale: f64,
    offset: f64,
    points: usize,
    seed: u64,
) -> Result<Vec<SpawnRow>, BuildError> {
    let s = Setup {
        frame: frame(),
        scale,
        offset,
    };
    let ground = s.quad(1.0, 0.0);
    let occluder = s.quad(0.5, GAP);
    let tris: Vec<Triangle> = ground.iter().chain(&occluder).copied().collect();
    let geom = SceneGeometry {
        triangles: Arc::from(tris.as_slice()),
        ..SceneGeometry::default()
    };
    let index = build_index(
        &IndexSpec::named("brute"),
        &geom,
        TriangleKernelKind::Watertight,
    )?;
    let light = DVec3::new(0.35, 0.2, 1.0).normalize();
    let light_dir = s.vector(light);
    let normal = Vec3A::from(s.vector(DVec3::Z));
    let scene_size = (scale * 2f64.sqrt()) as f32;
    // Surface points with their rounding: hit the ground from below.
    let mut rng = SplitMix64::new(seed);
    let mut samples: Vec<(Vec3A, bool)> = Vec::with_capacity(points);
    while samples.len() < points {
        let (u, v) = (0.02 + 0.96 * rng.next_unit(), 0.02 + 0.96 * rng.next_unit());
        // Where the exact shadow ray crosses the occluder's height.
        let u_cross = u + light.x * GAP / light.z;
        if (u_cross - 0.5).abs() < 0.01 {
            continue;
        }
        // From a camera 4 scene sizes away, so the point carries a realistic rounding error.
        let from = s.p32(u - 1.0, v + 0.5, -4.0);
        let Ok(up) = Ray::infinite(Vec3::from(from), Vec3::from(s.p32(u, v, 0.0) - from)) else {
            continue;
        };
        let tri = if u >= v { &ground[0] } else { &ground[1] };
        let Some(t) = Watertight::intersect(tri, &up, f32::INFINITY) else {
            continue;
        };
        samples.push((up.at(t), u_cross < 0.5));
    }
    let mut rows = Vec::new();
    for &m in METHODS {
        let (mut self_hits, mut contacts, mut missed) = (0, 0, 0);
        for &(p, under) in &samples {
            let ray = match m {
                SpawnMethod::Epsilon(e) => Ray::new(
                    Vec3::from(p),
                    light_dir,
                    e * scene_size / light_dir.length(),
                    f32::INFINITY,
                ),
                SpawnMethod::Offset => {
                    Ray::infinite(Vec3::from(offset_origin(p, normal)), light_dir)
                }
            }
            .expect("finite origin and unit direction");
            let hit = index.closest_hit(&ray).map(|h| h.prim);
            let is_self = matches!(hit, Some(0 | 1));
            self_hits += is_self as usize;
            if under {
                contacts += 1;
                missed += (!is_self && !matches!(hit, Some(2 | 3))) as usize;
            }
        }
        rows.push(SpawnRow {
            scale,
            offset,
            method: method_name(m),
            points: samples.len(),
            self_hits,
            self_hit_rate: self_hits as f64 / samples.len().max(1) as f64,
            contacts,
            missed_contacts: missed,
            missed_contact_rate: missed as f64 / contacts.max(1) as f64,
        });
    }
    Ok(rows)
}

/// Every configuration of [`CONFIGS`].
pub fn run(points: usize) -> Result<Vec<SpawnRow>, BuildError> {
    let mut rows = Vec::new();
    for (i, &(scale, offset)) in CONFIGS.iter().enumerate() {
        rows.extend(measure(scale, offset, points, 100 + i as u64)?);
    }
    Ok(rows)
}

/// Total failures (self-hits plus missed contacts) per method, in [`METHODS`] order.
pub fn failures_per_method(rows: &[SpawnRow]) -> Vec<(String, usize)> {
    METHODS
        .iter()
        .map(|&m| {
            let name = method_name(m);
            let n = rows
                .iter()
                .filter(|r| r.method == name)
                .map(|r| r.self_hits + r.missed_contacts)
                .sum();
            (name, n)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn offset_has_no_self_hits_and_a_huge_epsilon_misses_contacts() {
        let rows = measure(1.0, 0.0, 400, 1).unwrap();
        let get = |name: &str| rows.iter().find(|r| r.method == name).unwrap();
        assert!(get("offset").contacts > 50);
        assert_eq!(get("offset").self_hits, 0);
        assert_eq!(get("offset").missed_contacts, 0);
        // An epsilon of 1e-3 of the scene skips the occluder 1e-4 above the ground.
        let big = get("epsilon 1e-3");
        assert_eq!(big.missed_contacts, big.contacts);
    }
}
