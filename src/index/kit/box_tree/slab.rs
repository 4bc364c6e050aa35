//! The slab test of both children of a [`Node`] in one SIMD pass.
//!
//! Lane `i` of every register below is one slab plane: lanes 0 and 1 the `min` planes of
//! children `a` and `b`, lanes 2 and 3 their `max` planes (the node's layout). Per child the
//! pass computes exactly what [`Aabb::ray_interval`](crate::geometry::Aabb::ray_interval)
//! computes: the same products `(plane - origin) * inv_dir` with the same roundings, the same
//! NaN rule, min/max per axis, the far distance widened by [`SLAB_FAR_SCALE`] (as
//! `max(far * s, far * (2 - s))`, which is `far * s` for `far >= 0` and `far * (2 - s)` below,
//! the scalar function's choice), then clipped to `[t_min, t_max]`. The entries and exits are
//! therefore those of the scalar test (up to the sign of a zero, which no comparison sees), so
//! the pass is conservative (never rejects a box the exact ray meets) and monotone (a box
//! inside another gets a later or equal entry) for the same reasons, and culling with it stays
//! exact (see [`crate::geometry::Hit`]). `tests` checks the equality on random and degenerate
//! rays.
//!
//! [`slab_lanes`] does the same lane by lane over any [`Lanes`] register, with the same
//! per-lane operations: one box against a packet of rays ([`super::packet_slab`]).
//! [`hit_near_far`] tests four or eight boxes against one ray (the wide BVH's nodes) with the
//! planes chosen by the ray's direction signs (below).
//!
//! Two variants, chosen once per ray by [`Ray::fast_slabs`] (once per packet by the packet
//! walk: `SAFE` when any of its rays needs it, which changes no fast lane's decision or entry):
//! - `SAFE = false` when every component of `inv_dir` is finite and `t_min >= 0`. A product
//!   `(p - o) * inv` can then not be NaN: `p - o` is finite or, on overflow, infinite, and `inv`
//!   is finite and nonzero (`1/x` of a finite `x` is never 0), so NaN (`0 * inf` or `inf * 0`)
//!   cannot arise from finite boxes and the NaN selects of the scalar test are identities,
//!   skipped here. And the far distance is widened as `far * s` alone: where `far < 0`, both
//!   `far * s` and the scalar test's `far * (2 - s)` are negative, below an entry of at least
//!   `t_min >= 0`, so the box is missed either way.
//! - `SAFE = true` otherwise (a zero or denormal direction component, or `t_min < 0`): a NaN
//!   product (origin in the plane of a slab the ray runs parallel to) is replaced by `-inf` for
//!   the entry and `+inf` for the exit, so that axis puts no constraint on `t`, exactly as in the
//!   scalar test, and the far distance is widened on either sign.
//!
//! **Near and far planes.** Per axis, `min(t_lo, t_hi)` of the two planes' distances is the
//! distance to the plane the ray meets first: the `min` plane when `inv_dir` is positive (`+0`
//! and `+inf` included), else the `max` plane, because `(p - o) * inv` rounds monotonically in
//! `p` (and in the `SAFE` variant's infinite cases the selected plane gives the same `±inf` or
//! NaN-replacement). [`hit_near_far`] therefore reads each axis's near and far planes by the
//! ray's direction signs ([`SlabRay::near`]) instead of taking a min and a max, with the same
//! entries and decisions. A box with `min = +inf` and `max = -inf` on an axis is missed by every
//! ray (its near distance is `+inf`, its far one `-inf`): the wide nodes' absent children.

use super::lanes::Lanes;
use super::node::Node;
use crate::geometry::{Ray, SLAB_FAR_SCALE};
use glam::{Vec4, Vec4Swizzles};

/// A ray's slab constants, splatted once per ray.
#[derive(Debug, Clone, Copy)]
pub struct SlabRay {
    origin: [Vec4; 3],
    inv_dir: [Vec4; 3],
    t_min: Vec4,
    /// Per axis, which plane of a box the ray meets first: `0` for `min` (`inv_dir` positive,
    /// `+0` and `+inf` included), `1` for `max`.
    pub near: [usize; 3],
}

