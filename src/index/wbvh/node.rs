//! Wide nodes and the collapse of the binary SAH tree into them.
//!
//! A node of `C` chunks holds up to `4 * C` children: per chunk, the children's boxes in
//! structure-of-arrays form ([`Boxes4`], one SIMD slab test per chunk) and their references.
//! Lanes past `len` are unused (zero boxes) and masked out of every test.

use crate::geometry::Aabb;
use crate::index::bvh::node::{Child, Node};
use crate::index::bvh::slab::Boxes4;
use glam::Vec4;

/// Up to `4 * C` children.
#[derive(Debug, Clone, Copy)]
#[repr(C, align(32))]
pub struct WideNode<const C: usize> {
    pub boxes: [Boxes4; C],
    pub children: [[Child; 4]; C],
    /// Bit `i` set when child `i` exists (children fill lanes `0..n`).
    pub valid: u32,
}

impl<const C: usize> WideNode<C> {
    fn new(kids: &[(Aabb, Child)]) -> WideNode<C> {
        debug_assert!((2..=4 * C).contains(&kids.len()) || kids.len() == 1);
        let zero = Boxes4 {
            min: [Vec4::ZERO; 3],
            max: [Vec4::ZERO; 3],
        };
        let mut n = WideNode {
            boxes: [zero; C],
            children: [[Child::default(); 4]; C],
            valid: (1u32 << kids.len()) - 1,
        };
        for (i, (b, child)) in kids.iter().enumerate() {
            let (chunk, lane) = (i / 4, i % 4);
            for k in 0..3 {
                n.boxes[chunk].min[k][lane] = b.min[k];
                n.boxes[chunk].max[k][lane] = b.max[k];
            }
            n.children[chunk][lane] = *child;
        }
        n
    }
}

/// The wide tree: nodes in depth-first order (the root first), and a reference to the root,
/// which is a leaf when the binary tree is one leaf.
pub struct Collapsed<const C: usize> {
    pub root: Child,
    pub nodes: Vec<WideNode<C>>,
    pub depth: u32,
    pub leaves: usize,
}

/// Collapses the binary tree (`root` over `nodes`): each wide node takes its binary node's two
/// children and repeatedly replaces the inner child of largest surface area by its two
/// children while it has fewer than `4 * C`; the remaining inner children become wide nodes.
/// Leaves keep their primitive ranges.
pub fn collapse<const C: usize>(root: Child, nodes: &[Node]) -> Collapsed<C> {
    let mut out = Collapsed {
        root,
        nodes: Vec::new(),
        depth: 1,
        leaves: usize::from(root.is_leaf()),
    };
    if !root.is_leaf() {
        out.root = Child::inner(emit(root.index, nodes, &mut out, 1));
    }
    out
}

/// Appends the wide node for binary node `index` (and its subtree); returns its index.
fn emit<const C: usize>(index: u32, nodes: &[Node], out: &mut Collapsed<C>, level: u32) -> u32 {
    out.depth = out.depth.max(level + 1);
    let kids_of = |i: u32| {
        let n = &nodes[i as usize];
        [0, 1].map(|k| (n.child_bounds(k), n.children[k]))
    };
    let mut kids: Vec<(Aabb, Child)> = kids_of(index).to_vec();
    while kids.len() < 4 * C {
        let Some((pos, _)) = kids
            .iter()
            .enumerate()
            .filter(|(_, (_, c))| !c.is_leaf())
            .max_by(|a, b| a.1.0.surface_area().total_cmp(&b.1.0.surface_area()))
        else {
            break;
        };
        let (_, opened) = kids.swap_remove(pos);
        kids.extend(kids_of(opened.index));
    }
    let me = out.nodes.len();
    out.nodes.push(WideNode::new(&kids));
    for (i, (_, child)) in kids.iter().enumerate() {
        let c = if child.is_leaf() {
            out.leaves += 1;
            *child
        } else {
            Child::inner(emit(child.index, nodes, out, level + 1))
        };
        out.nodes[me].children[i / 4][i % 4] = c;
    }
    me as u32
}
