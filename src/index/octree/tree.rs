//! The octree's flat node layout, shared by both traversals: nodes with their cells, the two,
//! four or eight children of a node stored contiguously, leaf primitive ids in one array, and
//! face ropes.

use crate::geometry::{Aabb, Ray};
use crate::index::Stats;
use glam::Vec3A;

/// `count` of an internal node.
pub(super) const INTERNAL: u32 = u32::MAX;
/// A rope that leads nowhere (the face lies on the root's boundary).
pub(super) const NO_ROPE: u32 = u32::MAX;

/// One node, one cache line: its cell, its children or primitives, its split axes and its face
/// ropes (all a neighbour-traversal step reads; a leaf's content box, read only for non-empty
/// leaves, is kept apart in [`OctreeTree::contents`]).
///
/// An internal node splits the axes in `split` (octant bits of Revelles et al. 2000: `4` = x,
/// `2` = y, `1` = z) at one point, and has one child per octant whose bits lie in `split` (2, 4
/// or 8): the child of octant `c` (bit set = upper side on that axis; bits of unsplit axes are
/// ignored) is [`Node::child`]`(c)`, the children stored in increasing octant order from `first`.
#[derive(Debug, Clone, Copy)]
#[repr(C, align(64))]
pub(super) struct Node {
    /// Lower corner of the closed cell. Siblings share their split planes bit for bit (the
    /// parent's split point is computed once and copied), so any two leaves that touch agree on
    /// the plane between them.
    min: [f32; 3],
    /// Internal: index of the first of the eight children. Leaf: offset into `prim_ids`.
    pub first: u32,
    /// Upper corner of the closed cell (of the first child: its parent's split point on the split
    /// axes).
    max: [f32; 3],
    /// Leaf: number of primitive ids. Internal: [`INTERNAL`].
    pub count: u32,
    /// `ropes[f]`: the node across face `f` (see [`OctreeTree`]), or [`NO_ROPE`].
    pub ropes: [u32; 6],
    /// Internal: the octant bits of the axes split (at least one). Leaf: 0.
    pub split: u32,
}

/// `COMPACT[m][c]` (`c` a subset of `m`): the rank of octant `c` among the octants whose bits lie
/// in `m`, in increasing order (the bits of `c` in `m`'s positions, packed: a 3-bit `pext`).
const COMPACT: [[u8; 8]; 8] = {
    let mut t = [[0u8; 8]; 8];
    let mut m = 0;
    while m < 8 {
        let mut c = 0;
        while c < 8 {
            let (mut bit, mut out, mut k) = (1, 0, 0);
            while bit < 8 {
                if m & bit != 0 {
                    if c & bit != 0 {
                        out |= 1 << k;
                    }
                    k += 1;
                }
                bit <<= 1;
            }
            t[m][c] = out;
            c += 1;
        }
        m += 1;
    }
    t
};

impl Node {
    /// A leaf without primitives or ropes over `cell`.
    pub fn new(cell: Aabb) -> Node {
        Node {
            min: cell.min.to_array(),
            first: 0,
            max: cell.max.to_array(),
            count: 0,
            ropes: [NO_ROPE; 6],
            split: 0,
        }
    }

    /// The child of an internal node holding octant `c` (bits of unsplit axes ignored).
    #[inline(always)]
    pub fn child(&self, c: usize) -> u32 {
        let m = self.split as usize;
        self.first + u32::from(COMPACT[m][c & m])
    }

    /// Number of children of an internal node (2, 4 or 8).
    #[cfg(test)]
    pub fn child_count(&self) -> usize {
        1 << self.split.count_ones()
    }

    /// The closed cell.
    #[inline(always)]
    pub fn cell(&self) -> Aabb {
        Aabb::new(Vec3A::from_array(self.min), Vec3A::from_array(self.max))
    }

    /// The cell's upper corner (of a first child: the parent's split point on its split axes,
    /// the parent's upper corner on the others).
    #[inline(always)]
    pub fn max(&self) -> Vec3A {
        Vec3A::from_array(self.max)
    }

    #[inline(always)]
    pub fn is_leaf(&self) -> bool {
        self.count != INTERNAL
    }
}

/// Face of a cell: `2 * axis` for the lower face, `2 * axis + 1` for the upper face.
#[inline(always)]
pub(super) fn face(axis: usize, upper: bool) -> usize {
    2 * axis + upper as usize
}

