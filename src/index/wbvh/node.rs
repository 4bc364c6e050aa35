//! Wide nodes and the collapse of the binary SAH tree into them.
//!
//! A node of `C` chunks holds up to `4 * C` children: their boxes in structure-of-arrays form,
//! per axis the `min` planes of all children in `4 * C` consecutive lanes (likewise `max`), so
//! one SIMD slab pass tests four (`C = 1`) or eight (`C = 2`, one AVX pass) boxes, and their
//! references. Lanes past the children hold empty boxes (`+inf..-inf`), which every ray misses
//! and [`WideNode::valid`] leaves out.
//!
//! The binary SAH tree is collapsed into wide nodes by an SAH-optimal plan ([`collapse`]).
//!
//! Size: the references first, then the planes, no other field: `C = 1` is 128 bytes (two cache
//! lines), `C = 2` 256 bytes (four), aligned to a cache line.

use crate::geometry::Aabb;
use crate::index::kit::box_tree::lanes::F8;
use crate::index::kit::box_tree::layout::LayoutNode;
use crate::index::kit::box_tree::node::{Child, Node};
use crate::index::kit::box_tree::slab::{SlabRay, hit_near_far};
use glam::{Vec3A, Vec4};

/// Up to `4 * C` children, filling lanes `0..n`.
#[derive(Debug, Clone, Copy)]
#[repr(C, align(64))]
pub struct WideNode<const C: usize> {
    /// Child `4 * chunk + lane`'s reference in `children[chunk][lane]`.
    pub children: [[Child; 4]; C],
    /// `planes[side][axis][chunk][lane]`: child `4 * chunk + lane`'s lower (`side` 0) or upper
    /// (`side` 1) plane on `axis`. Lanes without a child hold the empty box `+inf..-inf` on
    /// every axis, which every ray misses (see [`crate::index::kit::box_tree::slab`]).
    pub planes: [[[Vec4; C]; 3]; 2],
}

const _: () = assert!(size_of::<WideNode<1>>() == 128 && size_of::<WideNode<2>>() == 256);

impl<const C: usize> WideNode<C> {
    pub(super) fn new(kids: &[(Aabb, Child)]) -> WideNode<C> {
        debug_assert!((2..=4 * C).contains(&kids.len()) || kids.len() == 1);
        let mut n = WideNode {
            children: [[Child::default(); 4]; C],
            planes: [[[Vec4::INFINITY; C]; 3], [[Vec4::NEG_INFINITY; C]; 3]],
        };
        for (i, (b, child)) in kids.iter().enumerate() {
            debug_assert!(b.min.cmple(b.max).all(), "child {i}'s box {b:?} is empty");
            let (chunk, lane) = (i / 4, i % 4);
            for k in 0..3 {
                n.planes[0][k][chunk][lane] = b.min[k];
                n.planes[1][k][chunk][lane] = b.max[k];
            }
            n.children[chunk][lane] = *child;
        }
        n
    }

    /// Bit `i` set when child `i` exists (its box is not empty on `x`).
    #[inline(always)]
    pub fn valid(&self) -> u32 {
        (0..C).fold(0, |m, c| {
            m | self.planes[0][0][c].cmple(self.planes[1][0][c]).bitmask() << (4 * c)
        })
    }

    /// Number of children.
    pub fn width(&self) -> usize {
        self.valid().count_ones() as usize
    }

    /// Child `i`'s reference (one indexed load: the chunks are consecutive).
    #[inline(always)]
    pub fn child(&self, i: usize) -> Child {
        self.children.as_flattened()[i]
    }

    /// Child `i`'s box.
    #[inline(always)]
    pub fn child_box(&self, i: usize) -> Aabb {
        let (chunk, lane) = (i / 4, i % 4);
        let side = |s: usize| Vec3A::from_array([0, 1, 2].map(|k| self.planes[s][k][chunk][lane]));
        Aabb::new(side(0), side(1))
    }

    /// The slab test of every child against `[ray.t_min, t_max]`, planes read by the ray's
    /// direction signs ([`hit_near_far`]): the mask of the hit children (bit `i` for child `i`;
    /// absent children are never hit) and the entry distances (`enter[i]`, meaningful where
    /// hit).
    #[inline(always)]
    pub fn hit<const SAFE: bool>(&self, ray: &SlabRay, t_max: f32) -> (u32, [f32; 8]) {
        if C == 2 {
            // SAFETY: `C == 2`, so both are the same type.
            let p = unsafe { &*std::ptr::from_ref(&self.planes).cast::<[[[Vec4; 2]; 3]; 2]>() };
            let (near, far) = near_far(p, ray.near, F8::from_halves);
            let (mask, enter) = hit_near_far::<SAFE, F8>(near, far, ray, t_max);
            (mask, enter.to_array())
        } else {
            let (near, far) = near_far(&self.planes, ray.near, |v: &[Vec4; C]| v[0]);
            let (mask, enter) = hit_near_far::<SAFE, Vec4>(near, far, ray, t_max);
            let [a, b, c, d] = enter.to_array();
            (mask, [a, b, c, d, 0.0, 0.0, 0.0, 0.0])
        }
    }
}

