//! Packet traversal of the box trees (Wald, Slusallek, Benthin and Wagner 2001), one walk for
//! the binary BVH and the wide ones (`bvh4`, `bvh8`) and for both queries ([`LaneQuery`]:
//! closest hits, any hit): up to [`MAX_PACKET`] neighbouring rays walk the tree together, four
//! in one SSE register per quantity, five to eight in one AVX register ([`F8`]), nine to
//! sixteen in one AVX-512 register ([`F16`]). A node is fetched once per packet; an active mask
//! (bit `k` for ray `k`) says which rays still need it. At an inner node each child's box is
//! tested once for the whole packet ([`PacketTree::hit`], [`super::packet_slab`]: one SIMD pass
//! per child, each lane exactly its ray's single-ray test, against that ray's `t_max`: its best
//! `t` so far for closest hits); each hit child goes on with the mask of the active rays that
//! hit it and their entries, the packet visits one first (closest hits: [`nearest_last`]) and
//! pushes the others. At a leaf every active ray runs the single-ray leaf test
//! ([`super::leaves::Leaves::closest`], [`super::leaves::Leaves::any`]).
//!
//! Each ray keeps its own closest hit; a popped child keeps only the rays whose entry into it
//! is not beyond their best `t` so far (one SIMD compare). Per ray this is exactly the
//! single-ray loop's culling (see [`super::walk`]): a ray skips a box only when its own
//! conservative, monotone box test rules out every hit that could beat or tie its best one, so
//! every ray returns its single-ray hit bit for bit, ties to the lowest id included, whatever
//! order the packet visits the children in. Any-hit packets drop a ray from the mask at its
//! first hit and stop when no ray is left.
//!
//! Hybrid switch ([`go_single`]): when fewer than half the lanes are active at a node, each of
//! the active rays finishes the node's subtree alone with the single-ray loop from its state so far
//! ([`LaneQuery::finish_alone`]), and the packet goes on with its stack.
//!
//! Counting: every active ray is charged a node visit per node and the node's box tests (as
//! the single-ray step counts them) per inner node, so tests and steps per ray compare with
//! single rays; with [`crate::index::NoStats`] (zero-sized) the counting is skipped at compile
//! time.
//!
//! Nothing is allocated: masks and best hits are arrays of [`MAX_PACKET`], the stack is fixed
//! (`N` entries, the tree's single-ray bound: a level pushes at most as many children as the
//! single-ray step does).

use super::lanes::{F8, Lanes, MAX_LANES};
use super::lanes16::F16;
use super::node::Child;
use super::packet_query::{AnyLanes, ClosestLanes, LaneQuery, bits};
use super::packet_slab::{PacketRays, hit_box, hit_box_by_sign};
use super::tree::{BoxTree, Top};
use crate::geometry::{Aabb, Hit, Ray};
use crate::index::kit::stack::Stack;
use crate::index::{MAX_PACKET, Stats};
use crate::scene::Geometry;
use glam::Vec4;

/// The packet methods of [`crate::index::BatchIndex`] for a type whose `tree()` is a [`Tree`]
/// that is a [`PacketTree`]: the packet walk.
macro_rules! tree_packets {
    () => {
        fn closest_hits_packet<G: $crate::scene::Geometry, S: $crate::index::Stats>(
            &self,
            geom: &G,
            rays: &[$crate::geometry::Ray],
            out: &mut [Option<$crate::geometry::Hit>],
            stats: &mut [S],
        ) {
            $crate::index::kit::box_tree::packet::closest_hits(&self.tree(), geom, rays, out, stats)
        }

        fn any_hits_packet<G: $crate::scene::Geometry, S: $crate::index::Stats>(
            &self,
            geom: &G,
            rays: &[$crate::geometry::Ray],
            out: &mut [bool],
            stats: &mut [S],
        ) {
            $crate::index::kit::box_tree::packet::any_hits(&self.tree(), geom, rays, out, stats)
        }
    };
}
pub(crate) use tree_packets;

/// A box tree as the packet walk sees it: nodes of up to `W` children, a stack bound of `N`
/// entries (at most `W - 1` pushes per level).
pub(crate) trait PacketTree<const W: usize, const N: usize>: BoxTree<N> {
    /// The box of child `i` of inner node `node` (`i` below [`PacketTree::boxes`]).
    fn child_box(&self, node: u32, i: usize) -> Aabb;
    /// Box tests of one ray at inner node `node`, as the single-ray step counts them: the
    /// number of children.
    fn boxes(&self, node: u32) -> u32;
    /// Child `i` of inner node `node`.
    fn child(&self, node: u32, i: usize) -> Child;

