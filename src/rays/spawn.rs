//! Where secondary rays (shadow, diffuse, ambient occlusion) start: the hit point moved off the
//! surface so the new ray does not hit the surface it leaves ("self-intersection").
//!
//! Methods compared by `accelbench stress`: a `t_min` epsilon in units of the scene size, and the
//! origin offset of Wächter and Binder (Ray Tracing Gems, ch. 6, "A Fast and Robust Method for
//! Avoiding Self-Intersection"), which moves the point along the geometric normal by a fixed
//! number of ulps of its own coordinates (and by a small amount near the origin), with that
//! near-origin amount either absolute (their constants) or relative to the scene's size.
//!
//! The default for every secondary ray (suite and renders) is the scene-relative offset
//! ([`offset_origin_scaled`] with [`spawn_scale`]): in the stress suite's study it was the only
//! method with no self-hit at any scale or offset and no missed contact wherever the gap spans
//! at least 1024 ulps (see `reports/stress/stress.md`).

use crate::geometry::Aabb;
use glam::Vec3A;

/// How secondary rays leave a surface.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum SpawnMethod {
    /// Start at the hit point, with `t_min = epsilon * scene_size / |dir|`.
    Epsilon(f32),
    /// Start at [`offset_origin`] (Wächter and Binder's constants, in absolute units) with
    /// `t_min = 0`.
    Offset,
    /// Start at [`offset_origin_scaled`] with the scene's size, `t_min = 0`.
    ScaledOffset,
}

/// Below this magnitude a coordinate is offset by an absolute amount (the integer offset would be
/// a denormal step).
const ORIGIN: f32 = 1.0 / 32.0;
/// Absolute offset near zero, in scene units.
const FLOAT_SCALE: f32 = 1.0 / 65536.0;
/// Offset in ulps of the coordinate.
const INT_SCALE: f32 = 256.0;

/// The point `p` on a surface moved off it along `n` (the geometric normal facing the side the
/// new ray leaves into; it need not be unit length but must not be zero), per Wächter and Binder,
/// with their constants in absolute units: right for scenes about 1 to 100 units across near the
/// origin; a scene 1e-3 across gets an offset of 1.5% of its size near the origin.
#[inline]
pub fn offset_origin(p: Vec3A, n: Vec3A) -> Vec3A {
    offset_origin_scaled(p, n, 1.0)
}

/// [`offset_origin`] with the near-origin region (`|coordinate| < scene_size / 32`) and the
/// absolute offset used there (`scene_size / 65536` along `n`) measured in units of the scene's
/// size (`scene_size > 0`, e.g. the diagonal of its bounds), so the method behaves the same at
/// every scale; far from the origin both move the point by 256 ulps of its coordinates.
#[inline]
pub fn offset_origin_scaled(p: Vec3A, n: Vec3A, scene_size: f32) -> Vec3A {
    let of_i = (n * INT_SCALE).to_array().map(|c| c as i32);
    let pa = p.to_array();
    let p_i: [f32; 3] = std::array::from_fn(|k| {
        let bits = pa[k].to_bits() as i32;
        let step = if pa[k] < 0.0 { -of_i[k] } else { of_i[k] };
        f32::from_bits(bits.wrapping_add(step) as u32)
    });
    let na = n.to_array();
    Vec3A::from_array(std::array::from_fn(|k| {
        if pa[k].abs() < ORIGIN * scene_size {
            pa[k] + FLOAT_SCALE * scene_size * na[k]
        } else {
            p_i[k]
        }
    }))
}

/// The scene size [`offset_origin_scaled`] takes: the diagonal of the scene's bounds, or 1 when
/// that is zero or not finite (a single point, an empty scene).
pub fn spawn_scale(bounds: &Aabb) -> f32 {
    let diagonal = bounds.extent().length();
    if diagonal.is_finite() && diagonal > 0.0 {
        diagonal
    } else {
        1.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn moves_to_the_normal_side_at_every_scale() {
        for scale in [1e-3f32, 1.0, 1e3, 1e6] {
            for sign in [1.0f32, -1.0] {
                let p = Vec3A::new(0.3, 0.7, 0.2) * scale * sign;
                let n = Vec3A::new(0.0, 0.0, 1.0);
                let q = offset_origin(p, n);
                assert!(q.z > p.z, "scale {scale} sign {sign}: {q:?} vs {p:?}");
                assert_eq!((q.x, q.y), (p.x, p.y));
                // Small: a few hundred ulps, or 1/65536 near zero.
                let ulp = (p.z.abs() * f32::EPSILON).max(FLOAT_SCALE);
                assert!(q.z - p.z <= 300.0 * ulp, "{}", q.z - p.z);
                let q = offset_origin(p, -n);
                assert!(q.z < p.z);
            }
        }
    }

    #[test]
    fn scaled_offset_is_relative_near_the_origin_and_in_ulps_far_from_it() {
        let n = Vec3A::Z;
        for size in [1e-4f32, 1e-2, 1.0, 1e3] {
            // Near the origin: scene_size / 65536 along the normal, whatever the scale.
            let p = Vec3A::new(0.1, 0.2, 0.003) * size;
            let q = offset_origin_scaled(p, n, size);
            let rel = (q.z - p.z) / size;
            assert!(
                (rel - FLOAT_SCALE).abs() < 1e-3 * FLOAT_SCALE,
                "size {size}: {rel}"
            );
        }
        // Far from the origin (relative to the scene): the same 256 ulps as the absolute method.
        let p = Vec3A::new(5.0, 7.0, 1e4);
        assert_eq!(offset_origin_scaled(p, n, 10.0), offset_origin(p, n));
        assert_eq!(
            offset_origin_scaled(p, n, 10.0).z.to_bits(),
            1e4f32.to_bits() + 256
        );
    }
}
