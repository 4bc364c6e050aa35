//! The near/far traversal loop over a flat array of nodes (depth-first, the child below a plane
//! right after its parent) and one array of primitive ids that leaves index contiguously (a leaf
//! of one primitive holds its id itself, so reaching its test reads no id array).
//!
//! Per ray: the node type's precomputation ([`SplitNode::prepare`], e.g. the inverse direction)
//! once, then per node one [`SplitNode::step`] (one crossing or a leaf range). An interior step
//! asks the cache for the second child's node at once (it is visited later, or next when the
//! ray passes the plane before the node's span), branches only on "second child only" (the
//! near child is the usual next node, so the next load starts before the crossing is compared),
//! and writes the far `(node, t0, t1)` span on a fixed stack on the call stack (never zeroed,
//! never allocated), kept by a flag rather than a branch. After a leaf, pending spans that
//! start strictly after the best hit are dropped as they are popped, so the walk ends as soon
//! as the best hit lies before every pending span.
//!
//! Mailboxing is a choice of the index (`MAILBOX`): without it a primitive referenced by
//! several leaves may be tested again on one ray, which returns the same `t` and so the same
//! closest hit (ties go to the lowest id either way).

use super::MAX_TREE_DEPTH;
use crate::geometry::{Aabb, Ray};
use crate::index::kit::mailbox::{Mailbox, with_mailbox};
use crate::index::kit::prefetch::prefetch;
use crate::index::kit::prim_test;
use crate::index::kit::stack::Stack;
use crate::index::{HitQuery, Stats};
use crate::scene::Geometry;

/// What a node tells the walk.
pub enum Step {
    /// A leaf over ids `first..first + count` of the id array, or when `count == 1` over
    /// primitive `first` itself.
    Leaf { first: u32, count: u32 },
    /// Children in ray order: `first` holds the ray up to the crossing, `second` after it;
    /// `[lo, hi]` contains the exact crossing parameter. `lo = hi = +inf` visits `first` only,
    /// `lo = hi = -inf` `second` only, `lo = -inf, hi = +inf` both over the whole interval.
    Cross {
        first: u32,
        second: u32,
        lo: f32,
        hi: f32,
    },
}

#[cfg(test)]
impl Step {
    /// `(first, second, lo, hi)` of a crossing; panics on a leaf (for tests of node steps).
    pub(crate) fn crossing(self) -> (u32, u32, f32, f32) {
        match self {
            Step::Cross {
                first,
                second,
                lo,
                hi,
            } => (first, second, lo, hi),
            Step::Leaf { .. } => panic!("expected a crossing, got a leaf"),
        }
    }
}

/// A node of a binary space partition that the near/far walk can step through.
pub trait SplitNode: Copy + std::fmt::Debug + Send + Sync + 'static {
    /// What a ray computes once for all its steps (origin and inverse direction, say).
    type RayData;
    /// The per-ray precomputation.
    fn prepare(ray: &Ray) -> Self::RayData;
    /// The step at this node, stored at index `at` (its child below the plane is `at + 1`).
    fn step(&self, at: u32, ray: &Self::RayData) -> Step;
}

/// A node and the parameter interval of the ray inside it.
#[derive(Clone, Copy)]
struct Span {
    node: u32,
    t0: f32,
    t1: f32,
}

/// A built tree as the walk reads it: depth-first nodes, the id array its leaves index, the
/// root cell's box.
#[derive(Clone, Copy)]
pub(super) struct Tree<'a, N> {
    pub nodes: &'a [N],
    pub ids: &'a [u32],
    pub bounds: &'a Aabb,
}

