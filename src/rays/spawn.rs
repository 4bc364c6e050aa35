//! Where secondary rays (shadow, diffuse, ambient occlusion) start: the hit point moved off the
//! surface so the new ray does not hit the surface it leaves ("self-intersection").
//!
//! Two methods, compared by `accelbench stress`: a `t_min` epsilon in units of the scene size, and
//! the origin offset of Wächter and Binder (Ray Tracing Gems, ch. 6, "A Fast and Robust Method for
//! Avoiding Self-Intersection"), which moves the point along the geometric normal by a fixed
//! number of ulps of its own coordinates (and by a small absolute amount near the origin), so it
//! works at every scene scale and offset.

use glam::Vec3A;

/// How secondary rays leave a surface.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum SpawnMethod {
    /// Start at the hit point, with `t_min = epsilon * scene_size / |dir|`.
    Epsilon(f32),
    /// Start at [`offset_origin`] with `t_min = 0`.
    Offset,
}

/// Below this magnitude a coordinate is offset by an absolute amount (the integer offset would be
/// a denormal step).
const ORIGIN: f32 = 1.0 / 32.0;
/// Absolute offset near zero, in scene units.
const FLOAT_SCALE: f32 = 1.0 / 65536.0;
/// Offset in ulps of the coordinate.
const INT_SCALE: f32 = 256.0;

/// The point `p` on a surface moved off it along `n` (the geometric normal facing the side the
/// new ray leaves into; it need not be unit length but must not be zero), per Wächter and Binder.
#[inline]
pub fn offset_origin(p: Vec3A, n: Vec3A) -> Vec3A {
    let of_i = (n * INT_SCALE).to_array().map(|c| c as i32);
    let pa = p.to_array();
    let p_i: [f32; 3] = std::array::from_fn(|k| {
        let bits = pa[k].to_bits() as i32;
        let step = if pa[k] < 0.0 { -of_i[k] } else { of_i[k] };
        f32::from_bits(bits.wrapping_add(step) as u32)
    });
    let na = n.to_array();
    Vec3A::from_array(std::array::from_fn(|k| {
        if pa[k].abs() < ORIGIN {
            pa[k] + FLOAT_SCALE * na[k]
        } else {
            p_i[k]
        }
    }))
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
}
