//! Camera motion blur: the eye moves along a straight segment during the shutter while the
//! camera's orientation stays fixed; each ray carries one time sample in `[0, 1)`. The scene is
//! static (moving objects would need time-varying geometry in every index: out of scope).

use super::{Camera, normalize_protocol};
use crate::geometry::{Ray, RayError};
use glam::DVec3;

/// The eye's path: at shutter time `tau` in `[0, 1)` it is at `eye + (tau - 0.5) * segment`, so
/// the segment is centred on the camera's eye.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EyeMotion {
    /// The whole displacement over the shutter, in scene units.
    pub segment: DVec3,
}

impl EyeMotion {
    /// The pinhole ray through screen point `(sx, sy)` ([`Camera::screen`]) from the eye at
    /// shutter time `tau`, over `[0, +inf]`.
    pub fn ray(&self, cam: &Camera, sx: f64, sy: f64, tau: f64) -> Result<Ray, RayError> {
        let origin = cam.eye + (tau - 0.5) * self.segment;
        let dir = normalize_protocol(cam.through_screen(sx, sy));
        Ray::infinite(origin.as_vec3(), dir.as_vec3())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::camera::on_z_axis;

    #[test]
    fn the_eye_sweeps_the_segment_and_directions_stay_pinhole() {
        let cam = on_z_axis(40.0, 8);
        let m = EyeMotion {
            segment: DVec3::new(1.0, 0.0, 0.0),
        };
        let (sx, sy) = cam.screen(3.5, 3.5);
        let a = m.ray(&cam, sx, sy, 0.0).unwrap();
        let b = m.ray(&cam, sx, sy, 0.75).unwrap();
        assert_eq!(a.origin.x, -0.5);
        assert_eq!(b.origin.x, 0.25);
        assert_eq!(a.dir, b.dir);
        assert_eq!(a.dir, cam.ray(3, 3).unwrap().dir);
    }
}
