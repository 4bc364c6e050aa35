//! What the shapes' tests and constructors share: the first hit among candidate `t`s, padded
//! bounds, the box overlap of a cell, frame and disc checks.

use super::ShapeError;
use crate::geometry::{Aabb, Ray};
use glam::{Mat3A, Vec3A};

/// The smallest finite candidate `>= t_min`, if it is `<= t_max` (NaN never passes).
#[inline(always)]
pub(super) fn first_hit<const N: usize>(
    candidates: [f32; N],
    ray: &Ray,
    t_max: f32,
) -> Option<f32> {
    let mut best = f32::INFINITY;
    for t in candidates {
        if t >= ray.t_min && t < best {
            best = t;
        }
    }
    (best.is_finite() && best <= t_max).then_some(best)
}

/// Bounds overlap with the cell padded as in [`crate::geometry::overlap`].
pub(super) fn bounds_overlap(bounds: &Aabb, cell: &Aabb) -> bool {
    bounds.overlaps(&cell.padded(crate::geometry::overlap::OVERLAP_PAD))
}

/// `center ± half` grown by a few ulps of the largest coordinate, so bounds computed through
/// rounded products still contain the exact surface.
pub(super) fn padded_bounds(center: Vec3A, half: Vec3A) -> Aabb {
    let pad = 8.0 * f32::EPSILON * (center.abs() + half).max_element() + f32::MIN_POSITIVE;
    let half = half + Vec3A::splat(pad);
    Aabb::new(center - half, center + half)
}

/// Checks the frame of a box or an ellipsoid: a finite `center`, every size finite and `> 0`,
/// orthonormal `axes`; returns the axes renormalized ([`orthonormal`]). `[center, size, axes]`
/// name the three in the error (`["box center", "box half-extent", "box axes"]`).
pub(super) fn checked_frame(
    center: Vec3A,
    sizes: Vec3A,
    axes: Mat3A,
    [center_name, size_name, axes_name]: [&'static str; 3],
) -> Result<Mat3A, ShapeError> {
    if !center.is_finite() {
        return Err(ShapeError::NonFinite(center_name));
    }
    if let Some(bad) = sizes
        .to_array()
        .into_iter()
        .find(|s| !(s.is_finite() && *s > 0.0))
    {
        return Err(ShapeError::NotPositive(size_name, bad));
    }
    orthonormal(axes_name, axes)
}

/// Checks that the columns of `m` form an orthonormal basis (to `1e-4`), and returns it with
/// its columns renormalized.
fn orthonormal(what: &'static str, m: Mat3A) -> Result<Mat3A, ShapeError> {
    if !m.is_finite() {
        return Err(ShapeError::NonFinite(what));
    }
    let err = (m.transpose() * m - Mat3A::IDENTITY).abs();
    let worst = err.x_axis.max(err.y_axis).max(err.z_axis).max_element();
    if worst > 1.0e-4 {
        return Err(ShapeError::NotOrthonormal(what));
    }
    Ok(Mat3A::from_cols(
        m.x_axis.normalize(),
        m.y_axis.normalize(),
        m.z_axis.normalize(),
    ))
}

/// The half-extents of a disc of radius `r` centred on the origin with unit normal `n`:
/// `r * sqrt(1 - n_i^2)` per axis.
pub(super) fn disc_half_extent(n: Vec3A, r: f32) -> Vec3A {
    let s = (Vec3A::ONE - n * n).max(Vec3A::ZERO);
    Vec3A::new(s.x.sqrt(), s.y.sqrt(), s.z.sqrt()) * r
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    #[test]
    fn first_hit_picks_smallest_in_range() {
        let r = Ray::new(Vec3::ZERO, Vec3::X, 1.0, 10.0).unwrap();
        assert_eq!(first_hit([5.0, 0.5, 2.0, f32::NAN], &r, 10.0), Some(2.0));
        assert_eq!(first_hit([0.5, 11.0], &r, 10.0), None);
        assert_eq!(first_hit([f32::INFINITY], &r, f32::INFINITY), None);
        // t_max does not change which candidate is chosen, only acceptance.
        assert_eq!(first_hit([3.0, 2.0], &r, 2.5), Some(2.0));
        assert_eq!(first_hit([3.0, 2.0], &r, 1.5), None);
    }

    #[test]
    fn orthonormal_accepts_rotations_only() {
        let r = Mat3A::from_rotation_y(0.3);
        assert!(orthonormal("t", r).is_ok());
        assert_eq!(
            orthonormal("t", Mat3A::from_diagonal(Vec3::new(1.0, 2.0, 1.0))),
            Err(ShapeError::NotOrthonormal("t"))
        );
    }

    #[test]
    fn disc_extent() {
        let e = disc_half_extent(Vec3A::Z, 2.0);
        assert_eq!(e, Vec3A::new(2.0, 2.0, 0.0));
    }
}
