//! Top-down SAH build straight into the final depth-first [`Node`] array (leaves live in their
//! parents' child references): a node's slot is taken before its children are built, and its
//! children's boxes come from the split, so no intermediate tree exists.
//!
//! The builder sees only [`PrimRef`]s (bounds, centroid, id). With spatial splits
//! ([`super::spatial`]) a node may cut its references at a plane instead of partitioning them,
//! so a primitive can be referenced by several leaves. Leaves append their ids to the id array
//! depth first, so every subtree's ids are one contiguous run, its left child's run first (the
//! wide BVH's collapse relies on this). Large subtrees build in parallel with `rayon::join`
//! when the current pool has more than one thread: the second child's subtree goes into its own
//! node and id arrays, appended after the first child's with its references shifted, so the
//! result is the same either way (every decision depends only on the references of the subtree
//! and the extra references it may make).

use super::binned;
use super::params::{BuildConfig, SplitMethod};
use super::prim_ref::{PrimRef, bounds_and_centroids};
use super::spatial::{self, Clip, Spatial, share};
use super::sweep;
use crate::geometry::Aabb;
use crate::index::kit::box_tree::node::{Child, Node};

/// Most levels of the tree (root = level 1). A node at this level becomes a leaf whatever its
/// size, so a traversal stack of `MAX_DEPTH` entries can never overflow.
pub const MAX_DEPTH: u32 = 64;

/// Subtrees with at least this many references build their two children in parallel.
const PARALLEL_MIN: usize = 4096;

/// The result: the final depth-first node array and the ids in leaf order.
#[derive(Debug, Clone)]
pub struct Built {
    /// The root's box and reference (a leaf when the whole scene is one).
    pub root_bounds: Aabb,
    pub root: Child,
    /// Inner nodes, depth first: a node's first child (if inner) follows it.
    pub nodes: Vec<Node>,
    /// Primitive ids in leaf order: leaf `i` reads a contiguous run; with spatial splits an id
    /// may occur in several leaves (never twice in one).
    pub prim_ids: Vec<u32>,
    pub leaves: usize,
    /// Levels of the deepest leaf (root = 1), at most [`MAX_DEPTH`].
    pub depth: u32,
}

/// The inner nodes and the ids of a subtree under construction, depth first, indexed from 0 at
/// the start of `nodes` and `prim_ids`, with its leaf count and deepest leaf level.
struct Out {
    nodes: Vec<Node>,
    prim_ids: Vec<u32>,
    leaves: usize,
    depth: u32,
}

impl Out {
    /// Room for a subtree over `refs` references (without spatial splits, exactly enough).
    fn with_capacity(refs: usize) -> Out {
        Out {
            nodes: Vec::with_capacity(refs.saturating_sub(1)),
            prim_ids: Vec::with_capacity(refs),
            leaves: 0,
            depth: 0,
        }
    }

    /// Appends a leaf over `refs` at `level`.
    fn leaf(&mut self, refs: &[PrimRef], level: u32) -> Child {
        let first = self.prim_ids.len() as u32;
        self.prim_ids.extend(refs.iter().map(PrimRef::id));
        self.leaves += 1;
        self.depth = self.depth.max(level);
        Child::leaf(first, refs.len() as u32)
    }

