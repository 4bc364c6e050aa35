//! What the packet walk ([`super::packet`]) keeps per ray for a query kind ([`PacketState`],
//! written once over [`HitQuery`] for closest hits and any hit): its leaf tests, which rays a
//! popped child keeps, and how one ray finishes alone (the hybrid switch,
//! [`PacketState::finish_alone`]).
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
use crate::geometry::Ray;
use crate::index::{HitQuery, MAX_PACKET, Stats};
use crate::scene::Geometry;

/// The state of a packet's rays for query `Q`. Bit `k` of a mask is ray `k`; lane `k` of an
/// array is ray `k` (lanes past the packet are never read).
pub(crate) struct PacketState<Q: HitQuery> {
    /// What ray `k`'s walk has found so far.
    found: [Q::Found; MAX_PACKET],
    /// Lane `k`: ray `k`'s [`HitQuery::reach`], the `t_max` of its box tests (closest hits: its
    /// best `t` so far; any hit: its own `t_max`).
    reach: [f32; MAX_PACKET],
    /// Bit `k`: ray `k`'s walk is over ([`HitQuery::over`]: any hit, it has hit something;
    /// closest hits, never).
    over: u32,
}

impl<Q: HitQuery> PacketState<Q> {
    /// The state of a packet of `rays` (at least one) before any test.
    #[inline(always)]
    pub(crate) fn new(rays: &[Ray]) -> Self {
        let found = std::array::from_fn(|k| Q::start(&rays[k.min(rays.len() - 1)]));
        let reach = std::array::from_fn(|k| rays.get(k).map_or(0.0, |r| Q::reach(&found[k], r)));
        PacketState {
            found,
            reach,
            over: 0,
        }
    }

    /// Each ray's `t_max` for the box tests (lane `k` for ray `k`).
    #[inline(always)]
    pub(crate) fn t_max(&self) -> &[f32; MAX_PACKET] {
        &self.reach
    }

    /// The rays of `active` that still need the tree (any hit: those without a hit yet).
    #[inline(always)]
    pub(crate) fn needing(&self, active: u32) -> u32 {
        active & !self.over
    }

    /// The single-ray leaf tests of leaf `at` for every ray of `active`.
    #[inline(always)]
    pub(crate) fn leaf<G: Geometry, S: Stats>(
        &mut self,
        leaves: Leaves,
        at: Child,
        geom: &G,
        rays: &[Ray],
        active: u32,
        stats: &mut [S],
    ) {
        for k in bits(active) {
            let ray = &rays[k];
            if leaves.query::<Q, G, S>(at, geom, ray, &mut self.found[k], &mut stats[k]) {
                self.over |= 1 << k;
            }
            self.reach[k] = Q::reach(&self.found[k], ray);
        }
    }

    /// Of the rays of `mask` whose entries into a popped child are the lanes of `entry`, those
    /// that still need it: closest hits, those whose entry is not beyond their best `t` (one
    /// SIMD compare); any hit, those without a hit (every entry is within their `t_max`).
    #[inline(always)]
    pub(crate) fn keep<V: Lanes>(&self, mask: u32, entry: V) -> u32 {
        match Q::CLOSEST {
            true => mask & entry.le(V::load(&self.reach)),
            false => mask & !self.over,
        }
    }

    /// Ray `k` walks the subtree `at` alone with the single-ray loop, from its state so far.
    #[inline(always)]
    pub(crate) fn finish_alone<const N: usize, T: BoxTree<N>, G: Geometry, S: Stats>(
        &mut self,
        tree: &T,
        geom: &G,
        ray: &Ray,
        k: usize,
        at: Child,
        stats: &mut S,
    ) {
        let found = finish::<Q, N, T, G, S>(tree, geom, ray, at, self.found[k], stats);
        self.over |= u32::from(Q::over(&found)) << k;
        self.reach[k] = Q::reach(&found, ray);
        self.found[k] = found;
    }

    /// The answers, one per ray.
    #[inline(always)]
    pub(crate) fn answers(&self, out: &mut [Q::Answer]) {
        for (o, found) in out.iter_mut().zip(&self.found) {
            *o = Q::answer(*found);
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