impl SlabRay {
    #[inline(always)]
    pub fn new(ray: &Ray) -> SlabRay {
        let (o, i) = (ray.origin, ray.inv_dir);
        SlabRay {
            origin: [Vec4::splat(o.x), Vec4::splat(o.y), Vec4::splat(o.z)],
            inv_dir: [Vec4::splat(i.x), Vec4::splat(i.y), Vec4::splat(i.z)],
            t_min: Vec4::splat(ray.t_min),
            near: [0, 1, 2].map(|k| usize::from(i[k].is_sign_negative())),
        }
    }
}

/// Per lane, the distance `(plane - origin) * inv_dir` to one slab plane, as an entry candidate
/// and an exit candidate: equal, except that with `SAFE` a NaN (origin on the slab plane,
/// direction 0 on that axis) becomes `-inf` for the entry and `+inf` for the exit ("no
/// constraint"), as in the scalar test. On a lane whose product is not NaN the select is the
/// identity, bit for bit.
#[inline(always)]
fn plane_distances<const SAFE: bool, V: Lanes>(planes: V, origin: V, inv_dir: V) -> (V, V) {
    let t = (planes - origin) * inv_dir;
    if SAFE {
        (t.nan_to(f32::NEG_INFINITY), t.nan_to(f32::INFINITY))
    } else {
        (t, t)
    }
}

/// Entry (lanes 0, 1: `t_near`) and exit (`t_far`) distances of one axis's two slabs per child,
/// duplicated in lanes 2, 3.
#[inline(always)]
fn axis<const SAFE: bool>(planes: Vec4, origin: Vec4, inv_dir: Vec4) -> (Vec4, Vec4) {
    let (near, far) = plane_distances::<SAFE, Vec4>(planes, origin, inv_dir);
    (near.min(near.zwxy()), far.max(far.zwxy()))
}

/// From the per-axis entries and exits of one box per lane: the hit mask (bit `i` for lane `i`)
/// of the lanes whose interval, with the far distance widened by [`SLAB_FAR_SCALE`] and clipped
/// to `[t_min, t_max]`, is not empty, and the entries. Without `SAFE` (`t_min >= 0`) the far
/// distance is widened for `far >= 0` only (see the module doc).
///
/// The test `enter <= min(widen(min(far_x, far_y, far_z)), t_max)` is computed as four
/// comparisons side by side, `enter <= widen(far_k)` for each axis and `enter <= t_max`: the
/// widening (a product by a positive constant, or the larger of two such products) is monotone
/// non-decreasing, and rounding keeps it so, so the widened minimum is the minimum of the
/// widened values, bit for bit; and no lane is NaN here (see the module doc), so `enter` is at
/// most a minimum exactly when it is at most each term. The decisions and entries are the
/// scalar test's. On the node step's critical path (the next node's address waits for this
/// mask) the far side's three dependent `min`s become four independent comparisons whose masks
/// are ANDed.
#[inline(always)]
fn clip<const SAFE: bool, V: Lanes>(near: [V; 3], far: [V; 3], t_min: V, t_max: V) -> (u32, V) {
    let enter = near[0].max(near[1]).max(near[2].max(t_min));
    let widen = |far: V| match SAFE {
        true => (far * V::splat(SLAB_FAR_SCALE)).max(far * V::splat(2.0 - SLAB_FAR_SCALE)),
        false => far * V::splat(SLAB_FAR_SCALE),
    };
    let mask = enter.le(widen(far[0]))
        & enter.le(widen(far[1]))
        & enter.le(widen(far[2]))
        & enter.le(t_max);
    (mask, enter)
}

/// The slab test lane by lane: lane `i` tests the box whose planes are lane `i` of `min[axis]`
/// and `max[axis]` against the ray whose constants are lane `i` of `origin`, `inv_dir`, `t_min`
/// and `t_max` (either side may be one value splatted over the lanes; the packet walk tests one
/// box against a packet of rays, [`super::packet_slab`]). Bit `i` of the mask is set when lane `i` hits, lane `i` of the
/// vector is its entry distance. Every lane performs the same operations in the same order as
/// [`hit_children`] and so, up to the sign of a zero, as the scalar test.
#[inline(always)]
pub(crate) fn slab_lanes<const SAFE: bool, V: Lanes>(
    min: [V; 3],
    max: [V; 3],
    origin: [V; 3],
    inv_dir: [V; 3],
    t_min: V,
    t_max: V,
) -> (u32, V) {
    let near_far = |k: usize| {
        let (ln, lf) = plane_distances::<SAFE, V>(min[k], origin[k], inv_dir[k]);
        let (hn, hf) = plane_distances::<SAFE, V>(max[k], origin[k], inv_dir[k]);
        (ln.min(hn), lf.max(hf))
    };
    let (nx, fx) = near_far(0);
    let (ny, fy) = near_far(1);
    let (nz, fz) = near_far(2);
    clip::<SAFE, V>([nx, ny, nz], [fx, fy, fz], t_min, t_max)
}

