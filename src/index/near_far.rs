//! The near/far traversal shared by the binary space partitions (kd-tree, general BSP): the
//! ray's parameter interval is cut at each split plane, the child the ray meets first is visited
//! first, the other one is pushed on a fixed stack with its own interval.
//!
//! Conservative bookkeeping keeps the hits identical to brute force:
//! - a tree reports the crossing parameter of a split plane as a bracket `[lo, hi]` that contains
//!   the exact crossing; the first child gets `[t0, min(t1, hi)]`, the second `[max(t0, lo), t1]`,
//!   so the two intervals overlap slightly instead of leaving a rounding gap between them;
//! - a pending node is skipped only when its interval starts *strictly after* the best hit, so
//!   a primitive behind a split plane whose hit ties the best `t` (a lower id may win the tie)
//!   is still tested;
//! - builders put a primitive within a padding distance of a plane on both sides.
//!
//! Each primitive is tested at most once per ray (the shared [`crate::index::mailbox`]).

use super::mailbox::with_mailbox;
use super::{BuildError, Stats};
use crate::geometry::overlap::OVERLAP_PAD;
use crate::geometry::{Aabb, ClosestHit, Hit, Ray};
use crate::scene::Geometry;

/// Deepest tree the traversal stack supports (builders reject a larger `max_depth`).
pub const MAX_TREE_DEPTH: u32 = 64;

/// Relative half-width of the bracket around a computed axis-plane crossing
/// `(split - origin) * inv_dir`: three roundings need `gamma(3)` (about 1.8e-7); the rest is
/// margin for the kernels' own rounding of `t` near a plane.
pub const CROSSING_REL: f32 = 1.0e-6;

/// The bounds of all primitives, or an error naming the problem (NaN, infinite coordinates).
pub fn scene_bounds<G: Geometry>(geom: &G, index: &str) -> Result<Aabb, BuildError> {
    let b = (0..geom.len() as u32).fold(Aabb::EMPTY, |b, p| b.union(geom.bounds(p)));
    if b.is_empty() || !b.min.is_finite() || !b.max.is_finite() {
        return Err(BuildError::Failed {
            index: index.into(),
            message: format!(
                "the scene bounds {:?}..{:?} are not finite; remove NaN or infinite coordinates",
                b.min, b.max
            ),
        });
    }
    Ok(b)
}

/// Classification padding for a scene with bounds `b`: [`OVERLAP_PAD`] of its largest
/// coordinate, as for every overlap test.
pub fn scene_pad(b: &Aabb) -> f32 {
    b.min.abs().max(b.max.abs()).max_element() * OVERLAP_PAD + f32::MIN_POSITIVE
}

/// One step of the traversal at a node.
pub enum Step<'a> {
    /// A leaf with its primitive ids.
    Leaf(&'a [u32]),
    /// The ray stays on one side of the split for the whole interval.
    Only(u32),
    /// Children in ray order: `first` holds the ray up to the crossing, `second` after it;
    /// `[lo, hi]` contains the exact crossing parameter (`-inf, +inf` for "both, everywhere").
    Cross {
        first: u32,
        second: u32,
        lo: f32,
        hi: f32,
    },
}

/// A binary space partition that the near/far traversal can walk.
pub trait NearFarTree {
    /// The conservative parameter interval of the ray in the root cell, or `None` for a miss.
    fn root_interval(&self, ray: &Ray) -> Option<(f32, f32)>;
    /// What to do at `node`.
    fn step(&self, node: u32, ray: &Ray) -> Step<'_>;
}

/// A node and the parameter interval of the ray inside it.
#[derive(Clone, Copy, Default)]
struct Span {
    node: u32,
    t0: f32,
    t1: f32,
}

/// Walks `tree` front to back, calling `leaf(prims, stats) -> stop` at each leaf; `bound()`
/// gives the current best `t` (pending nodes starting strictly after it are skipped).
#[inline(always)]
fn walk<T: NearFarTree, S: Stats>(
    tree: &T,
    ray: &Ray,
    stats: &mut S,
    mut leaf: impl FnMut(&[u32], &mut S) -> bool,
    bound: impl Fn() -> f32,
) {
    let Some((t0, t1)) = tree.root_interval(ray) else {
        return;
    };
    let mut stack = [Span::default(); MAX_TREE_DEPTH as usize + 1];
    let mut sp = 0usize;
    let mut cur = Some(Span { node: 0, t0, t1 });
    loop {
        let span = match cur.take() {
            Some(s) => s,
            None => {
                if sp == 0 {
                    return;
                }
                sp -= 1;
                let s = stack[sp];
                if s.t0 > bound() {
                    continue;
                }
                s
            }
        };
        stats.node_visit();
        match tree.step(span.node, ray) {
            Step::Leaf(prims) => {
                if leaf(prims, stats) {
                    return;
                }
            }
            Step::Only(child) => {
                cur = Some(Span {
                    node: child,
                    ..span
                })
            }
            Step::Cross {
                first,
                second,
                lo,
                hi,
            } => {
                let a = (hi >= span.t0).then(|| Span {
                    node: first,
                    t0: span.t0,
                    t1: span.t1.min(hi),
                });
                let b = (lo <= span.t1).then(|| Span {
                    node: second,
                    t0: span.t0.max(lo),
                    t1: span.t1,
                });
                match (a, b) {
                    (Some(a), Some(b)) => {
                        // One push per level: the stack holds at most `depth` spans.
                        stack[sp] = b;
                        sp += 1;
                        cur = Some(a);
                    }
                    (a, b) => cur = a.or(b),
                }
            }
        }
    }
}

/// The closest hit by near/far traversal (see the module doc for why it matches brute force).
#[inline]
pub fn closest_hit<T: NearFarTree, G: Geometry, S: Stats>(
    tree: &T,
    geom: &G,
    ray: &Ray,
    stats: &mut S,
) -> Option<Hit> {
    with_mailbox(geom.len(), |mb| {
        let best = std::cell::Cell::new(ClosestHit::new(ray.t_max));
        walk(
            tree,
            ray,
            stats,
            |prims, stats| {
                let mut b = best.get();
                for &p in prims {
                    if mb.first_visit(p) {
                        stats.prim_test();
                        if let Some(t) = geom.intersect(p, ray, b.t()) {
                            b.offer(t, p);
                        }
                    }
                }
                best.set(b);
                false
            },
            || best.get().t(),
        );
        best.get().get()
    })
}

/// Whether any primitive is hit (stops at the first).
#[inline]
pub fn any_hit<T: NearFarTree, G: Geometry, S: Stats>(
    tree: &T,
    geom: &G,
    ray: &Ray,
    stats: &mut S,
) -> bool {
    with_mailbox(geom.len(), |mb| {
        let mut found = false;
        walk(
            tree,
            ray,
            stats,
            |prims, stats| {
                found = prims.iter().any(|&p| {
                    mb.first_visit(p) && {
                        stats.prim_test();
                        geom.intersect(p, ray, ray.t_max).is_some()
                    }
                });
                found
            },
            || ray.t_max,
        );
        found
    })
}
