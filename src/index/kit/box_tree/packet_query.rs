//! What the packet walk ([`super::packet`]) does differently for closest hits and for any hit:
//! the per-ray state a packet keeps ([`LaneQuery`]), its leaf tests, which rays a popped child
//! keeps, and how one ray finishes alone (the hybrid switch, [`LaneQuery::finish_alone`]).
//!
//! Both queries give every ray its single-ray answer: leaves run the single-ray leaf tests, box
//! tests are the single-ray ones lane by lane ([`super::packet_slab`]), and a ray finishing
//! alone runs the single-ray loop of [`super::walk`] from the packet's current node with its
//! best hit so far, which visits that subtree exactly as the packet would have for it (the
//! packet's pushed children still come after, culled against the ray's new best `t`).

use super::lanes::Lanes;
use super::leaves::Leaves;
use super::node::Child;
use super::tree::BoxTree;
use super::walk::finish;
use crate::geometry::{ClosestHit, Hit, Ray};
use crate::index::{AnyHit, Closest, MAX_PACKET, Stats};
use crate::scene::Geometry;

/// One query kind of the packet walk: the state of a packet's rays and what the walk asks of
/// it. Bit `k` of a mask is ray `k`; `t_max` arrays are lane `k` for ray `k`.
pub(crate) trait LaneQuery {
    /// One ray's answer.
    type Answer: Copy;
    /// Whether the walk visits the children in near-to-far order (closest hits) or as found.
    const ORDERED: bool;
    /// The state of a packet of `rays` before any test.
    fn new(rays: &[Ray]) -> Self;
    /// Each ray's `t_max` for the box tests (lane `k` for ray `k`).
    fn t_max(&self) -> &[f32; MAX_PACKET];
    /// The rays of `active` that still need the tree (any hit: those without a hit yet).
    fn needing(&self, active: u32) -> u32;
    /// The single-ray leaf tests of leaf `at` for every ray of `active`.
    fn leaf<G: Geometry, S: Stats>(
        &mut self,
        leaves: Leaves,
        at: Child,
        geom: &G,
        rays: &[Ray],
        active: u32,
        stats: &mut [S],
    );
    /// Of the rays of `mask` whose entries into a popped child are the lanes of `entry`, those
    /// that still need it.
    fn keep<V: Lanes>(&self, mask: u32, entry: V) -> u32;
    /// Ray `k` walks the subtree `at` alone with the single-ray loop, from its state so far.
    fn finish_alone<const N: usize, T: BoxTree<N>, G: Geometry, S: Stats>(
        &mut self,
        tree: &T,
        geom: &G,
        ray: &Ray,
        k: usize,
        at: Child,
        stats: &mut S,
    );
    /// The answers, one per ray.
    fn answers(&self, out: &mut [Self::Answer]);
}

/// Closest hits: each ray's best hit so far; a popped child keeps the rays whose entry is not
/// beyond their best `t`.
pub(crate) struct ClosestLanes {
    best: [ClosestHit; MAX_PACKET],
    /// Lane `k`: ray `k`'s best `t` so far.
    best_t: [f32; MAX_PACKET],
}

impl LaneQuery for ClosestLanes {
    type Answer = Option<Hit>;
    const ORDERED: bool = true;

    #[inline(always)]
    fn new(rays: &[Ray]) -> Self {
        let best_t = std::array::from_fn(|k| rays.get(k).map_or(0.0, |r| r.t_max));
        ClosestLanes {
            best: std::array::from_fn(|k| ClosestHit::new(best_t[k])),
            best_t,
        }
    }

    #[inline(always)]
    fn t_max(&self) -> &[f32; MAX_PACKET] {
        &self.best_t
    }

    #[inline(always)]
    fn needing(&self, active: u32) -> u32 {
        active
    }

    #[inline(always)]
    fn leaf<G: Geometry, S: Stats>(
        &mut self,
        leaves: Leaves,
        at: Child,
        geom: &G,
        rays: &[Ray],
        active: u32,
        stats: &mut [S],
    ) {
        for k in bits(active) {
            leaves.query::<Closest, G, S>(at, geom, &rays[k], &mut self.best[k], &mut stats[k]);
            self.best_t[k] = self.best[k].t();
        }
    }

    /// The rays whose entry is not beyond their best `t` (one SIMD compare).
    #[inline(always)]
    fn keep<V: Lanes>(&self, mask: u32, entry: V) -> u32 {
        mask & entry.le(V::load(&self.best_t))
    }

    #[inline(always)]
    fn finish_alone<const N: usize, T: BoxTree<N>, G: Geometry, S: Stats>(
        &mut self,
        tree: &T,
        geom: &G,
        ray: &Ray,
        k: usize,
        at: Child,
        stats: &mut S,
    ) {
        self.best[k] = finish::<Closest, N, T, G, S>(tree, geom, ray, at, self.best[k], stats);
        self.best_t[k] = self.best[k].t();
    }

    #[inline(always)]
    fn answers(&self, out: &mut [Option<Hit>]) {
        for (o, b) in out.iter_mut().zip(&self.best) {
            *o = b.get();
        }
    }
}

/// Any hit: a ray leaves the packet at its first hit; the box tests use each ray's own
/// `[t_min, t_max]`.
pub(crate) struct AnyLanes {
    t_max: [f32; MAX_PACKET],
    /// Bit `k`: ray `k` has hit something.
    done: u32,
}

impl LaneQuery for AnyLanes {
    type Answer = bool;
    const ORDERED: bool = false;

    #[inline(always)]
    fn new(rays: &[Ray]) -> Self {
        let t_max = std::array::from_fn(|k| rays.get(k).map_or(0.0, |r| r.t_max));
        AnyLanes { t_max, done: 0 }
    }

    #[inline(always)]
    fn t_max(&self) -> &[f32; MAX_PACKET] {
        &self.t_max
    }

    #[inline(always)]
    fn needing(&self, active: u32) -> u32 {
        active & !self.done
    }

    #[inline(always)]
    fn leaf<G: Geometry, S: Stats>(
        &mut self,
        leaves: Leaves,
        at: Child,
        geom: &G,
        rays: &[Ray],
        active: u32,
        stats: &mut [S],
    ) {
        for k in bits(active) {
            if leaves.query::<AnyHit, G, S>(at, geom, &rays[k], &mut false, &mut stats[k]) {
                self.done |= 1 << k;
            }
        }
    }

    #[inline(always)]
    fn keep<V: Lanes>(&self, mask: u32, _entry: V) -> u32 {
        mask & !self.done
    }

    #[inline(always)]
    fn finish_alone<const N: usize, T: BoxTree<N>, G: Geometry, S: Stats>(
        &mut self,
        tree: &T,
        geom: &G,
        ray: &Ray,
        k: usize,
        at: Child,
        stats: &mut S,
    ) {
        let hit = finish::<AnyHit, N, T, G, S>(tree, geom, ray, at, false, stats);
        self.done |= u32::from(hit) << k;
    }

    #[inline(always)]
    fn answers(&self, out: &mut [bool]) {
        for (k, o) in out.iter_mut().enumerate() {
            *o = self.done >> k & 1 == 1;
        }
    }
}

/// The set bits of `mask`, lowest first (rays of a ray mask, children of a child mask).
#[inline(always)]
pub(crate) fn bits(mut mask: u32) -> impl Iterator<Item = usize> {
    std::iter::from_fn(move || {
        (mask != 0).then(|| {
            let k = mask.trailing_zeros() as usize;
            mask &= mask - 1;
            k
        })
    })
}
