//! Cache-aware orders of a box tree's inner nodes (the `layout` parameter of `bvh`, `bvh4` and
//! `bvh8`): a permutation of the node array applied after the build, every inner child
//! reference rewritten. The tree's topology, each node's boxes and the order of its children
//! stay, so every walk takes the same decisions, visits the same nodes and returns the same
//! hits; only where the nodes sit in memory changes.
//!
//! - [`Layout::Dfs`] (default): the builder's order, depth first (`bvh`: a node, its first
//!   child's subtree, then its second's; `bvh4`/`bvh8`: a node's inner children next to each
//!   other, then each one's subtree in turn).
//! - [`Layout::Veb`]: the van Emde Boas (cache-oblivious) order by height: a subtree of height
//!   `h` is stored as its top `h / 2` levels, laid out recursively, followed by each subtree
//!   hanging below them (in child order), each laid out recursively. Any block of nodes the
//!   memory system moves at once (a cache line pair, a page) then holds a connected piece of
//!   about that many levels, whatever its size (Prokop 1999; van Emde Boas 1977). Plain, by
//!   height: not weighted by access probability as Yoon and Manocha's COLBVH (2006) is.
//! - [`Layout::Treelet`]: treelets of one 4 KiB page's worth of nodes (64 binary nodes, 32 of
//!   `bvh4`, 16 of `bvh8`), each grown greedily from its root by taking the node of largest
//!   surface area (a ray's probability of reaching it) among those next to the treelet, as Aila
//!   and Karras (2010) form treelets; a treelet's nodes are stored together in the order they
//!   were taken, and the subtrees left hanging below it start treelets of their own, stored
//!   after it, depth first.
//!
//! Every order keeps the invariant refit and the wide collapse rely on: children after their
//! parent (the root first), so one backward pass sees every child before its parent.

use super::node::{Child, Node};
use serde::{Deserialize, Serialize};
use std::cmp::Ordering;
use std::collections::BinaryHeap;

/// Bytes of one treelet of [`Layout::Treelet`]: a 4 KiB page.
pub const TREELET_BYTES: usize = 4096;

/// Where a box tree's inner nodes sit in memory (`bvh:layout="veb"`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Layout {
    /// The builder's depth-first order.
    #[default]
    Dfs,
    /// Van Emde Boas order by height (cache-oblivious).
    Veb,
    /// Page-sized treelets grown by surface area (Aila and Karras 2010).
    Treelet,
}

impl Layout {
    /// Every layout, the default first.
    pub const ALL: [Layout; 3] = [Layout::Dfs, Layout::Veb, Layout::Treelet];

    /// Name as written in parameters.
    pub fn name(self) -> &'static str {
        match self {
            Layout::Dfs => "dfs",
            Layout::Veb => "veb",
            Layout::Treelet => "treelet",
        }
    }

    /// Whether this is the default (serialized parameters leave it out).
    pub fn is_default(&self) -> bool {
        *self == Layout::Dfs
    }
}

/// An inner node as the layouts see it: its inner children and their rewriting.
pub trait LayoutNode: Copy {
    /// Calls `f(index, area)` for each inner child, in child order, with the surface area of
    /// its box.
    fn inner_children(&self, f: impl FnMut(u32, f32));
    /// Rewrites each inner child's index `i` to `new_of[i]`.
    fn renumber(&mut self, new_of: &[u32]);
}

impl LayoutNode for Node {
    fn inner_children(&self, mut f: impl FnMut(u32, f32)) {
        for (i, c) in self.children.iter().enumerate() {
            if !c.is_leaf() {
                f(c.index, self.child_bounds(i).surface_area());
            }
        }
    }

    fn renumber(&mut self, new_of: &[u32]) {
        for c in &mut self.children {
            if !c.is_leaf() {
                c.index = new_of[c.index as usize];
            }
        }
    }
}

