//! The camera-model ray sets `dof`, `motion` and `lens`: one ray per pixel of the protocol
//! camera (same eye, basis, field of view and row-major order as the primary set), through
//! the pixel centre, with the model of [`CameraModel::for_scene`]. The lens point (`dof`) and
//! shutter time (`motion`) of each pixel are stratified over 4 x 4 pixel tiles
//! ([`sampler::per_pixel`]) and seeded, so a set is reproducible bit for bit from the bounds,
//! the size and the seed.

use crate::camera::sampler::per_pixel;
use crate::camera::{Camera, CameraError, CameraModel, CameraSample, ModelKind};
use crate::geometry::{Aabb, Ray};

/// Default seed of the `dof` and `motion` sets' lens and time samples.
pub const CAMERA_SET_SEED: u64 = 19;

/// `side x side` rays of camera model `kind` for bounds `b`, row-major, samples seeded by
/// `seed`.
pub fn camera_model_rays(
    b: &Aabb,
    side: u32,
    kind: ModelKind,
    seed: u64,
) -> Result<Vec<Ray>, CameraError> {
    let cam = Camera::protocol(b, side, side)?;
    let model = CameraModel::for_scene(kind, &cam, b)?;
    (0..side)
        .flat_map(|j| (0..side).map(move |i| (i, j)))
        .map(|(i, j)| {
            let u = per_pixel(i, j, side, seed);
            let s = CameraSample {
                film: [i as f64 + 0.5, j as f64 + 0.5],
                lens: u.lens,
                time: u.time,
            };
            model
                .ray(&cam, &s)
                .map_err(|_| CameraError::DegenerateBasis)
        })
        .collect()
}
