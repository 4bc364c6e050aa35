//! The thin-lens camera (depth of field): rays leave a disk of radius `aperture_radius` around
//! the eye (in the plane of the camera's `right` and `up`) and pass through the point the
//! pinhole ray of the same film point reaches on the focal plane, `focus_distance` in front of
//! the eye. Points on the focal plane are sharp; the rest blurs with distance from it.

use super::{Camera, normalize_protocol};
use crate::geometry::{Ray, RayError};
use std::f64::consts::FRAC_PI_4;

/// A thin lens in scene units.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ThinLens {
    /// Radius of the lens disk (0 gives the pinhole's directions from the eye).
    pub aperture_radius: f64,
    /// Distance of the focal plane along the view direction; positive.
    pub focus_distance: f64,
}

impl ThinLens {
    /// The ray through screen point `(sx, sy)` ([`Camera::screen`]) from the lens point of the
    /// unit-square sample `lens` (mapped to the disk by [`concentric_disk`]), over `[0, +inf]`.
    pub fn ray(&self, cam: &Camera, sx: f64, sy: f64, lens: [f64; 2]) -> Result<Ray, RayError> {
        let (dx, dy) = concentric_disk(lens);
        let r = self.aperture_radius;
        let origin = cam.eye + (dx * r) * cam.right + (dy * r) * cam.up;
        let focus = cam.eye + cam.through_screen(sx, sy) * self.focus_distance;
        let dir = normalize_protocol(focus - origin);
        Ray::infinite(origin.as_vec3(), dir.as_vec3())
    }
}

/// Shirley and Chiu's concentric map of the unit square onto the unit disk: equal areas to
/// equal areas, strata stay compact.
pub fn concentric_disk([u, v]: [f64; 2]) -> (f64, f64) {
    let (a, b) = (2.0 * u - 1.0, 2.0 * v - 1.0);
    if a == 0.0 && b == 0.0 {
        return (0.0, 0.0);
    }
    let (r, phi) = if a.abs() > b.abs() {
        (a, FRAC_PI_4 * (b / a))
    } else {
        (b, 2.0 * FRAC_PI_4 - FRAC_PI_4 * (a / b))
    };
    (r * phi.cos(), r * phi.sin())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::camera::on_z_axis;

    #[test]
    fn disk_samples_stay_in_the_disk_and_cover_it() {
        let mut area = [0usize; 4];
        for i in 0..64 {
            for j in 0..64 {
                let (x, y) = concentric_disk([(i as f64 + 0.5) / 64.0, (j as f64 + 0.5) / 64.0]);
                assert!(x * x + y * y <= 1.0 + 1e-12);
                area[(x > 0.0) as usize + 2 * (y > 0.0) as usize] += 1;
            }
        }
        // Equal-area map: each quadrant gets a quarter of the samples.
        assert!(area.iter().all(|&a| a == 1024), "{area:?}");
    }

    #[test]
    fn rays_of_one_film_point_meet_on_the_focal_plane() {
        let cam = on_z_axis(40.0, 8);
        let lens = ThinLens {
            aperture_radius: 0.3,
            focus_distance: 5.0,
        };
        let (sx, sy) = cam.screen(2.5, 6.5);
        let target = cam.eye + cam.through_screen(sx, sy) * 5.0;
        for s in [[0.1, 0.9], [0.5, 0.5], [0.8, 0.2]] {
            let r = lens.ray(&cam, sx, sy, s).unwrap();
            let o = r.origin.as_dvec3();
            // Off the eye by at most the aperture, and aimed at the focal point.
            assert!((o - cam.eye).length() <= 0.3 + 1e-6);
            let to_target = (target - o).normalize();
            assert!((to_target - r.dir.as_dvec3()).length() < 1e-6, "{s:?}");
        }
    }
}
