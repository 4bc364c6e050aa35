//! Top-down SAH build straight into the final depth-first [`Node`] array (leaves live in their
//! parents' child references): a node's slot is taken before its children are built, and its
//! children's boxes come from the split, so no intermediate tree exists.
//!
//! The builder sees only [`PrimRef`]s (bounds, centroid, id). Large subtrees build in parallel
//! with `rayon::join` when the current pool has more than one thread: the second child's
//! subtree goes into its own node array, appended after the first child's with its inner
//! indices shifted, so the result is the same either way (every decision depends only on the
//! primitives of the subtree).

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

/// The result: the final depth-first node array and the ids in leaf order.
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

/// The inner nodes of a subtree under construction, depth first, indexed from 0 at the start
/// of `nodes`, with its leaf count and deepest leaf level.
struct Out {
    nodes: Vec<Node>,
    leaves: usize,
    depth: u32,
}

impl Out {
    fn with_capacity(nodes: usize) -> Out {
        Out {
            nodes: Vec::with_capacity(nodes),
            leaves: 0,
            depth: 0,
        }
    }

    /// Records a leaf over `prim_ids[first..first + count]` at `level`.
    fn leaf(&mut self, first: u32, count: usize, level: u32) -> Child {
        self.leaves += 1;
        self.depth = self.depth.max(level);
        Child::leaf(first, count as u32)
    }

    /// Appends `other`'s nodes (shifting its inner references by where they land) and returns
    /// `root`, a reference into `other`, as a reference into `self`.
    fn append(&mut self, other: Out, root: Child) -> Child {
        let offset = self.nodes.len() as u32;
        let shift = move |c: Child| {
            if c.is_leaf() {
                c
            } else {
                Child::inner(c.index + offset)
            }
        };
        self.nodes.extend(other.nodes.into_iter().map(|mut n| {
            n.children = n.children.map(shift);
            n
        }));
        self.leaves += other.leaves;
        self.depth = self.depth.max(other.depth);
        shift(root)
    }
}

/// Settings shared by every node of one build.
struct Ctx<'a> {
    cfg: &'a BuildConfig,
    /// Whether large subtrees build their children with `rayon::join`.
    parallel: bool,
}

/// Builds the tree over `refs` (non-empty; reordered into leaf order).
pub fn build(mut refs: Vec<PrimRef>, cfg: &BuildConfig) -> Built {
    assert!(!refs.is_empty(), "the caller rejects empty scenes");
    let ctx = Ctx {
        cfg,
        parallel: rayon::current_num_threads() > 1,
    };
    let boxes = bounds_and_centroids(&refs);
    // A binary tree over n primitives has at most n - 1 inner nodes.
    let mut out = Out::with_capacity(refs.len() - 1);
    let root = subtree(
        &mut refs,
        boxes,
        0,
        1,
        &ctx,
        &mut out,
        &mut Scratch::default(),
    );
    Built {
        root_bounds: boxes.0,
        root,
        nodes: out.nodes,
        prim_ids: refs.iter().map(|r| r.id()).collect(),
        leaves: out.leaves,
        depth: out.depth,
    }
}

/// Builds the subtree over `refs`, whose bounds and centroid bounds are `boxes`, appending its
/// inner nodes to `out` depth first; its primitives start at slot `first`; `level` counts from
/// 1 at the root. Returns the reference to the subtree.
fn subtree(
    refs: &mut [PrimRef],
    boxes: (Aabb, Aabb),
    first: u32,
    level: u32,
    ctx: &Ctx,
    out: &mut Out,
    scratch: &mut Scratch,
) -> Child {
    let n = refs.len();
    let cfg = ctx.cfg;
    let (bounds, centroids) = boxes;
    if n == 1 || level == MAX_DEPTH {
        return out.leaf(first, n, level);
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
                return out.leaf(first, n, level);
            }
            (mid, children)
        }
        // Coincident centroids: no plane separates them; halve by count if too many.
        None if small => return out.leaf(first, n, level),
        None => (n / 2, None),
    };
    let (l, r) = refs.split_at_mut(mid);
    let (lb, rb) = children.unwrap_or_else(|| (bounds_and_centroids(l), bounds_and_centroids(r)));
    let right_first = first + mid as u32;
    let at = out.nodes.len();
    out.nodes
        .push(Node::new([lb.0, rb.0], [Child::default(); 2]));
    let children = if ctx.parallel && n >= PARALLEL_MIN {
        let mut right = Out::with_capacity(r.len() - 1);
        let (a, b) = rayon::join(
            || subtree(l, lb, first, level + 1, ctx, out, scratch),
            || {
                let mut scratch = Scratch::default();
                subtree(r, rb, right_first, level + 1, ctx, &mut right, &mut scratch)
            },
        );
        [a, out.append(right, b)]
    } else {
        let a = subtree(l, lb, first, level + 1, ctx, out, scratch);
        [a, subtree(r, rb, right_first, level + 1, ctx, out, scratch)]
    };
    out.nodes[at].children = children;
    Child::inner(at as u32)
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