    /// The packet slab test of inner node `node`'s children against each lane's `[t_min,
    /// t_max]`: per child `i`, the mask of the lanes that hit its box (0 for absent children)
    /// and their entries (meaningful in the mask). Packets whose rays agree on their direction
    /// signs read each axis's planes by sign ([`hit_box_by_sign`]), the others take a min and a
    /// max per axis ([`hit_box`]); both give every lane its single-ray decision and entry.
    #[inline(always)]
    fn hit<const SAFE: bool, V: Lanes>(
        &self,
        node: u32,
        rays: &PacketRays<V>,
        t_max: V,
    ) -> ([u32; W], [V; W]) {
        let mut masks = [0; W];
        let mut entries = [t_max; W];
        for i in 0..self.boxes(node) as usize {
            let b = self.child_box(node, i);
            let (min, max) = (b.min.to_array(), b.max.to_array());
            (masks[i], entries[i]) = match rays.near() {
                Some(near) => hit_box_by_sign::<SAFE, V>(min, max, near, rays, t_max),
                None => hit_box::<SAFE, V>(min, max, rays, t_max),
            };
        }
        (masks, entries)
    }
}

/// Calls `f` on the counters of every ray in `active`; nothing for zero-sized counters
/// ([`crate::index::NoStats`] of the timed passes), decided at compile time.
#[inline(always)]
pub(super) fn count<S: Stats>(active: u32, stats: &mut [S], f: impl Fn(&mut S)) {
    if std::mem::size_of::<S>() == 0 {
        return;
    }
    for k in bits(active) {
        f(&mut stats[k]);
    }
}

/// The hit children (non-empty `masks`) in visiting order reversed: the one to visit first
/// last, the rest before it to be pushed (so popped) in the order given. Two children: the
/// first child unless most of the rays that hit both enter the second strictly nearer (one
/// compare and two popcounts). More: by the entry of the child's lowest ray (its box entry for
/// the packet's leading ray when that ray hits it; the rays of a coherent packet agree),
/// farthest first, ties to the higher child.
#[inline(always)]
fn nearest_last<const W: usize, V: Lanes>(
    masks: &[u32; W],
    entries: &[V; W],
) -> ([usize; W], usize) {
    let mut order = [0usize; W];
    if W == 2 {
        return match (masks[0] != 0, masks[1] != 0) {
            (true, true) => {
                let both = masks[0] & masks[1];
                let second = entries[1].lt(entries[0]) & both;
                order = std::array::from_fn(|i| i);
                if 2 * second.count_ones() <= both.count_ones() {
                    order.swap(0, 1);
                }
                (order, 2)
            }
            (true, false) => (order, 1),
            (false, true) => {
                order[0] = 1;
                (order, 1)
            }
            (false, false) => (order, 0),
        };
    }
    let mut key = [0.0f32; W];
    let mut n = 0;
    for c in (0..W).filter(|&c| masks[c] != 0) {
        let near = entries[c].to_lanes()[masks[c].trailing_zeros() as usize];
        let mut j = n;
        while j > 0 && key[j - 1] < near {
            (order[j], key[j]) = (order[j - 1], key[j - 1]);
            j -= 1;
        }
        (order[j], key[j]) = (c, near);
        n += 1;
    }
    (order, n)
}

/// The hit children (non-empty `masks`) in the order [`nearest_last`] returns them, unsorted:
/// the lowest hit child visited first, the others pushed highest first (any hit).
#[inline(always)]
fn as_found<const W: usize>(masks: &[u32; W]) -> ([usize; W], usize) {
    let mut order = [0usize; W];
    let mut n = 0;
    for c in (0..W).rev().filter(|&c| masks[c] != 0) {
        order[n] = c;
        n += 1;
    }
    (order, n)
}

/// The packet's slab constants, and the mask of the rays that enter the root's box (each ray's
/// scalar root test, as the single-ray loop does it).
#[inline(always)]
fn start<V: Lanes, S: Stats>(top: &Top, rays: &[Ray], stats: &mut [S]) -> (PacketRays<V>, u32) {
    let mut active = 0;
    for (k, ray) in rays.iter().enumerate() {
        stats[k].box_tests(1);
        let entry = top.root_bounds.ray_entry(ray, ray.t_min, ray.t_max);
        active |= u32::from(entry.is_some()) << k;
    }
    (PacketRays::new(rays), active)
}

/// The packet test of `node`'s children, `SAFE` when the packet needs it, each child's mask
/// restricted to `active`, every active ray charged the node's box tests.
#[inline(always)]
fn test_children<const W: usize, const N: usize, T, V, S>(
    tree: &T,
    node: u32,
    active: u32,
    rays: &PacketRays<V>,
    t_max: V,
    stats: &mut [S],
) -> ([u32; W], [V; W])
where
    T: PacketTree<W, N>,
    V: Lanes,
    S: Stats,
{
    count(active, stats, |s| s.box_tests(tree.boxes(node)));
    let (mut masks, entries) = match rays.fast() {
        true => tree.hit::<false, V>(node, rays, t_max),
        false => tree.hit::<true, V>(node, rays, t_max),
    };
    for m in &mut masks {
        *m &= active;
    }
    (masks, entries)
}

