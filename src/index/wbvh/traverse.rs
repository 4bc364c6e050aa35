//! The wide tree's node step for the shared traversal loop ([`crate::index::kit::box_tree::walk`]).
//!
//! All children's boxes are tested in one SIMD slab pass
//! ([`crate::index::kit::box_tree::slab::hit_near_far`]: each axis's near and far planes read by the ray's
//! direction signs, with the entries and decisions of the scalar
//! [`crate::geometry::Aabb::ray_interval`], so conservative and monotone like it). Closest hit visits the nearest hit child and
//! pushes the others farthest first: one hit child is visited at once, two are ordered by one
//! comparison, three by a network of three compare-exchanges of integer keys (entry bits and
//! lane, so items move in one register), with no branch on the order, more by an insertion
//! sort of the keys (whose stores forward to its loads); any-hit pushes all but one.
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
use crate::index::kit::box_tree::node::Child;
use crate::index::kit::box_tree::tree::{self, BoxTree, Entry, Step};
use crate::index::kit::prefetch::{prefetch, prefetch_line};
use crate::index::kit::stack::Stack;

/// Stack capacity of the wide trees' traversal.
pub const STACK: usize = 7 * MAX_DEPTH as usize;

/// The tree as the queries see it.
pub type Tree<'a, const C: usize> = tree::Tree<'a, WideNode<C>>;

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
        // order-preserving bits above the lane, so no two are equal). Exactly three by a
        // network of three compare-exchanges, which has no branch to mispredict; more by an
        // insertion sort of at most 8.
        let key = |i: usize| u64::from(order_bits(enter[i])) << 32 | i as u64;
        let third = rest & (rest - 1);
        if third & (third - 1) == 0 {
            let (a, b) = (key(first), key(rest.trailing_zeros() as usize));
            let c = key(third.trailing_zeros() as usize);
            let (a, b) = (a.max(b), a.min(b));
            let (b, nearest) = (b.max(c), b.min(c));
            let (a, b) = (a.max(b), a.min(b));
            for k in [a, b] {
                let i = (k & 7) as usize;
                self.push(node.child(i), enter[i], s.stack);
            }
            return Some(node.child((nearest & 7) as usize));
        }
        let mut keys = [0u64; 8];
        let mut n = 0usize;
        let mut mask = mask;
        while mask != 0 {
            let i = mask.trailing_zeros() as usize;
            mask &= mask - 1;
            let key = key(i);
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
    fn any<const SAFE: bool, S: Stats>(&self, s: Step<S, Entry, STACK>) -> Option<Child> {
        let node = self.node(s.node);
        s.stats.box_tests(node.valid().count_ones());
        let (mut mask, enter) = node.hit::<SAFE>(s.ray, s.t_max);
        if mask == 0 {
            return None;
        }
        while mask & (mask - 1) != 0 {
            let i = mask.trailing_zeros() as usize;
            mask &= mask - 1;
            self.push(node.child(i), enter[i], s.stack);
        }
        let i = mask.trailing_zeros() as usize;
        Some(node.child(i))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::{Aabb, Ray};
    use crate::index::NoStats;
    use crate::index::kit::box_tree::leaves::Leaves;
    use crate::index::kit::box_tree::slab::SlabRay;
    use glam::{Vec3, Vec3A};

    /// One closest-hit step on a node whose children lie along the ray at `entries` (child `i`
    /// a box from `entries[i]` to `entries[i] + 0.5` on `x`): the child it returns, then the
    /// stack's entries as they pop.
    fn step(entries: &[f32]) -> (Child, Vec<Entry>) {
        let kids: Vec<(Aabb, Child)> = entries
            .iter()
            .enumerate()
            .map(|(i, &x)| {
                let b = Aabb::new(Vec3A::new(x, -1.0, -1.0), Vec3A::new(x + 0.5, 1.0, 1.0));
                (b, Child::inner(i as u32 + 1))
            })
            .collect();
        let nodes = [WideNode::<2>::new(&kids)];
        let root_bounds = kids.iter().fold(kids[0].0, |b, k| b.union(k.0));
        let tree = Tree {
            top: tree::Top {
                root_bounds: &root_bounds,
                root: Child::inner(0),
                leaves: Leaves::Ids(&[]),
            },
            nodes: &nodes,
        };
        let ray = Ray::new(Vec3::ZERO, Vec3::X, 0.0, f32::INFINITY).unwrap();
        let mut stack = Stack::<Entry, STACK>::new();
        let next = tree
            .closest::<true, NoStats>(Step {
                node: 0,
                ray: &SlabRay::new(&ray),
                t_max: f32::INFINITY,
                stats: &mut NoStats,
                stack: &mut stack,
            })
            .unwrap();
        (next, std::iter::from_fn(|| stack.pop()).collect())
    }

    /// Every number of hit children from 1 to 8, their distances in every rotation of the
    /// increasing order, its reversal, and with ties (for three children, every order): the
    /// step visits the nearest (the lowest lane among equal entries) and pushes the others so
    /// that they pop nearest first, each with its entry, none lost or repeated.
    #[test]
    fn hit_children_pop_front_to_back() {
        for n in 1..=8usize {
            let orders: Vec<Vec<f32>> = (0..n)
                .flat_map(|r| {
                    let up: Vec<f32> = (0..n).map(|i| ((i + r) % n) as f32 + 1.0).collect();
                    let down = up.iter().rev().copied().collect();
                    let ties = up.iter().map(|x| (x / 2.0).floor() + 1.0).collect();
                    [up, down, ties]
                })
                .collect();
            for entries in orders {
                let (next, popped) = step(&entries);
                let mut want: Vec<(u32, f32)> =
                    (0..n).map(|i| (i as u32 + 1, entries[i])).collect();
                want.sort_by(|a, b| a.1.total_cmp(&b.1).then(a.0.cmp(&b.0)));
                let got: Vec<(u32, f32)> = std::iter::once((next.index, want[0].1))
                    .chain(popped.iter().map(|(c, e)| (c.index, *e)))
                    .collect();
                assert_eq!(got, want, "entries {entries:?}");
            }
        }
    }
}
