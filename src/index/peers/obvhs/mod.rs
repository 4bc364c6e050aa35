//! obvhs 0.4 as a peer behind our [`Index`](super::Index) trait: `obvhs-bvh2` (PLOC-built binary
//! BVH) and `obvhs-cwbvh` (compressed 8-wide BVH). obvhs builds over our primitives' bounds and
//! traverses with its own box tests; its primitive callback maps obvhs's primitive order back to
//! scene ids and calls OUR kernel ([`Geometry::intersect`]), keeping OUR closest-hit order.
//!
//! obvhs culls a node when its entry is not below the ray's `tmax` (BVH2: `entry < tmax`),
//! which would drop ties at equal `t`. So the callback keeps the best hit itself and hands
//! obvhs a `tmax` slightly above the best `t` (`culling_bound`). That is not enough for
//! bit-identical hits, and `tests/it/obvhs_peer.rs` counts and classifies what remains:
//! - obvhs's slab test has no `1 + 2 gamma(3)` widening of the exit distance, so a ray through
//!   a box corner or edge (rays aimed at shared vertices) can see exit < entry and lose the box:
//!   a tie goes to a higher id, or a grazing hit is lost;
//! - obvhs replaces `1/0` by `+-1/f32::EPSILON`, so a ray with a zero direction component lying
//!   in a box's face plane is culled (CWBVH);
//! - CWBVH clamps a child's entry to `1e-4`, so hits at `t < 1e-4` are lost (11 of 262,144
//!   incoherent bunny rays, e.g. record bits
//!   `bd4d6375 3d0d0615 3d01ce57 00000000 bdabd90a bf75b5b5 3e8921b0 7f800000`: brute force
//!   hits prim 68706 at t = 4.93e-6, obvhs-cwbvh misses).

mod bvh2;
mod cwbvh;
mod tree;

pub use bvh2::ObvhsBvh2;
pub use cwbvh::ObvhsCwBvh;
pub use tree::Obvhs;

use crate::geometry::Ray;
use crate::index::BuildError;
use crate::scene::Geometry;
use obvhs::BvhBuildParams;
use serde::{Deserialize, Serialize};

/// obvhs's named build presets (`BvhBuildParams::*_build`), fastest first. The slow presets'
/// triangle pre-splitting does not apply: obvhs is given boxes, not triangles.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ObvhsPreset {
    Fastest,
    VeryFast,
    Fast,
    #[default]
    Medium,
    Slow,
    VerySlow,
}

impl ObvhsPreset {
    pub const ALL: [ObvhsPreset; 6] = [
        ObvhsPreset::Fastest,
        ObvhsPreset::VeryFast,
        ObvhsPreset::Fast,
        ObvhsPreset::Medium,
        ObvhsPreset::Slow,
        ObvhsPreset::VerySlow,
    ];

    /// Name as written in parameters (`obvhs-bvh2:preset="very_fast"`).
    pub fn name(self) -> &'static str {
        match self {
            ObvhsPreset::Fastest => "fastest",
            ObvhsPreset::VeryFast => "very_fast",
            ObvhsPreset::Fast => "fast",
            ObvhsPreset::Medium => "medium",
            ObvhsPreset::Slow => "slow",
            ObvhsPreset::VerySlow => "very_slow",
        }
    }

    fn build_params(self) -> BvhBuildParams {
        match self {
            ObvhsPreset::Fastest => BvhBuildParams::fastest_build(),
            ObvhsPreset::VeryFast => BvhBuildParams::very_fast_build(),
            ObvhsPreset::Fast => BvhBuildParams::fast_build(),
            ObvhsPreset::Medium => BvhBuildParams::medium_build(),
            ObvhsPreset::Slow => BvhBuildParams::slow_build(),
            ObvhsPreset::VerySlow => BvhBuildParams::very_slow_build(),
        }
    }
}

/// Parameters of `obvhs-bvh2` and `obvhs-cwbvh`: one of obvhs's presets (default `medium`).
#[derive(Debug, Clone, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct ObvhsParams {
    pub preset: ObvhsPreset,
}

/// Primitive bounds in obvhs's box type, in scene order; an error for an empty scene or
/// non-finite bounds (obvhs would build garbage or panic).
fn prim_boxes<G: Geometry>(geom: &G, index: &str) -> Result<Vec<obvhs::aabb::Aabb>, BuildError> {
    if geom.is_empty() {
        return Err(BuildError::EmptyScene);
    }
    let len = u32::try_from(geom.len()).map_err(|_| BuildError::Failed {
        index: index.into(),
        message: format!("{} primitives exceed u32 ids", geom.len()),
    })?;
    (0..len)
        .map(|prim| {
            let b = geom.bounds(prim);
            if b.min.is_finite() && b.max.is_finite() {
                Ok(obvhs::aabb::Aabb::new(b.min, b.max))
            } else {
                Err(BuildError::Failed {
                    index: index.into(),
                    message: format!(
                        "primitive {prim} has non-finite bounds {b:?}: remove NaN or infinite \
                         coordinates"
                    ),
                })
            }
        })
        .collect()
}

/// Our ray as obvhs's ray type (obvhs computes its own clamped inverse direction).
#[inline(always)]
fn obvhs_ray(ray: &Ray, t_max: f32) -> obvhs::ray::Ray {
    obvhs::ray::Ray::new(ray.origin, ray.dir, ray.t_min, t_max)
}

/// Relative slack above the best `t` given to obvhs as its `tmax` (about 8 ulps).
const SLACK: f32 = 8.0 * f32::EPSILON;

/// The `tmax` handed to obvhs when the best `t` so far is `t`: slightly larger, so that nodes
/// whose entry equals `t` (ties) or exceeds it by rounding are still visited. Infinity stays.
#[inline(always)]
fn culling_bound(t: f32) -> f32 {
    t + t.abs() * SLACK + f32::MIN_POSITIVE
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn culling_bound_is_strictly_above_and_keeps_infinity() {
        for t in [0.0f32, 1e-30, 0.5, 1.0, 3.0e7, -2.0] {
            assert!(culling_bound(t) > t, "{t}");
        }
        assert_eq!(culling_bound(f32::INFINITY), f32::INFINITY);
    }
}
