//! What the shared traversal loops see of a box tree: its top ([`Top`]: the box of the whole
//! tree, the root, the leaves), its nodes ([`Tree`]) and the node step a layout supplies
//! ([`BoxTree`]).

use super::leaves::Leaves;
use super::node::Child;
use super::slab::SlabRay;
use crate::geometry::Aabb;
use crate::index::Stats;
use crate::index::kit::stack::Stack;

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
    /// Any-hit step: pushes the hit children but one with their entries, in no particular
    /// order, and returns that one.
    fn any<const SAFE: bool, S: Stats>(&self, s: Step<S, Entry, N>) -> Option<Child>;
}
