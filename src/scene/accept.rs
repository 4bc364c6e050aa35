//! The last step of every primitive test ([`crate::scene::Geometry::intersect`]): the kernel's
//! `t` clamped into the slab interval of the primitive's own box, then accepted when it lies in
//! `[ray.t_min, t_max]` and finite. [`accept`] does it for one primitive, [`accept_lanes`] for the four
//! triangles of a leaf block, lane for lane the same operations in the same order, so bit for
//! bit the same `t` and decision.
//!
//! A hit has a finite `t`: a distance that overflows `f32` (a kernel's `t` of `+inf`, e.g. a
//! ray with a denormal direction toward a plane it nearly parallels) is a miss, since `+inf`
//! is the protocol's miss distance. Every index gets its hits through here, so all agree.
//!
//! The clamp is what keeps closest-hit culling exact (see the [`crate::scene::Geometry`]
//! contract). Written as selects on ordered comparisons rather than `f32::max`/`min`, whose
//! result on `+0` against `-0` is unspecified, so the two forms agree on the sign of a zero.
//!
//! Why a lane form: the box of a leaf's triangle does not depend on the kernel's `t`, so
//! [`accept_lanes`] computes all four boxes' intervals while the kernel still runs, and only
//! the two selects and the acceptance wait for `t`. The scalar form, run per hit lane after
//! the kernel, put its whole slab test and its branches on the ray's critical path.

use crate::geometry::triangle::lanes::TriangleLanes;
use crate::geometry::{Aabb, Ray, SLAB_FAR_SCALE};
use glam::Vec4;

/// `t` clamped into `enter..=exit`: `enter` when `t < enter`, else `exit` when `t > exit`, else
/// `t` (a NaN `t` stays NaN and is then rejected).
#[inline(always)]
fn clamp(t: f32, enter: f32, exit: f32) -> f32 {
    let t = if enter > t { enter } else { t };
    if exit < t { exit } else { t }
}

/// Clamps a kernel's `t` into the slab interval of `bounds` ([`Aabb::ray_interval`] over the
/// whole line) and applies the `[ray.t_min, t_max]` acceptance (see the
/// [`crate::scene::Geometry`] contract). `None` when the kernel missed, the conservative slab
/// test rejects the box, or the clamped `t` lies outside the interval or is `+inf` (a hit's
/// `t` is finite: `t_min` is, and an overflowing distance is a miss).
#[inline(always)]
pub fn accept(t: Option<f32>, bounds: Aabb, ray: &Ray, t_max: f32) -> Option<f32> {
    let t = t?;
    let (enter, exit) = bounds.ray_interval(ray, f32::NEG_INFINITY, f32::INFINITY)?;
    let t = clamp(t, enter, exit);
    (t >= ray.t_min && t <= t_max && t < f32::INFINITY).then_some(t)
}

/// [`accept`] on the four lanes of a block: for each lane `i` set in `hit`, the kernel's
/// `t[i]` against the box of `tris.triangle(i)` ([`crate::geometry::Triangle::bounds`]).
/// Returns the accepted lanes (a subset of `hit`) and their clamped `t`; lane `i` of the pair
/// is `accept(Some(t[i]), tris.triangle(i).bounds(), ray, t_max)`, bit for bit.
///
/// Every step is the scalar one on four lanes, in the same order and with the same `glam`
/// operations (`min`/`max` with their operand order, the NaN selects of
/// [`Aabb::ray_interval`], its `min_element`/`max_element` as pairwise reductions in `glam`'s
/// order, the far distance widened by [`SLAB_FAR_SCALE`] by sign); `enter.max(-inf)` and
/// `far.min(+inf)` are identities on these NaN-free values and are left out.
#[inline(always)]
pub fn accept_lanes(
    hit: u32,
    t: [f32; 4],
    tris: &TriangleLanes,
    ray: &Ray,
    t_max: f32,
) -> (u32, [f32; 4]) {
    match ray.fast_slabs() {
        true => accept_lanes_in::<false>(hit, t, tris, ray, t_max),
        false => accept_lanes_in::<true>(hit, t, tris, ray, t_max),
    }
}

