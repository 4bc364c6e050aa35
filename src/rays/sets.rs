//! The protocol's standard ray sets: "primary" (pinhole camera) and "incoherent" (uniform
//! origins in the bounds, uniform directions), computed in `f64` as the protocol prescribes.

use super::SplitMix64;
use crate::camera::{Camera, CameraError};
use crate::geometry::{Aabb, Ray};
use glam::DVec3;
use std::f64::consts::PI;

/// The standard sets a scene can be asked for.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, clap::ValueEnum, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum RaySetKind {
    Primary,
    Incoherent,
}

impl RaySetKind {
    pub fn name(self) -> &'static str {
        match self {
            RaySetKind::Primary => "primary",
            RaySetKind::Incoherent => "incoherent",
        }
    }
}

/// `width x height` camera rays of the protocol camera for bounds `b`, row-major.
pub fn primary_rays(b: &Aabb, width: u32, height: u32) -> Result<Vec<Ray>, CameraError> {
    let cam = Camera::protocol(b, width, height)?;
    cam.rays().map_err(|_| CameraError::DegenerateBasis)
}

/// `count` incoherent rays for bounds `b`, SplitMix64 seeded with `seed` (42 in the protocol).
/// A flat bounding box is fine (origins lie in the plane).
pub fn incoherent_rays(b: &Aabb, count: usize, seed: u64) -> Vec<Ray> {
    let min = b.min.as_dvec3();
    let e = b.max.as_dvec3() - min;
    let mut rng = SplitMix64::new(seed);
    (0..count)
        .map(|_| {
            let rx = rng.next_unit();
            let ry = rng.next_unit();
            let rz = rng.next_unit();
            let o = DVec3::new(min.x + rx * e.x, min.y + ry * e.y, min.z + rz * e.z);
            let u1 = rng.next_unit();
            let u2 = rng.next_unit();
            let w = 1.0 - 2.0 * u1;
            let s = (1.0 - w * w).max(0.0).sqrt();
            let phi = 2.0 * PI * u2;
            let d = DVec3::new(s * phi.cos(), s * phi.sin(), w);
            // A unit direction rounded to f32 is never zero, so this cannot fail.
            Ray::infinite(o.as_vec3(), d.as_vec3()).expect("unit direction")
        })
        .collect()
}