/// Walks `tree` front to back, calling `leaf(ids, stats) -> stop` at each leaf; `bound()` gives
/// the current best `t` (pending spans starting strictly after it are skipped).
#[inline(always)]
fn walk<N: SplitNode, S: Stats>(
    Tree { nodes, ids, bounds }: Tree<'_, N>,
    ray: &Ray,
    stats: &mut S,
    mut leaf: impl FnMut(&[u32], &mut S) -> bool,
    bound: impl Fn() -> f32,
) {
    let Some((t0, t1)) = bounds.ray_interval(ray, ray.t_min, ray.t_max) else {
        return;
    };
    let pre = N::prepare(ray);
    // At most one kept push per interior level (`MAX_TREE_DEPTH` of them), and `push_if`
    // writes the slot above the top.
    let mut stack = Stack::<Span, { MAX_TREE_DEPTH as usize + 1 }>::new();
    let mut cur = Span { node: 0, t0, t1 };
    loop {
        stats.node_visit();
        match nodes[cur.node as usize].step(cur.node, &pre) {
            Step::Leaf { first, count } => {
                let one = [first];
                let prims = if count == 1 {
                    &one[..]
                } else {
                    &ids[first as usize..(first + count) as usize]
                };
                if leaf(prims, stats) {
                    return;
                }
                cur = loop {
                    match stack.pop() {
                        None => return,
                        Some(s) if s.t0 <= bound() => break s,
                        Some(_) => {}
                    }
                };
            }
            Step::Cross {
                first,
                second,
                lo,
                hi,
            } => {
                prefetch(nodes.as_ptr().wrapping_add(second as usize));
                // `lo <= hi` and `t0 <= t1`, so at least one child is visited. The near one is
                // not when `hi < t0` (then `max(t0, lo) = t0`: the far span is the current one);
                // else the far one is kept when `lo <= t1`.
                if hi < cur.t0 {
                    cur.node = second;
                } else {
                    let far = Span {
                        node: second,
                        t0: max(cur.t0, lo),
                        t1: cur.t1,
                    };
                    stack.push_if(far, lo <= cur.t1);
                    cur.node = first;
                    cur.t1 = min(cur.t1, hi);
                }
            }
        }
    }
}

/// The larger of `a` and `b`, or `a` when `b` is NaN (one instruction, as [`f32::max`] for
/// numbers; the walk's `a` is never NaN).
#[inline(always)]
fn max(a: f32, b: f32) -> f32 {
    if b > a { b } else { a }
}

/// The smaller of `a` and `b`, or `a` when `b` is NaN.
#[inline(always)]
fn min(a: f32, b: f32) -> f32 {
    if b < a { b } else { a }
}

/// Runs `f` with this thread's mailbox when `MAILBOX`, else with an empty one it never touches.
#[inline(always)]
fn with_dedup<const MAILBOX: bool, R>(len: usize, f: impl FnOnce(&mut Mailbox) -> R) -> R {
    if MAILBOX {
        with_mailbox(len, f)
    } else {
        f(&mut Mailbox::default())
    }
}

/// The answer to query `Q` by near/far traversal (see the module doc of [`super`] for why a
/// closest hit matches brute force); `MAILBOX`: each primitive tested at most once. A leaf's
/// primitives are tested against `[t_min, Q::reach]`; an any-hit query stops at its first hit.
#[inline]
pub(super) fn query<Q: HitQuery, const MAILBOX: bool, N: SplitNode, G: Geometry, S: Stats>(
    tree: Tree<'_, N>,
    geom: &G,
    ray: &Ray,
    stats: &mut S,
) -> Q::Answer {
    with_dedup::<MAILBOX, _>(geom.len(), |mb| {
        let found = std::cell::Cell::new(Q::start(ray));
        walk(
            tree,
            ray,
            stats,
            |prims, stats| {
                let mut f = found.get();
                let over = prims.iter().any(|&p| {
                    (!MAILBOX || mb.first_visit(p))
                        && prim_test::test::<Q, G, S>(&mut f, geom, p, ray, stats)
                });
                found.set(f);
                over
            },
            || Q::reach(&found.get(), ray),
        );
        Q::answer(found.get())
    })
}
