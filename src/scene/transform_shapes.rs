//! Placing shapes by a [`Transform`] (scale, then rotate, then translate), computed in `f64` and
//! rounded to `f32` once, like triangles and spheres.

use super::transform::Transform;
use crate::geometry::shapes::{Cone, Cylinder, Ellipsoid, Obb, Polygon};
use crate::geometry::{Shape, ShapeError};
use glam::{DMat3, DVec3, Mat3A, Vec3A};

/// Why a shape cannot be placed by a transform; the message says what to fix.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ShapeTransformError {
    #[error("scale {1:?} is not uniform: a {0} can only be scaled by one factor (use scale = s)")]
    NonUniformScale(&'static str, [f64; 3]),
    #[error(
        "scale {1:?} is not uniform and the {0} is rotated: the result would not be a {0}; use a uniform scale, or scale before rotating"
    )]
    SkewedFrame(&'static str, [f64; 3]),
    #[error("the placed shape is invalid: {0}")]
    Shape(ShapeError),
}

/// The cause is in the message, not a chained source, so `{:#}` prints it once.
impl From<ShapeError> for ShapeTransformError {
    fn from(e: ShapeError) -> Self {
        ShapeTransformError::Shape(e)
    }
}

impl Transform {
    /// The transformed shape. Polygons take any transform; boxes and ellipsoids any scale that
    /// keeps their axes orthogonal (any scale when they are axis-aligned); cylinders and cones a
    /// uniform scale only. The identity returns the shape unchanged, bit for bit.
    pub fn shape(&self, s: &Shape) -> Result<Shape, ShapeTransformError> {
        if self.is_identity() {
            return Ok(s.clone());
        }
        let k = self.scale;
        let uniform = k.x.abs() == k.y.abs() && k.x.abs() == k.z.abs();
        let kind = s.kind();
        Ok(match s {
            Shape::Box(b) => {
                let (axes, half) = self.frame(kind, b.axes(), b.half_extents())?;
                Shape::Box(Obb::new(self.point(b.center()), half, axes)?)
            }
            Shape::Ellipsoid(e) => {
                let (axes, radii) = self.frame(kind, e.axes(), e.radii())?;
                Shape::Ellipsoid(Ellipsoid::new(self.point(e.center()), radii, axes)?)
            }
            Shape::ConvexPolygon(p) => Shape::ConvexPolygon(Polygon::convex(self.points(p))?),
            Shape::ConcavePolygon(p) => Shape::ConcavePolygon(Polygon::new(self.points(p))?),
            Shape::Cylinder(c) if uniform => Shape::Cylinder(Cylinder::new(
                self.point(c.base()),
                self.point(c.top()),
                (c.radius() as f64 * k.x.abs()) as f32,
            )?),
            Shape::Cone(c) if uniform => Shape::Cone(Cone::new(
                self.point(c.base()),
                self.point(c.apex()),
                (c.radius() as f64 * k.x.abs()) as f32,
            )?),
            Shape::Cylinder(_) | Shape::Cone(_) => {
                return Err(ShapeTransformError::NonUniformScale(kind, k.to_array()));
            }
        })
    }

    fn points(&self, p: &Polygon) -> Vec<Vec3A> {
        p.vertices().iter().map(|&v| self.point(v)).collect()
    }

    /// The frame and half-sizes of a box or ellipsoid after the transform: column `j` becomes
    /// `rotation * scale * axes_j`, whose length multiplies size `j`. The columns must stay
    /// orthogonal.
    fn frame(
        &self,
        kind: &'static str,
        axes: Mat3A,
        sizes: Vec3A,
    ) -> Result<(Mat3A, Vec3A), ShapeTransformError> {
        let mut cols = [DVec3::ZERO; 3];
        let mut out = [0.0f32; 3];
        for j in 0..3 {
            let m = self.scale * axes.col(j).as_dvec3();
            let len = m.length();
            cols[j] = self.rotation * (m / len);
            out[j] = (sizes[j] as f64 * len) as f32;
        }
        let frame = DMat3::from_cols(cols[0], cols[1], cols[2]);
        let skew = (frame.transpose() * frame - DMat3::IDENTITY).abs();
        if skew.x_axis.max(skew.y_axis).max(skew.z_axis).max_element() > 1.0e-5 {
            return Err(ShapeTransformError::SkewedFrame(
                kind,
                self.scale.to_array(),
            ));
        }
        Ok((frame.as_mat3().into(), Vec3A::from(out)))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn unit_box() -> Shape {
        Shape::Box(Obb::new(Vec3A::X, Vec3A::ONE, Mat3A::IDENTITY).unwrap())
    }

    #[test]
    fn box_scaled_rotated_translated() {
        let t = Transform::new(
            [2.0, 3.0, 4.0],
            Some(([0.0, 0.0, 1.0], 90.0)),
            [0.0, 0.0, 1.0],
        )
        .unwrap();
        let Shape::Box(b) = t.shape(&unit_box()).unwrap() else {
            panic!()
        };
        assert!((b.center() - Vec3A::new(0.0, 2.0, 1.0)).length() < 1e-6);
        assert_eq!(b.half_extents(), Vec3A::new(2.0, 3.0, 4.0));
        let bb = b.bounds();
        assert!((bb.min - Vec3A::new(-3.0, 0.0, -3.0)).abs().max_element() < 1e-5);
        // Scaling the rotated box non-uniformly again would skew it.
        let again = Transform::new([1.0, 2.0, 1.0], None, [0.0; 3]).unwrap();
        let turned = Transform::new([1.0; 3], Some(([0.0, 0.0, 1.0], 30.0)), [0.0; 3]).unwrap();
        let r = turned.shape(&unit_box()).unwrap();
        assert!(matches!(
            again.shape(&r),
            Err(ShapeTransformError::SkewedFrame("box", _))
        ));
    }

    #[test]
    fn cylinders_need_uniform_scale_and_identity_keeps_bits() {
        let c = Shape::Cylinder(Cylinder::new(Vec3A::ZERO, Vec3A::Z, 0.5).unwrap());
        let t = Transform::new([2.0, 1.0, 1.0], None, [0.0; 3]).unwrap();
        assert!(matches!(
            t.shape(&c),
            Err(ShapeTransformError::NonUniformScale("cylinder", _))
        ));
        let t = Transform::new([-2.0; 3], None, [1.0, 0.0, 0.0]).unwrap();
        let Shape::Cylinder(m) = t.shape(&c).unwrap() else {
            panic!()
        };
        assert_eq!((m.base(), m.radius()), (Vec3A::X, 1.0));
        assert!((m.top() - Vec3A::new(1.0, 0.0, -2.0)).length() < 1e-6);
        assert_eq!(Transform::IDENTITY.shape(&c).unwrap(), c);
    }
}
