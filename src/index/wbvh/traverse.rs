//! The wide tree's node step for the shared traversal loop ([`crate::index::bvh::walk`]).
//!
//! All children's boxes are tested in one SIMD slab pass
//! ([`crate::index::bvh::slab::hit_near_far`]: each axis's near and far planes read by the ray's
//! direction signs, with the entries and decisions of the scalar
//! [`crate::geometry::Aabb::ray_interval`], so conservative and monotone like it). Closest hit visits the nearest hit child and
//! pushes the others farthest first: one hit child is visited at once, two are ordered by one
//! comparison, more by an insertion sort of integer keys (entry bits and lane, so items move in
//! one register and the sort's stores forward to its loads); any-hit pushes all but one.
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
use crate::index::bvh::walk::{self, BoxTree, Entry, Step};
use crate::index::prefetch::{prefetch, prefetch_line};
use crate::index::stack::Stack;

/// Stack capacity of the wide trees' traversal.
pub const STACK: usize = 7 * MAX_DEPTH as usize;

/// The tree as the queries see it.
pub type Tree<'a, const C: usize> = walk::Tree<'a, WideNode<C>>;

impl<const C: usize> Tree<'_, C> {
    /// Node `index`, its reference line (its first) prefetched.
    #[inline(always)]
    fn node(&self, index: u32) -> &WideNode<C> {
        let node = &self.nodes[index as usize];
        prefetch_line(std::ptr::from_ref(node).cast());
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

impl<const C: usize> Tree<'_, C> {
    /// Pushes a hit child with its entry, its memory asked for.
    #[inline(always)]
    fn push(&self, child: Child, entry: f32, stack: &mut Stack<Entry, STACK>) {
        self.prefetch(child);
        stack.push((child, entry));
    }
}

/// The bits of a non-NaN `f32` as an integer of the same order (`-0.0` just below `+0.0`).
#[inline(always)]
fn order_bits(x: f32) -> u32 {
    let b = x.to_bits();
    if b >> 31 == 1 { !b } else { b | 1 << 31 }
}

impl<const C: usize> BoxTree<STACK> for Tree<'_, C> {
    #[inline(always)]
    fn closest<const SAFE: bool, S: Stats>(&self, s: Step<S, Entry, STACK>) -> Option<Child> {
        let node = self.node(s.node);
        s.stats.box_tests(node.valid().count_ones());
        let (mask, enter) = node.hit::<SAFE>(s.ray, s.t_max);
        if mask == 0 {
            return None;
        }
        let first = mask.trailing_zeros() as usize;
        let rest = mask & (mask - 1);
        if rest == 0 {
            return Some(node.child(first));
        }
        if rest & (rest - 1) == 0 {
            let second = rest.trailing_zeros() as usize;
            let (near, far) = match enter[second] < enter[first] {
                true => (second, first),
                false => (first, second),
            };
            self.push(node.child(far), enter[far], s.stack);
            return Some(node.child(near));
        }
        // Three or more: lanes sorted by entry, farthest first, as integer keys (the entry's
        // order-preserving bits above the lane), an insertion sort of at most 8.
        let mut keys = [0u64; 8];
        let mut n = 0usize;
        let mut mask = mask;
        while mask != 0 {
            let i = mask.trailing_zeros() as usize;
            mask &= mask - 1;
            let key = u64::from(order_bits(enter[i])) << 32 | i as u64;
            let mut j = n;
            while j > 0 && keys[j - 1] < key {
                keys[j] = keys[j - 1];
                j -= 1;
            }
            keys[j] = key;
            n += 1;
        }
        for &key in &keys[..n - 1] {
            let i = (key & 7) as usize;
            self.push(node.child(i), enter[i], s.stack);
        }
        Some(node.child((keys[n - 1] & 7) as usize))
    }

    #[inline(always)]
    fn any<const SAFE: bool, S: Stats>(&self, s: Step<S, Child, STACK>) -> Option<Child> {
        let node = self.node(s.node);
        s.stats.box_tests(node.valid().count_ones());
        let (mut mask, _) = node.hit::<SAFE>(s.ray, s.t_max);
        if mask == 0 {
            return None;
        }
        while mask & (mask - 1) != 0 {
            let i = mask.trailing_zeros() as usize;
            mask &= mask - 1;
            self.prefetch(node.child(i));
            s.stack.push(node.child(i));
        }
        let i = mask.trailing_zeros() as usize;
        Some(node.child(i))
    }
}
