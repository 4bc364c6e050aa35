//! The traversal loop shared by the binary and the wide BVH: closest hit front to back with
//! early termination, and any-hit. A tree layout supplies its node step ([`BoxTree`]); the loop
//! owns the stack, the leaves and the culling.
//!
//! Closest hit: the node step tests the node's children's boxes against `[t_min, best t]`,
//! pushes the hit children except the nearest with their entry distances (farthest first) and
//! returns the nearest to visit next; a popped child whose entry is strictly greater than the
//! best `t` so far is skipped. This is exact (see [`crate::geometry::Hit`]): kernels return a
//! `t` no smaller than the entry of any box containing the primitive, and the box tests are
//! the conservative, monotone [`Aabb::ray_interval`] (see [`super::slab`]), so a skipped box
//! can hold no hit that beats or ties the best one. Leaves test their primitives through
//! [`Geometry::intersect`] or its lane-wise block form (see [`super::leaves`]).
//!
//! Each query picks the slab variant once per ray ([`SlabRay::finite`]) and runs a loop
//! monomorphized on it.

use super::leaves::Leaves;
use super::node::Child;
use super::slab::SlabRay;
use crate::geometry::{Aabb, ClosestHit, Hit, Ray};
use crate::index::Stats;
use crate::index::stack::Stack;
use crate::scene::Geometry;

/// What every box tree has besides its inner nodes: the box of the whole tree, the root (an
/// inner node or a leaf) and the leaves' contents.
#[derive(Clone, Copy)]
pub struct Top<'a> {
    pub root_bounds: &'a Aabb,
    pub root: Child,
    pub leaves: Leaves<'a>,
}

/// A tree of boxes whose inner nodes the loop visits by index and whose leaves are
/// [`Leaves`]. `N` bounds the entries the node steps can leave on the stack.
pub trait BoxTree<const N: usize> {
    /// The root, its box and the leaves.
    fn top(&self) -> Top<'_>;
    /// Closest-hit step at inner node `node`: pushes the hit children but the nearest with their
    /// entries, farthest first, and returns the nearest; `None` when no child is hit.
    fn closest_step<const SAFE: bool, S: Stats>(
        &self,
        node: u32,
        ray: &SlabRay,
        t_max: f32,
        stats: &mut S,
        stack: &mut Stack<(Child, f32), N>,
    ) -> Option<Child>;
    /// Any-hit step: pushes the hit children but one and returns that one.
    fn any_step<const SAFE: bool, S: Stats>(
        &self,
        node: u32,
        ray: &SlabRay,
        t_max: f32,
        stats: &mut S,
        stack: &mut Stack<Child, N>,
    ) -> Option<Child>;
}

/// Asks the cache for every line of `*item` ahead of its use (x86_64; a no-op elsewhere). Reads
/// nothing and cannot fault, so any address is allowed.
#[inline(always)]
pub fn prefetch<T>(item: *const T) {
    #[cfg(target_arch = "x86_64")]
    {
        use std::arch::x86_64::{_MM_HINT_T0, _mm_prefetch};
        let first = item as usize & !63;
        let end = item as usize + size_of::<T>();
        for line in (first..end).step_by(64) {
            // SAFETY: prefetching is a hint; it does not access memory architecturally.
            unsafe { _mm_prefetch::<_MM_HINT_T0>(line as *const i8) };
        }
    }
    #[cfg(not(target_arch = "x86_64"))]
    let _ = item;
}

/// The closest hit in `[ray.t_min, ray.t_max]` (see the module doc).
#[inline(always)]
pub fn closest_hit<const N: usize, T: BoxTree<N>, G: Geometry, S: Stats>(
    tree: &T,
    geom: &G,
    ray: &Ray,
    stats: &mut S,
) -> Option<Hit> {
    stats.box_tests(1);
    tree.top()
        .root_bounds
        .ray_entry(ray, ray.t_min, ray.t_max)?;
    if SlabRay::finite(ray) {
        closest::<false, N, T, G, S>(tree, geom, ray, stats)
    } else {
        closest::<true, N, T, G, S>(tree, geom, ray, stats)
    }
}

#[inline(always)]
fn closest<const SAFE: bool, const N: usize, T: BoxTree<N>, G: Geometry, S: Stats>(
    tree: &T,
    geom: &G,
    ray: &Ray,
    stats: &mut S,
) -> Option<Hit> {
    let slab_ray = SlabRay::new(ray);
    let mut best = ClosestHit::new(ray.t_max);
    let mut stack = Stack::<(Child, f32), N>::new();
    let top = tree.top();
    let mut at = top.root;
    loop {
        stats.node_visit();
        if at.is_leaf() {
            top.leaves.closest(at, geom, ray, &mut best, stats);
        } else if let Some(next) =
            tree.closest_step::<SAFE, S>(at.index, &slab_ray, best.t(), stats, &mut stack)
        {
            at = next;
            continue;
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
#[inline(always)]
pub fn any_hit<const N: usize, T: BoxTree<N>, G: Geometry, S: Stats>(
    tree: &T,
    geom: &G,
    ray: &Ray,
    stats: &mut S,
) -> bool {
    stats.box_tests(1);
    if tree
        .top()
        .root_bounds
        .ray_entry(ray, ray.t_min, ray.t_max)
        .is_none()
    {
        return false;
    }
    if SlabRay::finite(ray) {
        any::<false, N, T, G, S>(tree, geom, ray, stats)
    } else {
        any::<true, N, T, G, S>(tree, geom, ray, stats)
    }
}

#[inline(always)]
fn any<const SAFE: bool, const N: usize, T: BoxTree<N>, G: Geometry, S: Stats>(
    tree: &T,
    geom: &G,
    ray: &Ray,
    stats: &mut S,
) -> bool {
    let slab_ray = SlabRay::new(ray);
    let mut stack = Stack::<Child, N>::new();
    let top = tree.top();
    let mut at = top.root;
    loop {
        stats.node_visit();
        if at.is_leaf() {
            if top.leaves.any(at, geom, ray, stats) {
                return true;
            }
        } else if let Some(next) =
            tree.any_step::<SAFE, S>(at.index, &slab_ray, ray.t_max, stats, &mut stack)
        {
            at = next;
            continue;
        }
        let Some(next) = stack.pop() else {
            return false;
        };
        at = next;
    }
}