/// Octant bit of `axis` (x = 4, y = 2, z = 1, as in Revelles et al.).
#[inline(always)]
pub(super) const fn octant_bit(axis: usize) -> usize {
    4 >> axis
}

/// The built octree that both traversals walk.
///
/// Invariants: `nodes[0]` is the root, a box enclosing the scene bounds (padded); the children of
/// a node tile its cell; every
/// primitive whose conservative overlap test ([`crate::scene::Geometry::overlaps_box`]) accepts a
/// leaf's cell is listed in that leaf; `nodes[n].ropes[f]` is the deepest node whose cell covers the
/// whole face `f` of node `n` from the other side (Samet's neighbour at the same or a shallower
/// depth, moved down as far as it still covers the face, after Havran; with split points off
/// the middle it may be thinner than `n` across the face), or [`NO_ROPE`] on the root's boundary;
/// `contents[n]` is leaf `n`'s content box (empty for internal nodes and empty leaves).
#[derive(Debug, Clone)]
pub struct OctreeTree {
    pub(super) nodes: Vec<Node>,
    /// Leaf `n`: the union of its primitives' bounds
    /// ([`crate::scene::Geometry::bounds`]); it may reach beyond the cell.
    pub(super) contents: Vec<Aabb>,
    pub(super) prim_ids: Vec<u32>,
    /// Deepest leaf level (the root is level 0).
    pub(super) max_level: usize,
    /// Number of primitives in the scene it was built on.
    pub(super) prim_count: usize,
}

impl OctreeTree {
    /// The root cell (a cube enclosing the scene, padded).
    pub fn root_cell(&self) -> Aabb {
        self.nodes[0].cell()
    }

    /// The cells of all leaves, in node order (for tests that aim rays at cell corners).
    pub fn leaf_cells(&self) -> impl Iterator<Item = Aabb> + '_ {
        self.nodes.iter().filter(|n| n.is_leaf()).map(Node::cell)
    }

    /// Primitive ids of a leaf.
    #[inline(always)]
    pub(super) fn leaf_prims(&self, node: &Node) -> &[u32] {
        &self.prim_ids[node.first as usize..(node.first + node.count) as usize]
    }

    /// The primitives of a leaf that can still beat `cutoff` (the best `t` so far, or
    /// `ray.t_max`): all of them when the ray meets the leaf's content box within
    /// `[ray.t_min, cutoff]`, none otherwise (one box test, counted).
    ///
    /// Exact: [`crate::scene::Geometry::intersect`] clamps a primitive's `t` into the slab
    /// interval of its own bounds, and the slab test is monotone, so a primitive's `t` lies in
    /// the interval of any box holding its bounds. When the ray misses the content box within
    /// `[t_min, cutoff]` (closed, so a tie at `cutoff` is kept), no primitive of the leaf can hit
    /// at or before `cutoff`. On a flat or boxy scene most leaves a ray crosses touch a wall only
    /// at one face, and this skips them.
    #[inline(always)]
    pub(super) fn leaf_prims_within<S: Stats>(
        &self,
        leaf: u32,
        ray: &Ray,
        cutoff: f32,
        stats: &mut S,
    ) -> &[u32] {
        let node = &self.nodes[leaf as usize];
        if node.count == 0 {
            return &[];
        }
        stats.box_tests(1);
        match self.contents[leaf as usize].ray_interval(ray, ray.t_min, cutoff) {
            Some(_) => self.leaf_prims(node),
            None => &[],
        }
    }

    /// Number of leaves.
    pub fn leaves(&self) -> usize {
        self.nodes.iter().filter(|n| n.is_leaf()).count()
    }

    /// Number of leaves without primitives.
    pub fn empty_leaves(&self) -> usize {
        self.nodes
            .iter()
            .filter(|n| n.is_leaf() && n.count == 0)
            .count()
    }

    /// Heap bytes: nodes (with their ropes), content boxes and leaf primitive ids.
    pub fn memory_bytes(&self) -> usize {
        self.nodes.capacity() * size_of::<Node>()
            + self.contents.capacity() * size_of::<Aabb>()
            + self.prim_ids.capacity() * size_of::<u32>()
    }
}
