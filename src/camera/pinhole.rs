//! The pinhole camera of the course: eye, look-at point, up, vertical field of view, image size;
//! one ray through each pixel centre. Computed in `f64` and rounded to `f32` once, in the
//! evaluation order of the ray protocol (`../shared/PROTOCOL.md`), so the protocol's "primary"
//! set is reproduced bit for bit.

use crate::geometry::{Aabb, Ray, RayError};
use glam::{DVec3, Vec3};

/// A pinhole camera with an orthonormal basis computed in `f64`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Camera {
    pub eye: DVec3,
    pub forward: DVec3,
    pub right: DVec3,
    pub up: DVec3,
    /// `tan(fov_y / 2)`.
    pub tan_half_fov: f64,
    pub width: u32,
    pub height: u32,
}

/// Errors of camera construction (degenerate basis, bad image size or field of view).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum CameraError {
    #[error("image size {0}x{1} is invalid: both must be at least 1")]
    ImageSize(u32, u32),
    #[error("field of view {0} degrees is invalid: it must lie strictly between 0 and 180")]
    Fov(f64),
    #[error(
        "camera eye and look-at point coincide, or the view direction is parallel to up; move the eye or change up"
    )]
    DegenerateBasis,
    #[error("camera parameters must be finite")]
    NonFinite,
    #[error(
        "the thin lens focuses on the scene's centre, but the centre is behind the camera (distance {0} along the view direction); point the camera at the scene"
    )]
    FocusBehind(f64),
    #[error("lens distortion k1 = {k1}, k2 = {k2} is invalid: {reason}")]
    Distortion { k1: f64, k2: f64, reason: String },
}

/// `a / |a|` as the protocol writes it (a division, not a multiplication by a reciprocal).
pub fn normalize_protocol(a: DVec3) -> DVec3 {
    let len = (a.x * a.x + a.y * a.y + a.z * a.z).sqrt();
    DVec3::new(a.x / len, a.y / len, a.z / len)
}

/// `a x b`, written out so the evaluation order is fixed.
pub fn cross_protocol(a: DVec3, b: DVec3) -> DVec3 {
    DVec3::new(
        a.y * b.z - a.z * b.y,
        a.z * b.x - a.x * b.z,
        a.x * b.y - a.y * b.x,
    )
}

impl Camera {
    /// A camera at `eye` looking at `target`, `world_up` giving the vertical, `fov_y_deg` the
    /// vertical field of view.
    pub fn look_at(
        eye: DVec3,
        target: DVec3,
        world_up: DVec3,
        fov_y_deg: f64,
        width: u32,
        height: u32,
    ) -> Result<Camera, CameraError> {
        if width == 0 || height == 0 {
            return Err(CameraError::ImageSize(width, height));
        }
        if !(fov_y_deg > 0.0 && fov_y_deg < 180.0) {
            return Err(CameraError::Fov(fov_y_deg));
        }
        if !(eye.is_finite() && target.is_finite() && world_up.is_finite()) {
            return Err(CameraError::NonFinite);
        }
        let forward = normalize_protocol(target - eye);
        let right = normalize_protocol(cross_protocol(forward, world_up));
        if !forward.is_finite() || !right.is_finite() {
            return Err(CameraError::DegenerateBasis);
        }
        let up = cross_protocol(right, forward);
        Ok(Camera {
            eye,
            forward,
            right,
            up,
            tan_half_fov: (fov_y_deg.to_radians() / 2.0).tan(),
            width,
            height,
        })
    }

    /// The protocol's standard camera for a scene with bounds `b`: eye at
    /// `c + ((d * n) * 1.1)` with `n = normalize(0.3, 0.35, 1.0)`, looking at the centre `c`, up
    /// `+Y`, 45 degrees.
    pub fn protocol(b: &Aabb, width: u32, height: u32) -> Result<Camera, CameraError> {
        let min = b.min.as_dvec3();
        let max = b.max.as_dvec3();
        let c = (min + max) / 2.0;
        let e = max - min;
        let d = (e.x * e.x + e.y * e.y + e.z * e.z).sqrt();
        let n = normalize_protocol(DVec3::new(0.3, 0.35, 1.0));
        let eye = c + ((n * d) * 1.1);
        Camera::look_at(eye, c, DVec3::Y, 45.0, width, height)
    }

