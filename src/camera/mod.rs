//! Cameras: the course's pinhole camera (the protocol's primary rays) and the models built on
//! its basis, each in its own file: a thin lens (depth of field), an eye moving during the
//! shutter (camera motion blur) and Brown-Conrady radial lens distortion. [`CameraModel`] picks
//! one; [`sampler`] supplies the stratified film, lens and time samples.
//!
//! Everything is computed in `f64` and rounded to `f32` once per ray, so every ray set and
//! render is reproducible bit for bit from its parameters and seed.

mod distortion;
mod model;
mod motion;
mod pinhole;
pub mod sampler;
mod thin_lens;

pub use distortion::Distortion;
pub use model::{CameraModel, CameraSample, ModelKind};
pub use motion::EyeMotion;
pub use pinhole::{Camera, CameraError, cross_protocol, normalize_protocol};
pub use thin_lens::ThinLens;

/// Test support: the camera at `(0, 0, 5)` looking at the origin (up `+y`), `size` pixels square.
#[cfg(test)]
fn on_z_axis(fov_y_deg: f64, size: u32) -> Camera {
    Camera::look_at(
        glam::DVec3::Z * 5.0,
        glam::DVec3::ZERO,
        glam::DVec3::Y,
        fov_y_deg,
        size,
        size,
    )
    .unwrap()
}
