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
//! Each query picks the slab variant once per ray ([`Ray::fast_slabs`]) and runs a loop
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

/// A tree as the queries see it: [`Top`] and the inner nodes (`N`: the layout's node type).
#[derive(Clone, Copy)]
pub struct Tree<'a, N> {
    pub top: Top<'a>,
    pub nodes: &'a [N],
}

/// What the loops read of every tree: its root, box and leaves.
pub trait Rooted {
    fn top(&self) -> Top<'_>;
}

impl<N> Rooted for Tree<'_, N> {
    #[inline(always)]
    fn top(&self) -> Top<'_> {
        self.top
    }
}

/// A closest-hit stack entry: a child and the ray's entry into its box.
pub type Entry = (Child, f32);

/// One node step's arguments: inner node `node`, the ray's slab constants, the end `t_max` of
/// the interval `[ray.t_min, t_max]` tested, the counters and the stack (items `T`, at most
/// `N`).
pub struct Step<'a, S, T: Copy, const N: usize> {
    pub node: u32,
    pub ray: &'a SlabRay,
    pub t_max: f32,
    pub stats: &'a mut S,
    pub stack: &'a mut Stack<T, N>,
}

/// A tree of boxes whose inner nodes the loop visits by index and whose leaves are
/// [`Leaves`]. `N` bounds the entries the node steps can leave on the stack.
pub trait BoxTree<const N: usize>: Rooted {
    /// Closest-hit step: pushes the hit children but the nearest with their entries, farthest
    /// first, and returns the nearest; `None` when no child is hit.
    fn closest<const SAFE: bool, S: Stats>(&self, s: Step<S, Entry, N>) -> Option<Child>;
    /// Any-hit step: pushes the hit children but one and returns that one.
    fn any<const SAFE: bool, S: Stats>(&self, s: Step<S, Child, N>) -> Option<Child>;
}

/// The four ray queries of [`crate::index::Index`] for a type whose `tree()` is a [`Tree`]
/// that is a [`BoxTree`] and a [`super::packet::PacketTree`]: this module's loops and the
/// packet walk's.
macro_rules! tree_queries {
    () => {
        $crate::index::query::ray_queries!(
            $crate::index::bvh::walk::closest_hit,
            $crate::index::bvh::walk::any_hit,
            |index| &index.tree()
        );

        fn closest_hits_packet<G: $crate::scene::Geometry, S: $crate::index::Stats>(
            &self,
            geom: &G,
            rays: &[$crate::geometry::Ray],
            out: &mut [Option<$crate::geometry::Hit>],
            stats: &mut [S],
        ) {
            $crate::index::bvh::packet::closest_hits(&self.tree(), geom, rays, out, stats)
        }

        fn any_hits_packet<G: $crate::scene::Geometry, S: $crate::index::Stats>(
            &self,
            geom: &G,
            rays: &[$crate::geometry::Ray],
            out: &mut [bool],
            stats: &mut [S],
        ) {
            $crate::index::bvh::packet::any_hits(&self.tree(), geom, rays, out, stats)
        }
    };
}
pub(crate) use tree_queries;

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
    if ray.fast_slabs() {
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
    let mut stack = Stack::<Entry, N>::new();
    let top = tree.top();
    let mut at = top.root;
    loop {
        stats.node_visit();
        if at.is_leaf() {
            top.leaves.closest(at, geom, ray, &mut best, stats);
        } else if let Some(next) = tree.closest::<SAFE, S>(Step {
            node: at.index,
            ray: &slab_ray,
            t_max: best.t(),
            stats: &mut *stats,
            stack: &mut stack,
        }) {
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
    if ray.fast_slabs() {
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
        } else if let Some(next) = tree.any::<SAFE, S>(Step {
            node: at.index,
            ray: &slab_ray,
            t_max: ray.t_max,
            stats: &mut *stats,
            stack: &mut stack,
        }) {
            at = next;
            continue;
        }
        let Some(next) = stack.pop() else {
            return false;
        };
        at = next;
    }
}