/// [`slab_lanes`] with each axis's planes read by the rays' direction signs: lane `i` of
/// `near[axis]` is the plane of lane `i`'s box its ray meets first ([`SlabRay::near`]), of
/// `far[axis]` the other one. The entries and decisions of [`slab_lanes`] on the `min` and
/// `max` planes (see the module doc), with one distance per plane and no min/max per axis.
#[inline(always)]
pub(crate) fn slab_lanes_by_sign<const SAFE: bool, V: Lanes>(
    near: [V; 3],
    far: [V; 3],
    origin: [V; 3],
    inv_dir: [V; 3],
    t_min: V,
    t_max: V,
) -> (u32, V) {
    let enter = |k: usize| plane_distances::<SAFE, V>(near[k], origin[k], inv_dir[k]).0;
    let exit = |k: usize| plane_distances::<SAFE, V>(far[k], origin[k], inv_dir[k]).1;
    clip::<SAFE, V>(
        [enter(0), enter(1), enter(2)],
        [exit(0), exit(1), exit(2)],
        t_min,
        t_max,
    )
}

/// Tests both children's boxes against `[ray.t_min, t_max]`: bit 0 of the mask is set when child
/// `a` is hit, bit 1 when `b` is; lanes 0 and 1 of the vector are their entry distances
/// (meaningful for hit children only).
#[inline(always)]
pub fn hit_children<const SAFE: bool>(node: &Node, ray: &SlabRay, t_max: f32) -> (u32, Vec4) {
    let (nx, fx) = axis::<SAFE>(node.x, ray.origin[0], ray.inv_dir[0]);
    let (ny, fy) = axis::<SAFE>(node.y, ray.origin[1], ray.inv_dir[1]);
    let (nz, fz) = axis::<SAFE>(node.z, ray.origin[2], ray.inv_dir[2]);
    let (mask, enter) =
        clip::<SAFE, Vec4>([nx, ny, nz], [fx, fy, fz], ray.t_min, Vec4::splat(t_max));
    (mask & 0b11, enter)
}

