//! Self-intersection of shadow rays: (a) a `t_min` epsilon against (b) the origin offset of
//! Wächter and Binder ([`crate::rays::spawn::offset_origin`], and its scene-relative variant
//! [`crate::rays::spawn::offset_origin_scaled`]), measured at several scene scales, offsets
//! from the origin and contact gaps.
//!
//! The scene (in local units): a tilted ground square `[0,1]^2` (two triangles, normal not on an
//! axis) and an occluder square over half of it, parallel at height `gap` (a real contact, like
//! an object resting almost on the floor), scaled by `scale` and translated by `offset` on every
//! axis. Surface points come from rays hitting the ground from below, from 4 scene sizes away
//! (so they carry the usual rounding), and shadow rays leave towards a directional light.
//! - self-hit: the shadow ray hits the ground it leaves;
//! - missed contact: the point is under the occluder (by exact local geometry, away from its
//!   border) but the shadow ray does not hit the occluder.
//!
//! A gap of only a few ulps of the coordinates cannot be told from the hit point's own rounding
//! by any method; each row says how many ulps its gap spans, and the verdict counts only
//! [resolvable](RESOLVABLE_ULPS) gaps.

use crate::geometry::triangle::Watertight;
use crate::geometry::{Ray, Triangle, TriangleKernel, TriangleKernelKind};
use crate::index::{BuildError, IndexSpec, build_index};
use crate::rays::SplitMix64;
use crate::rays::spawn::{SpawnMethod, offset_origin, offset_origin_scaled};
use crate::scene::SceneGeometry;
use glam::{DVec3, Vec3, Vec3A};
use serde::Serialize;
use std::sync::Arc;

/// Heights of the occluder over the ground, in local units (relative to the scene size).
pub const GAPS: &[f64] = &[1e-2, 1e-3, 1e-4, 1e-5];

/// `(scale, offset)` pairs measured: scales `1e-3 .. 1e4` at the origin, then scenes far from
/// the origin relative to their size.
pub const CONFIGS: &[(f64, f64)] = &[
    (1e-3, 0.0),
    (1.0, 0.0),
    (1e3, 0.0),
    (1e4, 0.0),
    (1e-2, 1.0),
    (1.0, 1e2),
    (10.0, 1e3),
    (1e3, 1e5),
    (1e5, 1e7),
    (0.1, 1e3),
    (1.0, 1e4),
];

/// A gap counts in the verdict when it spans at least this many ulps of the scene's largest
/// coordinate: four times the 256 ulps the offset moves a point, so a method that fails there
/// fails on a contact that float coordinates resolve with room to spare.
pub const RESOLVABLE_ULPS: f64 = 1024.0;

/// The methods compared: epsilons (relative to the scene size) and the two offsets.
pub const METHODS: &[SpawnMethod] = &[
    SpawnMethod::Epsilon(1e-7),
    SpawnMethod::Epsilon(1e-6),
    SpawnMethod::Epsilon(1e-5),
    SpawnMethod::Epsilon(1e-4),
    SpawnMethod::Epsilon(1e-3),
    SpawnMethod::Offset,
    SpawnMethod::ScaledOffset,
];