    /// Appends `other`'s nodes and ids (shifting its references by where they land) and
    /// returns `root`, a reference into `other`, as a reference into `self`.
    fn append(&mut self, other: Out, root: Child) -> Child {
        let (nodes, ids) = (self.nodes.len() as u32, self.prim_ids.len() as u32);
        let shift = move |c: Child| match c.is_leaf() {
            true => Child::leaf(c.index + ids, c.count),
            false => Child::inner(c.index + nodes),
        };
        self.nodes.extend(other.nodes.into_iter().map(|mut n| {
            n.children = n.children.map(shift);
            n
        }));
        self.prim_ids.extend(other.prim_ids);
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
    spatial: Option<Spatial<'a>>,
}

/// Reusable bins of one build thread.
#[derive(Default)]
struct Scratch {
    binned: binned::Scratch,
    spatial: spatial::Scratch,
}

/// Builds the tree over `refs` (non-empty; reordered), with spatial splits over the primitives
/// `clip` cuts when it is given.
pub fn build(mut refs: Vec<PrimRef>, cfg: &BuildConfig, clip: Option<&dyn Clip>) -> Built {
    assert!(!refs.is_empty(), "the caller rejects empty scenes");
    let boxes = bounds_and_centroids(&refs);
    let ctx = Ctx {
        cfg,
        parallel: rayon::current_num_threads() > 1,
        spatial: clip.map(|c| Spatial::new(c, &boxes.0, cfg.sah_block)),
    };
    let budget = match ctx.spatial {
        Some(_) => spatial::budget(refs.len(), cfg.split_budget),
        None => 0,
    };
    let mut out = Out::with_capacity(refs.len());
    let root = subtree(
        &mut refs,
        boxes,
        budget,
        1,
        &ctx,
        &mut out,
        &mut Scratch::default(),
    );
    Built {
        root_bounds: boxes.0,
        root,
        nodes: out.nodes,
        prim_ids: out.prim_ids,
        leaves: out.leaves,
        depth: out.depth,
    }
}

/// Builds the subtree over `refs`, whose bounds and centroid bounds are `boxes` and which may
/// make `budget` extra references by spatial splits, appending its inner nodes and ids to `out`
/// depth first; `level` counts from 1 at the root. Returns the reference to the subtree.
fn subtree(
    refs: &mut [PrimRef],
    boxes: (Aabb, Aabb),
    budget: usize,
    level: u32,
    ctx: &Ctx,
    out: &mut Out,
    scratch: &mut Scratch,
) -> Child {
    let n = refs.len();
    let cfg = ctx.cfg;
    let (bounds, centroids) = boxes;
    if n == 1 || level == MAX_DEPTH {
        return out.leaf(refs, level);
    }
    // Nodes with fewer primitives than bins use one bin per primitive: the sweep over empty
    // bins would cost more than the binning.
    let bins = cfg.bins.min(n as u32).max(2);
    // (cost, mid, child boxes if the splitter computed them)
    let split = match cfg.split {
        SplitMethod::Binned => {
            binned::split(refs, &centroids, bins, cfg.sah_block, &mut scratch.binned)
                .map(|s| (s.cost, s.mid, Some([s.left, s.right])))
        }
        SplitMethod::Sweep => {
            sweep::split(refs, cfg.sah_block as usize).map(|(cost, mid)| (cost, mid, None))
        }
    };
    let small = n <= cfg.leaf_size as usize;
    let (cost, mid, children) = match split {
        Some((cost, mid, children)) => (Some(cost), mid, children),
        // Coincident centroids: no plane separates them; halve by count if too many.
        None if small => return out.leaf(refs, level),
        None => (None, n / 2, None),
    };
    let [lb, rb] = children.unwrap_or_else(|| {
        let (l, r) = refs.split_at(mid);
        [bounds_and_centroids(l), bounds_and_centroids(r)]
    });
    let spatial = ctx
        .spatial
        .as_ref()
        .filter(|s| budget > 0 && s.worth_trying(&lb.0, &rb.0))
        .and_then(|s| {
            Some((
                s,
                s.find(refs, &bounds, bins, budget, &mut scratch.spatial)?,
            ))
        });
    // SAH in units of one primitive test: leaf n (rounded up to whole blocks), split
    // cost_ratio + expected tests.
    let area = bounds.surface_area();
    let expected = |cost: f32| if area > 0.0 { cost / area } else { 0.0 };
    let best = match (cost, spatial.map(|(_, c)| c.cost)) {
        (Some(o), Some(s)) => Some(o.min(s)),
        (o, s) => o.or(s),
    };
    let leaf = n.next_multiple_of(cfg.sah_block as usize) as f32;
    if small && best.is_some_and(|c| leaf <= cfg.cost_ratio + expected(c)) {
        return out.leaf(refs, level);
    }
    if let Some((s, c)) = spatial
        && let Some([(mut l, lb), (mut r, rb)]) = s.apply(refs, &c, cost)
    {
        let extra = (l.len() + r.len()).saturating_sub(n);
        let budgets = share(budget.saturating_sub(extra), l.len(), r.len());
        return node(
            [(&mut l, lb), (&mut r, rb)],
            budgets,
            level,
            ctx,
            out,
            scratch,
        );
    }
    let (l, r) = refs.split_at_mut(mid);
    let budgets = share(budget, l.len(), r.len());
    node([(l, lb), (r, rb)], budgets, level, ctx, out, scratch)
}

/// Appends the inner node at `level` over the two children `kids` (their references, bounds
/// and centroid bounds), builds their subtrees with `budgets` extra references, and returns
/// its reference.
fn node(
    kids: [(&mut [PrimRef], (Aabb, Aabb)); 2],
    budgets: [usize; 2],
    level: u32,
    ctx: &Ctx,
    out: &mut Out,
    scratch: &mut Scratch,
) -> Child {
    let [(l, lb), (r, rb)] = kids;
    let at = out.nodes.len();
    out.nodes
        .push(Node::new([lb.0, rb.0], [Child::default(); 2]));
    let children = if ctx.parallel && l.len() + r.len() >= PARALLEL_MIN {
        let mut right = Out::with_capacity(r.len());
        let (a, b) = rayon::join(
            || subtree(l, lb, budgets[0], level + 1, ctx, out, scratch),
            || {
                let mut scratch = Scratch::default();
                subtree(r, rb, budgets[1], level + 1, ctx, &mut right, &mut scratch)
            },
        );
        [a, out.append(right, b)]
    } else {
        let a = subtree(l, lb, budgets[0], level + 1, ctx, out, scratch);
        [a, subtree(r, rb, budgets[1], level + 1, ctx, out, scratch)]
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
            let built = build(input.clone(), &cfg, None);
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
        let serial = pool(1).install(|| build(input.clone(), &cfg, None));
        let parallel = pool(2).install(|| build(input.clone(), &cfg, None));
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
            let built = build(input.clone(), &cfg, None);
            check(&built, &input, cfg.leaf_size);
        }
    }
}
