//! Closest-hit and any-hit traversal of the flattened tree.
//!
//! Closest hit, front to back with early termination: at an inner node both children's boxes
//! are tested against `[t_min, best t]`; the nearer is visited next and the farther pushed with
//! its entry distance; a popped node whose entry is strictly greater than the best `t` so far is
//! skipped. This is exact (see [`crate::geometry::Hit`]): kernels return a `t` no smaller than
//! the entry of any box containing the primitive, and [`Aabb::ray_interval`] is conservative
//! and monotone, so a skipped box can hold no hit that beats or ties the best one.
//!
//! The stack is a fixed array of [`MAX_DEPTH`] entries: a node at level `L` has at most `L - 1`
//! pushed ancestors' siblings on the stack, and the build never makes a level deeper than
//! [`MAX_DEPTH`].

use super::build::MAX_DEPTH;
use super::node::Node;
use crate::geometry::{Aabb, ClosestHit, Hit, Ray};
use crate::index::Stats;
use crate::scene::Geometry;

const STACK: usize = MAX_DEPTH as usize;

#[inline(always)]
fn entry(node: &Node, ray: &Ray, t_max: f32) -> Option<f32> {
    Aabb::ray_entry(&node.bounds(), ray, ray.t_min, t_max)
}

/// The closest hit in `[ray.t_min, ray.t_max]` (see the module doc).
#[inline]
pub fn closest_hit<G: Geometry, S: Stats>(
    nodes: &[Node],
    prim_ids: &[u32],
    geom: &G,
    ray: &Ray,
    stats: &mut S,
) -> Option<Hit> {
    let mut best = ClosestHit::new(ray.t_max);
    stats.box_tests(1);
    entry(&nodes[0], ray, best.t())?;
    let mut stack = [(0u32, 0.0f32); STACK];
    let mut sp = 0usize;
    let mut at = 0usize;
    loop {
        stats.node_visit();
        let node = &nodes[at];
        if node.is_leaf() {
            let first = node.offset() as usize;
            for &prim in &prim_ids[first..first + node.count() as usize] {
                stats.prim_test();
                if let Some(t) = geom.intersect(prim, ray, best.t()) {
                    best.offer(t, prim);
                }
            }
        } else {
            let (a, b) = (at + 1, node.offset() as usize);
            stats.box_tests(2);
            match (
                entry(&nodes[a], ray, best.t()),
                entry(&nodes[b], ray, best.t()),
            ) {
                (Some(ea), Some(eb)) => {
                    let (near, far, far_entry) = if eb < ea { (b, a, ea) } else { (a, b, eb) };
                    stack[sp] = (far as u32, far_entry);
                    sp += 1;
                    at = near;
                    continue;
                }
                (Some(_), None) => {
                    at = a;
                    continue;
                }
                (None, Some(_)) => {
                    at = b;
                    continue;
                }
                (None, None) => {}
            }
        }
        // Pop the next node that can still hold the closest hit (entry <= best t).
        loop {
            if sp == 0 {
                return best.get();
            }
            sp -= 1;
            let (next, entry) = stack[sp];
            if entry <= best.t() {
                at = next as usize;
                break;
            }
        }
    }
}

/// Whether any primitive is hit in `[ray.t_min, ray.t_max]`; stops at the first, no ordering.
#[inline]
pub fn any_hit<G: Geometry, S: Stats>(
    nodes: &[Node],
    prim_ids: &[u32],
    geom: &G,
    ray: &Ray,
    stats: &mut S,
) -> bool {
    stats.box_tests(1);
    if entry(&nodes[0], ray, ray.t_max).is_none() {
        return false;
    }
    let mut stack = [0u32; STACK];
    let mut sp = 0usize;
    let mut at = 0usize;
    loop {
        stats.node_visit();
        let node = &nodes[at];
        if node.is_leaf() {
            let first = node.offset() as usize;
            for &prim in &prim_ids[first..first + node.count() as usize] {
                stats.prim_test();
                if geom.intersect(prim, ray, ray.t_max).is_some() {
                    return true;
                }
            }
        } else {
            let (a, b) = (at + 1, node.offset() as usize);
            stats.box_tests(2);
            let hit_a = entry(&nodes[a], ray, ray.t_max).is_some();
            let hit_b = entry(&nodes[b], ray, ray.t_max).is_some();
            match (hit_a, hit_b) {
                (true, true) => {
                    stack[sp] = b as u32;
                    sp += 1;
                    at = a;
                    continue;
                }
                (true, false) => {
                    at = a;
                    continue;
                }
                (false, true) => {
                    at = b;
                    continue;
                }
                (false, false) => {}
            }
        }
        if sp == 0 {
            return false;
        }
        sp -= 1;
        at = stack[sp] as usize;
    }
}
