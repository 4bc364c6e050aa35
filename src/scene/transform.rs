//! Placement of scene-file objects: scale, then rotate about the origin, then translate.
//! Computed in `f64` and rounded to `f32` once per coordinate; the identity leaves every bit
//! (also the sign of zero) unchanged.

use crate::geometry::{Sphere, Triangle};
use glam::{DMat3, DVec3, Vec3A};

/// An affine placement `p -> rotation * (scale * p) + translate`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Transform {
    pub scale: DVec3,
    pub rotation: DMat3,
    pub translate: DVec3,
}

/// Why a transform cannot be built or applied; the message says what to fix.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum TransformError {
    #[error("scale {0:?} is invalid: every factor must be finite and non-zero")]
    Scale([f64; 3]),
    #[error("translate {0:?} is invalid: every component must be finite")]
    Translate([f64; 3]),
    #[error("rotation axis {0:?} is invalid: it must be finite and non-zero")]
    Axis([f64; 3]),
    #[error("rotation angle {0} degrees is invalid: it must be finite")]
    Angle(f64),
    #[error("scale {0:?} is not uniform: spheres can only be scaled by one factor (use scale = s)")]
    NonUniformSphereScale([f64; 3]),
}

impl Default for Transform {
    fn default() -> Transform {
        Transform::IDENTITY
    }
}

impl Transform {
    pub const IDENTITY: Transform = Transform {
        scale: DVec3::ONE,
        rotation: DMat3::IDENTITY,
        translate: DVec3::ZERO,
    };

    /// A validated transform: non-zero finite scale factors (negative ones mirror), a finite
    /// non-zero rotation axis (any length) with a finite angle in degrees, a finite translation.
    pub fn new(
        scale: [f64; 3],
        rotate: Option<([f64; 3], f64)>,
        translate: [f64; 3],
    ) -> Result<Transform, TransformError> {
        if !scale.iter().all(|s| s.is_finite() && *s != 0.0) {
            return Err(TransformError::Scale(scale));
        }
        if !translate.iter().all(|t| t.is_finite()) {
            return Err(TransformError::Translate(translate));
        }
        let rotation = match rotate {
            None => DMat3::IDENTITY,
            Some((axis, degrees)) => {
                let a = DVec3::from(axis);
                if !a.is_finite() || a == DVec3::ZERO {
                    return Err(TransformError::Axis(axis));
                }
                if !degrees.is_finite() {
                    return Err(TransformError::Angle(degrees));
                }
                DMat3::from_axis_angle(a.normalize(), degrees.to_radians())
            }
        };
        Ok(Transform {
            scale: DVec3::from(scale),
            rotation,
            translate: DVec3::from(translate),
        })
    }

    pub fn is_identity(&self) -> bool {
        *self == Transform::IDENTITY
    }

    /// The transformed point, rounded to `f32` once.
    pub fn point(&self, p: Vec3A) -> Vec3A {
        if self.is_identity() {
            return p;
        }
        (self.rotation * (self.scale * p.as_dvec3()) + self.translate)
            .as_vec3()
            .into()
    }

    pub fn triangle(&self, t: &Triangle) -> Triangle {
        Triangle::new(self.point(t.v[0]), self.point(t.v[1]), self.point(t.v[2]))
    }

    /// The transformed sphere: centre transformed, radius times `|s|`; only a uniform scale `s`
    /// keeps a sphere a sphere.
    pub fn sphere(&self, s: &Sphere) -> Result<Sphere, TransformError> {
        let k = self.scale;
        if k.x.abs() != k.y.abs() || k.x.abs() != k.z.abs() {
            return Err(TransformError::NonUniformSphereScale(k.to_array()));
        }
        if self.is_identity() {
            return Ok(*s);
        }
        let radius = (s.radius as f64 * k.x.abs()) as f32;
        Ok(Sphere::new(self.point(s.center), radius))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn scale_rotate_translate_in_that_order() {
        let t = Transform::new([2.0; 3], Some(([0.0, 0.0, 5.0], 90.0)), [1.0, 0.0, 0.0]).unwrap();
        let p = t.point(Vec3A::X);
        // (1,0,0) -> scale (2,0,0) -> rotate 90 deg about +z (0,2,0) -> translate (1,2,0).
        assert!(
            (p - Vec3A::new(1.0, 2.0, 0.0)).abs().max_element() < 1e-6,
            "{p:?}"
        );
    }

    #[test]
    fn identity_keeps_bits() {
        let p = Vec3A::new(-0.0, 1.0e-30, 3.1);
        assert_eq!(
            Transform::IDENTITY.point(p).x.to_bits(),
            (-0.0f32).to_bits()
        );
        assert_eq!(Transform::IDENTITY.point(p), p);
    }

    #[test]
    fn bad_values_are_errors() {
        assert!(Transform::new([1.0, 0.0, 1.0], None, [0.0; 3]).is_err());
        assert!(Transform::new([f64::NAN; 3], None, [0.0; 3]).is_err());
        assert!(Transform::new([1.0; 3], None, [f64::INFINITY, 0.0, 0.0]).is_err());
        assert!(Transform::new([1.0; 3], Some(([0.0; 3], 10.0)), [0.0; 3]).is_err());
        assert!(Transform::new([1.0; 3], Some(([1.0, 0.0, 0.0], f64::NAN)), [0.0; 3]).is_err());
    }

    #[test]
    fn spheres_need_uniform_scale() {
        let s = Sphere::new(Vec3A::ONE, 0.5);
        let t = Transform::new([-2.0, 2.0, 2.0], None, [1.0, 0.0, 0.0]).unwrap();
        let m = t.sphere(&s).unwrap();
        assert_eq!((m.center, m.radius), (Vec3A::new(-1.0, 2.0, 2.0), 1.0));
        let t = Transform::new([1.0, 2.0, 1.0], None, [0.0; 3]).unwrap();
        assert!(matches!(
            t.sphere(&s),
            Err(TransformError::NonUniformSphereScale(_))
        ));
    }
}
