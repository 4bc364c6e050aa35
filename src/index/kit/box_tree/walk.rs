//! The traversal loop shared by the binary and the wide BVH: closest hit front to back with
//! early termination, and any-hit. A tree layout supplies its node step ([`BoxTree`]); the loop
//! owns the stack, the leaves and the culling.
//!
//! Closest hit: the node step tests the node's children's boxes against `[t_min, best t]`,
//! pushes the hit children except the nearest with their entry distances (farthest first) and
//! returns the nearest to visit next; a popped child whose entry is strictly greater than the
//! best `t` so far is skipped. This is exact (see [`crate::geometry::Hit`]): kernels return a
//! `t` no smaller than the entry of any box containing the primitive, and the box tests are
//! the conservative, monotone [`Aabb::ray_interval`](crate::geometry::Aabb::ray_interval) (see [`super::slab`]), so a skipped box
//! can hold no hit that beats or ties the best one. Leaves test their primitives through
//! [`Geometry::intersect`] or its lane-wise block form (see [`super::leaves`]).
//!
//! Each query picks the slab variant once per ray ([`Ray::fast_slabs`]) and runs a loop
//! monomorphized on it.
//!
//! A walk pauses between iterations ([`ClosestWalk`]), so a chunk of rays can also be walked
//! several at a time ([`super::stream`]).

use super::node::Child;
use super::slab::SlabRay;
use super::tree::{BoxTree, Entry, Rooted, Step};
use crate::geometry::{ClosestHit, Hit, Ray};
use crate::index::Stats;
use crate::index::kit::stack::Stack;
use crate::scene::Geometry;

/// The two ray queries of [`crate::index::Index`] for a type whose `tree()` is a [`Tree`] that
/// is a [`BoxTree`]: this module's loops.
macro_rules! tree_queries {
    () => {
        $crate::index::kit::ray_queries!(
            $crate::index::kit::box_tree::walk::closest_hit,
            $crate::index::kit::box_tree::walk::any_hit,
            |index| &index.tree()
        );
    };
}
pub(crate) use tree_queries;

/// Whether the ray meets the box of the whole tree in `[ray.t_min, ray.t_max]` (one box test).
#[inline(always)]
pub(super) fn enters_root<T: Rooted, S: Stats>(tree: &T, ray: &Ray, stats: &mut S) -> bool {
    stats.box_tests(1);
    let entry = tree.top().root_bounds.ray_entry(ray, ray.t_min, ray.t_max);
    entry.is_some()
}

/// The closest hit in `[ray.t_min, ray.t_max]` (see the module doc).
#[inline(always)]
pub fn closest_hit<const N: usize, T: BoxTree<N>, G: Geometry, S: Stats>(
    tree: &T,
    geom: &G,
    ray: &Ray,
    stats: &mut S,
) -> Option<Hit> {
    if !enters_root(tree, ray, stats) {
        return None;
    }
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
    let mut stack = Stack::new();
    let mut walk = ClosestWalk::<N>::new(tree.top().root, ray, &mut stack);
    while walk.step::<SAFE, T, G, S>(tree, geom, stats) {}
    walk.best.get()
}

/// One ray's closest-hit walk between two iterations of the loop: what [`closest_hit`] keeps.
/// The stack is borrowed, not held: it is a few kilobytes, and a walk moved into place (an
/// array of walks, a walk returned by `new`) would copy all of it.
pub(super) struct ClosestWalk<'r, 's, const N: usize> {
    ray: &'r Ray,
    slab_ray: SlabRay,
    pub(super) best: ClosestHit,
    stack: &'s mut Stack<Entry, N>,
    /// The subtree visited next.
    at: Child,
}

impl<'r, 's, const N: usize> ClosestWalk<'r, 's, N> {
    /// A walk of `ray` from `root` on `stack` (emptied).
    #[inline(always)]
    pub(super) fn new(root: Child, ray: &'r Ray, stack: &'s mut Stack<Entry, N>) -> Self {
        stack.clear();
        ClosestWalk {
            ray,
            slab_ray: SlabRay::new(ray),
            best: ClosestHit::new(ray.t_max),
            stack,
            at: root,
        }
    }

    /// Starts over with `ray` on the same stack.
    #[inline(always)]
    pub(super) fn restart(&mut self, root: Child, ray: &'r Ray) {
        self.ray = ray;
        self.slab_ray = SlabRay::new(ray);
        self.best = ClosestHit::new(ray.t_max);
        self.stack.clear();
        self.at = root;
    }

    /// Visits `at` (a node step, or a leaf's tests) and moves to the next subtree that can
    /// still hold the closest hit; `false` when there is none (the walk is over).
    #[inline(always)]
    pub(super) fn step<const SAFE: bool, T: BoxTree<N>, G: Geometry, S: Stats>(
        &mut self,
        tree: &T,
        geom: &G,
        stats: &mut S,
    ) -> bool {
        stats.node_visit();
        if self.at.is_leaf() {
            let leaves = tree.top().leaves;
            leaves.closest(self.at, geom, self.ray, &mut self.best, stats);
        } else if let Some(next) = tree.closest::<SAFE, S>(Step {
            node: self.at.index,
            ray: &self.slab_ray,
            t_max: self.best.t(),
            stats: &mut *stats,
            stack: &mut *self.stack,
        }) {
            self.at = next;
            return true;
        }
        // Pop the next child that can still hold the closest hit (entry <= best t).
        loop {
            let Some((next, entry)) = self.stack.pop() else {
                return false;
            };
            if entry <= self.best.t() {
                self.at = next;
                return true;
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
    if !enters_root(tree, ray, stats) {
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