impl<const C: usize> LayoutNode for WideNode<C> {
    fn inner_children(&self, mut f: impl FnMut(u32, f32)) {
        for i in 0..self.width() {
            let c = self.child(i);
            if !c.is_leaf() {
                f(c.index, self.child_box(i).surface_area());
            }
        }
    }

    /// Lanes past the children keep their default reference.
    fn renumber(&mut self, new_of: &[u32]) {
        let width = self.width();
        for c in self.children.as_flattened_mut().iter_mut().take(width) {
            if !c.is_leaf() {
                c.index = new_of[c.index as usize];
            }
        }
    }
}

/// Per axis, the planes a ray meets first (`near[axis]`: 0 for the lower planes, 1 for the
/// upper) and the others, each loaded by `load`. Written out, with no bounds check (`& 1`) and
/// no array `map`, so the step stays one straight run of loads.
#[inline(always)]
fn near_far<P, V>(p: &[[P; 3]; 2], near: [usize; 3], load: impl Fn(&P) -> V) -> ([V; 3], [V; 3]) {
    let plane = |k: usize, far: usize| load(&p[(near[k] ^ far) & 1][k]);
    (
        [plane(0, 0), plane(1, 0), plane(2, 0)],
        [plane(0, 1), plane(1, 1), plane(2, 1)],
    )
}

/// The wide tree: nodes with the root first and each node's inner children next to each other,
/// and a reference to the root, which is a leaf when the binary tree is one leaf.
pub struct Collapsed<const C: usize> {
    pub root: Child,
    pub nodes: Vec<WideNode<C>>,
    pub depth: u32,
    pub leaves: usize,
}

/// Collapses the binary tree (`root` over `nodes`) into wide nodes by the SAH-optimal plan of
/// Ylitie et al. 2017 ([`Plan`]): each wide node takes, among the ways of covering its binary
/// node's subtree by at most `4 * C` subtrees, the one of least SAH cost, and each chosen
/// subtree is a leaf or, in turn, a wide node. Leaves keep their primitive ranges, and an inner
/// child whose subtree holds at most `leaf_lanes` primitives becomes one leaf over them (with
/// `leaf_lanes` = 4, the lanes of a triangle block, a subtree of up to four triangles costs one
/// block test instead of a node step and up to four partly empty blocks).
pub fn collapse<const C: usize>(root: Child, nodes: &[Node], leaf_lanes: u32) -> Collapsed<C> {
    let binary = Binary {
        nodes,
        merged: merged_leaves(nodes, leaf_lanes),
    };
    let plan = Plan::new(&binary, 4 * C);
    let root = binary.child(root);
    let mut out = Collapsed {
        root,
        nodes: Vec::new(),
        depth: 1,
        leaves: usize::from(root.is_leaf()),
    };
    if !root.is_leaf() {
        out.root = Child::inner(emit(root.index, &binary, &plan, &mut out, 1));
    }
    out
}

/// The binary tree as the collapse reads it.
struct Binary<'a> {
    nodes: &'a [Node],
    /// Per binary node, the leaf replacing its subtree, if merged.
    merged: Vec<Option<Child>>,
}

impl Binary<'_> {
    /// `c`, or the leaf replacing its subtree.
    fn child(&self, c: Child) -> Child {
        match c.is_leaf() {
            true => c,
            false => self.merged[c.index as usize].unwrap_or(c),
        }
    }

    /// Binary node `i`'s two children with their boxes.
    fn kids(&self, i: u32) -> [(Aabb, Child); 2] {
        let n = &self.nodes[i as usize];
        [0, 1].map(|k| (n.child_bounds(k), self.child(n.children[k])))
    }
}

/// Per binary node, a leaf over its subtree's primitives when there are at most `merge_up_to`
/// of them. A subtree's primitives are one contiguous run of ids (the top-down build
/// partitions in place, so siblings' runs are adjacent); children come after their parent in
/// `nodes`, so one backward pass computes every run.
fn merged_leaves(nodes: &[Node], merge_up_to: u32) -> Vec<Option<Child>> {
    let mut runs = vec![(0u32, 0u32); nodes.len()];
    for i in (0..nodes.len()).rev() {
        let [a, b] = nodes[i].children.map(|c| match c.is_leaf() {
            true => (c.index, c.index + c.count),
            false => runs[c.index as usize],
        });
        debug_assert!(
            a.1 == b.0 || b.1 == a.0,
            "sibling runs {a:?} {b:?} not adjacent"
        );
        runs[i] = (a.0.min(b.0), a.1.max(b.1));
    }
    let leaf = |(first, end): (u32, u32)| {
        (end - first <= merge_up_to).then(|| Child::leaf(first, end - first))
    };
    runs.into_iter().map(leaf).collect()
}

