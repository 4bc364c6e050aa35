//! Packet traversal of the box trees (Wald, Slusallek, Benthin and Wagner 2001), one walk for
//! the binary BVH and the wide ones (`bvh4`, `bvh8`): up to [`MAX_PACKET`] neighbouring rays
//! walk the tree together. A node is fetched once per packet; an active mask (bit `k` for ray
//! `k`) says which rays still need it. At an inner node every active ray tests the node's
//! children's boxes ([`PacketTree::hit`], the single-ray node step's own SIMD test, so every
//! ray's box test is exactly its single-ray test); each hit child goes on with the mask of the
//! rays that hit it and their entries, the packet visits first the child some ray enters
//! nearest, and pushes the others farthest first. At a leaf every active ray runs the
//! single-ray leaf test ([`super::leaves::Leaves::closest`], [`super::leaves::Leaves::any`]).
//!
//! Each ray keeps its own closest hit; a popped child keeps only the rays whose entry into it
//! is not beyond their best `t` so far. Per ray this is exactly the single-ray loop's culling
//! (see [`super::walk`]): a ray skips a box only when its own conservative, monotone box test
//! rules out every hit that could beat or tie its best one, so every ray returns its
//! single-ray hit bit for bit, ties to the lowest id included. Any-hit packets drop a ray from
//! the mask at its first hit and stop when no ray is left.
//!
//! Nothing is allocated: lanes, masks and entries are arrays of [`MAX_PACKET`], the stack is
//! fixed (`N` entries, the tree's single-ray bound: a level pushes at most as many children
//! as the single-ray step does).

use super::node::Child;
use super::slab::{self, SlabRay};
use super::traverse::{STACK, Tree};
use super::walk::{Rooted, Top};
use crate::geometry::{ClosestHit, Hit, Ray};
use crate::index::stack::Stack;
use crate::index::{MAX_PACKET, Stats};
use crate::scene::Geometry;

/// A box tree as the packet walk sees it: nodes of up to `W` children, a stack bound of `N`
/// entries (at most `W - 1` pushes per level).
pub(crate) trait PacketTree<const W: usize, const N: usize>: Rooted {
    /// One ray's slab test of inner node `node`'s children against `[ray.t_min, t_max]`,
    /// exactly the single-ray node step's test: the mask of the hit children (bit `i` for
    /// child `i`) and their entries (meaningful where hit).
    fn hit<const SAFE: bool>(&self, node: u32, ray: &SlabRay, t_max: f32) -> (u32, [f32; W]);
    /// Box tests of one ray at inner node `node`, as the single-ray step counts them.
    fn boxes(&self, node: u32) -> u32;
    /// Child `i` of inner node `node`.
    fn child(&self, node: u32, i: usize) -> Child;
}

impl PacketTree<2, STACK> for Tree<'_> {
    #[inline(always)]
    fn hit<const SAFE: bool>(&self, node: u32, ray: &SlabRay, t_max: f32) -> (u32, [f32; 2]) {
        let (hit, enter) = slab::hit_children::<SAFE>(&self.nodes[node as usize], ray, t_max);
        (hit, [enter.x, enter.y])
    }

    #[inline(always)]
    fn boxes(&self, _node: u32) -> u32 {
        2
    }

    #[inline(always)]
    fn child(&self, node: u32, i: usize) -> Child {
        self.nodes[node as usize].children[i]
    }
}

/// One ray of a packet: its slab constants, which slab variant it takes, its best hit.
struct Lane {
    slab: SlabRay,
    finite: bool,
    best: ClosestHit,
}

/// The set bits of `mask`, lowest first (rays of a ray mask, children of a child mask).
fn bits(mut mask: u32) -> impl Iterator<Item = usize> {
    std::iter::from_fn(move || {
        (mask != 0).then(|| {
            let k = mask.trailing_zeros() as usize;
            mask &= mask - 1;
            k
        })
    })
}

/// Per child, the mask of the active rays that hit its box (with `t_max` each ray's bound) and
/// their entries (meaningful in the mask).
#[inline(always)]
fn test_children<const W: usize, const N: usize, T: PacketTree<W, N>, S: Stats>(
    tree: &T,
    node: u32,
    active: u32,
    lanes: &[Lane; MAX_PACKET],
    t_max: impl Fn(usize) -> f32,
    stats: &mut [S],
) -> ([u32; W], [[f32; MAX_PACKET]; W]) {
    let mut masks = [0u32; W];
    let mut entries = [[0.0; MAX_PACKET]; W];
    for k in bits(active) {
        let lane = &lanes[k];
        stats[k].box_tests(tree.boxes(node));
        let (hit, enter) = if lane.finite {
            tree.hit::<false>(node, &lane.slab, t_max(k))
        } else {
            tree.hit::<true>(node, &lane.slab, t_max(k))
        };
        for c in bits(hit) {
            masks[c] |= 1 << k;
            entries[c][k] = enter[c];
        }
    }
    (masks, entries)
}