const _: () = assert!(
    MAX_PACKET == MAX_LANES,
    "a packet's lanes fill one register"
);

/// Whether a packet of `V::WIDTH` lanes with `active` rays lets them finish alone (the hybrid
/// switch of Benthin, Wald, Woop, Ernst and Mark 2012): when fewer than half its lanes are
/// active, each remaining ray walks the current subtree with the single-ray loop. Half, because
/// on bunny rays (one thread) it kept the coherent primary packets at their speed without the
/// switch (thresholds of 4 and 8 of 16 measured within the intervals of 0) while bringing
/// incoherent 16-ray packets from 0.25x of single rays (no switch) to about 0.8x (`bvh8`) and
/// 1.1x (`bvh`); switching later (12 or 16 of 16) cost the primary packets of `bvh` a fifth.
#[inline(always)]
pub(super) fn go_single<V: Lanes>(active: u32) -> bool {
    2 * active.count_ones() < V::WIDTH as u32
}

/// Closest hits of a packet of at most [`MAX_PACKET`] rays (`out`, `stats` as long as `rays`).
pub(crate) fn closest_hits<const W: usize, const N: usize, T, G, S>(
    tree: &T,
    geom: &G,
    rays: &[Ray],
    out: &mut [Option<Hit>],
    stats: &mut [S],
) where
    T: PacketTree<W, N>,
    G: Geometry,
    S: Stats,
{
    by_width::<ClosestLanes, W, N, T, G, S>(tree, geom, rays, out, stats);
}

/// Any-hit results of a packet of at most [`MAX_PACKET`] rays.
pub(crate) fn any_hits<const W: usize, const N: usize, T, G, S>(
    tree: &T,
    geom: &G,
    rays: &[Ray],
    out: &mut [bool],
    stats: &mut [S],
) where
    T: PacketTree<W, N>,
    G: Geometry,
    S: Stats,
{
    by_width::<AnyLanes, W, N, T, G, S>(tree, geom, rays, out, stats);
}

/// The walk in the narrowest register that holds the packet: four lanes, eight or sixteen.
#[inline(always)]
fn by_width<Q, const W: usize, const N: usize, T, G, S>(
    tree: &T,
    geom: &G,
    rays: &[Ray],
    out: &mut [Q::Answer],
    stats: &mut [S],
) where
    Q: LaneQuery,
    T: PacketTree<W, N>,
    G: Geometry,
    S: Stats,
{
    match rays.len() {
        0 => {}
        1..=4 => walk::<Q, W, N, T, G, S, Vec4>(tree, geom, rays, out, stats),
        5..=8 => walk::<Q, W, N, T, G, S, F8>(tree, geom, rays, out, stats),
        _ => walk::<Q, W, N, T, G, S, F16>(tree, geom, rays, out, stats),
    }
}

/// The packet walk of query `Q` in registers `V` (see the module doc).
#[inline(always)]
fn walk<Q, const W: usize, const N: usize, T, G, S, V>(
    tree: &T,
    geom: &G,
    rays: &[Ray],
    out: &mut [Q::Answer],
    stats: &mut [S],
) where
    Q: LaneQuery,
    T: PacketTree<W, N>,
    G: Geometry,
    S: Stats,
    V: Lanes,
{
    let top = tree.top();
    let (packet, mut active) = start::<V, S>(&top, rays, stats);
    let mut q = Q::new(rays);
    let mut stack = Stack::<(Child, u32, V), N>::new();
    let mut at = top.root;
    loop {
        active = q.needing(active);
        if active != 0 && go_single::<V>(active) {
            for k in bits(active) {
                q.finish_alone(tree, geom, &rays[k], k, at, &mut stats[k]);
            }
            active = 0;
        }
        if active != 0 {
            count(active, stats, S::node_visit);
            if at.is_leaf() {
                q.leaf(top.leaves, at, geom, rays, active, stats);
            } else {
                let t_max = V::load(q.t_max());
                let (masks, entries) = test_children(tree, at.index, active, &packet, t_max, stats);
                let (order, n) = match Q::ORDERED {
                    true => nearest_last(&masks, &entries),
                    false => as_found(&masks),
                };
                if n > 0 {
                    for &c in &order[..n - 1] {
                        stack.push((tree.child(at.index, c), masks[c], entries[c]));
                    }
                    let next = order[n - 1];
                    at = tree.child(at.index, next);
                    active = masks[next];
                    continue;
                }
            }
        }
        // Pop until a child some ray still needs.
        active = 0;
        while active == 0 {
            let Some((child, mask, entry)) = stack.pop() else {
                q.answers(out);
                return;
            };
            active = q.keep(mask, entry);
            at = child;
        }
    }
}