/// Reorders `nodes` (children after their parent, the tree under `root`) into `layout`,
/// rewriting every inner reference and `root`. The default layout leaves them as they are.
pub fn apply<N: LayoutNode>(layout: Layout, root: &mut Child, nodes: &mut Vec<N>) {
    if layout == Layout::Dfs || root.is_leaf() {
        return;
    }
    let order = order(layout, root.index, nodes);
    let mut new_of = vec![u32::MAX; nodes.len()];
    for (new, &old) in order.iter().enumerate() {
        new_of[old as usize] = new as u32;
    }
    assert!(
        order.len() == nodes.len() && new_of.iter().all(|&n| n != u32::MAX),
        "the {} layout is not a permutation of the nodes",
        layout.name()
    );
    *nodes = order
        .iter()
        .map(|&old| {
            let mut n = nodes[old as usize];
            n.renumber(&new_of);
            n
        })
        .collect();
    root.index = new_of[root.index as usize];
    debug_assert!(root.index == 0 && children_after_parents(nodes));
}

/// The node order of `layout` for the tree of `nodes` (in the builder's order) under inner node
/// `root`: `order[k]` is the index of the node stored at `k`, every node reachable from `root`
/// once ([`Layout::Dfs`]: the builder's order as it is).
pub fn order<N: LayoutNode>(layout: Layout, root: u32, nodes: &[N]) -> Vec<u32> {
    let mut out = Vec::with_capacity(nodes.len());
    match layout {
        Layout::Dfs => out.extend(0..nodes.len() as u32),
        Layout::Veb => {
            let h = heights(nodes);
            veb(root, h[root as usize], nodes, &h, &mut out, &mut Vec::new());
        }
        Layout::Treelet => {
            let size = (TREELET_BYTES / size_of::<N>()).max(1);
            treelets(root, nodes, size, &mut out);
        }
    }
    out
}

/// Whether every inner child's index is above its parent's (what refit's backward pass needs).
pub fn children_after_parents<N: LayoutNode>(nodes: &[N]) -> bool {
    let mut ok = true;
    for (i, n) in nodes.iter().enumerate() {
        n.inner_children(|c, _| ok &= c as usize > i);
    }
    ok
}

/// Per node, the levels of inner nodes of its subtree (1 for a node whose children are all
/// leaves). Children come after their parent, so one backward pass suffices.
fn heights<N: LayoutNode>(nodes: &[N]) -> Vec<u32> {
    let mut h = vec![1u32; nodes.len()];
    for i in (0..nodes.len()).rev() {
        let mut most = 0;
        nodes[i].inner_children(|c, _| {
            assert!(c as usize > i, "node {i}'s child {c} comes before it");
            most = most.max(h[c as usize]);
        });
        h[i] = most + 1;
    }
    h
}

/// Appends the van Emde Boas order of the nodes less than `levels` levels below `root`:
/// the top `levels / 2` levels, then each subtree hanging below them, in child order.
/// `scratch` holds the pending subtree roots of the callers (left as it was found).
fn veb<N: LayoutNode>(
    root: u32,
    levels: u32,
    nodes: &[N],
    h: &[u32],
    out: &mut Vec<u32>,
    scratch: &mut Vec<u32>,
) {
    let levels = levels.min(h[root as usize]);
    if levels <= 1 {
        out.push(root);
        return;
    }
    let top = levels / 2;
    veb(root, top, nodes, h, out, scratch);
    let start = scratch.len();
    at_depth(root, top, nodes, scratch);
    for k in start..scratch.len() {
        veb(scratch[k], levels - top, nodes, h, out, scratch);
    }
    scratch.truncate(start);
}

/// Appends the inner nodes exactly `depth` levels below `node`, in child order.
fn at_depth<N: LayoutNode>(node: u32, depth: u32, nodes: &[N], out: &mut Vec<u32>) {
    if depth == 0 {
        out.push(node);
        return;
    }
    nodes[node as usize].inner_children(|c, _| at_depth(c, depth - 1, nodes, out));
}

/// A node next to a growing treelet: larger area first, then the one found first.
#[derive(PartialEq)]
struct Candidate {
    area: f32,
    seq: u32,
    node: u32,
}

impl Eq for Candidate {}

impl Ord for Candidate {
    fn cmp(&self, o: &Self) -> Ordering {
        self.area
            .total_cmp(&o.area)
            .then_with(|| o.seq.cmp(&self.seq))
    }
}

impl PartialOrd for Candidate {
    fn partial_cmp(&self, o: &Self) -> Option<Ordering> {
        Some(self.cmp(o))
    }
}