    /// Screen coordinates `(u * tan(fov/2) * aspect, v * tan(fov/2))` of the film point `(x, y)`
    /// in pixel units (`(0, 0)` the top-left corner of the image, `(width, height)` the
    /// bottom-right; a pixel centre is `(i + 0.5, j + 0.5)`). `aspect = width / height` widens the
    /// horizontal field of view; for a square image this is the protocol's `(u * t, v * t)`
    /// bit for bit (a multiplication by 1 is exact).
    pub fn screen(&self, x: f64, y: f64) -> (f64, f64) {
        let aspect = self.width as f64 / self.height as f64;
        let u = (x / self.width as f64) * 2.0 - 1.0;
        let v = 1.0 - (y / self.height as f64) * 2.0;
        let t = self.tan_half_fov;
        ((u * t) * aspect, v * t)
    }

    /// The unnormalized direction `forward + sx * right + sy * up` through screen point
    /// `(sx, sy)` (see [`Camera::screen`]); its `forward` component is 1, so `eye + d * f` lies on
    /// the plane at distance `f` in front of the eye.
    pub fn through_screen(&self, sx: f64, sy: f64) -> DVec3 {
        self.forward + sx * self.right + sy * self.up
    }

    /// Direction through the centre of pixel column `i`, row `j` (row 0 at the top), in `f64`.
    pub fn direction(&self, i: u32, j: u32) -> DVec3 {
        let u = ((i as f64 + 0.5) / self.width as f64) * 2.0 - 1.0;
        let v = 1.0 - ((j as f64 + 0.5) / self.height as f64) * 2.0;
        let t = self.tan_half_fov;
        normalize_protocol(self.forward + (u * t) * self.right + (v * t) * self.up)
    }

    /// The ray through pixel `(i, j)`, over `[0, +inf]`.
    pub fn ray(&self, i: u32, j: u32) -> Result<Ray, RayError> {
        Ray::infinite(self.eye.as_vec3(), self.direction(i, j).as_vec3())
    }

    /// All pixel rays in row-major order.
    pub fn rays(&self) -> Result<Vec<Ray>, RayError> {
        (0..self.height)
            .flat_map(|j| (0..self.width).map(move |i| (i, j)))
            .map(|(i, j)| self.ray(i, j))
            .collect()
    }

    /// The eye in `f32`.
    pub fn eye_f32(&self) -> Vec3 {
        self.eye.as_vec3()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::camera::on_z_axis;
    use glam::Vec3A;

    #[test]
    fn centre_ray_points_at_target_and_corners_span_fov() {
        let cam = on_z_axis(90.0, 2);
        // 2x2 image, 90 degrees: pixel centres at u, v = +-0.5, tan(45) = 1.
        let d = cam.direction(0, 0);
        let expect = DVec3::new(-0.5, 0.5, -1.0) / (1.5f64).sqrt();
        assert!((d - expect).abs().max_element() < 1e-15, "{d:?}");
        let d = cam.direction(1, 1);
        let expect = DVec3::new(0.5, -0.5, -1.0) / (1.5f64).sqrt();
        assert!((d - expect).abs().max_element() < 1e-15, "{d:?}");
    }

    #[test]
    fn bad_cameras_are_errors() {
        let b = Aabb::new(Vec3A::ZERO, Vec3A::ONE);
        assert_eq!(
            Camera::protocol(&b, 0, 4).err(),
            Some(CameraError::ImageSize(0, 4))
        );
        assert!(Camera::look_at(DVec3::ZERO, DVec3::ZERO, DVec3::Y, 45.0, 4, 4).is_err());
        assert!(Camera::look_at(DVec3::ZERO, DVec3::Y, DVec3::Y, 45.0, 4, 4).is_err());
        assert!(Camera::look_at(DVec3::ZERO, DVec3::X, DVec3::Y, 180.0, 4, 4).is_err());
    }
}
