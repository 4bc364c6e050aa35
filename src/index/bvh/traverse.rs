//! The binary tree's node step for the shared traversal loop
//! ([`crate::index::kit::box_tree::walk`]): both
//! children's boxes in one SIMD pass ([`slab::hit_children`]); the nearer hit child is visited
//! next and the farther pushed with its entry.
//!
//! The stack holds at most [`MAX_DEPTH`] entries: a node at level `L` has at most `L - 1`
//! pushed ancestors' siblings on the stack, and the build never makes a level deeper than
//! [`MAX_DEPTH`].

use super::build::MAX_DEPTH;
use crate::index::Stats;
use crate::index::kit::box_tree::node::{Child, Node};
use crate::index::kit::box_tree::slab;
use crate::index::kit::box_tree::tree::{self, BoxTree, Entry, Step};

/// Stack capacity of the binary tree's traversal.
pub const STACK: usize = MAX_DEPTH as usize;

/// The tree as the queries see it: the root's box and reference, the inner nodes, and the
/// primitive ids in leaf order.
pub type Tree<'a> = tree::Tree<'a, Node>;

impl BoxTree<STACK> for Tree<'_> {
    #[inline(always)]
    fn closest<const SAFE: bool, S: Stats>(&self, s: Step<S, Entry, STACK>) -> Option<Child> {
        self.step::<SAFE, true, S>(s)
    }

    #[inline(always)]
    fn any<const SAFE: bool, S: Stats>(&self, s: Step<S, Entry, STACK>) -> Option<Child> {
        self.step::<SAFE, false, S>(s)
    }
}

impl Tree<'_> {
    /// Both children's boxes in one pass; when both are hit, the nearer is visited next with
    /// `NEAR_FIRST` (closest hit) and the first otherwise (any hit), the other pushed with its
    /// entry.
    #[inline(always)]
    fn step<const SAFE: bool, const NEAR_FIRST: bool, S: Stats>(
        &self,
        s: Step<S, Entry, STACK>,
    ) -> Option<Child> {
        let node = &self.nodes[s.node as usize];
        let [a, b] = node.children;
        s.stats.box_tests(2);
        let (hit, enter) = slab::hit_children::<SAFE>(node, s.ray, s.t_max);
        match hit {
            0b11 => {
                let (ea, eb) = (enter.x, enter.y);
                let (near, far, far_entry) = match NEAR_FIRST && eb < ea {
                    true => (b, a, ea),
                    false => (a, b, eb),
                };
                s.stack.push((far, far_entry));
                Some(near)
            }
            0b01 => Some(a),
            0b10 => Some(b),
            _ => None,
        }
    }
}
