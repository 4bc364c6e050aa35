//! The interval (frustum) test of the beam walk ([`super::beam`]): one conservative box test
//! for a whole packet (Boulos, Wald, Benthin, Shirley et al. 2007; Wald, Boulos and Shirley
//! 2007). Per axis the packet keeps the interval of its rays' origins and of their inverse
//! directions ([`Frustum`]); a box is culled only when the lowest entry any ray of the packet
//! could have is beyond the highest exit any could have.
//!
//! **Which packets.** Only packets whose rays all take the fast slab test
//! ([`Ray::fast_slabs`]: every `inv_dir` component finite, so nonzero, and `t_min >= 0`) and
//! agree on the sign bit of every `inv_dir` component ([`Frustum::new`] is `None` otherwise; the
//! beam walk then takes the packet walk). The signs say which plane of each axis is every
//! ray's near one (`min` for a positive inverse, `max` for a negative one), and no product is
//! NaN: a plane minus an origin is a finite or infinite number, times a finite nonzero one.
//!
//! **The bound, with f32 rounding.** Each ray's single-ray test computes per axis the near
//! distance `n = fl(fl(p - o) * i)` and the far one `f = fl(fl(q - o) * i)` (`p`, `q` the near
//! and far planes, `o` its origin, `i` its inverse direction), enters at `max(n_x, n_y, n_z,
//! t_min)`, leaves at `min(w(f_x), w(f_y), w(f_z), t_max)` with `w(f) = fl(f * SLAB_FAR_SCALE)`
//! (the `SAFE` variant's `max(f * s, f * (2 - s))` decides the same for these rays, and is what
//! the bound uses, above both) and hits when entry `<=` exit. Round-to-nearest is monotone
//! (`x <= y` implies `fl(x) <= fl(y)`, infinities included), so bounds computed with the same
//! operations on the interval ends bound the rounded per-ray values without any extra margin:
//!
//! - `fl(p - o) >= fl(p - o_hi)` for `i > 0` (`o <= o_hi`), and `fl(p - o) <= fl(p - o_lo)`
//!   for `i < 0`; call that end `d`. The product `x * i` with `x` on `d`'s side and `i` in
//!   `[i_lo, i_hi]` (one sign) is at least `min(d * i_lo, d * i_hi)` in exact arithmetic
//!   (monotone in `x`, then linear in `i`), so the rounded product is at least
//!   `min(fl(d * i_lo), fl(d * i_hi))`: a lower bound `N` of every ray's `n` on that axis.
//! - Symmetrically `fl(q - o) <= fl(q - o_lo)` for `i > 0`, `>= fl(q - o_hi)` for `i < 0`, and
//!   the far distance is at most `F = max(fl(e * i_lo), fl(e * i_hi))` for that end `e`.
//!   `w` is monotone, so `w(f) <= max(fl(F * s), fl(F * (2 - s)))`.
//! - Every ray enters at or after `max(N_x, N_y, N_z, min t_min)` and leaves at or before
//!   `min(w(F_x), w(F_y), w(F_z), T)` with `T` the largest `t_max` (best `t`) of the rays
//!   asked about. When the first is greater than the second, every ray's entry is greater than
//!   its exit: its single-ray test misses the box. That is the only case [`Frustum::misses`]
//!   says `true` (a strict `>`, false on NaN, so a NaN could only keep a box).
//!
//! The wide nodes' absent children (`min = +inf`, `max = -inf`) are never asked about.
//! `tests` checks the implication on random and adversarial packets and boxes (grazing rays,
//! tiny, huge and flat boxes, origins on box planes, huge and tiny direction components).

use crate::geometry::{Aabb, Ray, SLAB_FAR_SCALE};
use glam::{BVec3A, Vec3A};

/// A packet's intervals, arranged for [`Frustum::misses`].
#[derive(Debug, Clone, Copy)]
pub struct Frustum {
    /// Per axis, whether the rays' inverse direction is negative (sign bit set): the `max`
    /// plane is then their near one.
    neg: BVec3A,
    /// Per axis, the origin end that gives the lowest near distance: the largest origin where
    /// `inv_dir > 0`, the smallest where `inv_dir < 0`.
    o_near: Vec3A,
    /// Per axis, the origin end that gives the highest far distance (the other end).
    o_far: Vec3A,
    inv_lo: Vec3A,
    inv_hi: Vec3A,
    /// The smallest `t_min` of the packet.
    t_min: f32,
}