/// [`accept_lanes`] in two variants, as the node slab test ([`crate::index::kit::box_tree::slab`]):
/// `SAFE = false` for rays whose `inv_dir` components are all finite and whose `t_min >= 0`
/// ([`Ray::fast_slabs`]), `SAFE = true` for the others. Without `SAFE`:
/// - the NaN selects are skipped: `(plane - origin) * inv_dir` of finite planes is never NaN
///   (a finite or infinite difference times a finite nonzero factor), so they are identities;
/// - the far distance is widened as `far * SLAB_FAR_SCALE` alone. Where `far >= 0` (`-0`
///   included) that is the scalar form's choice; where `far < 0`, both that product and the
///   scalar form's `far * (2 - SLAB_FAR_SCALE)` are negative (a factor near 1 does not round a
///   nonzero `far` to zero), so the clamped `t`, at most the exit, lies below `t_min >= 0` and
///   the lane is rejected either way.
#[inline(always)]
fn accept_lanes_in<const SAFE: bool>(
    hit: u32,
    t: [f32; 4],
    tris: &TriangleLanes,
    ray: &Ray,
    t_max: f32,
) -> (u32, [f32; 4]) {
    let corner = |c: usize, k: usize| Vec4::from_array(tris.v[c][k]);
    let not_nan = |x: Vec4, fill: f32| match SAFE {
        true => Vec4::select(x.cmpeq(x), x, Vec4::splat(fill)),
        false => x,
    };
    let axis = |k: usize| {
        let lo = corner(0, k).min(corner(1, k)).min(corner(2, k));
        let hi = corner(0, k).max(corner(1, k)).max(corner(2, k));
        let (o, inv) = (Vec4::splat(ray.origin[k]), Vec4::splat(ray.inv_dir[k]));
        let (t_lo, t_hi) = ((lo - o) * inv, (hi - o) * inv);
        let near = not_nan(t_lo, f32::NEG_INFINITY).min(not_nan(t_hi, f32::NEG_INFINITY));
        let far = not_nan(t_lo, f32::INFINITY).max(not_nan(t_hi, f32::INFINITY));
        (near, far)
    };
    let ([nx, ny, nz], [fx, fy, fz]) = {
        let (x, y, z) = (axis(0), axis(1), axis(2));
        ([x.0, y.0, z.0], [x.1, y.1, z.1])
    };
    // `Vec3A::max_element` / `min_element`: `(x op z) op (y op z)`.
    let enter = nx.max(nz).max(ny.max(nz));
    let far = fx.min(fz).min(fy.min(fz));
    let exit = match SAFE {
        true => {
            let scale = Vec4::select(
                far.cmpge(Vec4::ZERO),
                Vec4::splat(SLAB_FAR_SCALE),
                Vec4::splat(2.0 - SLAB_FAR_SCALE),
            );
            far * scale
        }
        false => far * Vec4::splat(SLAB_FAR_SCALE),
    };
    let t = Vec4::from_array(t);
    let t = Vec4::select(enter.cmpgt(t), enter, t);
    let t = Vec4::select(exit.cmplt(t), exit, t);
    let keep = enter.cmple(exit)
        & t.cmpge(Vec4::splat(ray.t_min))
        & t.cmple(Vec4::splat(t_max))
        & t.cmplt(Vec4::splat(f32::INFINITY));
    (hit & keep.bitmask(), t.to_array())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Triangle;
    use glam::Vec3A;

    /// Draws from `choices`: small values, zeros of both signs and coordinates near
    /// `f32::MAX`, so ties, signed zeros, zero direction components, origins on slab planes
    /// and overflowing differences `plane - origin` all occur.
    fn pick(state: &mut u64, choices: &[f32]) -> f32 {
        *state = state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        choices[(*state >> 33) as usize % choices.len()]
    }

    #[test]
    fn the_lane_form_is_the_scalar_form_bit_for_bit() {
        let coords = [
            -2.0, -1.0, -0.0, 0.0, 0.5, 1.0, 3.0, 1e-30, -7.25, 3e38, -3e38,
        ];
        let dirs = [-1.0, -0.0, 0.0, 0.25, 1.0, -3.0, 1e-20];
        let ts = [
            -1.0,
            -0.0,
            0.0,
            0.5,
            1.0,
            2.0,
            10.0,
            f32::NAN,
            1e30,
            f32::INFINITY,
        ];
        let mut s = 7u64;
        let mut accepted = 0;
        for _ in 0..20_000 {
            let p = |s: &mut u64| Vec3A::new(pick(s, &coords), pick(s, &coords), pick(s, &coords));
            let tris: Vec<Triangle> = (0..4)
                .map(|_| Triangle::new(p(&mut s), p(&mut s), p(&mut s)))
                .collect();
            let dir = Vec3A::new(
                pick(&mut s, &dirs),
                pick(&mut s, &dirs),
                pick(&mut s, &dirs),
            );
            let t_min = pick(&mut s, &[0.0, -1.0, 0.25]);
            let Ok(ray) = Ray::new(p(&mut s).into(), dir.into(), t_min, f32::INFINITY) else {
                continue;
            };
            let t_max = pick(&mut s, &[f32::INFINITY, 1.0, 0.0]);
            let t = [0; 4].map(|_| pick(&mut s, &ts));
            let hit = (s >> 40) as u32 & 0b1111;
            let lanes = TriangleLanes::new(&tris);
            let (mask, out) = accept_lanes(hit, t, &lanes, &ray, t_max);
            for i in 0..4 {
                let want = (hit >> i & 1 == 1)
                    .then(|| accept(Some(t[i]), tris[i].bounds(), &ray, t_max))
                    .flatten();
                let got = (mask >> i & 1 == 1).then_some(out[i]);
                assert_eq!(
                    want.map(f32::to_bits),
                    got.map(f32::to_bits),
                    "lane {i}: {:?} t {} ray {ray:?} t_max {t_max}",
                    tris[i],
                    t[i]
                );
                accepted += usize::from(want.is_some());
            }
        }
        assert!(
            accepted > 1000,
            "only {accepted} lanes accepted: the cases are too easy"
        );
    }
}
