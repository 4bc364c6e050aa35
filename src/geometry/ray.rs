//! Rays with everything the kernels and slab tests precompute once per ray.

use super::real::{KernelRay, Shear};
use glam::{Vec3, Vec3A};
use thiserror::Error;

/// Why a ray could not be built. Rays are validated at the boundary (CLI, file readers,
/// generators) so that the hot path never sees NaN, infinities or zero directions.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum RayError {
    #[error("ray origin {0:?} has a NaN or infinite component")]
    NonFiniteOrigin(Vec3),
    #[error("ray direction {0:?} has a NaN or infinite component")]
    NonFiniteDirection(Vec3),
    #[error("ray direction is zero (all three components are 0)")]
    ZeroDirection,
    #[error(
        "ray interval [{0}, {1}] is invalid: t_min must be finite and not NaN, t_max must not be NaN, and t_min <= t_max"
    )]
    BadInterval(f32, f32),
}

/// A ray `origin + t * dir` for `t` in the closed interval `[t_min, t_max]`.
///
/// Invariants (enforced by [`Ray::new`]): origin and direction finite, direction not zero,
/// `t_min` finite, `t_max` not NaN (may be `+inf`), `t_min <= t_max`. `dir` need not be
/// normalized; `t` is measured in units of `dir`. `inv_dir` is `1/dir` per component, so a zero
/// component (`+0.0` or `-0.0`) gives `+inf` or `-inf`, never NaN.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ray {
    pub origin: Vec3A,
    pub dir: Vec3A,
    pub inv_dir: Vec3A,
    pub t_min: f32,
    pub t_max: f32,
    pub shear: Shear,
}

impl Ray {
    /// Builds a validated ray.
    pub fn new(origin: Vec3, dir: Vec3, t_min: f32, t_max: f32) -> Result<Ray, RayError> {
        if !origin.is_finite() {
            return Err(RayError::NonFiniteOrigin(origin));
        }
        if !dir.is_finite() {
            return Err(RayError::NonFiniteDirection(dir));
        }
        if dir == Vec3::ZERO {
            return Err(RayError::ZeroDirection);
        }
        if !t_min.is_finite() || t_max.is_nan() || t_min > t_max {
            return Err(RayError::BadInterval(t_min, t_max));
        }
        let dir = Vec3A::from(dir);
        Ok(Ray {
            origin: Vec3A::from(origin),
            dir,
            inv_dir: Vec3A::ONE / dir,
            t_min,
            t_max,
            shear: Shear::new(dir),
        })
    }

    /// A ray over `[0, +inf]`.
    pub fn infinite(origin: Vec3, dir: Vec3) -> Result<Ray, RayError> {
        Ray::new(origin, dir, 0.0, f32::INFINITY)
    }

    /// The same ray with another interval (validated).
    pub fn with_interval(&self, t_min: f32, t_max: f32) -> Result<Ray, RayError> {
        Ray::new(self.origin.into(), self.dir.into(), t_min, t_max)
    }

    /// Whether the slab tests may take their variant without NaN selects and with the far
    /// distance widened by one product (`SAFE = false` in `index::kit::box_tree::slab` and in
    /// `scene::accept`): every `inv_dir` component finite and `t_min >= 0`.
    #[inline(always)]
    pub fn fast_slabs(&self) -> bool {
        self.inv_dir.is_finite() && self.t_min >= 0.0
    }

    /// The point at parameter `t`.
    #[inline]
    pub fn at(&self, t: f32) -> Vec3A {
        KernelRay::at(self, t)
    }
}

impl KernelRay for Ray {
    type Scalar = f32;
    type Vec = Vec3A;
    #[inline(always)]
    fn origin(&self) -> Vec3A {
        self.origin
    }
    #[inline(always)]
    fn dir(&self) -> Vec3A {
        self.dir
    }
    #[inline(always)]
    fn t_min(&self) -> f32 {
        self.t_min
    }
    #[inline(always)]
    fn shear(&self) -> &Shear {
        &self.shear
    }
}

impl Shear {
    fn new(dir: Vec3A) -> Shear {
        let a = dir.abs();
        // Largest component; ties go to the lowest axis so the choice is deterministic.
        let kz = if a.x >= a.y && a.x >= a.z {
            0
        } else if a.y >= a.z {
            1
        } else {
            2
        };
        let mut kx = (kz + 1) % 3;
        let mut ky = (kx + 1) % 3;
        if dir[kz] < 0.0 {
            std::mem::swap(&mut kx, &mut ky);
        }
        Shear::with_axes([kx, ky, kz], dir)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn zero_components_give_signed_infinite_inverse() {
        let r = Ray::infinite(Vec3::ZERO, Vec3::new(0.0, -0.0, 1.0)).unwrap();
        assert_eq!(r.inv_dir.x, f32::INFINITY);
        assert_eq!(r.inv_dir.y, f32::NEG_INFINITY);
        assert_eq!(r.inv_dir.z, 1.0);
    }

    #[test]
    fn bad_rays_are_typed_errors() {
        assert_eq!(
            Ray::infinite(Vec3::ZERO, Vec3::ZERO),
            Err(RayError::ZeroDirection)
        );
        assert!(matches!(
            Ray::infinite(Vec3::new(f32::NAN, 0.0, 0.0), Vec3::X),
            Err(RayError::NonFiniteOrigin(_))
        ));
        assert!(matches!(
            Ray::infinite(Vec3::ZERO, Vec3::new(0.0, f32::INFINITY, 0.0)),
            Err(RayError::NonFiniteDirection(_))
        ));
        assert!(matches!(
            Ray::new(Vec3::ZERO, Vec3::X, 2.0, 1.0),
            Err(RayError::BadInterval(..))
        ));
        assert!(matches!(
            Ray::new(Vec3::ZERO, Vec3::X, 0.0, f32::NAN),
            Err(RayError::BadInterval(..))
        ));
        assert!(Ray::new(Vec3::ZERO, Vec3::X, 1.0, 1.0).is_ok());
    }

    #[test]
    fn shear_picks_dominant_axis_and_keeps_winding() {
        let r = Ray::infinite(Vec3::ZERO, Vec3::new(0.1, -3.0, 0.5)).unwrap();
        assert_eq!(r.shear.kz, 1);
        // dir[kz] < 0 swaps kx and ky
        assert_eq!((r.shear.kx, r.shear.ky), (0, 2));
        assert_eq!(r.shear.sz, 1.0 / -3.0);
    }
}
