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
//! per-lane operations: four or eight boxes against one ray ([`hit_boxes4`], [`hit_boxes8`],
//! the wide BVH's nodes) or one box against a packet of rays ([`super::packet_slab`]).
//!
//! Two variants, chosen once per ray by [`SlabRay::finite`] (once per packet by the packet
//! walk: `SAFE` when any of its rays needs it, which changes no finite lane):
//! - `SAFE = false` when every component of `inv_dir` is finite. A product `(p - o) * inv` can
//!   then not be NaN: `p - o` is finite or, on overflow, infinite, and `inv` is finite and
//!   nonzero (`1/x` of a finite `x` is never 0), so NaN (`0 * inf` or `inf * 0`) cannot arise
//!   from finite boxes and the NaN selects of the scalar test are identities, skipped here.
//! - `SAFE = true` otherwise (a zero or denormal direction component): a NaN product (origin in
//!   the plane of a slab the ray runs parallel to) is replaced by `-inf` for the entry and `+inf`
//!   for the exit, so that axis puts no constraint on `t`, exactly as in the scalar test.

use super::lanes::{F8, Lanes};
use super::node::Node;
use crate::geometry::{Ray, SLAB_FAR_SCALE};
use glam::{Vec4, Vec4Swizzles};

/// A ray's slab constants, splatted once per ray.
#[derive(Debug, Clone, Copy)]
pub struct SlabRay {
    origin: [Vec4; 3],
    inv_dir: [Vec4; 3],
    t_min: Vec4,
}

impl SlabRay {
    #[inline(always)]
    pub fn new(ray: &Ray) -> SlabRay {
        let (o, i) = (ray.origin, ray.inv_dir);
        SlabRay {
            origin: [Vec4::splat(o.x), Vec4::splat(o.y), Vec4::splat(o.z)],
            inv_dir: [Vec4::splat(i.x), Vec4::splat(i.y), Vec4::splat(i.z)],
            t_min: Vec4::splat(ray.t_min),
        }
    }

