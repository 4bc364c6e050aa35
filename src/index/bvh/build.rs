//! Top-down SAH build into a pointer tree, then flattened depth-first into [`Node`]s (leaves
//! live in their parents' child references).
//!
//! The builder sees only [`PrimRef`]s (bounds, centroid, id). Large subtrees build in parallel
//! with `rayon::join` when the current pool has more than one thread; the tree is the same
//! either way (every decision depends only on the primitives of the subtree).

use super::binned::{self, Scratch};
use super::node::{Child, Node};
use super::params::{BuildConfig, SplitMethod};
use super::prim_ref::{PrimRef, bounds_and_centroids};
use super::sweep;
use crate::geometry::Aabb;

/// Most levels of the tree (root = level 1). A node at this level becomes a leaf whatever its
/// size, so a traversal stack of `MAX_DEPTH` entries can never overflow.
pub const MAX_DEPTH: u32 = 64;

/// Subtrees with at least this many primitives build their two children in parallel.
const PARALLEL_MIN: usize = 4096;

/// The flattened result.
#[derive(Debug, Clone)]
pub struct Built {
    /// The root's box and reference (a leaf when the whole scene is one).
    pub root_bounds: Aabb,
    pub root: Child,
    /// Inner nodes, depth first: a node's first child (if inner) follows it.
    pub nodes: Vec<Node>,
    /// Primitive ids in leaf order: leaf `i` reads a contiguous run.
    pub prim_ids: Vec<u32>,
    pub leaves: usize,
    /// Levels of the deepest leaf (root = 1), at most [`MAX_DEPTH`].
    pub depth: u32,
}

enum Tree {
    Leaf {
        bounds: Aabb,
        first: u32,
        count: u32,
    },
    Inner {
        bounds: Aabb,
        children: Box<[Tree; 2]>,
    },
}

/// Builds the tree over `refs` (non-empty; reordered into leaf order).
pub fn build(mut refs: Vec<PrimRef>, cfg: &BuildConfig) -> Built {
    assert!(!refs.is_empty(), "the caller rejects empty scenes");
    let parallel = rayon::current_num_threads() > 1;
    let boxes = bounds_and_centroids(&refs);
    let tree = subtree(
        &mut refs,
        boxes,
        0,
        1,
        cfg,
        parallel,
        &mut Scratch::default(),
    );
    let mut out = Built {
        root_bounds: tree.bounds(),
        root: Child::default(),
        nodes: Vec::with_capacity(refs.len()),
        prim_ids: refs.iter().map(|r| r.id()).collect(),
        leaves: 0,
        depth: 0,
    };
    out.root = flatten(tree, 1, &mut out);
    out
}

/// Builds the subtree over `refs`, whose bounds and centroid bounds are `boxes`; its primitives
/// start at slot `first`; `level` counts from 1 at the root.
fn subtree(
    refs: &mut [PrimRef],
    boxes: (Aabb, Aabb),
    first: u32,
    level: u32,
    cfg: &BuildConfig,
    par: bool,
    scratch: &mut Scratch,
) -> Tree {
    let n = refs.len();
    let (bounds, centroids) = boxes;
    let leaf = Tree::Leaf {
        bounds,
        first,
        count: n as u32,
    };
    if n == 1 || level == MAX_DEPTH {
        return leaf;
    }
    // (cost, mid, child boxes if the splitter computed them)
    let split = match cfg.split {
        // Nodes with fewer primitives than bins use one bin per primitive: the sweep over empty
        // bins would cost more than the binning.
        SplitMethod::Binned => {
            binned::split(refs, &centroids, cfg.bins.min(n as u32).max(2), scratch)
                .map(|s| (s.cost, s.mid, Some((s.left, s.right))))
        }
        SplitMethod::Sweep => sweep::split(refs).map(|(cost, mid)| (cost, mid, None)),
    };
    let small = n <= cfg.leaf_size as usize;
    let (mid, children) = match split {
        Some((cost, mid, children)) => {
            // SAH in units of one primitive test: leaf n, split cost_ratio + expected tests.
            let area = bounds.surface_area();
            let expected = if area > 0.0 { cost / area } else { 0.0 };
            if small && n as f32 <= cfg.cost_ratio + expected {
                return leaf;
            }
            (mid, children)
        }
        // Coincident centroids: no plane separates them; halve by count if too many.
        None if small => return leaf,
        None => (n / 2, None),
    };
    let (l, r) = refs.split_at_mut(mid);
    let (lb, rb) = children.unwrap_or_else(|| (bounds_and_centroids(l), bounds_and_centroids(r)));
    let right_first = first + mid as u32;
    let (a, b) = if par && n >= PARALLEL_MIN {
        rayon::join(
            || subtree(l, lb, first, level + 1, cfg, par, scratch),
            || {
                subtree(
                    r,
                    rb,
                    right_first,
                    level + 1,
                    cfg,
                    par,
                    &mut Scratch::default(),
                )
            },
        )
    } else {
        (
            subtree(l, lb, first, level + 1, cfg, par, scratch),
            subtree(r, rb, right_first, level + 1, cfg, par, scratch),
        )
    };
    Tree::Inner {
        bounds,
        children: Box::new([a, b]),
    }
}