/// Results of one method at one scale and offset.
#[derive(Debug, Clone, Serialize)]
pub struct SpawnRow {
    pub scale: f64,
    pub offset: f64,
    /// Occluder height relative to the scene size.
    pub gap: f64,
    /// The gap in ulps of the scene's largest coordinate (`f32`).
    pub gap_ulps: f64,
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
        SpawnMethod::ScaledOffset => "scaled offset".to_owned(),
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

/// `gap` (relative) in ulps of the largest coordinate of the scene at `(scale, offset)`.
pub fn gap_in_ulps(scale: f64, offset: f64, gap: f64) -> f64 {
    // Every point is within 2 scene units of the offset on each axis.
    let largest = (offset.abs() + 2.0 * scale) as f32;
    let ulp = f32::from_bits(largest.to_bits() + 1) - largest;
    gap * scale / ulp as f64
}

/// Measures every method at `(scale, offset)` with the occluder `gap` above the ground, on
/// `points` surface points.
pub fn measure(
    scale: f64,
    offset: f64,
    gap: f64,
    points: usize,
    seed: u64,
) -> Result<Vec<SpawnRow>, BuildError> {
    let s = Setup {
        frame: frame(),
        scale,
        offset,
    };
    let ground = s.quad(1.0, 0.0);
    let occluder = s.quad(0.5, gap);
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
        let u_cross = u + light.x * gap / light.z;
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
                SpawnMethod::ScaledOffset => Ray::infinite(
                    Vec3::from(offset_origin_scaled(p, normal, scene_size)),
                    light_dir,
                ),
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
            gap,
            gap_ulps: gap_in_ulps(scale, offset, gap),
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

/// Every configuration of [`CONFIGS`] with every gap of [`GAPS`].
pub fn run(points: usize) -> Result<Vec<SpawnRow>, BuildError> {
    let mut rows = Vec::new();
    for (i, &(scale, offset)) in CONFIGS.iter().enumerate() {
        for (j, &gap) in GAPS.iter().enumerate() {
            let seed = 100 + (i * GAPS.len() + j) as u64;
            rows.extend(measure(scale, offset, gap, points, seed)?);
        }
    }
    Ok(rows)
}

/// Failures of one method. Self-hits count on every row (they darken every lit surface, gap or
/// not); missed contacts count where the gap is [resolvable](RESOLVABLE_ULPS).
#[derive(Debug, Clone, PartialEq)]
pub struct MethodFailures {
    pub method: String,
    pub self_hits: usize,
    /// Rows with at least one self-hit.
    pub self_hit_rows: usize,
    pub missed_resolvable: usize,
    /// Rows with a resolvable gap and at least one missed contact.
    pub missed_resolvable_rows: usize,
    /// Missed contacts on every row, resolvable or not.
    pub missed_all: usize,
}

impl MethodFailures {
    /// What the verdict minimises: self-hits plus missed resolvable contacts.
    pub fn counted(&self) -> usize {
        self.self_hits + self.missed_resolvable
    }
}

/// [`MethodFailures`] per method, in [`METHODS`] order.
pub fn failures_per_method(rows: &[SpawnRow]) -> Vec<MethodFailures> {
    METHODS
        .iter()
        .map(|&m| {
            let name = method_name(m);
            let mine: Vec<&SpawnRow> = rows.iter().filter(|r| r.method == name).collect();
            let resolvable = || mine.iter().filter(|r| r.gap_ulps >= RESOLVABLE_ULPS);
            MethodFailures {
                method: name,
                self_hits: mine.iter().map(|r| r.self_hits).sum(),
                self_hit_rows: mine.iter().filter(|r| r.self_hits > 0).count(),
                missed_resolvable: resolvable().map(|r| r.missed_contacts).sum(),
                missed_resolvable_rows: resolvable().filter(|r| r.missed_contacts > 0).count(),
                missed_all: mine.iter().map(|r| r.missed_contacts).sum(),
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn offset_has_no_self_hits_and_a_huge_epsilon_misses_contacts() {
        let rows = measure(1.0, 0.0, 1e-4, 400, 1).unwrap();
        let get = |name: &str| rows.iter().find(|r| r.method == name).unwrap();
        assert!(get("offset").contacts > 50);
        assert_eq!(get("offset").self_hits, 0);
        assert_eq!(get("offset").missed_contacts, 0);
        // An epsilon of 1e-3 of the scene skips the occluder 1e-4 above the ground.
        let big = get("epsilon 1e-3");
        assert_eq!(big.missed_contacts, big.contacts);
    }

    #[test]
    fn the_absolute_offset_skips_contacts_in_a_tiny_scene_and_the_scaled_one_does_not() {
        // 1e-3 units across: the absolute near-origin offset (1/65536) is 1.5% of the scene,
        // far above a 1e-3 gap (1e-6 units).
        let rows = measure(1e-3, 0.0, 1e-3, 400, 2).unwrap();
        let get = |name: &str| rows.iter().find(|r| r.method == name).unwrap();
        let abs = get("offset");
        assert!(abs.contacts > 50);
        assert_eq!(abs.missed_contacts, abs.contacts);
        let scaled = get("scaled offset");
        assert_eq!((scaled.self_hits, scaled.missed_contacts), (0, 0));
    }

    #[test]
    fn gap_ulps_counts_ulps_of_the_largest_coordinate() {
        // Near 1e3 an f32 ulp is 2^-14; the largest coordinate is 1e3 + 2 * 10.
        let ulps = gap_in_ulps(10.0, 1e3, 1e-3);
        assert!((ulps - 1e-2 * 16384.0).abs() < 1e-9, "{ulps}");
    }
}