/// The hit children (those with a non-empty mask) ordered farthest first by the nearest entry
/// of any of their rays, and how many there are.
#[inline(always)]
fn farthest_first<const W: usize>(
    masks: &[u32; W],
    entries: &[[f32; MAX_PACKET]; W],
) -> ([usize; W], usize) {
    let mut order = [0usize; W];
    let mut key = [0.0f32; W];
    let mut n = 0;
    for c in (0..W).filter(|&c| masks[c] != 0) {
        let near = bits(masks[c]).fold(f32::INFINITY, |m, k| m.min(entries[c][k]));
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

/// Slab constants and an empty best hit per ray (lanes past `rays.len()` copy ray 0 and stay
/// inactive), and the mask of the rays that enter the root's box.
#[inline(always)]
fn start<S: Stats>(top: &Top, rays: &[Ray], stats: &mut [S]) -> ([Lane; MAX_PACKET], u32) {
    assert!(!rays.is_empty() && rays.len() <= MAX_PACKET);
    let lanes = std::array::from_fn(|k| {
        let ray = rays.get(k).unwrap_or(&rays[0]);
        Lane {
            slab: SlabRay::new(ray),
            finite: SlabRay::finite(ray),
            best: ClosestHit::new(ray.t_max),
        }
    });
    let mut active = 0;
    for (k, ray) in rays.iter().enumerate() {
        stats[k].box_tests(1);
        if top
            .root_bounds
            .ray_entry(ray, ray.t_min, ray.t_max)
            .is_some()
        {
            active |= 1 << k;
        }
    }
    (lanes, active)
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
    let top = tree.top();
    let (mut lanes, mut active) = start(&top, rays, stats);
    let mut stack = Stack::<(Child, u32, [f32; MAX_PACKET]), N>::new();
    let mut at = top.root;
    while active != 0 {
        for k in bits(active) {
            stats[k].node_visit();
        }
        let mut next = None;
        if at.is_leaf() {
            for k in bits(active) {
                let best = &mut lanes[k].best;
                top.leaves.closest(at, geom, &rays[k], best, &mut stats[k]);
            }
        } else {
            let (masks, entries) =
                test_children(tree, at.index, active, &lanes, |k| lanes[k].best.t(), stats);
            let (order, n) = farthest_first(&masks, &entries);
            if n > 0 {
                for &c in &order[..n - 1] {
                    stack.push((tree.child(at.index, c), masks[c], entries[c]));
                }
                let near = order[n - 1];
                next = Some((tree.child(at.index, near), masks[near]));
            }
        }
        // Pop until a child some ray can still get a better or tied hit in.
        while next.is_none() {
            let Some((child, mask, entry)) = stack.pop() else {
                break;
            };
            let mask = bits(mask)
                .filter(|&k| entry[k] <= lanes[k].best.t())
                .fold(0, |m, k| m | 1 << k);
            if mask != 0 {
                next = Some((child, mask));
            }
        }
        let Some((child, mask)) = next else { break };
        at = child;
        active = mask;
    }
    for (k, o) in out.iter_mut().enumerate() {
        *o = lanes[k].best.get();
    }
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
    let top = tree.top();
    let (lanes, mut active) = start(&top, rays, stats);
    out.fill(false);
    let mut done = 0u32;
    let mut stack = Stack::<(Child, u32), N>::new();
    let mut at = top.root;
    loop {
        active &= !done;
        if active != 0 {
            for k in bits(active) {
                stats[k].node_visit();
            }
            if at.is_leaf() {
                for k in bits(active) {
                    if top.leaves.any(at, geom, &rays[k], &mut stats[k]) {
                        out[k] = true;
                        done |= 1 << k;
                    }
                }
            } else {
                let (masks, _) =
                    test_children(tree, at.index, active, &lanes, |k| rays[k].t_max, stats);
                let mut hit = bits(
                    masks
                        .iter()
                        .enumerate()
                        .fold(0, |m, (c, &r)| m | u32::from(r != 0) << c),
                );
                if let Some(first) = hit.next() {
                    for c in hit {
                        stack.push((tree.child(at.index, c), masks[c]));
                    }
                    at = tree.child(at.index, first);
                    active = masks[first];
                    continue;
                }
            }
        }
        let Some((child, mask)) = stack.pop() else {
            return;
        };
        at = child;
        active = mask;
    }
}
