//! The wide tree's node step for the shared traversal loop ([`crate::index::bvh::walk`]).
//!
//! Every chunk of four children's boxes is tested in one SIMD slab pass ([`hit_boxes4`], the
//! binary BVH's arithmetic, so conservative and monotone exactly like the scalar
//! [`crate::geometry::Aabb::ray_interval`]). Closest hit sorts the hit children by entry
//! distance, pushes all but the nearest farthest first and visits the nearest; any-hit pushes
//! all but one.
//!
//! Node and leaf loads dominate the time (they miss the caches on incoherent rays), so a step
//! asks for the node's reference line along with its box lines (the references are read only
//! after the box test), and for the memory of every hit child it pushes, to be in cache when
//! the child is popped.
//!
//! The stack holds at most [`STACK`] entries: at most 7 siblings (8 children, one visited) per
//! level, and levels are bounded by the binary tree's [`MAX_DEPTH`].

use super::node::WideNode;
use crate::index::Stats;
use crate::index::bvh::MAX_DEPTH;
use crate::index::bvh::node::Child;
use crate::index::bvh::slab::SlabRay;
use crate::index::bvh::walk::{BoxTree, Top, prefetch};
use crate::index::stack::Stack;

/// Stack capacity of the wide trees' traversal.
pub const STACK: usize = 7 * MAX_DEPTH as usize;

/// The tree as the queries see it.
#[derive(Clone, Copy)]
pub struct Tree<'a, const C: usize> {
    pub top: Top<'a>,
    pub nodes: &'a [WideNode<C>],
}

impl<const C: usize> Tree<'_, C> {
    /// Node `index`, its reference line prefetched.
    #[inline(always)]
    fn node(&self, index: u32) -> &WideNode<C> {
        let node = &self.nodes[index as usize];
        prefetch(&node.children);
        node
    }

    /// Prefetches what visiting `child` reads first: its node, or its leaf's first block.
    #[inline(always)]
    fn prefetch(&self, child: Child) {
        if child.is_leaf() {
            self.top.leaves.prefetch(child);
        } else {
            prefetch(self.nodes.as_ptr().wrapping_add(child.index as usize));
        }
    }
}

impl<const C: usize> BoxTree<STACK> for Tree<'_, C> {
    #[inline(always)]
    fn top(&self) -> Top<'_> {
        self.top
    }

    #[inline(always)]
    fn closest_step<const SAFE: bool, S: Stats>(
        &self,
        node: u32,
        ray: &SlabRay,
        t_max: f32,
        stats: &mut S,
        stack: &mut Stack<(Child, f32), STACK>,
    ) -> Option<Child> {
        let node = self.node(node);
        stats.box_tests(node.valid().count_ones());
        let (mut mask, enter) = node.hit::<SAFE>(ray, t_max);
        if mask == 0 {
            return None;
        }
        // Hit children sorted by entry, farthest first (insertion sort, at most 8).
        let mut hit = [(Child::default(), 0.0f32); 8];
        let mut n = 0usize;
        while mask != 0 {
            let i = mask.trailing_zeros() as usize;
            mask &= mask - 1;
            let item = (node.child(i), enter[i]);
            let mut j = n;
            while j > 0 && hit[j - 1].1 < item.1 {
                hit[j] = hit[j - 1];
                j -= 1;
            }
            hit[j] = item;
            n += 1;
        }
        for &item in &hit[..n - 1] {
            self.prefetch(item.0);
            stack.push(item);
        }
        Some(hit[n - 1].0)
    }

    #[inline(always)]
    fn any_step<const SAFE: bool, S: Stats>(
        &self,
        node: u32,
        ray: &SlabRay,
        t_max: f32,
        stats: &mut S,
        stack: &mut Stack<Child, STACK>,
    ) -> Option<Child> {
        let node = self.node(node);
        stats.box_tests(node.valid().count_ones());
        let (mut mask, _) = node.hit::<SAFE>(ray, t_max);
        if mask == 0 {
            return None;
        }
        while mask & (mask - 1) != 0 {
            let i = mask.trailing_zeros() as usize;
            mask &= mask - 1;
            self.prefetch(node.child(i));
            stack.push(node.child(i));
        }
        let i = mask.trailing_zeros() as usize;
        Some(node.child(i))
    }
}