impl Frustum {
    /// The packet's frustum, or `None` when a ray needs the `SAFE` slab test or the rays
    /// disagree on the sign of some `inv_dir` component (see the module doc).
    #[inline(always)]
    pub fn new(rays: &[Ray]) -> Option<Frustum> {
        let first = rays.first()?;
        let signs = sign_bits(first.inv_dir);
        let neg = BVec3A::new(signs & 1 != 0, signs & 2 != 0, signs & 4 != 0);
        let (mut o_lo, mut o_hi) = (first.origin, first.origin);
        let (mut inv_lo, mut inv_hi) = (first.inv_dir, first.inv_dir);
        let mut t_min = first.t_min;
        for r in rays {
            if !r.fast_slabs() || sign_bits(r.inv_dir) != signs {
                return None;
            }
            o_lo = o_lo.min(r.origin);
            o_hi = o_hi.max(r.origin);
            inv_lo = inv_lo.min(r.inv_dir);
            inv_hi = inv_hi.max(r.inv_dir);
            t_min = t_min.min(r.t_min);
        }
        Some(Frustum {
            neg,
            o_near: Vec3A::select(neg, o_lo, o_hi),
            o_far: Vec3A::select(neg, o_hi, o_lo),
            inv_lo,
            inv_hi,
            t_min,
        })
    }

    /// Per axis, whether the packet's near plane is the `max` one (`[x, y, z]`, as
    /// [`super::slab::SlabRay::near`]: 1 for `max`).
    #[inline(always)]
    pub fn near(&self) -> [usize; 3] {
        let m = self.neg.bitmask();
        [0, 1, 2].map(|k| (m >> k & 1) as usize)
    }

    /// Whether no ray of the packet whose `t_max` is at most `t_max` can hit `b`: `true` only
    /// when every such ray's single-ray slab test misses it (see the module doc).
    #[inline(always)]
    pub fn misses(&self, b: &Aabb, t_max: f32) -> bool {
        let (enter, exit) = self.bounds(b, t_max);
        enter > exit
    }

    /// The lowest entry into `b` and the highest exit from it that a ray of the packet with
    /// `t_max` at most `t_max` can have in its single-ray test (see the module doc).
    #[inline(always)]
    pub fn bounds(&self, b: &Aabb, t_max: f32) -> (f32, f32) {
        let near = Vec3A::select(self.neg, b.max, b.min);
        let far = Vec3A::select(self.neg, b.min, b.max);
        let dn = near - self.o_near;
        let df = far - self.o_far;
        let lo = (dn * self.inv_lo).min(dn * self.inv_hi);
        let hi = (df * self.inv_lo).max(df * self.inv_hi);
        let hi = (hi * SLAB_FAR_SCALE).max(hi * (2.0 - SLAB_FAR_SCALE));
        let enter = lo.max_element().max(self.t_min);
        let exit = hi.min_element().min(t_max);
        (enter, exit)
    }

    /// Whether `ray` (one of the packet's) hits `b` over `[ray.t_min, t_max]`: its single-ray
    /// fast slab test, the planes read by the packet's signs (the first-active-ray test).
    #[inline(always)]
    pub fn ray_hits(&self, b: &Aabb, ray: &Ray, t_max: f32) -> bool {
        let near = Vec3A::select(self.neg, b.max, b.min);
        let far = Vec3A::select(self.neg, b.min, b.max);
        let n = (near - ray.origin) * ray.inv_dir;
        let f = (far - ray.origin) * ray.inv_dir;
        let enter = n.max_element().max(ray.t_min);
        let exit = (f * SLAB_FAR_SCALE).min_element().min(t_max);
        enter <= exit
    }
}

/// The sign bits of `v`'s components (bit `k` for axis `k`).
#[inline(always)]
fn sign_bits(v: Vec3A) -> u32 {
    v.is_negative_bitmask()
}

#[cfg(test)]
#[path = "frustum_tests.rs"]
mod tests;
