//! `wave`: a sine wave travelling along `x` lifts and lowers the scene along `y`. A point at
//! fraction `u` of the rest bounds' `x` extent moves up by `amplitude` times the bounds'
//! diagonal times `sin(2π (waves u - t))`: one period over the frames, so the last frame
//! equals the first. A terrain waves like water; a closed mesh wobbles.

use super::{Motion, fraction};
use crate::geometry::Aabb;
use glam::Vec3A;
use std::f32::consts::TAU;

/// Height of the wave as a fraction of the rest bounds' diagonal, and wavelengths across the
/// bounds' `x` extent.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Wave {
    pub amplitude: f32,
    pub waves: f32,
}

impl Motion for Wave {
    fn place(&self, p: Vec3A, rest: &Aabb, t: f32) -> Vec3A {
        let u = fraction(p.x, rest.min.x, rest.max.x, 0.0);
        let lift = self.amplitude * rest.extent().length() * (TAU * (self.waves * u - t)).sin();
        Vec3A::new(p.x, p.y + lift, p.z)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lifts_along_y_only_and_travels_along_x() {
        let rest = Aabb::new(Vec3A::ZERO, Vec3A::new(4.0, 0.0, 3.0));
        let w = Wave {
            amplitude: 0.1,
            waves: 1.0,
        };
        // Diagonal 5: the crest is 0.5 high, at u = 1/4 when t = 0 and u = 1/2 when t = 1/4.
        let crest = w.place(Vec3A::new(1.0, 0.0, 2.0), &rest, 0.0);
        assert!(
            (crest - Vec3A::new(1.0, 0.5, 2.0)).length() < 1e-6,
            "{crest}"
        );
        let moved = w.place(Vec3A::new(2.0, 0.0, 2.0), &rest, 0.25);
        assert!((moved.y - 0.5).abs() < 1e-6, "{moved}");
        assert_eq!((moved.x, moved.z), (2.0, 2.0));
    }
}
