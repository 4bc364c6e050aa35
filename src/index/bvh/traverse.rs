//! Closest-hit and any-hit traversal of the flattened tree.
//!
//! Closest hit, front to back with early termination: at an inner node both children's boxes
//! are tested in one pass ([`slab::hit_children`]) against `[t_min, best t]`; the nearer is
//! visited next and the farther pushed with its entry distance; a popped child whose entry is
//! strictly greater than the best `t` so far is skipped. This is exact (see
//! [`crate::geometry::Hit`]): kernels return a `t` no smaller than the entry of any box
//! containing the primitive, and the slab test is the conservative, monotone
//! [`Aabb::ray_interval`] (see [`slab`]), so a skipped box can hold no hit that beats or ties the
//! best one.
//!
//! Each query picks the slab variant once per ray ([`SlabRay::finite`]) and runs a loop
//! monomorphized on it.
//!
//! The stack is a fixed array of [`MAX_DEPTH`] entries: a node at level `L` has at most `L - 1`
//! pushed ancestors' siblings on the stack, and the build never makes a level deeper than
//! [`MAX_DEPTH`].

use super::build::MAX_DEPTH;
use super::node::{Child, Node};
use super::slab::{self, SlabRay};
use crate::geometry::{Aabb, ClosestHit, Hit, Ray};
use crate::index::Stats;
use crate::index::stack::Stack;
use crate::scene::Geometry;

const STACK: usize = MAX_DEPTH as usize;

/// The tree as the queries see it: the root's box and reference, the inner nodes, and the
/// primitive ids in leaf order.
#[derive(Clone, Copy)]
pub struct Tree<'a> {
    pub root_bounds: &'a Aabb,
    pub root: Child,
    pub nodes: &'a [Node],
    pub prim_ids: &'a [u32],
}

impl Tree<'_> {
    /// The primitive ids of leaf `leaf`.
    #[inline(always)]
    fn prims(&self, leaf: Child) -> &[u32] {
        let first = leaf.index as usize;
        &self.prim_ids[first..first + leaf.count as usize]
    }
}

/// The closest hit in `[ray.t_min, ray.t_max]` (see the module doc).
#[inline]
pub fn closest_hit<G: Geometry, S: Stats>(
    tree: Tree,
    geom: &G,
    ray: &Ray,
    stats: &mut S,
) -> Option<Hit> {
    stats.box_tests(1);
    tree.root_bounds.ray_entry(ray, ray.t_min, ray.t_max)?;
    if SlabRay::finite(ray) {
        closest::<false, G, S>(tree, geom, ray, stats)
    } else {
        closest::<true, G, S>(tree, geom, ray, stats)
    }
}

#[inline(always)]
fn closest<const SAFE: bool, G: Geometry, S: Stats>(
    tree: Tree,
    geom: &G,
    ray: &Ray,
    stats: &mut S,
) -> Option<Hit> {
    let slab_ray = SlabRay::new(ray);
    let mut best = ClosestHit::new(ray.t_max);
    let mut stack = Stack::<(Child, f32), STACK>::new();
    let mut at = tree.root;
    loop {
        stats.node_visit();
        if at.is_leaf() {
            for &prim in tree.prims(at) {
                stats.prim_test();
                if let Some(t) = geom.intersect(prim, ray, best.t()) {
                    best.offer(t, prim);
                }
            }
        } else {
            let node = &tree.nodes[at.index as usize];
            let [a, b] = node.children;
            stats.box_tests(2);
            let (hit, enter) = slab::hit_children::<SAFE>(node, &slab_ray, best.t());
            match hit {
                0b11 => {
                    let (ea, eb) = (enter.x, enter.y);
                    let (near, far, far_entry) = if eb < ea { (b, a, ea) } else { (a, b, eb) };
                    stack.push((far, far_entry));
                    at = near;
                    continue;
                }
                0b01 => {
                    at = a;
                    continue;
                }
                0b10 => {
                    at = b;
                    continue;
                }
                _ => {}
            }
        }
        // Pop the next child that can still hold the closest hit (entry <= best t).
        loop {
            let Some((next, entry)) = stack.pop() else {
                return best.get();
            };
            if entry <= best.t() {
                at = next;
                break;
            }
        }
    }
}

/// Whether any primitive is hit in `[ray.t_min, ray.t_max]`; stops at the first, no ordering.
#[inline]
pub fn any_hit<G: Geometry, S: Stats>(tree: Tree, geom: &G, ray: &Ray, stats: &mut S) -> bool {
    stats.box_tests(1);
    if tree
        .root_bounds
        .ray_entry(ray, ray.t_min, ray.t_max)
        .is_none()
    {
        return false;
    }
    if SlabRay::finite(ray) {
        any::<false, G, S>(tree, geom, ray, stats)
    } else {
        any::<true, G, S>(tree, geom, ray, stats)
    }
}

#[inline(always)]
fn any<const SAFE: bool, G: Geometry, S: Stats>(
    tree: Tree,
    geom: &G,
    ray: &Ray,
    stats: &mut S,
) -> bool {
    let slab_ray = SlabRay::new(ray);
    let mut stack = Stack::<Child, STACK>::new();
    let mut at = tree.root;
    loop {
        stats.node_visit();
        if at.is_leaf() {
            for &prim in tree.prims(at) {
                stats.prim_test();
                if geom.intersect(prim, ray, ray.t_max).is_some() {
                    return true;
                }
            }
        } else {
            let node = &tree.nodes[at.index as usize];
            let [a, b] = node.children;
            stats.box_tests(2);
            match slab::hit_children::<SAFE>(node, &slab_ray, ray.t_max).0 {
                0b11 => {
                    stack.push(b);
                    at = a;
                    continue;
                }
                0b01 => {
                    at = a;
                    continue;
                }
                0b10 => {
                    at = b;
                    continue;
                }
                _ => {}
            }
        }
        let Some(next) = stack.pop() else {
            return false;
        };
        at = next;
    }
}
