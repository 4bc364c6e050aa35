//! The two questions a ray asks of an index, as types ([`Closest`]: the closest hit;
//! [`AnyHit`]: whether anything is hit), and what a walk keeps while it answers one
//! ([`HitQuery`]). Every family's walk (brute force, the box trees, the near/far partitions, the
//! cell walks) is written once over `Q: HitQuery` and answers both.
//!
//! The one rule a walk follows: a primitive is tested against `[ray.t_min, Q::reach(found)]`
//! through the shared kernel ([`crate::index::kit::prim_test::test`]), a hit is handed to
//! [`HitQuery::hit`], and the walk ends when that says so. For [`Closest`] the reach is the best
//! `t` so far (so a subtree whose entry lies beyond it is skipped) and no hit ends the walk; for
//! [`AnyHit`] the reach is `ray.t_max` and the first hit ends it.

use crate::geometry::{ClosestHit, Hit, Ray};

/// A query kind: its answer per ray and the state a walk keeps for it.
pub trait HitQuery: Send + Sync + 'static {
    /// One ray's answer (`Option<Hit>` or `bool`; the default is a miss).
    type Answer: Copy + Default + Send + Sync;
    /// What one ray's walk keeps (the best hit so far, or whether one was found).
    type Found: Copy;
    /// Whether a hit is better the nearer it is: the walk then visits the near side first and
    /// skips what starts beyond [`HitQuery::reach`].
    const CLOSEST: bool;

    /// Nothing found yet for `ray`.
    fn start(ray: &Ray) -> Self::Found;

    /// The far end of the parameter interval a primitive or a box still matters in.
    fn reach(found: &Self::Found, ray: &Ray) -> f32;

    /// Notes a hit on primitive `prim` at `t` (`t` within [`HitQuery::reach`]); `true` when the
    /// walk is over.
    fn hit(found: &mut Self::Found, t: f32, prim: u32) -> bool;

    /// The answer from what the walk found.
    fn answer(found: Self::Found) -> Self::Answer;

    /// The answer of an index that asks a library rather than walking itself: `closest()` for
    /// [`Closest`], `any()` for [`AnyHit`] (only the one called runs).
    fn select(closest: impl FnOnce() -> Option<Hit>, any: impl FnOnce() -> bool) -> Self::Answer;
}

/// The closest hit (primitive and `t`), or `None`.
pub enum Closest {}

/// Whether any primitive is hit (shadow rays).
pub enum AnyHit {}

impl HitQuery for Closest {
    type Answer = Option<Hit>;
    type Found = ClosestHit;
    const CLOSEST: bool = true;

    #[inline(always)]
    fn start(ray: &Ray) -> ClosestHit {
        ClosestHit::new(ray.t_max)
    }

    #[inline(always)]
    fn reach(found: &ClosestHit, _: &Ray) -> f32 {
        found.t()
    }

    #[inline(always)]
    fn hit(found: &mut ClosestHit, t: f32, prim: u32) -> bool {
        found.offer(t, prim);
        false
    }

    #[inline(always)]
    fn answer(found: ClosestHit) -> Option<Hit> {
        found.get()
    }

    #[inline(always)]
    fn select(closest: impl FnOnce() -> Option<Hit>, _: impl FnOnce() -> bool) -> Option<Hit> {
        closest()
    }
}

impl HitQuery for AnyHit {
    type Answer = bool;
    type Found = bool;
    const CLOSEST: bool = false;

    #[inline(always)]
    fn start(_: &Ray) -> bool {
        false
    }

    #[inline(always)]
    fn reach(_: &bool, ray: &Ray) -> f32 {
        ray.t_max
    }

    #[inline(always)]
    fn hit(found: &mut bool, _: f32, _: u32) -> bool {
        *found = true;
        true
    }

    #[inline(always)]
    fn answer(found: bool) -> bool {
        found
    }

    #[inline(always)]
    fn select(_: impl FnOnce() -> Option<Hit>, any: impl FnOnce() -> bool) -> bool {
        any()
    }
}