    /// Whether the ray may take the `SAFE = false` variant (every `inv_dir` component finite).
    #[inline(always)]
    pub fn finite(ray: &Ray) -> bool {
        ray.inv_dir.is_finite()
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
/// to `[t_min, t_max]`, is not empty, and the entries.
#[inline(always)]
fn clip<V: Lanes>(near: [V; 3], far: [V; 3], t_min: V, t_max: V) -> (u32, V) {
    let enter = near[0].max(near[1]).max(near[2].max(t_min));
    let far = far[0].min(far[1]).min(far[2]);
    let exit = (far * V::splat(SLAB_FAR_SCALE))
        .max(far * V::splat(2.0 - SLAB_FAR_SCALE))
        .min(t_max);
    (enter.le(exit), enter)
}

/// The slab test lane by lane: lane `i` tests the box whose planes are lane `i` of `min[axis]`
/// and `max[axis]` against the ray whose constants are lane `i` of `origin`, `inv_dir`, `t_min`
/// and `t_max` (either side may be one value splatted over the lanes: many boxes against one
/// ray, [`hit_boxes4`] and [`hit_boxes8`], or one box against a packet of rays,
/// [`super::packet_slab`]). Bit `i` of the mask is set when lane `i` hits, lane `i` of the
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
    clip([nx, ny, nz], [fx, fy, fz], t_min, t_max)
}

/// Tests both children's boxes against `[ray.t_min, t_max]`: bit 0 of the mask is set when child
/// `a` is hit, bit 1 when `b` is; lanes 0 and 1 of the vector are their entry distances
/// (meaningful for hit children only).
#[inline(always)]
pub fn hit_children<const SAFE: bool>(node: &Node, ray: &SlabRay, t_max: f32) -> (u32, Vec4) {
    let (nx, fx) = axis::<SAFE>(node.x, ray.origin[0], ray.inv_dir[0]);
    let (ny, fy) = axis::<SAFE>(node.y, ray.origin[1], ray.inv_dir[1]);
    let (nz, fz) = axis::<SAFE>(node.z, ray.origin[2], ray.inv_dir[2]);
    let (mask, enter) = clip([nx, ny, nz], [fx, fy, fz], ray.t_min, Vec4::splat(t_max));
    (mask & 0b11, enter)
}

/// Four boxes in structure-of-arrays form: lane `i` of `min[axis]` and `max[axis]` is box `i`.
#[derive(Debug, Clone, Copy)]
pub struct Boxes4 {
    pub min: [Vec4; 3],
    pub max: [Vec4; 3],
}

/// Tests four boxes against `[ray.t_min, t_max]` with the same arithmetic as
/// [`hit_children`] (and so as the scalar test): bit `i` of the mask is set when box `i` is
/// hit, lane `i` of the vector is its entry distance.
#[inline(always)]
pub fn hit_boxes4<const SAFE: bool>(b: &Boxes4, ray: &SlabRay, t_max: f32) -> (u32, Vec4) {
    slab_lanes::<SAFE, Vec4>(
        b.min,
        b.max,
        ray.origin,
        ray.inv_dir,
        ray.t_min,
        Vec4::splat(t_max),
    )
}

/// Tests eight boxes against `[ray.t_min, t_max]`, lane `i` of `min[axis]`/`max[axis]` being
/// box `i` (two [`Vec4`] per plane: lanes 0..4, then 4..8): [`slab_lanes`] over [`F8`] (one
/// AVX pass, or two four-lane passes without AVX; `_mm256` min/max/compare have the SSE
/// instructions' NaN rules, so the lanes equal the four-box test's). Bit `i` of the mask is set
/// when box `i` is hit, `enter[i]` is its entry distance.
#[inline(always)]
pub fn hit_boxes8<const SAFE: bool>(
    min: &[[Vec4; 2]; 3],
    max: &[[Vec4; 2]; 3],
    ray: &SlabRay,
    t_max: f32,
) -> (u32, [f32; 8]) {
    let ray8 = |v: &[Vec4; 3]| v.map(|l| F8::splat(l.x));
    let (mask, enter) = slab_lanes::<SAFE, F8>(
        min.each_ref().map(F8::from_halves),
        max.each_ref().map(F8::from_halves),
        ray8(&ray.origin),
        ray8(&ray.inv_dir),
        F8::splat(ray.t_min.x),
        F8::splat(t_max),
    );
    (mask, enter.to_lanes())
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use crate::geometry::Aabb;
    use crate::index::bvh::node::Child;
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
            if SlabRay::finite(&ray) {
                assert_eq!(both::<false>(&node, &ray, t_max), want, "{ray:?} {boxes:?}");
            } else {
                safe_rays += 1;
            }
            hits += want.iter().flatten().count();
        }
        // The generator must exercise both variants and both outcomes.
        assert!(safe_rays > 10_000 && hits > 10_000, "{safe_rays} {hits}");
    }

    /// The four- and eight-box tests equal the scalar test on the same random and degenerate
    /// rays (boxes 0..4 through the four-box test, all eight through the eight-box test).
    #[test]
    fn four_and_eight_box_tests_equal_the_scalar_slab_test() {
        let mut rng = Rng(0x2545_f491_4f6c_dd1d);
        let (mut hits, mut safe_rays) = (0, 0);
        for _ in 0..100_000 {
            let boxes: [Aabb; 8] = std::array::from_fn(|_| rng.aabb());
            let lanes = |f: fn(&Aabb) -> Vec3A, h: usize| {
                let p: [Vec3A; 4] = std::array::from_fn(|i| f(&boxes[4 * h + i]));
                [0, 1, 2].map(|k| Vec4::new(p[0][k], p[1][k], p[2][k], p[3][k]))
            };
            let b4 = Boxes4 {
                min: lanes(|b| b.min, 0),
                max: lanes(|b| b.max, 0),
            };
            let (lo, hi) = (lanes(|b| b.min, 1), lanes(|b| b.max, 1));
            let min8 = [0, 1, 2].map(|k| [b4.min[k], lo[k]]);
            let max8 = [0, 1, 2].map(|k| [b4.max[k], hi[k]]);
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
            let four = |(mask, enter): (u32, Vec4)| {
                [0, 1, 2, 3].map(|i| (mask >> i & 1 == 1).then_some(enter[i]))
            };
            let eight = |(mask, enter): (u32, [f32; 8])| {
                std::array::from_fn::<_, 8, _>(|i| (mask >> i & 1 == 1).then_some(enter[i]))
            };
            let sr = SlabRay::new(&ray);
            let want4 = [want[0], want[1], want[2], want[3]];
            assert_eq!(four(hit_boxes4::<true>(&b4, &sr, t_max)), want4, "{ray:?}");
            assert_eq!(eight(hit_boxes8::<true>(&min8, &max8, &sr, t_max)), want);
            if SlabRay::finite(&ray) {
                assert_eq!(four(hit_boxes4::<false>(&b4, &sr, t_max)), want4, "{ray:?}");
                assert_eq!(eight(hit_boxes8::<false>(&min8, &max8, &sr, t_max)), want);
            } else {
                safe_rays += 1;
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
                    assert!(!SlabRay::finite(&ray));
                    let got = both::<true>(&node, &ray, f32::INFINITY);
                    assert!(got.iter().all(Option::is_some), "{o:?} {d:?}: {got:?}");
                    assert_eq!(got, [unit, next].map(|b| scalar(&b, &ray, f32::INFINITY)));
                }
            }
        }
    }
}