/// Boxes in structure-of-arrays form against `[ray.t_min, t_max]`, each axis's planes read by
/// the ray's direction signs (see the module doc): lane `i` of `near[axis]` is box `i`'s plane
/// on `axis` that the ray meets first (`min` or `max` by [`SlabRay::near`]), of `far[axis]` the
/// other one. The same entries and decisions as [`slab_lanes`] on the `min` and `max` planes,
/// with one distance per plane and no min/max per axis. Bit `i` of the mask is set when box `i`
/// is hit, lane `i` of the vector is its entry distance.
#[inline(always)]
pub fn hit_near_far<const SAFE: bool, V: Lanes>(
    near: [V; 3],
    far: [V; 3],
    ray: &SlabRay,
    t_max: f32,
) -> (u32, V) {
    let (o, inv) = (&ray.origin, &ray.inv_dir);
    let enter =
        |k: usize| plane_distances::<SAFE, V>(near[k], V::splat(o[k].x), V::splat(inv[k].x)).0;
    let exit =
        |k: usize| plane_distances::<SAFE, V>(far[k], V::splat(o[k].x), V::splat(inv[k].x)).1;
    clip::<SAFE, V>(
        [enter(0), enter(1), enter(2)],
        [exit(0), exit(1), exit(2)],
        V::splat(ray.t_min.x),
        V::splat(t_max),
    )
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use crate::geometry::Aabb;
    use crate::index::kit::box_tree::lanes::{F8, MAX_LANES};
    use crate::index::kit::box_tree::node::Child;
    use glam::{Vec3, Vec3A};

    /// A small deterministic generator (xorshift), so the test needs no seed plumbing.
    pub(crate) struct Rng(pub u64);
    impl Rng {
        pub fn next(&mut self) -> u64 {
            self.0 ^= self.0 << 13;
            self.0 ^= self.0 >> 7;
            self.0 ^= self.0 << 17;
            self.0
        }
        /// One of a few grid values (so origins land on box planes) or a random float.
        pub fn coord(&mut self) -> f32 {
            let r = self.next();
            match r % 4 {
                0 => [-1.0, 0.0, 0.5, 1.0, 2.0][(r >> 8) as usize % 5],
                _ => ((r >> 16) as u32 as f32 / u32::MAX as f32) * 4.0 - 2.0,
            }
        }
        /// A direction component: often +0, -0 or a denormal, else random.
        pub fn dir(&mut self) -> f32 {
            let r = self.next();
            match r % 8 {
                0 => 0.0,
                1 => -0.0,
                2 => 1e-45,
                _ => self.coord(),
            }
        }
        pub fn aabb(&mut self) -> Aabb {
            let p = Vec3A::new(self.coord(), self.coord(), self.coord());
            let q = Vec3A::new(self.coord(), self.coord(), self.coord());
            Aabb::new(p.min(q), p.max(q))
        }
    }

    /// What the scalar test says about a box: `Some(entry)` when hit.
    fn scalar(b: &Aabb, ray: &Ray, t_max: f32) -> Option<f32> {
        b.ray_entry(ray, ray.t_min, t_max)
    }

    fn both<const SAFE: bool>(node: &Node, ray: &Ray, t_max: f32) -> [Option<f32>; 2] {
        let (mask, enter) = hit_children::<SAFE>(node, &SlabRay::new(ray), t_max);
        [0, 1].map(|i| (mask >> i & 1 == 1).then_some(enter[i]))
    }

    #[test]
    fn equals_the_scalar_slab_test_on_random_and_degenerate_rays() {
        let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
        let (mut hits, mut safe_rays) = (0, 0);
        for _ in 0..200_000 {
            let boxes = [rng.aabb(), rng.aabb()];
            let node = Node::new(boxes, [Child::leaf(0, 1), Child::leaf(1, 1)]);
            let o = Vec3::new(rng.coord(), rng.coord(), rng.coord());
            let d = Vec3::new(rng.dir(), rng.dir(), rng.dir());
            let Ok(ray) = Ray::new(o, d, rng.coord().min(0.0), f32::INFINITY) else {
                continue;
            };
            let t_max = if rng.next().is_multiple_of(2) {
                f32::INFINITY
            } else {
                rng.coord().abs() * 3.0
            };
            let want = boxes.map(|b| scalar(&b, &ray, t_max));
            // The safe variant must agree on every ray, the fast one on the rays it is chosen for.
            assert_eq!(both::<true>(&node, &ray, t_max), want, "{ray:?} {boxes:?}");
            if ray.fast_slabs() {
                assert_eq!(both::<false>(&node, &ray, t_max), want, "{ray:?} {boxes:?}");
            } else {
                safe_rays += 1;
            }
            hits += want.iter().flatten().count();
        }
        // The generator must exercise both variants and both outcomes.
        assert!(safe_rays > 10_000 && hits > 10_000, "{safe_rays} {hits}");
    }

    /// `boxes` in structure-of-arrays lanes of `V` (one box per lane), each axis's near and far
    /// planes chosen by the ray's direction signs, as the wide nodes store and read them.
    pub(crate) fn near_far_lanes<V: Lanes>(boxes: &[Aabb], ray: &SlabRay) -> ([V; 3], [V; 3]) {
        let lanes = |side: [usize; 3]| {
            [0, 1, 2].map(|k| {
                let mut a = [0.0; MAX_LANES];
                for (i, b) in boxes.iter().enumerate().take(V::WIDTH) {
                    a[i] = [b.min, b.max][side[k]][k];
                }
                V::load(&a)
            })
        };
        (lanes(ray.near), lanes(ray.near.map(|s| 1 - s)))
    }

    /// The sign-selected test of the wide nodes ([`hit_near_far`]) equals the scalar test on
    /// the same random and degenerate rays, four boxes per [`Vec4`] pass and eight per [`F8`]
    /// pass, and misses empty boxes (`+inf..-inf`, a wide node's absent children).
    #[test]
    fn near_far_tests_of_four_and_eight_boxes_equal_the_scalar_slab_test() {
        let mut rng = Rng(0x2545_f491_4f6c_dd1d);
        let (mut hits, mut safe_rays) = (0, 0);
        let empty = Aabb::new(Vec3A::INFINITY, Vec3A::NEG_INFINITY);
        for _ in 0..100_000 {
            let mut boxes: [Aabb; 8] = std::array::from_fn(|_| rng.aabb());
            let absent = (rng.next() % 8) as usize;
            boxes[absent..].fill(empty);
            let o = Vec3::new(rng.coord(), rng.coord(), rng.coord());
            let d = Vec3::new(rng.dir(), rng.dir(), rng.dir());
            let t_min = match rng.next() % 3 {
                0 => rng.coord().min(0.0),
                _ => rng.coord().abs(),
            };
            let Ok(ray) = Ray::new(o, d, t_min, f32::INFINITY) else {
                continue;
            };
            let t_max = if rng.next().is_multiple_of(2) {
                f32::INFINITY
            } else {
                t_min + rng.coord().abs() * 3.0
            };
            let want = boxes.map(|b| match b == empty {
                true => None,
                false => scalar(&b, &ray, t_max),
            });
            let sr = SlabRay::new(&ray);
            let lanes = |(mask, enter): (u32, [f32; MAX_LANES])| {
                std::array::from_fn::<_, 8, _>(|i| (mask >> i & 1 == 1).then_some(enter[i]))
            };
            let four = |safe: bool, h: usize| {
                let (near, far) = near_far_lanes::<Vec4>(&boxes[4 * h..], &sr);
                let (mask, enter) = match safe {
                    true => hit_near_far::<true, Vec4>(near, far, &sr, t_max),
                    false => hit_near_far::<false, Vec4>(near, far, &sr, t_max),
                };
                lanes((mask, Lanes::to_lanes(enter)))
            };
            let eight = |safe: bool| {
                let (near, far) = near_far_lanes::<F8>(&boxes, &sr);
                let (mask, enter) = match safe {
                    true => hit_near_far::<true, F8>(near, far, &sr, t_max),
                    false => hit_near_far::<false, F8>(near, far, &sr, t_max),
                };
                lanes((mask, enter.to_lanes()))
            };
            let mut safe_kinds = vec![true];
            if ray.fast_slabs() {
                safe_kinds.push(false);
            } else {
                safe_rays += 1;
            }
            for safe in safe_kinds {
                let halves = [four(safe, 0), four(safe, 1)];
                assert_eq!(halves[0][..4], want[..4], "{ray:?} {safe}");
                assert_eq!(halves[1][..4], want[4..], "{ray:?} {safe}");
                assert_eq!(eight(safe), want, "{ray:?} {safe}");
            }
            hits += want.iter().flatten().count();
        }
        assert!(safe_rays > 5_000 && hits > 20_000, "{safe_rays} {hits}");
    }

    #[test]
    fn rays_in_a_face_plane_with_zero_components_hit_through_the_safe_variant() {
        let unit = Aabb::new(Vec3A::ZERO, Vec3A::ONE);
        let next = Aabb::new(Vec3A::new(1.0, 0.0, 0.0), Vec3A::new(2.0, 1.0, 1.0));
        let node = Node::new([unit, next], [Child::leaf(0, 1), Child::leaf(1, 1)]);
        for z in [0.0f32, 1.0] {
            for dz in [0.0f32, -0.0] {
                // Along the face z = const shared by both boxes, and along their shared face x = 1.
                for (o, d) in [
                    ([-1.0, 0.5, z], [1.0, 0.0, dz]),
                    ([1.0, -1.0, z], [dz, 1.0, 0.0]),
                ] {
                    let ray = Ray::infinite(Vec3::from(o), Vec3::from(d)).unwrap();
                    assert!(!ray.fast_slabs());
                    let got = both::<true>(&node, &ray, f32::INFINITY);
                    assert!(got.iter().all(Option::is_some), "{o:?} {d:?}: {got:?}");
                    assert_eq!(got, [unit, next].map(|b| scalar(&b, &ray, f32::INFINITY)));
                }
            }
        }
    }
}