impl Tree {
    fn bounds(&self) -> Aabb {
        match self {
            Tree::Leaf { bounds, .. } | Tree::Inner { bounds, .. } => *bounds,
        }
    }
}

/// Appends `tree`'s inner nodes depth-first (a node, then its first child's subtree, then its
/// second child's) and returns the reference to it; `level` is its level (root = 1).
fn flatten(tree: Tree, level: u32, out: &mut Built) -> Child {
    out.depth = out.depth.max(level);
    match tree {
        Tree::Leaf { first, count, .. } => {
            out.leaves += 1;
            Child::leaf(first, count)
        }
        Tree::Inner { children, .. } => {
            let at = out.nodes.len();
            let [a, b] = *children;
            let boxes = [a.bounds(), b.bounds()];
            out.nodes.push(Node::new(boxes, [Child::default(); 2]));
            let a = flatten(a, level + 1, out);
            let b = flatten(b, level + 1, out);
            out.nodes[at].children = [a, b];
            Child::inner(at as u32)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::index::bvh::params::{BvhParams, Preset};
    use glam::Vec3A;

    fn refs(n: u32) -> Vec<PrimRef> {
        (0..n)
            .map(|i| {
                let f = i as f32;
                let c = Vec3A::new((f * 0.37).sin() * 10.0, (f * 0.11).cos() * 5.0, f * 0.01);
                PrimRef::new(Aabb::new(c - 0.1, c + 0.2), i)
            })
            .collect()
    }

    /// Every child's box lies inside its parent's, every leaf's box contains its primitives,
    /// every primitive is in exactly one leaf, and leaves respect the leaf size.
    fn check(built: &Built, input: &[PrimRef], leaf_size: u32) {
        let mut seen = vec![0u32; input.len()];
        let mut stack = vec![(built.root, built.root_bounds)];
        let mut inner = 0;
        while let Some((child, b)) = stack.pop() {
            if child.is_leaf() {
                assert!(child.count <= leaf_size);
                for &id in &built.prim_ids[child.index as usize..][..child.count as usize] {
                    seen[id as usize] += 1;
                    assert_eq!(b.union(input[id as usize].bounds()), b);
                }
            } else {
                inner += 1;
                let n = &built.nodes[child.index as usize];
                for i in 0..2 {
                    let c = n.child_bounds(i);
                    assert_eq!(
                        b.union(c),
                        b,
                        "node {} sticks out of its parent",
                        child.index
                    );
                    stack.push((n.children[i], c));
                }
            }
        }
        assert!(seen.iter().all(|&s| s == 1));
        assert_eq!(inner, built.nodes.len());
        assert_eq!(built.nodes.len() + 1, built.leaves);
    }

    #[test]
    fn every_preset_builds_a_valid_tree() {
        let input = refs(3000);
        for p in Preset::ALL {
            let cfg = BvhParams::preset(p).config().unwrap();
            let built = build(input.clone(), &cfg);
            check(&built, &input, cfg.leaf_size);
            assert!(built.depth < 40, "{}: depth {}", p.name(), built.depth);
        }
    }

    #[test]
    fn parallel_and_serial_builds_are_identical() {
        let input = refs(20_000);
        let cfg = BvhParams::default().config().unwrap();
        let pool = |t| {
            rayon::ThreadPoolBuilder::new()
                .num_threads(t)
                .build()
                .unwrap()
        };
        let serial = pool(1).install(|| build(input.clone(), &cfg));
        let parallel = pool(2).install(|| build(input.clone(), &cfg));
        assert_eq!(serial.prim_ids, parallel.prim_ids);
        let key = |b: &Built| -> Vec<_> {
            b.nodes
                .iter()
                .map(|n| (n.child_bounds(0), n.child_bounds(1), n.children))
                .collect()
        };
        assert_eq!(key(&serial), key(&parallel));
        assert_eq!(
            (serial.root, serial.root_bounds),
            (parallel.root, parallel.root_bounds)
        );
    }

    #[test]
    fn coincident_centroids_split_by_count() {
        // Nested boxes around one point: no plane separates the centroids.
        let input: Vec<PrimRef> = (0..100u32)
            .map(|i| {
                let h = Vec3A::splat(1.0 + i as f32);
                PrimRef::new(Aabb::new(-h, h), i)
            })
            .collect();
        for p in Preset::ALL {
            let cfg = BvhParams::preset(p).config().unwrap();
            let built = build(input.clone(), &cfg);
            check(&built, &input, cfg.leaf_size);
        }
    }
}
