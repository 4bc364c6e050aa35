//! What the capped cylinder and cone share: an axis segment, the ray split into parts along and
//! off that axis, and the rim-safe range tests that keep side and caps watertight.

use super::ShapeError;
use crate::geometry::Ray;
use glam::Vec3A;

/// Relative widening of the cylinder's and cone's range tests (a few ulps of the magnitudes
/// involved), so rims are watertight.
pub(super) const RIM_SLACK: f32 = 8.0 * f32::EPSILON;

/// Gives a capped solid with an [`AxialSegment`] field `seg` its axis, height and radius
/// ([`AxialSegment::axis`], `height`, `radius`) through `Deref`.
macro_rules! deref_to_segment {
    ($shape:ty) => {
        /// The axis, its height and radius ([`AxialSegment::axis`], `height`, `radius`).
        impl std::ops::Deref for $shape {
            type Target = AxialSegment;
            fn deref(&self) -> &AxialSegment {
                &self.seg
            }
        }
    };
}

/// The axis of a capped cylinder or cone: the segment from `start` along the unit `axis` for
/// `height`, and the `radius` of its widest disc (the cylinder's caps, the cone's base).
///
/// Invariants: finite `start`, unit `axis`, `height` and `radius` finite and `> 0`. The values
/// are the kernel's `f32` values, as stored.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AxialSegment {
    pub(super) start: Vec3A,
    pub(super) axis: Vec3A,
    pub(super) height: f32,
    pub(super) radius: f32,
}

impl AxialSegment {
    /// The segment from `from` to `to`, after checking that both points are finite, `radius` is
    /// finite and `> 0` and the points are distinct. `[shape, radius]` name the shape and its
    /// radius in the error (`["cone", "cone radius"]`).
    pub(super) fn new(
        from: Vec3A,
        to: Vec3A,
        radius: f32,
        [shape, radius_name]: [&'static str; 2],
    ) -> Result<AxialSegment, ShapeError> {
        if !(from.is_finite() && to.is_finite()) {
            return Err(ShapeError::NonFinite(shape));
        }
        if !(radius.is_finite() && radius > 0.0) {
            return Err(ShapeError::NotPositive(radius_name, radius));
        }
        let height = (to - from).length();
        if !(height.is_finite() && height > 0.0) {
            return Err(ShapeError::ZeroLength(shape));
        }
        Ok(AxialSegment {
            start: from,
            axis: (to - from) / height,
            height,
            radius,
        })
    }

    /// The far end, `start + axis * height`.
    pub fn end(&self) -> Vec3A {
        self.start + self.axis * self.height
    }

    /// The unit axis from the start to the end.
    pub fn axis(&self) -> Vec3A {
        self.axis
    }

    /// The distance from the start to the end.
    pub fn height(&self) -> f32 {
        self.height
    }

    pub fn radius(&self) -> f32 {
        self.radius
    }
}

/// The axial coordinate `z` of `q` (relative to the axis origin) along the unit `axis`, and its
/// radial part `q - axis z`.
#[inline]
pub(super) fn split(q: Vec3A, axis: Vec3A) -> (f32, Vec3A) {
    let z = q.dot(axis);
    (z, q - axis * z)
}

/// A ray in an axis frame: origin `o` relative to the axis origin split into `oz` (along the
/// unit axis) and `op` (off it), the direction likewise into `dz` and `dp`.
#[derive(Debug, Clone, Copy)]
pub(super) struct AxialRay {
    pub oz: f32,
    pub dz: f32,
    pub op: Vec3A,
    pub dp: Vec3A,
    op_len: f32,
    dp_len: f32,
}

impl AxialRay {
    #[inline]
    pub fn new(ray: &Ray, origin: Vec3A, axis: Vec3A) -> AxialRay {
        let (oz, op) = split(ray.origin - origin, axis);
        let (dz, dp) = split(ray.dir, axis);
        AxialRay {
            oz,
            dz,
            op,
            dp,
            op_len: op.length(),
            dp_len: dp.length(),
        }
    }

    /// `t` when the point at `t` lies within `0 <= z <= height`, widened by a bound on the test's
    /// own rounding; NaN otherwise (so [`super::first_hit`] ignores it).
    #[inline]
    pub fn within_height(&self, t: f32, height: f32) -> f32 {
        let z = self.oz + t * self.dz;
        let slack = RIM_SLACK * (self.oz.abs() + (t * self.dz).abs());
        if z >= -slack && z <= height + slack {
            t
        } else {
            f32::NAN
        }
    }

    /// Where the ray crosses the cap plane at axial coordinate `z` within `radius` of the axis
    /// (widened like [`Self::within_height`], so a ray through the rim is taken by the side or
    /// the cap), or NaN.
    #[inline]
    pub fn cap(&self, z: f32, radius: f32) -> f32 {
        if self.dz == 0.0 {
            return f32::NAN;
        }
        let t = (z - self.oz) / self.dz;
        let reach = radius + RIM_SLACK * (self.op_len + t.abs() * self.dp_len);
        if (self.op + self.dp * t).length_squared() <= reach * reach {
            t
        } else {
            f32::NAN
        }
    }
}

/// Test support: rays aimed from random outside points at random points of a rim.
#[cfg(test)]
pub(super) mod rim_test {
    use crate::geometry::test_support::unit_floats;
    use crate::geometry::{Aabb, Ray};
    use glam::{DVec3, Vec3A};

    /// Shoots `n` rays from random points in `[-4, 4]^3` outside `bounds` at `rim(angle, i)` and
    /// asserts that none slips: misses (or hits beyond the rim) although its exact line enters
    /// the solid (`depth`, how far a point lies inside it, exceeds `1e-6` near `t = 1`).
    pub fn assert_rim_watertight(
        seed: u64,
        n: usize,
        bounds: Aabb,
        rim: impl Fn(f32, usize) -> Vec3A,
        hit: impl Fn(&Ray) -> Option<f32>,
        depth: impl Fn(DVec3) -> f64,
    ) {
        let mut next = unit_floats(seed);
        let mut slipped = Vec::new();
        for i in 0..n {
            let target = rim(std::f32::consts::TAU * next(), i);
            let o = Vec3A::new(next(), next(), next()) * 8.0 - 4.0;
            if bounds.contains(o) {
                continue;
            }
            let ray = Ray::infinite(o.into(), (target - o).into()).unwrap();
            match hit(&ray) {
                Some(t) if t <= 1.0 + 1e-4 => {}
                // Only a ray whose exact line enters the solid must hit; one that just touches
                // the rim (on the silhouette, within the rounding of the aim) may miss.
                other if deepest(&ray, &depth) > 1e-6 => slipped.push((ray, other)),
                _ => {}
            }
        }
        assert!(
            slipped.is_empty(),
            "{} slipped, first {:?}",
            slipped.len(),
            slipped[0]
        );
    }

    /// The largest of `depth(point)` over the exact line of `ray` for `t` in `[0.99, 1.01]`.
    fn deepest(ray: &Ray, depth: impl Fn(DVec3) -> f64) -> f64 {
        let (o, d) = (ray.origin.as_dvec3(), ray.dir.as_dvec3());
        (0..=2000)
            .map(|k| depth(o + d * (0.99 + 0.02 * k as f64 / 2000.0)))
            .fold(f64::NEG_INFINITY, f64::max)
    }
}
