//! Closest-hit and any-hit traversal of the wide tree.
//!
//! At an inner node every chunk of four children's boxes is tested in one SIMD slab pass
//! ([`hit_boxes4`], the binary BVH's arithmetic, so conservative and monotone exactly like the
//! scalar [`crate::geometry::Aabb::ray_interval`]) against `[t_min, best t]`. Closest hit visits
//! the hit children front to back: they are sorted by entry distance, the nearest is visited
//! next and the others pushed farthest first with their entries; a popped child whose entry is
//! strictly greater than the best `t` is skipped, which is exact for the same reason as in the
//! binary BVH (kernels return a `t` no smaller than the entry of any box containing the
//! primitive). Leaves test their primitives through [`Geometry::intersect`] in id order.
//!
//! The stack is a fixed array: a node at level `L` has at most `(4C - 1)(L - 1)` pushed
//! siblings below it, and levels are bounded by the binary tree's [`MAX_DEPTH`].

use super::node::WideNode;
use crate::geometry::{Aabb, ClosestHit, Hit, Ray};
use crate::index::Stats;
use crate::index::bvh::MAX_DEPTH;
use crate::index::bvh::node::Child;
use crate::index::bvh::slab::{SlabRay, hit_boxes4};
use crate::index::stack::Stack;
use crate::scene::Geometry;

/// The tree as the queries see it.
#[derive(Clone, Copy)]
pub struct Tree<'a, const C: usize> {
    pub root_bounds: &'a Aabb,
    pub root: Child,
    pub nodes: &'a [WideNode<C>],
    pub prim_ids: &'a [u32],
}

impl<const C: usize> Tree<'_, C> {
    #[inline(always)]
    fn prims(&self, leaf: Child) -> &[u32] {
        let first = leaf.index as usize;
        &self.prim_ids[first..first + leaf.count as usize]
    }
}

/// Room for the siblings pushed on the way down: at most 7 (8 children, one visited) per level
/// and [`MAX_DEPTH`] levels.
const STACK: usize = 7 * MAX_DEPTH as usize;

/// The hit mask over all `4C` children and their entries.
#[inline(always)]
fn hit_node<const SAFE: bool, const C: usize>(
    node: &WideNode<C>,
    ray: &SlabRay,
    t_max: f32,
) -> (u32, [[f32; 4]; C]) {
    let mut mask = 0u32;
    let mut enter = [[0.0f32; 4]; C];
    for (k, boxes) in node.boxes.iter().enumerate() {
        let (m, e) = hit_boxes4::<SAFE>(boxes, ray, t_max);
        mask |= m << (4 * k);
        enter[k] = e.to_array();
    }
    (mask & node.valid, enter)
}

/// The closest hit in `[ray.t_min, ray.t_max]` (see the module doc).
#[inline]
pub fn closest_hit<const C: usize, G: Geometry, S: Stats>(
    tree: Tree<C>,
    geom: &G,
    ray: &Ray,
    stats: &mut S,
) -> Option<Hit> {
    stats.box_tests(1);
    tree.root_bounds.ray_entry(ray, ray.t_min, ray.t_max)?;
    if SlabRay::finite(ray) {
        closest::<false, C, G, S>(tree, geom, ray, stats)
    } else {
        closest::<true, C, G, S>(tree, geom, ray, stats)
    }
}

#[inline(always)]
fn closest<const SAFE: bool, const C: usize, G: Geometry, S: Stats>(
    tree: Tree<C>,
    geom: &G,
    ray: &Ray,
    stats: &mut S,
) -> Option<Hit> {
    let slab_ray = SlabRay::new(ray);
    let mut best = ClosestHit::new(ray.t_max);
    let mut stack = Stack::<(Child, f32), STACK>::new();
    let mut at = tree.root;
    loop {
        stats.node_visit();
        if at.is_leaf() {
            for &prim in tree.prims(at) {
                stats.prim_test();
                if let Some(t) = geom.intersect(prim, ray, best.t()) {
                    best.offer(t, prim);
                }
            }
        } else {
            let node = &tree.nodes[at.index as usize];
            stats.box_tests(node.valid.count_ones());
            let (mut mask, enter) = hit_node::<SAFE, C>(node, &slab_ray, best.t());
            if mask != 0 {
                // Hit children sorted by entry, farthest first (insertion sort, at most 4C).
                let mut hit = [(Child::default(), 0.0f32); 8];
                let mut n = 0usize;
                while mask != 0 {
                    let i = mask.trailing_zeros() as usize;
                    mask &= mask - 1;
                    let item = (node.children[i / 4][i % 4], enter[i / 4][i % 4]);
                    let mut j = n;
                    while j > 0 && hit[j - 1].1 < item.1 {
                        hit[j] = hit[j - 1];
                        j -= 1;
                    }
                    hit[j] = item;
                    n += 1;
                }
                for &item in &hit[..n - 1] {
                    stack.push(item);
                }
                at = hit[n - 1].0;
                continue;
            }
        }
        // Pop the next child that can still hold the closest hit (entry <= best t).
        loop {
            let Some((next, entry)) = stack.pop() else {
                return best.get();
            };
            if entry <= best.t() {
                at = next;
                break;
            }
        }
    }
}

/// Whether any primitive is hit in `[ray.t_min, ray.t_max]`; stops at the first.
#[inline]
pub fn any_hit<const C: usize, G: Geometry, S: Stats>(
    tree: Tree<C>,
    geom: &G,
    ray: &Ray,
    stats: &mut S,
) -> bool {
    stats.box_tests(1);
    if tree
        .root_bounds
        .ray_entry(ray, ray.t_min, ray.t_max)
        .is_none()
    {
        return false;
    }
    if SlabRay::finite(ray) {
        any::<false, C, G, S>(tree, geom, ray, stats)
    } else {
        any::<true, C, G, S>(tree, geom, ray, stats)
    }
}

#[inline(always)]
fn any<const SAFE: bool, const C: usize, G: Geometry, S: Stats>(
    tree: Tree<C>,
    geom: &G,
    ray: &Ray,
    stats: &mut S,
) -> bool {
    let slab_ray = SlabRay::new(ray);
    let mut stack = Stack::<Child, STACK>::new();
    let mut at = tree.root;
    loop {
        stats.node_visit();
        if at.is_leaf() {
            for &prim in tree.prims(at) {
                stats.prim_test();
                if geom.intersect(prim, ray, ray.t_max).is_some() {
                    return true;
                }
            }
        } else {
            let node = &tree.nodes[at.index as usize];
            stats.box_tests(node.valid.count_ones());
            let (mut mask, _) = hit_node::<SAFE, C>(node, &slab_ray, ray.t_max);
            if mask != 0 {
                while mask & (mask - 1) != 0 {
                    let i = mask.trailing_zeros() as usize;
                    mask &= mask - 1;
                    stack.push(node.children[i / 4][i % 4]);
                }
                let i = mask.trailing_zeros() as usize;
                at = node.children[i / 4][i % 4];
                continue;
            }
        }
        let Some(next) = stack.pop() else {
            return false;
        };
        at = next;
    }
}