/// The collapse's plan (Ylitie, Karras and Laine 2017, "Efficient incoherent ray traversal on
/// GPUs through compressed wide BVHs", section 4.1), by dynamic programming over the binary
/// tree, children before parents. Every way of grouping the binary tree into wide nodes keeps
/// the same leaves (the binary tree's and the merged subtrees, each once), so the SAH cost
/// differs only in the wide nodes: the plan minimizes their summed surface area (the expected
/// number of node steps of a random ray, up to a constant factor).
///
/// For binary node `n` and `j` in `1..=width` slots, `cost[n][j - 1]` is the least summed area
/// of the wide nodes needed to cover `n`'s subtree by at most `j` children of one wide node, and
/// `split[n][j - 1]` how: `0` for `n` itself as one child (a wide node over the best cover of
/// its subtree by `width` children, costing its own area more), `k > 0` for `k` slots to the
/// cover of `n`'s first child and `j - k` to its second's. A leaf is always one child, at no
/// cost. Merged nodes have no entry of their own (their parents see leaves).
struct Plan {
    cost: Vec<[f32; 8]>,
    split: Vec<[u8; 8]>,
}

impl Plan {
    fn new(binary: &Binary, width: usize) -> Plan {
        let n = binary.nodes.len();
        let mut plan = Plan {
            cost: vec![[0.0; 8]; n],
            split: vec![[0; 8]; n],
        };
        for i in (0..n).rev() {
            if binary.merged[i].is_some() {
                continue;
            }
            let [(box_a, a), (box_b, b)] = binary.kids(i as u32);
            let cover = |c: Child, j: usize| match c.is_leaf() {
                true => 0.0,
                false => plan.cost[c.index as usize][j - 1],
            };
            // Best cover of the two children by `j` slots and the first child's share (the
            // first share of least cost; 1 when no cost is finite: boxes of infinite or NaN
            // area).
            let spread = |j: usize| {
                (1..j).fold((f32::INFINITY, 1u8), |best, k| {
                    let c = cover(a, k) + cover(b, j - k);
                    if c < best.0 { (c, k as u8) } else { best }
                })
            };
            let children = spread(width);
            let whole = box_a.union(box_b).surface_area() + children.0;
            let (mut cost, mut split) = ([whole; 8], [0u8; 8]);
            for j in 2..width {
                let s = spread(j);
                if s.0 <= whole {
                    (cost[j - 1], split[j - 1]) = s;
                }
            }
            // The cover by `width` slots always splits: it is the wide node's own children.
            (cost[width - 1], split[width - 1]) = children;
            (plan.cost[i], plan.split[i]) = (cost, split);
        }
        plan
    }

    /// Appends to `out` the children covering `child` (with box `bounds`) in at most `j` slots.
    fn gather(
        &self,
        binary: &Binary,
        (bounds, child): (Aabb, Child),
        j: usize,
        out: &mut Vec<(Aabb, Child)>,
    ) {
        let k = match child.is_leaf() {
            true => 0,
            false => self.split[child.index as usize][j - 1] as usize,
        };
        if k == 0 {
            out.push((bounds, child));
        } else {
            let [a, b] = binary.kids(child.index);
            self.gather(binary, a, k, out);
            self.gather(binary, b, j - k, out);
        }
    }
}

/// The children of the wide node for binary node `index`: the plan's cover of its subtree by
/// `4 * C` children (at least its two children, since the cover by `4 * C` slots always splits).
fn open<const C: usize>(index: u32, binary: &Binary, plan: &Plan) -> Vec<(Aabb, Child)> {
    let width = 4 * C;
    let k = plan.split[index as usize][width - 1] as usize;
    debug_assert!(
        k > 0,
        "the cover of node {index} by {width} slots does not split"
    );
    let [a, b] = binary.kids(index);
    let mut kids = Vec::with_capacity(width);
    plan.gather(binary, a, k, &mut kids);
    plan.gather(binary, b, width - k, &mut kids);
    kids
}

/// Appends the wide node for binary node `index` and its subtree; returns its index.
fn emit<const C: usize>(
    index: u32,
    binary: &Binary,
    plan: &Plan,
    out: &mut Collapsed<C>,
    level: u32,
) -> u32 {
    let me = out.nodes.len();
    let kids = open::<C>(index, binary, plan);
    out.nodes.push(WideNode::new(&kids));
    emit_children(me, &kids, binary, plan, out, level);
    me as u32
}

/// Links node `me` (built from `kids`) to its children: its inner children's nodes are
/// appended next to each other, then each one's subtree in turn, so a node's children share
/// cache pages.
fn emit_children<const C: usize>(
    me: usize,
    kids: &[(Aabb, Child)],
    binary: &Binary,
    plan: &Plan,
    out: &mut Collapsed<C>,
    level: u32,
) {
    out.depth = out.depth.max(level + 1);
    let mut inner = Vec::new();
    for (i, (_, child)) in kids.iter().enumerate() {
        let c = if child.is_leaf() {
            out.leaves += 1;
            *child
        } else {
            let slot = out.nodes.len();
            let grandkids = open::<C>(child.index, binary, plan);
            out.nodes.push(WideNode::new(&grandkids));
            inner.push((slot, grandkids));
            Child::inner(slot as u32)
        };
        out.nodes[me].children[i / 4][i % 4] = c;
    }
    for (slot, grandkids) in inner {
        emit_children(slot, &grandkids, binary, plan, out, level + 1);
    }
}
