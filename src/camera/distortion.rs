//! Radial lens distortion after Brown and Conrady: a point of the ideal (pinhole) image at
//! normalized radius `r_u` appears at `r_d = r_u (1 + k1 r_u^2 + k2 r_u^4)`. Radii are in units
//! of the image's half-height on the screen plane (`r = 1` at the middle of the top edge).
//! `k1 < 0` is barrel distortion (the image is squeezed towards its edges, straight lines bow
//! outwards), `k1 > 0` pincushion.
//!
//! A film point is a distorted position; its ray goes through the undistorted one, found by
//! bisection on the radius (the map is checked to be increasing, so the inverse exists and is
//! unique).

use super::{Camera, CameraError, normalize_protocol};
use crate::geometry::{Ray, RayError};

/// Largest undistorted radius the inverse searches (far beyond any sensible image corner).
const MAX_UNDISTORTED_RADIUS: f64 = 4.0;
/// Bisection steps: `MAX_UNDISTORTED_RADIUS / 2^64` is below the `f64` spacing of the radius.
const BISECTION_STEPS: u32 = 64;

/// Brown-Conrady radial coefficients.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Distortion {
    pub k1: f64,
    pub k2: f64,
}

impl Distortion {
    /// The default of the `lens` ray set: moderate barrel distortion (`k1 = -0.1`,
    /// `k2 = 0.01`: the corner of a square image, at distorted radius `sqrt(2)`, looks where a
    /// pinhole's radius 1.815 would).
    pub const BARREL: Distortion = Distortion { k1: -0.1, k2: 0.01 };

    /// Distorted radius of undistorted radius `r`.
    fn distort(&self, r: f64) -> f64 {
        let r2 = r * r;
        r * (1.0 + self.k1 * r2 + self.k2 * r2 * r2)
    }

    /// Checks the coefficients are finite, the map increasing on `[0, 4]` and that it reaches
    /// `max_radius` (the image corner's distorted radius) there, so every film point has one
    /// undistorted position.
    pub fn validate(&self, max_radius: f64) -> Result<(), CameraError> {
        let bad = |reason: &str| CameraError::Distortion {
            k1: self.k1,
            k2: self.k2,
            reason: reason.to_owned(),
        };
        if !(self.k1.is_finite() && self.k2.is_finite()) {
            return Err(bad("the coefficients must be finite"));
        }
        // d r_d / d r_u = 1 + 3 k1 s + 5 k2 s^2 with s = r_u^2: a parabola in s on [0, 16].
        let slope = |s: f64| 1.0 + 3.0 * self.k1 * s + 5.0 * self.k2 * s * s;
        let s_max = MAX_UNDISTORTED_RADIUS * MAX_UNDISTORTED_RADIUS;
        let mut lowest = slope(0.0).min(slope(s_max));
        if self.k2 > 0.0 {
            let vertex = -3.0 * self.k1 / (10.0 * self.k2);
            if (0.0..=s_max).contains(&vertex) {
                lowest = lowest.min(slope(vertex));
            }
        }
        if lowest <= 0.0 {
            return Err(bad(
                "the distortion folds the image over (r_d is not increasing in r_u up to 4); use smaller |k1|, |k2|",
            ));
        }
        if self.distort(MAX_UNDISTORTED_RADIUS) < max_radius {
            return Err(bad(
                "the image corners map beyond an undistorted radius of 4; use a smaller |k1|",
            ));
        }
        Ok(())
    }

    /// The undistorted radius whose distorted radius is `r_d` (bisection on `[0, 4]`).
    pub fn undistort_radius(&self, r_d: f64) -> f64 {
        let (mut lo, mut hi) = (0.0, MAX_UNDISTORTED_RADIUS);
        for _ in 0..BISECTION_STEPS {
            let mid = 0.5 * (lo + hi);
            if self.distort(mid) < r_d {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        0.5 * (lo + hi)
    }

    /// The ray whose distorted image is screen point `(sx, sy)` ([`Camera::screen`]), from the
    /// eye over `[0, +inf]`.
    pub fn ray(&self, cam: &Camera, sx: f64, sy: f64) -> Result<Ray, RayError> {
        let t = cam.tan_half_fov;
        let (x, y) = (sx / t, sy / t);
        let r_d = (x * x + y * y).sqrt();
        let scale = if r_d > 0.0 {
            self.undistort_radius(r_d) / r_d
        } else {
            1.0
        };
        let dir = normalize_protocol(cam.through_screen(sx * scale, sy * scale));
        Ray::infinite(cam.eye.as_vec3(), dir.as_vec3())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn undistort_inverts_distort_and_barrel_widens_the_view() {
        let d = Distortion::BARREL;
        d.validate(2f64.sqrt()).unwrap();
        for r in [0.0, 0.1, 0.7, 1.0, 1.5] {
            let u = d.undistort_radius(d.distort(r));
            assert!((u - r).abs() < 1e-12, "{r}: {u}");
        }
        // Barrel: the film edge sees further out than the pinhole would.
        assert!(d.undistort_radius(1.0) > 1.0);
        let corner = d.undistort_radius(2f64.sqrt());
        assert!((corner - 1.8153).abs() < 1e-4, "{corner}");
        assert_eq!(Distortion { k1: 0.0, k2: 0.0 }.undistort_radius(0.5), 0.5);
    }

    #[test]
    fn folding_or_non_finite_coefficients_are_errors() {
        for (k1, k2) in [(-0.5, 0.0), (f64::NAN, 0.0), (0.0, -0.01), (-3.0, 1.0)] {
            let e = Distortion { k1, k2 }.validate(1.5).unwrap_err();
            assert!(e.to_string().contains("k1"), "{e}");
        }
        assert!(Distortion { k1: 0.05, k2: 0.0 }.validate(1.5).is_ok());
    }
}
