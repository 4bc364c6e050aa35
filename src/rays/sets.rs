//! The protocol's standard ray sets: "primary" (pinhole camera) and "incoherent" (uniform
//! origins in the bounds, uniform directions), computed in `f64` as the protocol prescribes, and
//! the names of the camera-model sets (`camera_sets`).

use super::{CAMERA_SET_SEED, SplitMix64, camera_model_rays};
use crate::camera::{Camera, CameraError, ModelKind};
use crate::geometry::{Aabb, Ray};
use glam::DVec3;
use std::f64::consts::PI;

/// The standard sets a scene can be asked for.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, clap::ValueEnum, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum RaySetKind {
    Primary,
    Incoherent,
    /// Thin-lens camera (depth of field), see `camera_sets`.
    Dof,
    /// Eye moving during the shutter (camera motion blur).
    Motion,
    /// Brown-Conrady barrel distortion.
    Lens,
}

impl RaySetKind {
    pub fn name(self) -> &'static str {
        match self {
            RaySetKind::Primary => "primary",
            RaySetKind::Incoherent => "incoherent",
            RaySetKind::Dof => "dof",
            RaySetKind::Motion => "motion",
            RaySetKind::Lens => "lens",
        }
    }

    /// The camera model of a camera-model set (`None` for the protocol's sets).
    pub fn camera_model(self) -> Option<ModelKind> {
        match self {
            RaySetKind::Dof => Some(ModelKind::Dof),
            RaySetKind::Motion => Some(ModelKind::Motion),
            RaySetKind::Lens => Some(ModelKind::Lens),
            RaySetKind::Primary | RaySetKind::Incoherent => None,
        }
    }
}

/// The set `kind` for bounds `b`: `side x side` camera rays (primary and camera-model sets) or
/// `count` incoherent rays; `seed` overrides the default seed (42 for incoherent, 19
/// ([`CAMERA_SET_SEED`]) for dof and motion; primary and lens draw nothing).
pub fn ray_set(
    kind: RaySetKind,
    b: &Aabb,
    side: u32,
    count: usize,
    seed: Option<u64>,
) -> Result<Vec<Ray>, CameraError> {
    Ok(match (kind, kind.camera_model()) {
        (RaySetKind::Primary, _) => primary_rays(b, side, side)?,
        (RaySetKind::Incoherent, _) => incoherent_rays(b, count, seed.unwrap_or(42)),
        (_, Some(model)) => camera_model_rays(b, side, model, seed.unwrap_or(CAMERA_SET_SEED))?,
        (_, None) => unreachable!("every other set is a camera-model set"),
    })
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