/// Appends the treelets of at most `size` nodes: each grown from its root by the candidate of
/// largest area, stored in the order taken; the candidates left over are the roots of the next
/// treelets, stored after it, depth first (the first found first).
fn treelets<N: LayoutNode>(root: u32, nodes: &[N], size: usize, out: &mut Vec<u32>) {
    let mut roots = vec![root];
    let mut heap = BinaryHeap::new();
    let mut left: Vec<Candidate> = Vec::new();
    while let Some(r) = roots.pop() {
        let mut seq = 0u32;
        heap.push(Candidate {
            area: f32::INFINITY,
            seq,
            node: r,
        });
        let mut taken = 0;
        while taken < size {
            let Some(c) = heap.pop() else { break };
            out.push(c.node);
            taken += 1;
            nodes[c.node as usize].inner_children(|node, area| {
                seq += 1;
                heap.push(Candidate { area, seq, node });
            });
        }
        left.clear();
        left.extend(heap.drain());
        left.sort_unstable_by_key(|c| std::cmp::Reverse(c.seq));
        roots.extend(left.iter().map(|c| c.node));
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Aabb;
    use glam::Vec3A;

    /// A complete binary tree of `levels` levels of inner nodes in depth-first order, child `k`
    /// of a node at depth `d` boxed by a cube of side `(k + 1) / (d + 1)`.
    fn complete(levels: u32) -> Vec<Node> {
        fn build(level: u32, levels: u32, nodes: &mut Vec<Node>, leaf: &mut u32) -> Child {
            if level == levels {
                *leaf += 1;
                return Child::leaf(*leaf, 1);
            }
            let at = nodes.len();
            nodes.push(Node::new([Aabb::EMPTY; 2], [Child::default(); 2]));
            let kids = [0, 1].map(|_| build(level + 1, levels, nodes, leaf));
            let side = |k: usize| Vec3A::splat((k + 1) as f32 / (level + 1) as f32);
            let boxes = [0, 1].map(|k| Aabb::new(Vec3A::ZERO, side(k)));
            nodes[at] = Node::new(boxes, kids);
            Child::inner(at as u32)
        }
        let mut nodes = Vec::new();
        build(0, levels, &mut nodes, &mut 0);
        nodes
    }

    #[test]
    fn veb_of_a_complete_tree_is_the_textbook_order() {
        // Four levels: the top two (root, its children), then the four subtrees of two levels,
        // each its root and its two children.
        let nodes = complete(4);
        let o = order(Layout::Veb, 0, &nodes);
        // Depth-first indices: root 0; children 1 and 8; grandchildren 2, 5, 9, 12.
        assert_eq!(o, [0, 1, 8, 2, 3, 4, 5, 6, 7, 9, 10, 11, 12, 13, 14]);
        assert_ne!(o, order(Layout::Dfs, 0, &nodes));
    }

    #[test]
    fn every_layout_is_a_permutation_with_children_after_parents() {
        for levels in [1, 2, 3, 5, 8, 11] {
            let nodes = complete(levels);
            for layout in Layout::ALL {
                let o = order(layout, 0, &nodes);
                let mut sorted = o.clone();
                sorted.sort_unstable();
                assert!(
                    sorted.iter().copied().eq(0..nodes.len() as u32),
                    "{layout:?}"
                );
                let (mut root, mut moved) = (Child::inner(0), nodes.clone());
                apply(layout, &mut root, &mut moved);
                assert_eq!(root, Child::inner(0));
                assert!(children_after_parents(&moved), "{layout:?} {levels}");
            }
        }
        assert_eq!(
            order(Layout::Dfs, 0, &complete(6)),
            (0..63).collect::<Vec<_>>()
        );
    }

    #[test]
    fn treelets_fill_pages_by_area() {
        // 64 binary nodes per page: the first treelet takes the larger child (the second,
        // boxed larger) before the first at every step where both are candidates.
        let nodes = complete(9);
        let o = order(Layout::Treelet, 0, &nodes);
        assert_eq!(o[0], 0);
        let second = nodes[0].children[1].index;
        assert_eq!(o[1], second, "the larger child first");
        // The first 64 nodes are a connected treelet: each one's parent is among them.
        let first: std::collections::HashSet<u32> = o[..64].iter().copied().collect();
        for (i, n) in nodes.iter().enumerate() {
            n.inner_children(|c, _| {
                if first.contains(&c) {
                    assert!(first.contains(&(i as u32)), "{c}'s parent {i} outside");
                }
            });
        }
    }
}
