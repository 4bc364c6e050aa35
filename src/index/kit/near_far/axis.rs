//! The crossing of an axis-aligned split plane, shared by the kd-tree's nodes and the BSP's
//! axis-plane nodes: one subtraction, two multiplications by per-ray scaled inverse directions,
//! and the near child chosen by a per-ray mask (no branch on the direction's sign).

use super::{CROSSING_REL, Step};
use crate::geometry::Ray;

/// What a ray precomputes for axis-plane steps, per axis (padded to four lanes so that an axis
/// index `0..3` needs no bounds check): the origin and direction, the inverse direction scaled
/// by `1 + 2 CROSSING_REL` (`inv_wide`) and by `1 - 2 CROSSING_REL` (`inv_narrow`), and which
/// child the ray meets first (`swap`: all ones when the direction is negative, the child above
/// the plane first).
pub struct AxisRay {
    origin: [f32; 4],
    dir: [f32; 4],
    inv_wide: [f32; 4],
    inv_narrow: [f32; 4],
    swap: [u32; 4],
}

/// The scale factors of the inverse direction: the bracket's relative half-width is at least
/// [`CROSSING_REL`] after the four roundings of the scaled product (each at most 6e-8).
const WIDE: f32 = 1.0 + 2.0 * CROSSING_REL;
const NARROW: f32 = 1.0 - 2.0 * CROSSING_REL;

impl AxisRay {
    #[inline(always)]
    pub fn new(ray: &Ray) -> AxisRay {
        let inv: [f32; 4] = ray.inv_dir.extend(0.0).into();
        AxisRay {
            origin: ray.origin.extend(0.0).into(),
            dir: ray.dir.extend(0.0).into(),
            inv_wide: inv.map(|i| i * WIDE),
            inv_narrow: inv.map(|i| i * NARROW),
            swap: inv.map(|i| if i < 0.0 { u32::MAX } else { 0 }),
        }
    }
}

/// The step at the plane `x[axis] = split` (`axis < 4`, lane 3 unused) with children `below`
/// and `above`.
///
/// The crossing is `t = (split - origin) * inv_dir`, the formula of
/// [`crate::geometry::Aabb::ray_interval`]. It is bracketed by the two products
/// `(split - origin) * inv_narrow` and `(split - origin) * inv_wide`: they have the sign of `t`,
/// and their magnitudes lie below and above both the computed `t` and the exact crossing by at
/// least `CROSSING_REL |t|` (two times [`CROSSING_REL`] minus the roundings), at least the
/// half-width `|t| CROSSING_REL` of the bracket `t -+ |t| CROSSING_REL` the nodes had before.
/// The child the direction points away from comes first. A ray parallel to the plane (or one
/// whose wide product is not finite) is handled by [`parallel_step`].
#[inline(always)]
pub fn axis_step(split: f32, axis: usize, below: u32, above: u32, ray: &AxisRay) -> Step {
    let axis = axis & 3;
    let d = split - ray.origin[axis];
    let wide = d * ray.inv_wide[axis];
    if !wide.is_finite() {
        return parallel_step(split, ray.origin[axis], ray.dir[axis], below, above);
    }
    // `|narrow| <= |wide|`: finite, with the same sign.
    let narrow = d * ray.inv_narrow[axis];
    let (lo, hi) = if wide < narrow {
        (wide, narrow)
    } else {
        (narrow, wide)
    };
    let first = below ^ ((below ^ above) & ray.swap[axis]);
    Step::Cross {
        first,
        second: first ^ below ^ above,
        lo,
        hi,
    }
}

/// A ray parallel to the plane at `split` (direction `d == 0`) stays on its origin's side, which
/// is exact, and in the plane it is on both; a crossing that overflows or is `0 * inf` (a
/// subnormal direction) visits both children over the whole interval, the origin's side first.
#[cold]
#[inline(never)]
fn parallel_step(split: f32, o: f32, d: f32, below: u32, above: u32) -> Step {
    let (first, second) = if o < split || (o == split && d > 0.0) {
        (below, above)
    } else {
        (above, below)
    };
    let only_first = d == 0.0 && o != split;
    Step::Cross {
        first,
        second,
        lo: if only_first {
            f32::INFINITY
        } else {
            f32::NEG_INFINITY
        },
        hi: f32::INFINITY,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    fn cross(step: Step) -> (u32, u32, f32, f32) {
        step.crossing()
    }

    #[test]
    fn bracket_contains_the_computed_crossing_with_the_old_margin() {
        let dirs = [Vec3::new(0.3, -0.7, 0.2), Vec3::new(-1e-3, 2.0, -5.0)];
        for dir in dirs {
            let ray = Ray::new(Vec3::new(0.1, 0.25, -3.0), dir, 0.0, f32::INFINITY).unwrap();
            let pre = AxisRay::new(&ray);
            for axis in 0..3 {
                for split in [-7.5f32, -0.01, 0.0, 0.37, 12.0] {
                    let t = (split - ray.origin[axis]) * ray.inv_dir[axis];
                    let (first, second, lo, hi) = cross(axis_step(split, axis, 1, 9, &pre));
                    let slack = t.abs() * CROSSING_REL;
                    assert!(lo <= t - slack && hi >= t + slack, "{lo} {t} {hi}");
                    let below_first = dir[axis] > 0.0;
                    assert_eq!((first, second), if below_first { (1, 9) } else { (9, 1) });
                }
            }
        }
    }

    #[test]
    fn parallel_rays_stay_on_their_side() {
        let ray = Ray::new(Vec3::new(0.0, 1.0, 0.0), Vec3::X, 0.0, f32::INFINITY).unwrap();
        let pre = AxisRay::new(&ray);
        // Below the plane y = 2: only the child below.
        assert_eq!(
            cross(axis_step(2.0, 1, 1, 9, &pre)),
            (1, 9, f32::INFINITY, f32::INFINITY)
        );
        // In the plane y = 1: both, over the whole interval.
        assert_eq!(cross(axis_step(1.0, 1, 1, 9, &pre)).2, f32::NEG_INFINITY);
    }
}
