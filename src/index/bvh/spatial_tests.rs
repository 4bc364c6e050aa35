//! Tests of the spatial splits: pieces cover their primitives within the budget, the tree does
//! not depend on the thread count, boxes (spheres) split into boxes.

use super::*;
use crate::geometry::Triangle;
use crate::geometry::triangle::Watertight;
use crate::index::bvh::build::{Built, build};
use crate::index::bvh::params::BvhParams;
use crate::index::kit::box_tree::node::Child;
use crate::scene::generators::{slivers, sphere_field};
use crate::scene::{Mixed, Triangles};

fn built<G: Geometry>(geom: &G, threads: usize) -> Built {
    let refs = (0..geom.len() as u32)
        .map(|id| PrimRef::new(geom.bounds(id), id))
        .collect();
    let params = BvhParams {
        spatial_splits: true,
        ..BvhParams::default()
    };
    let cfg = params.config().unwrap();
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap();
    pool.install(|| build(refs, &cfg, Some(geom)))
}

/// Every leaf's box with its ids; asserts that children lie inside their parents and that
/// no leaf names a primitive twice.
fn leaves(b: &Built) -> Vec<(Aabb, &[u32])> {
    let mut out = Vec::new();
    let mut stack = vec![(b.root, b.root_bounds)];
    while let Some((c, bounds)) = stack.pop() {
        if c.is_leaf() {
            let ids = &b.prim_ids[c.index as usize..][..c.count as usize];
            let mut sorted = ids.to_vec();
            sorted.sort_unstable();
            sorted.dedup();
            assert_eq!(sorted.len(), ids.len(), "a leaf names a primitive twice");
            out.push((bounds, ids));
            continue;
        }
        let n = &b.nodes[c.index as usize];
        for i in 0..2 {
            let kid: (Child, Aabb) = (n.children[i], n.child_bounds(i));
            assert_eq!(bounds.union(kid.1), bounds, "a child sticks out");
            stack.push(kid);
        }
    }
    out
}

/// Points spread over the triangle: corners, edges and inside (barycentric steps of 1/8).
fn samples(t: &Triangle) -> Vec<Vec3A> {
    let mut v = Vec::new();
    for i in 0..=8u8 {
        for j in 0..=8 - i {
            let (a, b) = (f32::from(i) / 8.0, f32::from(j) / 8.0);
            let p = t.v[0] * (1.0 - a - b) + t.v[1] * a + t.v[2] * b;
            v.push(p.clamp(t.bounds().min, t.bounds().max));
        }
    }
    v
}

#[test]
fn slab_bounds_cut_a_triangle() {
    let t = Triangle::new(
        Vec3A::ZERO,
        Vec3A::new(4.0, 0.0, 0.0),
        Vec3A::new(0.0, 4.0, 2.0),
    );
    let b = slab_bounds(&t, 0, 1.0, 2.0);
    assert_eq!(
        b,
        Aabb::new(Vec3A::new(1.0, 0.0, 0.0), Vec3A::new(2.0, 3.0, 1.5))
    );
    assert!(slab_bounds(&t, 0, 5.0, 6.0).is_empty());
}

#[test]
fn slivers_split_within_budget_and_every_point_stays_in_a_leaf() {
    let tris = slivers(3000, 7);
    let geom = Triangles::<Watertight>::new(tris.clone().into());
    let b = built(&geom, 1);
    let n = tris.len();
    let refs = b.prim_ids.len();
    let per_prim = BvhParams::default().config().unwrap().split_budget;
    assert!(
        refs > n && refs as f32 <= per_prim * n as f32,
        "{refs} references"
    );
    let mut boxes = vec![Vec::new(); n];
    for (bounds, ids) in leaves(&b) {
        for &id in ids {
            assert!(!bounds.intersection(tris[id as usize].bounds()).is_empty());
            boxes[id as usize].push(bounds);
        }
    }
    for (t, boxes) in tris.iter().zip(&boxes) {
        for p in samples(t) {
            assert!(
                boxes.iter().any(|b| b.contains(p)),
                "{p} of {t:?} in no leaf"
            );
        }
    }
}

#[test]
fn the_tree_does_not_depend_on_the_thread_count() {
    let geom = Triangles::<Watertight>::new(slivers(20_000, 3).into());
    let (serial, parallel) = (built(&geom, 1), built(&geom, 2));
    assert_eq!(serial.prim_ids, parallel.prim_ids);
    let key = |b: &Built| -> Vec<_> {
        let nodes = b.nodes.iter();
        nodes
            .map(|n| (n.child_bounds(0), n.child_bounds(1), n.children))
            .collect()
    };
    assert_eq!(key(&serial), key(&parallel));
    assert!(serial.prim_ids.len() > 20_000);
}

#[test]
fn spheres_split_by_their_boxes() {
    let spheres = sphere_field(2000, 5);
    let geom = Mixed::<Watertight>::new(Vec::<Triangle>::new().into(), spheres.clone().into());
    let b = built(&geom, 1);
    let mut boxes = vec![Aabb::EMPTY; spheres.len()];
    for (bounds, ids) in leaves(&b) {
        for &id in ids {
            boxes[id as usize] = boxes[id as usize].union(bounds);
        }
    }
    // The pieces of a box are boxes: their leaves' boxes cover it.
    for (s, b) in spheres.iter().zip(&boxes) {
        assert_eq!(b.union(s.bounds()), *b);
    }
}
