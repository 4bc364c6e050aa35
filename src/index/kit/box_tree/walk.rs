//! The traversal loop shared by the binary and the wide BVH, written once for both query kinds
//! ([`HitQuery`]): a tree layout supplies its node step ([`BoxTree`]); the loop owns the stack,
//! the leaves and the culling.
//!
//! Closest hit ([`Closest`]): the node step tests the node's children's boxes against
//! `[t_min, best t]`, pushes the hit children except the nearest with their entry distances
//! (farthest first) and returns the nearest to visit next; a popped child whose entry is
//! strictly greater than the best `t` so far is skipped. This is exact (see
//! [`crate::geometry::Hit`]): kernels return a `t` no smaller than the entry of any box
//! containing the primitive, and the box tests are the conservative, monotone
//! [`Aabb::ray_interval`](crate::geometry::Aabb::ray_interval) (see [`super::slab`]), so a
//! skipped box can hold no hit that beats or ties the best one. Any hit ([`crate::index::AnyHit`]): the node
//! step tests against `[t_min, ray.t_max]` and pushes the hit children in no particular order
//! (every entry is within `t_max`, so none is skipped), and the first hit ends the walk. Leaves
//! test their primitives through [`Geometry::intersect`] or its lane-wise block form (see
//! [`super::leaves`]).
//!
//! Each query picks the slab variant once per ray ([`Ray::fast_slabs`]) and runs a loop
//! monomorphized on it.
//!
//! A walk pauses between iterations ([`Walk`]), so a chunk of rays can also be walked
//! several at a time ([`super::stream`]).

use super::node::Child;
use super::slab::SlabRay;
use super::tree::{BoxTree, Entry, Rooted, Step};
use crate::geometry::Ray;
use crate::index::kit::stack::Stack;
use crate::index::{Closest, HitQuery, Stats};
use crate::scene::Geometry;

/// Whether the ray meets the box of the whole tree in `[ray.t_min, ray.t_max]` (one box test).
#[inline(always)]
pub(super) fn enters_root<T: Rooted, S: Stats>(tree: &T, ray: &Ray, stats: &mut S) -> bool {
    stats.box_tests(1);
    let entry = tree.top().root_bounds.ray_entry(ray, ray.t_min, ray.t_max);
    entry.is_some()
}

/// The answer to query `Q` in `[ray.t_min, ray.t_max]` (see the module doc).
#[inline(always)]
pub fn query<Q: HitQuery, const N: usize, T: BoxTree<N>, G: Geometry, S: Stats>(
    tree: &T,
    geom: &G,
    ray: &Ray,
    stats: &mut S,
) -> Q::Answer {
    if !enters_root(tree, ray, stats) {
        return Q::answer(Q::start(ray));
    }
    let root = tree.top().root;
    Q::answer(finish::<Q, N, T, G, S>(
        tree,
        geom,
        ray,
        root,
        Q::start(ray),
        stats,
    ))
}

/// The walk of query `Q` through the subtree `at`, going on from what was `found` before (the
/// root and nothing, for [`query`]; a packet hands its rays over to it mid-tree): what it finds.
#[inline(always)]
pub(super) fn finish<Q: HitQuery, const N: usize, T: BoxTree<N>, G: Geometry, S: Stats>(
    tree: &T,
    geom: &G,
    ray: &Ray,
    at: Child,
    found: Q::Found,
    stats: &mut S,
) -> Q::Found {
    let mut stack = Stack::new();
    let mut walk = Walk::<Q, N>::new(at, ray, &mut stack);
    walk.found = found;
    if ray.fast_slabs() {
        while walk.step::<false, T, G, S>(tree, geom, stats) {}
    } else {
        while walk.step::<true, T, G, S>(tree, geom, stats) {}
    }
    walk.found
}

/// The closest hit in `[ray.t_min, ray.t_max]`: [`query`] for [`Closest`].
#[inline(always)]
pub fn closest_hit<const N: usize, T: BoxTree<N>, G: Geometry, S: Stats>(
    tree: &T,
    geom: &G,
    ray: &Ray,
    stats: &mut S,
) -> Option<crate::geometry::Hit> {
    query::<Closest, N, T, G, S>(tree, geom, ray, stats)
}

/// One ray's walk for query `Q` between two iterations of the loop: what [`query`] keeps.
/// The stack is borrowed, not held: it is a few kilobytes, and a walk moved into place (an
/// array of walks, a walk returned by `new`) would copy all of it.
pub(super) struct Walk<'r, 's, Q: HitQuery, const N: usize> {
    ray: &'r Ray,
    slab_ray: SlabRay,
    found: Q::Found,
    stack: &'s mut Stack<Entry, N>,
    /// The subtree visited next.
    at: Child,
}

/// A closest-hit walk (the one the stream techniques interleave).
pub(super) type ClosestWalk<'r, 's, const N: usize> = Walk<'r, 's, Closest, N>;

impl<'r, 's, Q: HitQuery, const N: usize> Walk<'r, 's, Q, N> {
    /// A walk of `ray` from `root` on `stack` (emptied).
    #[inline(always)]
    pub(super) fn new(root: Child, ray: &'r Ray, stack: &'s mut Stack<Entry, N>) -> Self {
        stack.clear();
        Walk {
            ray,
            slab_ray: SlabRay::new(ray),
            found: Q::start(ray),
            stack,
            at: root,
        }
    }

    /// Starts over with `ray` on the same stack.
    #[inline(always)]
    pub(super) fn restart(&mut self, root: Child, ray: &'r Ray) {
        self.ray = ray;
        self.slab_ray = SlabRay::new(ray);
        self.found = Q::start(ray);
        self.stack.clear();
        self.at = root;
    }

    /// The answer from what the walk found so far (the query's answer once the walk is over).
    #[inline(always)]
    pub(super) fn answer(&self) -> Q::Answer {
        Q::answer(self.found)
    }

    /// Visits `at` (a node step, or a leaf's tests) and moves to the next subtree that can
    /// still hold the answer; `false` when there is none (the walk is over).
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
            if leaves.query::<Q, G, S>(self.at, geom, self.ray, &mut self.found, stats) {
                return false;
            }
        } else {
            let step = Step {
                node: self.at.index,
                ray: &self.slab_ray,
                t_max: Q::reach(&self.found, self.ray),
                stats: &mut *stats,
                stack: &mut *self.stack,
            };
            let next = match Q::CLOSEST {
                true => tree.closest::<SAFE, S>(step),
                false => tree.any::<SAFE, S>(step),
            };
            if let Some(next) = next {
                self.at = next;
                return true;
            }
        }
        // Pop the next child that can still hold the answer (entry <= reach; for an any-hit
        // query every pushed entry is).
        let reach = Q::reach(&self.found, self.ray);
        loop {
            let Some((next, entry)) = self.stack.pop() else {
                return false;
            };
            if entry <= reach {
                self.at = next;
                return true;
            }
        }
    }
}
