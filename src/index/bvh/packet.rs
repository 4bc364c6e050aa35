//! Packet traversal of the binary BVH (Wald, Slusallek, Benthin and Wagner 2001): up to
//! [`MAX_PACKET`] neighbouring rays walk the tree together. A node is fetched once per packet;
//! an active mask (bit `k` for ray `k`) says which rays still need it. At an inner node every
//! active ray tests both children's boxes ([`slab::hit_children`], the single-ray SIMD pass, so
//! every ray's box test is exactly its own single-ray test), each child goes on with the mask
//! of the rays that hit it, and the packet visits the child most of those rays enter first. At
//! a leaf every active ray tests the leaf's primitives through [`Geometry::intersect`].
//!
//! Each ray keeps its own closest hit; a popped child keeps only the rays whose entry into it
//! is not beyond their best `t` so far. Per ray this is exactly the single-ray loop's culling
//! (see [`super::walk`]): a ray skips a box only when its own conservative, monotone box test
//! rules out every hit that could beat or tie its best one, so every ray returns its
//! single-ray hit bit for bit, ties to the lowest id included. Any-hit packets drop a ray from
//! the mask at its first hit and stop when no ray is left.

use super::Bvh;
use super::node::Child;
use super::slab::{self, SlabRay};
use super::traverse::STACK;
use crate::geometry::{ClosestHit, Hit, Ray};
use crate::index::stack::Stack;
use crate::index::{MAX_PACKET, Stats};
use crate::scene::Geometry;

/// One ray of a packet: its slab constants, which slab variant it takes, its best hit.
struct Lane {
    slab: SlabRay,
    finite: bool,
    best: ClosestHit,
}

/// The lanes of `mask`, lowest first.
fn lanes(mut mask: u32) -> impl Iterator<Item = usize> {
    std::iter::from_fn(move || {
        (mask != 0).then(|| {
            let k = mask.trailing_zeros() as usize;
            mask &= mask - 1;
            k
        })
    })
}

/// Per child, the mask of the active rays that hit its box (with `t_max` each ray's bound) and
/// their entries; counts two box tests per active ray.
#[inline(always)]
fn test_children<S: Stats>(
    bvh: &Bvh,
    node: u32,
    active: u32,
    lanes_of: &[Lane],
    t_max: impl Fn(usize) -> f32,
    stats: &mut [S],
) -> ([u32; 2], [[f32; MAX_PACKET]; 2]) {
    let node = &bvh.nodes[node as usize];
    let mut masks = [0u32; 2];
    let mut entries = [[f32::INFINITY; MAX_PACKET]; 2];
    for k in lanes(active) {
        let lane = &lanes_of[k];
        stats[k].box_tests(2);
        let (hit, enter) = if lane.finite {
            slab::hit_children::<false>(node, &lane.slab, t_max(k))
        } else {
            slab::hit_children::<true>(node, &lane.slab, t_max(k))
        };
        for (c, e) in [(0, enter.x), (1, enter.y)] {
            if hit & (1 << c) != 0 {
                masks[c] |= 1 << k;
                entries[c][k] = e;
            }
        }
    }
    (masks, entries)
}

/// The child to visit first: the only one hit, or the one most of the rays that hit both
/// enter first (ties to child `a`).
fn nearer(masks: [u32; 2], entries: &[[f32; MAX_PACKET]; 2]) -> usize {
    if masks[0] == 0 || masks[1] == 0 {
        return usize::from(masks[0] == 0);
    }
    let both = masks[0] & masks[1];
    let b_first = lanes(both)
        .filter(|&k| entries[1][k] < entries[0][k])
        .count();
    usize::from(2 * b_first > both.count_ones() as usize)
}

/// Slab constants and an empty best hit per ray (lanes past `rays.len()` copy ray 0 and stay
/// inactive), and the mask of the rays that enter the root's box.
#[inline(always)]
fn start<S: Stats>(bvh: &Bvh, rays: &[Ray], stats: &mut [S]) -> ([Lane; MAX_PACKET], u32) {
    let lanes_of = std::array::from_fn(|k| {
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
        if bvh
            .root_bounds
            .ray_entry(ray, ray.t_min, ray.t_max)
            .is_some()
        {
            active |= 1 << k;
        }
    }
    (lanes_of, active)
}

/// Closest hits of a packet of at most [`MAX_PACKET`] rays (`out`, `stats` as long as `rays`).
pub fn closest_hits<G: Geometry, S: Stats>(
    bvh: &Bvh,
    geom: &G,
    rays: &[Ray],
    out: &mut [Option<Hit>],
    stats: &mut [S],
) {
    assert!(!rays.is_empty() && rays.len() <= MAX_PACKET);
    let (mut lane, mut active) = start(bvh, rays, stats);
    let mut stack = Stack::<(Child, u32, [f32; MAX_PACKET]), STACK>::new();
    let mut at = bvh.root;
    while active != 0 {
        for k in lanes(active) {
            stats[k].node_visit();
        }
        let mut next = None;
        if at.is_leaf() {
            let first = at.index as usize;
            for &prim in &bvh.prim_ids[first..first + at.count as usize] {
                for k in lanes(active) {
                    stats[k].prim_test();
                    if let Some(t) = geom.intersect(prim, &rays[k], lane[k].best.t()) {
                        lane[k].best.offer(t, prim);
                    }
                }
            }
        } else {
            let (masks, entries) =
                test_children(bvh, at.index, active, &lane, |k| lane[k].best.t(), stats);
            let children = bvh.nodes[at.index as usize].children;
            let near = nearer(masks, &entries);
            let far = 1 - near;
            if masks[far] != 0 {
                stack.push((children[far], masks[far], entries[far]));
            }
            if masks[near] != 0 {
                next = Some((children[near], masks[near]));
            }
        }
        // Pop until a child some ray can still get a better or tied hit in.
        while next.is_none() {
            let Some((child, mask, entry)) = stack.pop() else {
                break;
            };
            let mask = lanes(mask)
                .filter(|&k| entry[k] <= lane[k].best.t())
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
        *o = lane[k].best.get();
    }
}

/// Any-hit results of a packet of at most [`MAX_PACKET`] rays.
pub fn any_hits<G: Geometry, S: Stats>(
    bvh: &Bvh,
    geom: &G,
    rays: &[Ray],
    out: &mut [bool],
    stats: &mut [S],
) {
    assert!(!rays.is_empty() && rays.len() <= MAX_PACKET);
    let (lane, mut active) = start(bvh, rays, stats);
    out.fill(false);
    let mut done = 0u32;
    let mut stack = Stack::<(Child, u32), STACK>::new();
    let mut at = bvh.root;
    loop {
        active &= !done;
        if active != 0 {
            for k in lanes(active) {
                stats[k].node_visit();
            }
            if at.is_leaf() {
                let first = at.index as usize;
                for &prim in &bvh.prim_ids[first..first + at.count as usize] {
                    for k in lanes(active & !done) {
                        stats[k].prim_test();
                        if geom.intersect(prim, &rays[k], rays[k].t_max).is_some() {
                            out[k] = true;
                            done |= 1 << k;
                        }
                    }
                }
            } else {
                let (masks, _) =
                    test_children(bvh, at.index, active, &lane, |k| rays[k].t_max, stats);
                let children = bvh.nodes[at.index as usize].children;
                if masks[1] != 0 {
                    stack.push((children[1], masks[1]));
                }
                if masks[0] != 0 {
                    at = children[0];
                    active = masks[0];
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
