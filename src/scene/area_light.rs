//! Rectangular area lights: a parallelogram `corner + a * edge1 + b * edge2`, `a, b` in `[0, 1]`,
//! sampled on a fixed `samples x samples` stratified grid.

use glam::Vec3;
use serde::{Deserialize, Serialize};

/// Largest accepted `samples` (strata per edge): 64 x 64 = 4096 shadow rays per light per pixel.
pub const MAX_AREA_LIGHT_SAMPLES: u32 = 64;

/// A rectangular (parallelogram) light. Its `intensity` is the total: each of the
/// `samples * samples` samples is a point light of `intensity / samples^2`, so a fully visible
/// area light lights like a point light of the same intensity. The light itself is not geometry:
/// camera rays do not see it and it casts no shadow.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AreaLight {
    /// One corner, in scene units.
    pub corner: Vec3,
    /// The two edges from `corner`.
    pub edge1: Vec3,
    pub edge2: Vec3,
    /// Total RGB intensity (default white).
    #[serde(default = "super::white")]
    pub intensity: Vec3,
    /// Strata per edge (default 4, i.e. 16 shadow rays per shaded point).
    #[serde(default = "four")]
    pub samples: u32,
}

fn four() -> u32 {
    4
}

impl AreaLight {
    /// Checks finite values, a non-negative intensity, edges spanning an area, and `samples` in
    /// `1..=MAX_AREA_LIGHT_SAMPLES`; the message says what to fix.
    pub fn validate(&self) -> Result<(), String> {
        let finite = self.corner.is_finite()
            && self.edge1.is_finite()
            && self.edge2.is_finite()
            && self.intensity.is_finite();
        if !finite || self.intensity.min_element() < 0.0 {
            return Err(format!(
                "corner {:?}, edges {:?} {:?} and intensity {:?} must be finite, intensity >= 0",
                self.corner.to_array(),
                self.edge1.to_array(),
                self.edge2.to_array(),
                self.intensity.to_array()
            ));
        }
        if self.edge1.cross(self.edge2).length_squared() == 0.0 {
            return Err(format!(
                "edges {:?} and {:?} span no area: give two non-parallel, non-zero edges",
                self.edge1.to_array(),
                self.edge2.to_array()
            ));
        }
        if !(1..=MAX_AREA_LIGHT_SAMPLES).contains(&self.samples) {
            return Err(format!(
                "samples = {} is invalid: give 1 to {MAX_AREA_LIGHT_SAMPLES} strata per edge",
                self.samples
            ));
        }
        Ok(())
    }

    /// The point at parameters `(a, b)` in `[0, 1]^2`.
    #[inline]
    pub fn point(&self, a: f32, b: f32) -> Vec3 {
        self.corner + self.edge1 * a + self.edge2 * b
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn validation() {
        let l = AreaLight {
            corner: Vec3::ZERO,
            edge1: Vec3::X,
            edge2: Vec3::Z,
            intensity: Vec3::ONE,
            samples: 4,
        };
        assert!(l.validate().is_ok());
        assert_eq!(l.point(1.0, 1.0), Vec3::new(1.0, 0.0, 1.0));
        let parallel = AreaLight {
            edge2: Vec3::X * 2.0,
            ..l
        };
        assert!(parallel.validate().unwrap_err().contains("no area"));
        let zero = AreaLight { samples: 0, ..l };
        assert!(zero.validate().unwrap_err().contains("samples"));
        let nan = AreaLight {
            corner: Vec3::NAN,
            ..l
        };
        assert!(nan.validate().is_err());
    }
}
